#include "cases/results_case.hpp"

#include <algorithm>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"
#include "util/time_directories.hpp"

namespace fs = std::filesystem;

namespace hydrojump::cases {

namespace {

// Whether `line` assigns one of `keys` (`key = ...`, any spacing).
bool assigns_one_of(std::string_view line, std::initializer_list<std::string_view> keys) {
  const auto start = line.find_first_not_of(" \t");
  if (start == std::string_view::npos) return false;
  const std::string_view body = line.substr(start);
  for (const std::string_view key : keys) {
    if (body.rfind(key, 0) != 0) continue;
    const auto next = body.find_first_not_of(" \t", key.size());
    if (next != std::string_view::npos && body[next] == '=') return true;
  }
  return false;
}

// A line of a case file as it may be quoted in a message: bytes outside printable ASCII as \xNN (a
// damaged file must not put raw binary on the terminal), at most 120 characters.
std::string quotable(std::string_view line) {
  std::string out;
  for (const char ch : line) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte >= 0x20 && byte < 0x7f) {
      out += ch;
    } else {
      static const char* const hex = "0123456789abcdef";
      out += "\\x";
      out += hex[byte >> 4];
      out += hex[byte & 0xf];
    }
    if (out.size() > 120) return out.substr(0, 120) + "...";
  }
  return out;
}

}  // namespace

bool is_run_control_line(std::string_view line) {
  return assigns_one_of(line, {"max_density_variation", "checkpoint_interval_wall_s"});
}

bool is_descriptive_line(std::string_view line) {
  return assigns_one_of(line, {"description", "citations", "source", "note"});
}

bool is_laboratory_comparison_line(std::string_view line) {
  return assigns_one_of(line, {"eta_percent", "eta_smooth_percent", "published_sph_eta_percent", "roller_length_m",
                               "jump_length_m", "front_file"});
}

namespace {

// A table header line ("[case.measured]", "[[case]]") without its surrounding blanks; nothing for any
// other line.
std::optional<std::string> table_header(const std::string& line) {
  const auto start = line.find_first_not_of(" \t");
  if (start == std::string::npos || line[start] != '[') return std::nullopt;
  const auto end = line.find_last_not_of(" \t\r");
  return line.substr(start, end + 1 - start);
}

}  // namespace

std::vector<std::string> setting_lines(std::string_view case_text) {
  std::istringstream in{std::string(case_text)};
  std::vector<std::string> lines;
  bool in_measurements = false;  // inside [case.measured]
  for (std::string line; std::getline(in, line);) {
    const auto start = line.find_first_not_of(" \t");
    if (start != std::string::npos && line[start] == '#') continue;
    if (const auto header = table_header(line)) in_measurements = *header == "[case.measured]";
    // The measurements the results are only compared with; sequent_depth_m (which the SPH run monitor
    // reports against) stays a setting.
    if (in_measurements && is_laboratory_comparison_line(line)) continue;
    if (is_run_control_line(line) || is_descriptive_line(line)) continue;
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> method_setting_lines(std::string_view case_text, std::string_view method) {
  if (method != "sph" && method != "vof")
    throw std::invalid_argument("method_setting_lines: unknown method \"" + std::string(method) + "\" (sph, vof)");
  const std::string other = method == "sph" ? "[vof]" : "[sph]";
  std::vector<std::string> kept;
  bool in_other = false;  // inside the other method's table
  for (std::string& line : setting_lines(case_text)) {
    if (const auto header = table_header(line)) in_other = *header == other;
    if (!in_other) kept.push_back(std::move(line));
  }
  return kept;
}

SettingDifference first_setting_difference(std::string_view case_text_a, std::string_view case_text_b) {
  const auto la = setting_lines(case_text_a), lb = setting_lines(case_text_b);
  for (std::size_t k = 0; k < std::max(la.size(), lb.size()); ++k) {
    const std::string x = k < la.size() ? la[k] : "(end)", y = k < lb.size() ? lb[k] : "(end)";
    if (x != y) return {x, y};
  }
  return {};
}

bool holds_results(const fs::path& solver_dir) {
  for (const char* name : {"checkpoint.bin", "particles.pvd", "summary.json", "log.interFoam"})
    if (fs::exists(solver_dir / name)) return true;
  // An OpenFOAM run without its log (interFoam run by hand): its time directories, serial or decomposed.
  return !util::time_directories(solver_dir, 0.0).empty() || !util::time_directories(solver_dir / "processor0", 0.0).empty();
}

void record_results_case(const fs::path& solver_dir) {
  const fs::path case_toml = solver_dir / "case.toml";
  const std::string text = util::read_text_file(case_toml);
  if (text.empty()) throw std::runtime_error("cannot read " + case_toml.string());
  util::write_file_atomically(solver_dir / results_case_file_name, text);
}

fs::path recorded_case_file(const fs::path& solver_dir) {
  return fs::exists(solver_dir / results_case_file_name) ? solver_dir / results_case_file_name : solver_dir / "case.toml";
}

void require_results_of(const fs::path& solver_dir, const fs::path& case_toml) {
  if (!holds_results(solver_dir)) return;
  const fs::path recorded = recorded_case_file(solver_dir);
  if (!fs::exists(recorded))
    throw std::runtime_error(solver_dir.string() + " holds the results of a run but no case.toml: they cannot be "
                             "told apart from another case's (move the directory away, or generate the case again "
                             "and rerun it)");
  std::error_code ec;
  const std::string recorded_text = fs::is_regular_file(recorded, ec) ? util::read_text_file(recorded) : std::string();
  if (recorded_text.empty())
    throw std::runtime_error(recorded.string() + " is empty or not a readable file, so the results in " + solver_dir.string() +
                             " cannot be told apart from another case's (restore it, or generate the case again and rerun it)");
  const std::string case_text = fs::is_regular_file(case_toml, ec) ? util::read_text_file(case_toml) : std::string();
  if (case_text.empty())
    throw std::runtime_error(case_toml.string() + " is empty or not a readable file, so the results in " +
                             solver_dir.string() + " cannot be checked against it (restore it, or generate the case again)");
  const auto d = first_setting_difference(recorded_text, case_text);
  if (!d.any()) return;
  throw std::runtime_error(solver_dir.string() + " holds results made with other settings than " + case_toml.string() +
                           ": " + recorded.filename().string() + " has '" + quotable(d.a) + "' where " + case_toml.string() +
                           " has '" + quotable(d.b) + "' (generate the case again and rerun it, or restore the case.toml)");
}

}  // namespace hydrojump::cases
