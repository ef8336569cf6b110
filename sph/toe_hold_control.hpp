// Holding a hydraulic jump's toe at the basin start with the tailwater, as a laboratory tailgate does
// ([case.tailwater] control = "hold_toe", the default for stilling basins): the SPH twin of the VOF
// tailgate (reference/tailwater_control.hpp). Ead & Rajaratnam (2002) set their tailgate so that the
// toe stood at the start of the corrugated bed, then measured y2: the tailwater is a result, not an
// input.
//
// Why. An outlet that holds a fixed depth leaves the basin's water volume free, and on a smooth bed
// the jump has no preferred place: a tailwater 1 % off Bélanger's depth moves the toe at about 1 % of
// U1. A basin that keeps its water volume holds the jump: moved downstream by dx, it leaves
// (y2 - y1) dx of water behind, which raises the level behind the roller and pushes it back. So the
// control holds the volume, and moves that volume to bring the toe to the target. It acts at every
// output time t_n (spacing dt = run.output_interval_s) on the outflow buffers' target depth y_t
// (open_boundaries.hpp), with the volume target V* of cases/toe_hold_law.hpp:
//
//   I(n)   = I(n-1) + (y2* - y1) / T_x * (x_toe(n) - x_target) * dt          (more water when the toe
//   V*(n)  = I(n) + k_p (y2* - y1) (x_toe(n) - x_target)                      lies downstream)
//   y_t(n) = clamp( y2* - (V(n) - V*(n)) / (T_V S),  y2*/2,  3 y2*/2 )             (volume)
//
// V(n) the water in the domain per unit width (m^2: the fluid and outflow-buffer mass over rho0, the
// run monitor's fluid_mass), x_toe(n) the run monitor's toe at t_n (cases/jump_toe.hpp; no toe counts
// as a toe at the outlet: the jump has left the basin), x_target the basin start, y2* the case's
// tailwater depth (the initial level) and S = (c_t^2 - U_t^2) / (2 c_t) the outlet's gain, with
// U_t = q / y2* and c_t = sqrt(g y2*): the absorbing (characteristic) outlet, at the tailwater state,
// lets out S delta more for a target lowered by delta (open_boundaries.hpp), so the law drains a volume
// error V - V* at the rate (V - V*) / T_V, as the VOF tailgate's Umean = (q + (V - V*)/T_V) / y2* does.
// (A hydrostatic_level outlet holds its level firmly: its gain is larger, and the volume settles
// faster than T_V.) The toe term moves the
// toe to the target over about T_x. The proportional part k_p is off by default. Tried at k_p = 0.5
// (quick, ead2002, T_x one sloshing period, averaged over the fourth period): it brought SPH A_smooth's
// toe back from the start-up sooner and undershot less (0.158 m against 0.118 m for a 0.2-m target),
// but then swung with a 6-s period that did not decay (0.154 +- 0.027 m against 0.255 +- 0.014 m);
// VOF A_smooth swung less (sd 0.029 against 0.057 m) but stood lower (0.138 against 0.241 m) and its
// y2 fell from 0.961 to 0.924 y2*; VOF A, pushed to 0.53 m by its start-up, came back more slowly
// (0.258 against 0.207 m). The loop's lags (the outlet's wave reaches the jump after half a sloshing
// period) leave little room for more gain. I(0) = V(0) - k_p (y2* - y1) (x_toe(0) - x_target), so that
// V*(0) = V(0) at the first output. At steady state the toe stands
// at x_target and the outlet lets out q: the tailwater then is the depth the jump needs, a prediction
// the comparator sets beside Bélanger's and the laboratory's.
//
// I and y_t are saved in checkpoints (SolverClock), and the law reads only the current output, so a
// resumed run continues exactly. The control acts only at outputs on the output grid (not at the end
// state of a run stopped between two), which an extended run drops.
//
// Usage ([case.tailwater])
//   | key                 | values / range | default    | meaning                                    |
//   |---------------------|----------------|------------|--------------------------------------------|
//   | control             | "hold_toe",    | "hold_toe" | this control, or the outlet holds depth_m  |
//   |                     | "fixed_depth"  |            |                                            |
//   | volume_hold_time_s  | (0, 1000] s    | 1.0        | T_V                                        |
//   | toe_hold_time_s     | (0, 1000] s    | 5.0        | T_x                                        |
//   | toe_hold_gain       | [0, 10]        | 0          | k_p                                        |
// SPH needs an outflow buffer ("hydrostatic_level" or "absorbing"), not a tailgate weir or a level held
// at the downstream section (those hold a depth: give control = "fixed_depth").
// Example:
//   [case.tailwater]
//   rule = "belanger"        # the initial level
//   control = "hold_toe"
#pragma once

#include <limits>

#include "cases/geometry.hpp"
#include "cases/spec.hpp"
#include "cases/toe_hold_law.hpp"

namespace hydrojump::sph {

struct ToeHoldLaw {
  cases::ToeHoldGains gains;         // y1, y2* (the initial level), x_target, the outlet, T_x, k_p
  double outlet_gain_m_s = 0.0;      // S = (c_t^2 - U_t^2) / (2 c_t), U_t = q / y2*, c_t = sqrt(g y2*)
  double interval_s = 0.0;           // dt, the output interval
  double volume_hold_time_s = 1.0;   // T_V
  double rho0 = 1000.0;              // V = mass / rho0

  // The law of a stilling basin with control = "hold_toe" (throws std::invalid_argument otherwise).
  static ToeHoldLaw from_case(const cases::Case& c, const cases::CaseGeometry& geometry, double gravity_m_s2,
                              double rho0);
};

struct ToeHoldState {
  double volume_integral_m2 = 0.0;   // I, the integral part of V*; 0: not started
  double volume_target_m2 = 0.0;     // V* = I + k_p (y2* - y1) (x_toe - x_target)
  double outlet_depth_m = 0.0;       // y_t (y2* until the first step)
};

// One control step at an output with the water mass `water_mass_kg_per_m` and the toe `toe_x_m` (NaN:
// no toe), from the previous I (0: the first output): the new I, V* and y_t (y_t depends on V* and V
// alone, not on its previous value).
ToeHoldState toe_hold_step(const ToeHoldLaw& law, double volume_integral_m2, double water_mass_kg_per_m,
                           double toe_x_m);

}  // namespace hydrojump::sph
