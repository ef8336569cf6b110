// The volume target of the toe-holding control ([case.tailwater] control = "hold_toe", the default for
// stilling basins): the part of the law both solvers share. The SPH solver steers its outflow buffer's
// depth with it (sph/toe_hold_control.hpp), the VOF runner the outlet's mean velocity
// (reference/tailwater_control.hpp); both then drain the volume error V - V* over T_V.
//
// At each control step n (an output in SPH, a leg of interFoam in VOF) of length dt, with the toe x_toe(n):
//   P(n)  = k_p (y2* - y1) (x_toe(n) - x_target)
//   I(n)  = I(n-1) + (y2* - y1) / T_x (x_toe(n) - x_target) dt
//   V*(n) = I(n) + P(n)
// y1 the inflow depth, y2* the case's tailwater depth (the initial level), x_target the basin start,
// T_x = [case.tailwater] toe_hold_time_s and k_p = toe_hold_gain. More water when the toe lies
// downstream: the jump, moved downstream by dx at constant volume, leaves (y2* - y1) dx of water behind
// it, so V* moves the volume the toe's displacement stands for. A step without a toe (NaN: the jump has
// left the basin) counts as a toe at the outlet.
#pragma once

#include "cases/geometry.hpp"
#include "cases/spec.hpp"

namespace hydrojump::cases {

struct ToeHoldGains {
  double inflow_depth_m = 0.0;     // y1
  double tailwater_depth_m = 0.0;  // y2*
  double target_toe_x_m = 0.0;     // x_target, the basin start
  double outlet_x_m = 0.0;         // where a step without a toe puts it
  double toe_hold_time_s = 5.0;    // T_x
  double toe_hold_gain = 0.0;      // k_p
};

// The gains of a stilling basin under control = "hold_toe" and its geometry (throws
// std::invalid_argument, naming the case, for any other case or a geometry without inflow and outflow).
ToeHoldGains toe_hold_gains(const Case& c, const CaseGeometry& geometry);

// P = k_p (y2* - y1) (x_toe - x_target)
double toe_hold_proportional(const ToeHoldGains& g, double toe_x_m);

struct VolumeTarget {
  double integral_m2 = 0.0;       // I(n)
  double volume_target_m2 = 0.0;  // V*(n) = I(n) + P(n)
};

// One step from I(n-1) over dt_s with the step's toe.
VolumeTarget toe_hold_volume_target(const ToeHoldGains& g, double previous_integral_m2, double toe_x_m, double dt_s);

}  // namespace hydrojump::cases
