// Which outputs of a run lie in a time window.
//
// The SPH solver writes an output at the first time step that reaches its nominal time, so an output
// may come up to one time step late (the output of 20 s at 20.0000068 s; interFoam shortens its step to
// land on its write times). A window [t0, t1] therefore accepts an output within a tolerance of its bounds:
//
//   t0 - tolerance <= t <= t1 + tolerance,   tolerance = 1 % of the output interval
//
// far more than a time step (1e-5 to 1e-3 s) and far less than the spacing of two outputs, so a late
// output counts for its nominal time and never the neighbouring output for it. Without the tolerance a
// window [16, 20] s lost its last output, and the SPH monitor's mean discharges took in the interval
// before 16 s.
//
// Usage
//   | function                | returns                                                           |
//   |-------------------------|-------------------------------------------------------------------|
//   | output_time_tolerance_s | 1 % of the output interval (1e-9 s if the interval is unknown, 0) |
//   | in_output_window        | whether an output at t belongs to the window [t0, t1]             |
//   | outputs_in_window       | how many output times k dt (k >= 1) the window holds               |
// Example:
//   const double tol = cases::output_time_tolerance_s(c.run.output_interval_s);
//   for (double t : times) if (cases::in_output_window(t, 16.0, 20.0, tol)) use(t);
#pragma once

#include <algorithm>
#include <cmath>

namespace hydrojump::cases {

inline double output_time_tolerance_s(double output_interval_s) {
  return std::max(1e-9, 0.01 * output_interval_s);
}

inline bool in_output_window(double t, double t0, double t1, double tolerance_s) {
  return t >= t0 - tolerance_s && t <= t1 + tolerance_s;
}

// The output times k dt (k = 1, 2, ...) in [t0, t1], with the tolerance above; the initial state
// (k = 0) is not one (OpenFOAM's results start after it). A time mean needs two.
inline long outputs_in_window(double t0, double t1, double output_interval_s) {
  if (!(output_interval_s > 0.0) || !(t1 >= t0)) return 0;
  const double eps = 0.01;  // the tolerance, in output intervals
  const double first = std::max(1.0, std::ceil(t0 / output_interval_s - eps));
  const double last = std::floor(t1 / output_interval_s + eps);
  // Counted in double and capped, so that a window of 1e18 s is not an overflow (a negative count).
  return last >= first ? static_cast<long>(std::min(last - first + 1.0, 1e15)) : 0;
}

}  // namespace hydrojump::cases
