#include "reference/discharge_samples.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "util/time_directories.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

std::vector<std::pair<double, double>> read_surface_field_value(const fs::path& function_dir,
                                                               const std::string& file_name) {
  std::vector<std::pair<double, double>> rows;
  // Appends the rows of `file`, which replace those from its first row's time on.
  const auto read_rows_of = [&rows](const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file.string() + ": cannot be read");
    std::string line;
    int line_number = 0;
    bool first = true;
    while (std::getline(in, line)) {
      ++line_number;
      if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
      std::istringstream ss(line);
      double t = 0.0, value = 0.0;
      if (!(ss >> t >> value)) {
        throw std::runtime_error(file.string() + ":" + std::to_string(line_number) +
                                 ": expected a time and a value, got \"" + line + "\"");
      }
      if (first) {
        while (!rows.empty() && rows.back().first >= t - 1e-12) rows.pop_back();
        first = false;
      }
      rows.emplace_back(t, value);
    }
  };
  const std::string stem = fs::path(file_name).stem().string(), extension = fs::path(file_name).extension().string();
  for (const auto& [start, dir] : util::time_directories(function_dir)) {
    const fs::path file = dir / file_name;
    if (!fs::exists(file)) continue;
    while (!rows.empty() && rows.back().first >= start - 1e-12) rows.pop_back();
    read_rows_of(file);
    // A run started again from the same time (a leg retried after a crash or a kill before its first
    // output) finds the file there and writes `<stem>_<start time>.dat` beside it (OpenFOAM's
    // writeFile::createFile); a third attempt overwrites that one. Its rows are the latest: the first
    // file's rows after the start time belong to an abandoned attempt, even those the retry has not
    // reached yet.
    std::vector<fs::path> retries;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.size() > stem.size() + 1 + extension.size() && name.rfind(stem + "_", 0) == 0 &&
          entry.path().extension() == extension)
        retries.push_back(entry.path());
    }
    if (retries.empty()) continue;
    while (!rows.empty() && rows.back().first > start + 1e-12) rows.pop_back();
    std::sort(retries.begin(), retries.end());
    for (const fs::path& retry : retries) read_rows_of(retry);
  }
  return rows;
}

std::optional<double> surface_field_value_mean(const fs::path& function_dir, double t0, double t1) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const auto& [t, value] : read_surface_field_value(function_dir)) {
    if (t < t0 - 1e-9 || t > t1 + 1e-9) continue;
    sum += value;
    ++count;
  }
  if (count == 0) return std::nullopt;
  return sum / static_cast<double>(count);
}

std::optional<PatchDischarges> patch_discharges(const fs::path& case_dir, double t0, double t1, double thickness_m) {
  if (!(thickness_m > 0.0)) return std::nullopt;
  const fs::path post = case_dir / "postProcessing";
  const auto inlet = surface_field_value_mean(post / "discharge_inlet", t0, t1);
  const auto outlet = surface_field_value_mean(post / "discharge_outlet", t0, t1);
  if (!inlet || !outlet) return std::nullopt;
  const auto top = surface_field_value_mean(post / "discharge_atmosphere", t0, t1);
  PatchDischarges q;
  q.inflow_m2_s = -*inlet / thickness_m;
  q.outflow_m2_s = *outlet / thickness_m;
  q.top_outflow_m2_s = top ? *top / thickness_m : 0.0;
  q.top_sampled = top.has_value();
  return q;
}

}  // namespace hydrojump::reference
