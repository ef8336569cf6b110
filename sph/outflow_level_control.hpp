// Outflow level control: holds the case's tailwater depth at the "downstream" section, where the
// laboratory measured it, instead of at the outlet.
//
// The outflow buffers (open_boundaries.hpp) hold their target depth y_t at the outlet. On a corrugated
// bed the flow keeps losing momentum to the bed beyond the jump, so the level falls towards the outlet:
// with y_t = y2 the depth at the downstream section (and the tailwater the jump sees) settles a few per
// cent above y2 (1.5-4.8 % in runs A, B, D and E at quick). In the flume Ead & Rajaratnam (2002)
// measured y2 at the end of the jump and set their tailgate by trial until the toe sat at the start of
// the corrugations. With sph.outflow_level_reference = "downstream_section" an integral controller
// moves the outlet's target depth until the section holds y2:
//
//   y_t(t_k) = clamp( y_t(t_{k-1}) - (dt_c / T_c) (h_s(t_k) - y2),  0.5 y2,  1.5 y2 ),   t_k = k dt_c
//
// with h_s the water depth at the downstream section, measured as the run monitor measures it (a
// column of width 2 dx, basin_monitor.hpp), y2 the case's tailwater depth, T_c the integral time
// (sph.outflow_level_time_s) and dt_c = 0.01 s. The outlet relaxes its level over
// tau ~ L / (U_t + sqrt(g y_t)) (L the subcritical reach, about 1 s for run A); the loop
// T_c s^2 tau + T_c s + 1 = 0 has the damping ratio 0.5 sqrt(T_c / tau), so T_c = 2 s (the default)
// gives about 0.7. The control instants are multiples of dt_c on the run's clock, and y_t is saved in
// checkpoints (SolverClock::outflow_target_depth), so a resumed run continues exactly.
//
// The downstream depth becomes an input: a run so controlled tests the toe, eta and the jump length,
// not y2 (summary.json records where the tailwater was held and the outlet's target depth over time).
//
// Usage
//   | key (section [sph])       | values / range                       | default  | meaning                      |
//   |---------------------------|--------------------------------------|----------|------------------------------|
//   | outflow_level_reference   | "outlet", "downstream_section"       | "outlet" | where y2 is held             |
//   | outflow_level_time_s      | (0, 100] s                           | 2.0      | T_c ("downstream_section")   |
// Only with outflow_condition = "absorbing" or "hydrostatic_level", and a case with a "downstream"
// section (stilling basins).
// Example (cases/*.toml):
//   [case.sph]
//   outflow_condition = "absorbing"
//   outflow_level_reference = "downstream_section"
//   outflow_level_time_s = 2.0
#pragma once

#include <optional>

#include "sph/particles.hpp"

namespace hydrojump::sph {

class OutflowLevelControl {
 public:
  static constexpr double control_interval_s = 0.01;  // dt_c

  // Holds `target_depth_m` (y2) at x = `section_x_m`, measured over a column of width `column_width_m`
  // (2 dx), with the integral time `time_constant_s`. Throws std::invalid_argument for non-positive
  // numbers.
  OutflowLevelControl(double section_x_m, double target_depth_m, double time_constant_s, double column_width_m);

  // Called after a step from t to t + dt with the outlet's current target depth: when a control
  // instant k dt_c lies in (t, t + dt], measures h_s and returns the new target depth (else nothing).
  std::optional<double> update(const ParticleSet& particles, double t, double dt, double outlet_depth_m) const;

  // y_t - (dt_c / T_c) (h_s - y2), clamped to [0.5 y2, 1.5 y2].
  double next_outlet_depth(double outlet_depth_m, double section_depth_m) const;

  double section_x() const { return section_x_; }
  double target_depth() const { return target_depth_; }
  double time_constant() const { return time_constant_; }

 private:
  double section_x_, target_depth_, time_constant_, column_width_;
};

}  // namespace hydrojump::sph
