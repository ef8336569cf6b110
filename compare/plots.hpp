// Running the matplotlib scripts of compare/plot/ (they read the CSVs only) with /usr/bin/python3.
//
// Where the scripts are found, first match wins:
//   1. $HYDROJUMP_PLOT_DIR
//   2. the source tree's compare/plot (compile definition HYDROJUMP_PLOT_SCRIPT_DIR), if it exists
//   3. <directory of the executable>/../share/hydrojump/plot (the install layout, see CMakeLists.txt)
//   4. <directory of the executable>/plot
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace hydrojump::compare {

// The plot-script directory; throws std::runtime_error listing every place tried.
std::filesystem::path plot_script_dir();

// Runs /usr/bin/python3 SCRIPT ARGS... with stdout and stderr appended to `log_file`. Returns "" on
// success, else a one-line reason (python missing, non-zero exit with the log's last line, ...).
std::string run_plot_script(const std::string& script, const std::vector<std::string>& args,
                            const std::filesystem::path& log_file);

// Per-case figures from CSV_DIR into FIG_DIR (plot_case.py). Returns "" or the reason it failed.
std::string plot_case_figures(const std::filesystem::path& csv_dir, const std::filesystem::path& fig_dir);

// eta bars across runs (smooth theory, experiment, published SPH, this SPH, this VOF) from the
// per-case csv/eta.csv files of a study; for the study runner. Returns "" or the reason it failed.
std::string plot_eta_bars(const std::vector<std::filesystem::path>& eta_csv_files, const std::filesystem::path& png,
                          const std::filesystem::path& log_file);

// The same for the case directories of a study: uses DIR/csv/eta.csv of each directory that has one
// (cases whose comparison failed are left out). Returns "" or the reason it failed.
std::string plot_study_eta_bars(const std::vector<std::filesystem::path>& case_dirs, const std::filesystem::path& png);

}  // namespace hydrojump::compare
