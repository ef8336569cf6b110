#include "app/stage_info.hpp"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>

#include <toml++/toml.h>

#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"
#include "util/number_text.hpp"

namespace fs = std::filesystem;

namespace hydrojump::app {

namespace {

// The first line of `text` if `first`, else its last non-empty line; control characters dropped.
std::string one_line(const std::string& text, bool first) {
  std::istringstream in(text);
  std::string picked;
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    picked = line;
    if (first) break;
  }
  std::string out;
  for (char ch : picked)
    if (static_cast<unsigned char>(ch) >= 0x20) out += ch;
  const auto end = out.find_last_not_of(' ');
  return end == std::string::npos ? std::string() : out.substr(0, end + 1);
}

}  // namespace

std::string machine_text() {
  std::ifstream in("/proc/cpuinfo");
  std::string model = "unknown CPU";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto start = line.find_first_not_of(" \t", line.find(':') == std::string::npos ? line.size() : line.find(':') + 1);
    if (start != std::string::npos) model = line.substr(start);  // "model name\t:" alone keeps "unknown CPU"
    break;
  }
  std::string clean;
  for (char ch : model)
    if (ch != '"' && ch != '\\' && static_cast<unsigned char>(ch) >= 0x20) clean += ch;
  return clean + ", " + std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " cores";
}

std::pair<double, int> earlier_legs(const fs::path& dir, const std::string& stage) {
  std::istringstream in(util::read_text_file(dir / (stage + ".legs")));
  double seconds = 0.0;
  int legs = 0;
  if (!(in >> seconds >> legs) || !(seconds >= 0.0) || legs < 0) return {0.0, 0};
  return {seconds, legs};
}

void add_leg(const fs::path& dir, const std::string& stage, double seconds) {
  const auto [before, legs] = earlier_legs(dir, stage);
  util::write_file_atomically(dir / (stage + ".legs"), util::number_text(before + seconds) + " " + std::to_string(legs + 1) + "\n");
}

void write_stage_info(const fs::path& dir, const std::string& stage, double seconds, int threads) {
  const auto [before, legs] = earlier_legs(dir, stage);
  const double total = before + seconds;
  std::ostringstream text;  // fixed notation: always a TOML float
  text << "# all legs of this stage (a run stopped and resumed counts each leg)\nwall_time_s = " << std::fixed
       << std::setprecision(3) << total << "\nlegs = " << legs + 1 << "\nthreads = " << threads << "\nmachine = \""
       << machine_text() << "\"\n";
  util::write_file_atomically(dir / (stage + ".stage.toml"), text.str());
  fs::remove(dir / (stage + ".legs"));
}

fs::file_time_type leg_start_time(const fs::path& marker) {
  std::error_code ec;  // an empty path is a missing file too
  const auto written = fs::last_write_time(marker, ec);
  return ec ? fs::file_time_type::clock::now() : written;
}

std::string failure_text(const fs::path& dir, const std::string& stage, const fs::path& log_file, int exit_status,
                         fs::file_time_type leg_start) {
  const fs::path diagnosis = dir / stage / "failure.txt";
  std::error_code ec;
  const auto written = fs::last_write_time(diagnosis, ec);
  if (!ec && written >= leg_start) {
    const std::string line = one_line(util::read_text_file(diagnosis), true);
    if (!line.empty()) return line;
  }
  const std::string last = one_line(util::read_text_file(log_file), false);
  return "exit status " + std::to_string(exit_status) + (last.empty() ? std::string(", nothing logged") : ": " + last);
}

void write_stage_failure(const fs::path& dir, const std::string& stage, const std::string& run_key,
                         const std::string& failure, int threads) {
  const auto [seconds, legs] = earlier_legs(dir, stage);
  toml::table t;
  t.insert("run_key", run_key);
  t.insert("failure", failure);
  t.insert("wall_time_s", seconds);
  t.insert("legs", std::max(1, legs));
  t.insert("threads", threads);
  t.insert("machine", machine_text());
  std::ostringstream text;
  text << "# the stage failed (its legs so far); `hydrojump record` keeps it as a record of a failed run\n" << t << "\n";
  util::write_file_atomically(dir / (stage + ".failed"), text.str());
}

}  // namespace hydrojump::app
