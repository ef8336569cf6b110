// Outputs of one case comparison, all written atomically (util/atomic_file.hpp) into OUT:
//   comparison.json            every number of the comparison (NaN/missing as null)
//   csv/sections.csv           per method and section: time means and standard deviations
//   csv/section_timeseries.csv per method, section and output time: surface, depth, q, U, u_max, E
//   csv/profiles.csv           per method and section: time-mean u(z), w(z), wet fraction
//   csv/longitudinal.csv       per method and station: mean surface, near-surface/mean/max velocity
//                              (means over the frames in which the station is wet: n_times, n_wet)
//   csv/metrics.csv            y2, Lj, Lr, eta, ... SPH, VOF, experiment, published SPH side by side
//   csv/profile_differences.csv, csv/eta.csv (one row: this case's eta bars), csv/case.csv (inputs),
//   csv/snapshot_<method>.csv  the velocity field of the last frame in the window
//   figures/*.png              from compare/plot/plot_case.py (reads the CSVs only)
//   report.md, report.html     the human-readable report (HTML with the figures embedded, base64)
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

#include "compare/case_comparison.hpp"

namespace hydrojump::compare {

// Writes out_dir/{csv/, figures/ (when `plots`), comparison.json, report.md, report.html}. Returns why
// the figures could not be made (the plot script's failure, its log named), empty when they were or
// when none were asked for; the report says so too.
std::string write_report(const CaseComparison& c, const std::filesystem::path& out_dir, bool plots, std::ostream& log);

// Pieces exposed for tests.
std::string comparison_json(const CaseComparison& c);
std::string base64_encode(const std::string& bytes);

}  // namespace hydrojump::compare
