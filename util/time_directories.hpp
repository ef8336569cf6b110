// OpenFOAM's time directories: the subdirectories of a case (or of a processor directory, or of a
// function object's postProcessing/<name>/) whose names are times, "0", "0.05", "1e-05", "12.5".
// The one place that reads such names; the OpenFOAM runner, the sample readers, `compare` and the
// results check all list them here.
//
//   | function           | gives                                                           |
//   |--------------------|-----------------------------------------------------------------|
//   | parse_time_name    | the time a directory name stands for, or nothing                |
//   | time_directories   | the number-named subdirectories, sorted by time                 |
// Example:
//   for (const auto& [t, dir] : time_directories(case_dir, 0.0)) ...   // the times after t = 0
#pragma once

#include <filesystem>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace hydrojump::util {

struct TimeDirectory {
  double time_s;
  std::filesystem::path path;
};

// The time `name` stands for: a finite decimal number in OpenFOAM's time-name syntax (digits, a
// point, an exponent; no sign, no blanks, no "nan" or "inf"), nothing otherwise ("0.orig",
// "0.05.incomplete", "processor0", "-1").
std::optional<double> parse_time_name(std::string_view name);

// The subdirectories of `dir` named by a time later than `after_s` (all of them by default), sorted
// by time; none when `dir` is missing or unreadable.
std::vector<TimeDirectory> time_directories(const std::filesystem::path& dir,
                                            double after_s = -std::numeric_limits<double>::infinity());

}  // namespace hydrojump::util
