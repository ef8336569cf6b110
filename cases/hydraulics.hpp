// Open-channel hydraulics of a jump in a rectangular channel, per unit width.
// Used for derived spec quantities, default sections, and by the comparator for eta.
#pragma once

#include <functional>

namespace hydrojump::cases {

// The x in [lo, hi] with f(x) = target for f increasing on [lo, hi], by bisection to a relative width
// `rel_tol` of the interval (the root finder of the weir, tailgate and reservoir-level equations).
// The ends are never evaluated (f may be undefined there, as the weir head at P = 0); the caller
// must bracket the root: with f < target on all of (lo, hi) the result is hi, with f > target it is lo.
double solve_increasing(const std::function<double(double)>& f, double target, double lo, double hi,
                        double rel_tol = 1e-15);

// q = y U  [m^2/s]
double unit_discharge(double depth_m, double velocity_m_s);

// Fr = U / sqrt(g y)
double froude_number(double depth_m, double velocity_m_s, double gravity_m_s2);

// Belanger: y2* / y1 = (sqrt(1 + 8 Fr1^2) - 1) / 2   (horizontal smooth bed)
double belanger_sequent_depth(double y1_m, double froude1);

// Roller length of a classical jump (Hager, Bremen & Kawagoshi 1990, Classical hydraulic jump: length
// of roller, J. Hydraul. Res. 28(5):591-608), wide rectangular channel, toe to the end of the reverse
// surface flow:
//   Lr / y1 = -12 + 160 tanh(Fr1 / 20)          (2.5 <= Fr1 <= 20; NaN outside, or for y1 <= 0)
double hager_roller_length(double inflow_depth_m, double froude_number);

// The mean free surface of a classical jump's roller (Hager 1992, Energy Dissipators and Hydraulic
// Jump, Kluwer, ch. 2), from the toe (X = 0) on, as the fraction of the rise y2 - y1:
//   Y = (y - y1) / (y2 - y1) = tanh(1.5 X),   X = (x - x_toe) / Lr
// (0 for X <= 0; 0.905 at the roller's end X = 1).
double roller_surface_fraction(double x_over_roller_length);

// Specific energy above the local bed: E = y + q^2 / (2 g y^2)
double specific_energy(double depth_m, double discharge_m2_s, double gravity_m_s2);

// Energy dissipation rate eta = (E1 - E2) / E1  (a fraction, not percent)
double energy_dissipation_rate(double e1_m, double e2_m);

// Everything derived from the inflow (y1, U1) and the tailwater depth y2 of a stilling basin.
struct JumpHydraulics {
  double discharge_m2_s = 0.0;         // q
  double froude1 = 0.0;                // Fr1
  double belanger_y2_m = 0.0;          // y2*, smooth-bed sequent depth
  double e1_m = 0.0;                   // E1 at y1
  double e2_m = 0.0;                   // E2 at the tailwater depth
  double eta = 0.0;                    // (E1 - E2)/E1 with the tailwater depth
  double eta_smooth = 0.0;             // (E1 - E2*)/E1 with y2*
};

JumpHydraulics jump_hydraulics(double y1_m, double u1_m_s, double tailwater_m, double gravity_m_s2);

// Sharp-crested (thin-plate) weir across the channel with Rehbock's discharge coefficient
// (Henderson 1966, Open Channel Flow, sec. 6.7), H the head above the crest, P the crest height above
// the upstream bed:
//   q = 2/3 Cd sqrt(2 g) H^(3/2),   Cd = 0.611 + 0.08 H / P
// Calibrated for H/P up to about 1 and usable, with growing error, to H/P ~ 2.5; beyond that the weir
// is a low sill and the formula overestimates the discharge (rehbock_valid_head_ratio).
constexpr double rehbock_valid_head_ratio = 2.5;
double rehbock_weir_discharge(double head_m, double weir_height_m, double gravity_m_s2);

// The head H that passes q over a weir of height P (the inverse of rehbock_weir_discharge, which
// increases with H). Throws std::invalid_argument for q <= 0 or P <= 0.
double rehbock_weir_head(double discharge_m2_s, double weir_height_m, double gravity_m_s2);

// The weir (tailgate) height P that holds the upstream depth y = P + H(q, P) at discharge q
// (P + H grows with P: solved by bisection on 0 < P < y). Throws std::invalid_argument when q <= 0
// or y <= 0.
double tailgate_height_for_depth(double discharge_m2_s, double upstream_depth_m, double gravity_m_s2);

}  // namespace hydrojump::cases
