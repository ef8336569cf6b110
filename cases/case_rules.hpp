// Rules that give a stilling basin's case-dependent settings from the case's own inputs, written once
// and the same for every basin (runs A-E of the reference study and any basin a user brings). A study
// states a rule's coefficient once ([sph], [run]); the reader resolves it per case, and the resolved
// case.toml carries the resulting numbers.
//
//   | rule                                  | spec key                                 | gives                    |
//   |---------------------------------------|------------------------------------------|--------------------------|
//   | mixing length from the sequent depth  | [sph] sps_mixing_length_per_sequent_depth| l_m = c_l y2*            |
//   | run length from the sloshing period   | [run] start_up_sloshing_periods,         | the averaging window and |
//   |                                       |       window_sloshing_periods            | the end time             |
//   | toe control time from the sloshing    | [run] toe_hold_sloshing_periods          | [case.tailwater]         |
//   | period                                |                                          | toe_hold_time_s          |
//
// y2* is Belanger's sequent depth of the inflow (y1, Fr1): an input-only length, never the measured y2.
#pragma once

#include "cases/spec.hpp"

namespace hydrojump::cases {

// The eddy length of a jump scales with its depth: Rodi (1993, Turbulence models and their application
// in hydraulics, sec. 2.3) gives a mixing length of 0.07-0.1 times the layer thickness for free shear
// layers and wall jets. With the layer taken as the sequent depth,
//   l_m = c_l y2*,   y2* = y1 (sqrt(1 + 8 Fr1^2) - 1) / 2
// c_l = 0.1 held the smooth twins of the reference study within 1 % of Belanger (calibrated against
// theory, not against the laboratory's corrugated-bed runs).
double mixing_length_from_sequent_depth(double coefficient, const StillingBasinCase& basin, double gravity_m_s2);

// The lowest sloshing mode of the water in a basin of length L at depth y (a standing wave of length
// 2L, shallow-water speed sqrt(g y)):
//   T_s = 2 L / sqrt(g y)
// the time a start-up surge needs to cross the domain and come back.
double sloshing_period_s(double length_m, double depth_m, double gravity_m_s2);

// The run of a stilling basin from its sloshing period (L the whole domain, inflow to outlet; y = y2*):
//   average_start = N_s T_s,  average_end = end_time = average_start + N_w T_s
// each rounded up to a whole number of output intervals.
RunSettings run_from_sloshing_periods(const RunRule& rule, const StillingBasinCase& basin, double gravity_m_s2);

// The toe-holding control's time (sph/toe_hold_control.hpp, reference/tailwater_control.hpp) from the
// basin's sloshing period (L the whole domain, y = y2*):
//   T_x = c_x T_s
// The outlet reaches the jump through the basin's water, a shallow-water wave taking about T_s / 2; a
// control much faster than that overshoots, and one much slower leaves the toe where the start-up
// surge put it. Tried on runs A and A_smooth at quick (the toe is the protocol's set-point, not a
// laboratory result): VOF A with T_x = 5 s still stood 0.1 m downstream of the basin start at 9 s;
// c_x = 0.65 (2.0 s) held VOF A but swung VOF A_smooth's toe by +-0.1 m and drowned SPH A_smooth's
// jump at the inflow by 6.4 s; c_x = 1 (3.1 s) with 3 sloshing periods of start-up held both VOF
// toes within 0.02 m (A) and 0.1 m (A_smooth) over the window.
double toe_hold_time_from_sloshing_periods(double periods, const StillingBasinCase& basin, double gravity_m_s2);

}  // namespace hydrojump::cases
