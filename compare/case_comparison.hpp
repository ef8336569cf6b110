// Comparing one case directory: `compare_case_directory(RUN_DIR)` reads RUN_DIR/sph (a .pvd particle
// series) and RUN_DIR/vof (an OpenFOAM case) over the case's averaging window, samples both on the
// case's sections and on a line of stations along the channel, computes the jump metrics of each, the
// discrepancies between them and against the laboratory values, and writes the report (report.hpp).
// This is the one call a study runner needs per case; a missing method is reported, not fatal.
//
// The case comes from RUN_DIR/sph/case.toml (or RUN_DIR/vof/case.toml), the resolved one-case spec
// written by `hydrojump generate`; the geometry (bed, sections, domain) from cases::make_geometry.
#pragma once

#include <filesystem>
#include <limits>
#include <iosfwd>
#include <optional>
#include <string>

#include "cases/spec.hpp"
#include "compare/discrepancy.hpp"
#include "compare/jump_metrics.hpp"
#include "compare/point_cloud.hpp"
#include "compare/time_statistics.hpp"

namespace hydrojump::compare {

struct CompareOptions {
  std::filesystem::path out_dir;                 // empty: RUN_DIR
  InterpolationScheme scheme = InterpolationScheme::mls_linear;
  std::optional<double> window_start_s, window_end_s;  // override the case's averaging window
  bool plots = true;
  int section_points = 41;                       // profile points per section (odd)
  int station_points = 21;                       // profile points per station (odd)
  double station_spacing_m = 0.0;                // 0: the finer of SPH dx and the VOF bed cell size
  JumpMetricOptions metrics;
  std::filesystem::path sph_pvd;                 // empty: the .pvd found under RUN_DIR/sph
};

struct MethodOutcome {
  std::string method;                            // "sph" | "vof"
  bool available = false;
  std::string status;                            // "ok", or why the result is missing
  std::string source;                            // the file or directory read
  MethodStatistics stats;
  JumpMetrics metrics;
};

struct CaseComparison {
  std::string case_id, description, resolution;
  double inflow_depth_m = 0.0, inflow_velocity_m_s = 0.0, tailwater_depth_m = 0.0, gravity_m_s2 = 9.81;
  std::string tailwater_control;                 // the case's [case.tailwater] control
  double floor_z_m = 0.0, basin_start_m = 0.0, basin_end_m = 0.0;
  double bed_wavelength_m = 0.0;                 // 0 for a smooth bed
  double window_start_s = 0.0, window_end_s = 0.0;
  double belanger_y2_m = 0.0, eta_smooth_theory_percent = 0.0;
  double particle_spacing_m = 0.0, vof_cell_size_m = 0.0;
  std::string interpolation;
  std::string measured_source;
  std::string measured_note;                     // [case.measured] note: what is known about the values
  MeasuredReference lab;
  std::vector<ColumnSpec> sections;
  MethodOutcome sph, vof;
  // Set by compare_case_directory: why the figures were not made (empty when they were, or with --no-plots).
  std::string figures_problem;
  SurfaceDifference surface;
  std::vector<ProfileDifference> profiles;
  std::vector<MetricRow> metrics;
};

// Reads the one-case spec in RUN_DIR/sph/case.toml or RUN_DIR/vof/case.toml. Throws naming both paths,
// or when a method's results were made with other settings (cases/results_case.hpp).
cases::Study load_run_case(const std::filesystem::path& run_dir);

// Everything except writing: samples both methods and computes metrics and discrepancies.
CaseComparison compare_case(const cases::Study& study, const std::filesystem::path& run_dir,
                            const CompareOptions& options, std::ostream& log);

// The console summary of a comparison: per method with results, the toe (frames' mean, sd, trend), y2,
// eta and Lj with the experiment's values in brackets, then the method's notes, e.g.
//   vof: toe 0.627 +- 0.015 m (predicted) (trend +0.0128 m/s), y2 0.0972 m (imposed) [0.104] {y2* 0.132,
//        y2/y2* 0.736}, eta 44.02 % (imposed) [48.43], Lj 0.3825 m (predicted) [0.41]
//   (under control = "hold_toe" the toe is imposed and y2, eta predicted; {} holds the inputs-only values)
//   vof: water balance over the window (...): ...; NOT steady by the window means (...)
std::string summary_text(const CaseComparison& c);

// compare_case, then write_report into options.out_dir (default RUN_DIR), then summary_text into `log`.
// Returns the comparison.
CaseComparison compare_case_directory(const std::filesystem::path& run_dir, const CompareOptions& options,
                                      std::ostream& log);

// A note when water leaves the VOF domain through its top (the `atmosphere` patch; function object
// `discharge_atmosphere`, sum of alphaPhi0.water over the patch) at a mean rate above
// top_outflow_note_fraction of the inflow q over the window [t0, t1]; thickness_m is the one-cell span
// of the 2D mesh. Empty below that, or when the case has no such samples (written by an older hydrojump).
inline constexpr double top_outflow_note_fraction = 0.01;
std::string vof_top_outflow_note(const std::filesystem::path& vof_dir, double t0, double t1,
                                 double inflow_q_m2_s, double thickness_m);

// A note when the VOF run's tailwater was set by the tailgate control (`tailwater_control = "hold_toe"`,
// reference/tailwater_control.hpp): from the control steps in [t0, t1] of vof_dir/tailwater_control.csv,
// the range and mean of the outlet's Umean and the mean of the legs' toes, and what that means for y2
// (the depth the held jump needed, not the prescribed y2*). Empty without a log or without a step in the
// window.
std::string vof_tailwater_control_note(const std::filesystem::path& vof_dir, double t0, double t1);

// One line on the VOF run's water balance and steadiness over the window [t0, t1], the counterpart of
// the SPH run monitor's verdict (sph_run_note) with the same rule (cases/jump_toe.hpp):
//   q_in  = -<sum alphaPhi0.water on the inlet> / thickness     (function object discharge_inlet;
//   q_out =  <... on the outlet> / thickness                     OpenFOAM's face fluxes point out of
//   q_top =  <... on the atmosphere> / thickness                 the domain), means over the rows in
//                                                               the window
//   outflow - inflow = (q_out + q_top - q_in) / q               (> 0: the basin drains)
//   steady by the window means <=> |outflow - inflow| < steady_discharge_tolerance and
//                                   |toe_trend| * steady_span_s < toe_drift_tolerance_m
// Empty when the case has no inlet and outlet samples in the window.
struct VofRunNoteInputs {
  std::filesystem::path vof_dir;
  double window_start_s = 0.0, window_end_s = 0.0;
  double inflow_q_m2_s = 0.0;
  double thickness_m = 0.0;            // the one-cell span of the 2D mesh
  double toe_trend_m_per_s = 0.0;      // NaN: no trend (too few frames with a toe)
  double toe_drift_tolerance_m = 0.0;  // cases::toe_drift_tolerance_m
  // As the SPH monitor's rule (cases::window_balance): not steady with a frame without a toe, or
  // when the run has not reached the window's end.
  int frames = 0;                      // frames in the window
  int frames_without_toe = 0;
  bool reaches_window_end = true;
};
// The numbers behind a run note's verdict: (outflow - inflow) / q over the window and whether the run is
// steady by the window means (unset where the note could not judge).
struct RunBalance {
  double imbalance = std::numeric_limits<double>::quiet_NaN();
  std::optional<bool> steady;
};

std::string vof_run_note(const VofRunNoteInputs& in, RunBalance* balance = nullptr);

// One line on the SPH run's own verdict from its summary.json (jump state, steady or not, inflow
// discharge error, over the run's averaging window, which the line names); when the comparison's
// window [window_start_s, window_end_s] is another one, the line says that its verdicts are not for it
// and gives the water balance and toe trend over the comparison's window from the run's basin.csv
// beside summary.json (cases::window_balance, the monitor's own rule), steady by the window means or not.
// Empty when the file is absent; a file that cannot be read or has no jump_state gives a line saying
// that the verdict is not shown, and values that are not numbers are named and left out (a damaged
// file is reported, never silently dropped, and never ends the comparison); so are basin.csv's damaged
// rows (other than a torn last line, which a running run writes). window_end_s <= window_start_s: no
// comparison window.
// basin.csv's outputs within time_tolerance_s of the window are in it (cases/output_times.hpp).
// `balance`, when given, gets the verdict's numbers (for the comparison's window).
std::string sph_run_note(const std::filesystem::path& summary_file, double window_start_s = 0.0,
                         double window_end_s = 0.0, double time_tolerance_s = 1e-9, RunBalance* balance = nullptr);

}  // namespace hydrojump::compare
