#include "cases/case_rules.hpp"

#include <cmath>

#include "cases/hydraulics.hpp"

namespace hydrojump::cases {

namespace {

double belanger_of(const StillingBasinCase& b, double g) {
  return belanger_sequent_depth(b.inflow_depth_m, froude_number(b.inflow_depth_m, b.inflow_velocity_m_s, g));
}

// The smallest whole number of intervals dt that covers t (a hair of rounding tolerated).
double whole_intervals(double t, double dt) { return std::ceil(t / dt - 1e-9) * dt; }

}  // namespace

double mixing_length_from_sequent_depth(double coefficient, const StillingBasinCase& basin, double gravity_m_s2) {
  return coefficient * belanger_of(basin, gravity_m_s2);
}

double sloshing_period_s(double length_m, double depth_m, double gravity_m_s2) {
  return 2.0 * length_m / std::sqrt(gravity_m_s2 * depth_m);
}

RunSettings run_from_sloshing_periods(const RunRule& rule, const StillingBasinCase& basin, double gravity_m_s2) {
  const double length = basin.upstream_length_m + basin.basin_length_m + basin.downstream_length_m;
  const double period = sloshing_period_s(length, belanger_of(basin, gravity_m_s2), gravity_m_s2);
  RunSettings run;
  run.output_interval_s = rule.output_interval_s;
  run.average_start_s = whole_intervals(rule.start_up_sloshing_periods * period, rule.output_interval_s);
  run.end_time_s = run.average_start_s + whole_intervals(rule.window_sloshing_periods * period, rule.output_interval_s);
  run.average_end_s = run.end_time_s;
  return run;
}

double toe_hold_time_from_sloshing_periods(double periods, const StillingBasinCase& basin, double gravity_m_s2) {
  const double length = basin.upstream_length_m + basin.basin_length_m + basin.downstream_length_m;
  return periods * sloshing_period_s(length, belanger_of(basin, gravity_m_s2), gravity_m_s2);
}

}  // namespace hydrojump::cases
