#include "util/time_directories.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace hydrojump::util {

std::optional<double> parse_time_name(std::string_view name) {
  // strtod alone would also take a sign, leading blanks, hexadecimal, "nan" and "inf".
  if (name.empty()) return std::nullopt;
  for (const char ch : name) {
    const bool allowed = (ch >= '0' && ch <= '9') || ch == '.' || ch == 'e' || ch == 'E' || ch == '+' || ch == '-';
    if (!allowed) return std::nullopt;
  }
  if (!((name.front() >= '0' && name.front() <= '9') || name.front() == '.')) return std::nullopt;
  const std::string text(name);
  char* end = nullptr;
  const double t = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(t)) return std::nullopt;
  return t;
}

std::vector<TimeDirectory> time_directories(const std::filesystem::path& dir, double after_s) {
  std::vector<TimeDirectory> out;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    if (!it->is_directory(type_ec)) continue;
    const auto t = parse_time_name(it->path().filename().string());
    if (t && *t > after_s) out.push_back({*t, it->path()});
  }
  std::sort(out.begin(), out.end(), [](const TimeDirectory& a, const TimeDirectory& b) { return a.time_s < b.time_s; });
  return out;
}

}  // namespace hydrojump::util
