#include "util/system_memory.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace hydrojump::util {

std::optional<std::uint64_t> parse_mem_available(std::string_view text) {
  // A line "MemAvailable:   12345678 kB".
  constexpr std::string_view key = "MemAvailable:";
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = text.substr(at, end - at);
    if (line.substr(0, key.size()) == key) {
      std::istringstream in{std::string(line.substr(key.size()))};
      std::uint64_t kb = 0;
      std::string unit;
      if (in >> kb >> unit && unit == "kB" && kb < (std::uint64_t{1} << 53)) return kb * 1024;
      return std::nullopt;
    }
    at = end + 1;
  }
  return std::nullopt;
}

std::optional<std::uint64_t> memory_limit_bytes(const char* value) {
  if (value == nullptr) return std::nullopt;
  const std::string text = value;
  char* end = nullptr;
  const double mb = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !(mb > 0.0) || !(mb < 1e12))
    throw std::invalid_argument(std::string(memory_limit_variable) + " = \"" + text +
                                "\" is not a memory limit: expected a positive number of MB (e.g. 8000), or unset it");
  return static_cast<std::uint64_t>(mb * 1e6);
}

std::optional<std::uint64_t> available_memory_bytes() {
  std::optional<std::uint64_t> available;
  if (std::ifstream in("/proc/meminfo"); in) {
    std::ostringstream text;
    text << in.rdbuf();
    available = parse_mem_available(text.str());
  }
  const std::optional<std::uint64_t> limit = memory_limit_bytes(std::getenv(memory_limit_variable));
  if (limit && (!available || *limit < *available)) return limit;
  return available;
}

void check_memory_need(const std::string& what, double need_bytes, const std::string& basis, const std::string& way_out,
                       std::optional<std::uint64_t> available) {
  if (!available || !(need_bytes > static_cast<double>(*available))) return;
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(0);
  text << what << " needs about " << std::ceil(need_bytes / 1e6) << " MB (" << basis << ") but this machine has "
       << std::floor(static_cast<double>(*available) / 1e6) << " MB available (MemAvailable in /proc/meminfo): " << way_out;
  throw MemoryShortage(text.str());
}

}  // namespace hydrojump::util
