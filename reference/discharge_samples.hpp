// The water discharge through the patches of a generated stilling basin, read from what its
// `surfaceFieldValue` function objects wrote (case_writer.hpp): discharge_inlet, discharge_outlet and
// discharge_atmosphere, each the sum of alphaPhi0.water over the patch, in m^3/s through the
// one-cell-thick 2D mesh. OpenFOAM's boundary face fluxes point out of the domain, so
//
//   q_in  = -<inlet flux> / thickness      q_out = <outlet flux> / thickness
//   q_top =  <atmosphere flux> / thickness (water lost through the lid)            in m^2/s,
//
// <.> the mean of the rows in a time window. Used by the runner's progress lines and by the
// comparator's water-balance note (compare/case_comparison.hpp).
//
// Usage
//   | function                    | returns                                                    |
//   |-----------------------------|------------------------------------------------------------|
//   | read_surface_field_value    | (t, first column) rows across the run's start-time dirs    |
//   | surface_field_value_mean    | their mean over a time window; nullopt without rows        |
//   | patch_discharges            | window means of q_in, q_out, q_top; nullopt without rows   |
// Example:
//   if (auto q = reference::patch_discharges(dir, t - 1.0, t, plan.thickness_m))
//     std::cout << q->outflow_m2_s / q->inflow_m2_s;
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace hydrojump::reference {

// One column of an OpenFOAM `surfaceFieldValue` function object over time: the rows (t, value of the
// first field) of every `<function_dir>/<start time>/surfaceFieldValue.dat`. A resumed run starts a
// new start-time directory; its rows replace the earlier directory's rows from that start time on. A run
// started again from the same time writes `<stem>_<start time>.dat` beside the first file: its rows
// replace the first file's from its first row's time on.
// Empty when the directory does not exist (cases written before the function object was added).
// Throws naming the file and line on a row that is not two or more numbers. A `volFieldValue` function
// object's rows are read the same way with file_name "volFieldValue.dat".
std::vector<std::pair<double, double>> read_surface_field_value(const std::filesystem::path& function_dir,
                                                               const std::string& file_name = "surfaceFieldValue.dat");

// Mean of that column over [t0, t1]; nullopt without a row in the window.
std::optional<double> surface_field_value_mean(const std::filesystem::path& function_dir, double t0, double t1);

struct PatchDischarges {
  double inflow_m2_s = 0.0;       // q_in
  double outflow_m2_s = 0.0;      // q_out
  double top_outflow_m2_s = 0.0;  // q_top (0 when not sampled)
  bool top_sampled = false;       // discharge_atmosphere has rows in the window
};

// Means over [t0, t1] of CASE_DIR/postProcessing/discharge_{inlet,outlet,atmosphere}; nullopt when the
// inlet or the outlet has no row in the window or thickness_m is not positive.
std::optional<PatchDischarges> patch_discharges(const std::filesystem::path& case_dir, double t0, double t1,
                                                double thickness_m);

}  // namespace hydrojump::reference
