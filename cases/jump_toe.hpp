// The jump toe: one definition for every method (the SPH run monitor, the comparator).
//
// Given the free-surface elevation zeta(x) above the upstream floor (= corrugation crest) level at
// uniformly spaced stations x_0 < x_1 < ..., the toe is the first station x_i >= x_from where the
// running mean of zeta over a centred window of `window_y1` y1 exceeds `threshold_y1` y1 and stays
// above it over the following `persistence_y1` y1:
//
//   x_toe = min { x_i >= x_from : zbar(x_k) > threshold_y1 y1  for all x_k in [x_i, x_i + persistence_y1 y1] }
//
// A bare "first x above 1.5 y1" trips on splashes and air pockets in the roller; the running mean
// (about 2 cm for y1 = 25.4 mm) with a persistence of about 5 cm was stable in trial interFoam runs
// (shared/reference/study-notes.md, section 5).
//
// Usage
//   | field           | default | meaning                                      |
//   |-----------------|---------|----------------------------------------------|
//   | threshold_y1    | 1.5     | surface rise that marks the jump, in y1      |
//   | window_y1       | 0.8     | running-mean window, in y1                   |
//   | persistence_y1  | 2.0     | how far the rise must persist, in y1         |
// Example:
//   const std::size_t i = cases::find_jump_toe(x, zeta, x_upstream, y1, cases::ToeCriterion{});
//   if (i < x.size()) toe_x = x[i];
//
// Steadiness of a jump over a window, one rule for the SPH run monitor and the comparator:
//
//   steady  <=>  |mean q_out - mean q_in| / q < steady_discharge_tolerance   (2 %; the basin neither
//                                                                            fills nor drains)
//           and  |d x_toe / dt| * steady_span_s < toe_drift_tolerance_m      (the toe's least-squares
//                                                                            trend moves it less than
//                                                                            a bed wavelength, or 2 y1
//                                                                            on a smooth bed, per second)
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cases/options.hpp"

namespace hydrojump::cases {

struct ToeCriterion {
  double threshold_y1 = 1.5;
  double window_y1 = 0.8;
  double persistence_y1 = 2.0;
};

// Running mean of `v` over a centred window of `half_width` samples each side (NaNs skipped; NaN
// where the window holds no finite value).
std::vector<double> running_mean(const std::vector<double>& v, int half_width);

// Index of the toe station, or x.size() if there is none (see above). `x` uniformly spaced.
std::size_t find_jump_toe(const std::vector<double>& x, const std::vector<double>& zeta, double x_from, double y1,
                          const ToeCriterion& criterion);

inline constexpr double steady_discharge_tolerance = 0.02;  // |q_out - q_in| / q
inline constexpr double steady_span_s = 1.0;                // the drift is measured over this time

// The toe drift allowed per steady_span_s: the bed wavelength on a corrugated bed, 2 y1 on a smooth one
// (bed_profile "smooth").
double toe_drift_tolerance_m(BedShape bed_profile, double wavelength_m, double inflow_depth_m);

// The rule above on a window's means: |outflow_minus_inflow_over_q| < steady_discharge_tolerance and
// |toe_trend_m_per_s| * steady_span_s < toe_drift_tolerance_m (false when either input is NaN).
bool steady_by_means(double outflow_minus_inflow_over_q, double toe_trend_m_per_s, double toe_drift_tolerance_m);

// A basin's water balance and toe trend over the outputs t_k in [t0, t1] of a run monitor's time series
// (the SPH run's basin.csv: q_in_k, q_out_k are the discharges over the interval (t_{k-1}, t_k]); an
// output within `time_tolerance_s` of the window is in it (cases/output_times.hpp: outputs come late):
//
//   outflow - inflow = sum_k (q_out_k - q_in_k) (t_k - t_{k-1}) / (q (t_last - t_first))
//                      over the outputs t_first < t_k <= t_last, t_first and t_last the first and the
//                      last output in [t0, t1]                       (> 0: the basin drains)
//   toe trend        = least_squares_slope over the outputs in [t0, t1] with a toe
//
// the same as the monitor's mass totals (mass_out - mass_in between t_first and t_last, divided by
// rho0 q (t_last - t_first)). NaN for a window with fewer than two outputs or with a discharge missing
// (NaN) after its first output. Outputs at a time not after the previous one are skipped.
struct WindowBalance {
  double outflow_minus_inflow_over_q = 0.0;
  double toe_trend_m_per_s = 0.0;
  std::size_t outputs = 0;       // outputs in [t0, t1]
  std::size_t toe_missing = 0;   // of them, outputs without a toe
  double first_output_s = 0.0, last_output_s = 0.0;
  bool reaches_window_end = false;  // the series has an output at t >= t1 - tolerance (the window is complete)
};
WindowBalance window_balance(const std::vector<double>& t, const std::vector<double>& q_in,
                             const std::vector<double>& q_out, const std::vector<double>& toe_x, double t0,
                             double t1, double time_tolerance_s, double q);

// Least-squares slope dy/dt over the pairs with finite y (NaN with fewer than 3 of them):
//   slope = sum (t_k - t_mean)(y_k - y_mean) / sum (t_k - t_mean)^2
double least_squares_slope(const std::vector<double>& t, const std::vector<double>& y);

}  // namespace hydrojump::cases
