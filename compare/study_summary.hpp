// Study-level summary across case directories compared by `hydrojump compare`: the eta table
// (smooth-bed theory, experiment, published SPH, this SPH, this VOF, with the differences) and the
// sequent depth / jump length table, read back from each DIR/csv/eta.csv and DIR/csv/metrics.csv.
// For the study runner's report; cases without a finished comparison are listed as missing.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hydrojump::compare {

struct StudySummary {
  std::string markdown;       // the two tables, ready to paste into the study report
  std::string eta_csv;        // one row per case (the columns of csv/eta.csv)
  std::vector<std::filesystem::path> eta_files;   // the csv/eta.csv files found (for plot_eta_bars)
};

// `cases`: (case id, case directory) pairs in report order.
StudySummary summarize_study(const std::vector<std::pair<std::string, std::filesystem::path>>& cases);

}  // namespace hydrojump::compare
