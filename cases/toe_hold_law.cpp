#include "cases/toe_hold_law.hpp"

#include <cmath>
#include <stdexcept>

namespace hydrojump::cases {

ToeHoldGains toe_hold_gains(const Case& c, const CaseGeometry& geometry) {
  if (!c.holds_toe() || geometry.inflows.empty() || geometry.outflows.empty())
    throw std::invalid_argument("case \"" + c.id + "\": the toe-holding tailwater control needs a stilling basin with an "
                                "inflow, an outflow and [case.tailwater] control = \"hold_toe\"");
  const StillingBasinCase& b = *c.stilling_basin();
  ToeHoldGains g;
  g.inflow_depth_m = geometry.inflows.front().depth_m;
  g.tailwater_depth_m = geometry.outflows.front().tailwater_depth_m;
  g.target_toe_x_m = geometry.expected_toe_x_m;
  g.outlet_x_m = geometry.x_max_m;
  g.toe_hold_time_s = b.control.toe_hold_time_s;
  g.toe_hold_gain = b.control.toe_hold_gain;
  return g;
}

double toe_hold_proportional(const ToeHoldGains& g, double toe_x_m) {
  const double toe = std::isfinite(toe_x_m) ? toe_x_m : g.outlet_x_m;
  return g.toe_hold_gain * (g.tailwater_depth_m - g.inflow_depth_m) * (toe - g.target_toe_x_m);
}

VolumeTarget toe_hold_volume_target(const ToeHoldGains& g, double previous_integral_m2, double toe_x_m, double dt_s) {
  const double toe = std::isfinite(toe_x_m) ? toe_x_m : g.outlet_x_m;
  VolumeTarget t;
  // I(n) = I(n-1) + (y2* - y1) / T_x (x_toe - x_target) dt;  V*(n) = I(n) + P(n)
  t.integral_m2 = previous_integral_m2 + (g.tailwater_depth_m - g.inflow_depth_m) / g.toe_hold_time_s *
                                             (toe - g.target_toe_x_m) * dt_s;
  t.volume_target_m2 = t.integral_m2 + toe_hold_proportional(g, toe);
  return t;
}

}  // namespace hydrojump::cases
