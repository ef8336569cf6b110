// The structure of a classical (smooth-bed) hydraulic jump as published, and the check of a computed
// jump against it: is it a wall jet under a surface roller, as in the flume, or some other flow with
// the same depths?
//
// Roller length (Hager, Bremen & Kawagoshi 1990, Classical hydraulic jump: length of roller,
// J. Hydraul. Res. 28(5):591-608), a wide rectangular channel, from the toe to the end of the reverse
// surface flow:
//     Lr / y1 = -12 + 160 tanh(Fr1 / 20)                                  (2.5 <= Fr1 <= 20 here)
// Jump length (USBR, Peterka 1958, Hydraulic design of stilling basins and energy dissipators,
// Eng. Monograph 25; study notes, section 4), toe to the settled surface:
//     Lj = 6 y2*                                                           (4 <= Fr1 <= 20 here)
// Both are inputs-only values: the report prints them in the "smooth theory" column beside Belanger's
// y2*, for a corrugated bed as what the same inflow does on a smooth bed.
//
// Wall-jet profile. Rajaratnam (1965, The hydraulic jump as a wall jet, J. Hydraul. Div. 91(HY5):
// 107-132) found that the forward flow under the roller of a jump follows the profile of a plane
// turbulent wall jet, which Verhoff (1963, Princeton Univ. report 626) fitted as
//     u / u_m = 1.48 eta^(1/7) [1 - erf(0.68 eta)],    eta = (z - z_bed) / delta,
// with u_m the maximum forward velocity and delta the height above the bed at which u falls to u_m / 2
// above the maximum. wall_jet_deviation is the root mean square of (u/u_m - that profile) over the wet
// heights with 0 < eta <= 1 of a section's time-mean profile (the forward flow; above it lies the
// roller's reverse flow, which the wall-jet analysis does not describe). A profile with no height above
// u_m where u has fallen to u_m / 2 (the fastest flow at the surface: a surface jet) has no delta: NaN.
//
// The check (classic_structure): the jet height (jump_metrics.hpp) below one half and the deviation at
// most 0.15 u_m at the section two tailwater depths past the basin start, inside the roller of every
// jump of the study (Lr is 20-45 y1, the section ~10-20 y1 from the toe).
#pragma once

#include "cases/hydraulics.hpp"
#include "compare/time_statistics.hpp"

namespace hydrojump::compare {

// Lr of a classical jump (Hager et al. 1990), m; NaN outside 2.5 <= Fr1 <= 20 or for y1 <= 0
// (cases/hydraulics.hpp: the initial water's roller follows it too).
using cases::hager_roller_length;

// Lj = 6 y2* of a classical jump (USBR), m; NaN outside 4 <= Fr1 <= 20.
double usbr_jump_length(double belanger_sequent_depth_m, double froude_number);

// Verhoff's wall-jet profile u/u_m at eta = z/delta (eta >= 0).
double wall_jet_profile(double eta);

struct WallJetFit {
  double max_velocity_m_s = not_a_number;      // u_m
  double max_height_m = not_a_number;          // z(u_m) - z_bed
  double half_velocity_height_m = not_a_number;  // delta
  double deviation = not_a_number;             // RMS of u/u_m - profile over 0 < eta <= 1
  int points = 0;                              // heights in that RMS
};

// The fit of a section's time-mean profile (heights where fewer than half the frames had water do not
// count): the fastest forward flow and its height (NaN without a usable height); a NaN delta and
// deviation when u never falls to u_m / 2 above the maximum or u_m <= 0.
WallJetFit fit_wall_jet(const ColumnStatistics& section);

// Tolerances of the structure check above.
inline constexpr double classic_jet_height_limit = 0.5;
inline constexpr double classic_wall_jet_deviation_limit = 0.15;

// The check: a wall jet (jet height < 0.5) whose profile follows Verhoff's within 0.15 u_m.
bool classic_structure(double jet_height_fraction, double wall_jet_deviation);

}  // namespace hydrojump::compare
