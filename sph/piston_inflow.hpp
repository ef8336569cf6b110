// Piston inflow: the set-up of the corrugated-bed SPH study (Bo, Wu, Wang, Zhang & Gu 2019, Advances in
// Science and Technology of Water Resources 39(2):72-78) instead of an inflow buffer. A reservoir upstream of a sluice gate is pushed by a piston that keeps its level at H_r, so
// the gate passes Q(H_r): q if the jet contracts to y1 below the gate as assumed (Cc = 0.611). With L
// the reservoir length and Q(H) the gate's discharge,
//
//   L dH/dt = u_p H - Q(H).
//
// At the constant speed U_p0 = q / H_r the level is not self-correcting (unstable where U_p0 > dQ/dH,
// true at H_r: 0.224 vs 0.125 m/s for run A), so the piston's speed follows the level,
// u_p = U_p0 + K (H_r - H) (wall_motion.hpp, sph.piston_level_gain_per_s = K, default 10 1/s; 0 for
// the constant speed). The inflow is then what the gate passes at H_r: at dx = 5 mm the jet contracts
// less than 0.611 (Cc = 0.75 in the 0.4 s test), so the default opening passes ~18 % more than q and
// the reservoir runs out early (a clear stop); give sph.sluice_opening_m = y1 / Cc. The inflow buffer
// holds q exactly; the piston is the published set-up. The
// geometry (reservoir, gate plate, piston, level H_r from E1, opening y1 / 0.611, length) is
// cases::add_piston_reservoir; the piston is a moving wall (sph/wall_motion.hpp). Nothing is created:
// the water that enters the basin is the water that crosses the inflow section x_in (the downstream
// face of the gate), measured as the decrease of the water upstream of it,
//
//   m_in(t) = M_up(0) - M_up(t),   M_up = sum of the fluid masses with x < x_in,
//
// which is exact bookkeeping: nothing else enters or leaves the reservoir, except a density outlier
// removed there (sph/density_outliers.hpp), whose mass M_up(t) loses without a crossing and which is
// taken out of M_up's reference (forget_removed). It is the run's inflow
// mass (run_log.csv, basin.csv, summary.json: the inflow discharge is its rate, to be compared with q).
//
// Usage
//   | key (section [sph])  | meaning                                                          |
//   |----------------------|------------------------------------------------------------------|
//   | inflow_condition     | "piston" (default "buffer")                                      |
//   | sluice_opening_m     | gate opening, 0-100 m; 0 (default): y1 / 0.611                   |
//   | reservoir_length_m   | piston start to gate, 0-1000 m; 0 (default): U_p T_end + 2 H_r    |
//   | piston_level_gain_per_s | K of the level control, 0-1000 1/s; default 10, 0: constant speed |
// Example (cases/*.toml):
//   [case.sph]
//   inflow_condition = "piston"
// The reservoir costs particles: run A's is 2.7 m x 0.23 m for 10 s (about 23,000 more at dx = 5 mm,
// three times the basin's), and its depth raises c0 = coef sqrt(g H_max).
#pragma once

#include "sph/particles.hpp"

namespace hydrojump::sph {

class GateCrossing {
 public:
  explicit GateCrossing(double x_in) : x_in_(x_in) {}
  // Takes the water upstream of x_in now as the reference (at the start of a run or a resume).
  void start(const ParticleSet& particles);
  // The mass that crossed x_in since the last call (or start), kg/m.
  double advance(const ParticleSet& particles);
  // A particle of mass m removed at x by another rule (a density outlier, sph/density_outliers.hpp):
  // upstream of x_in it left the reservoir without crossing, so the reference drops by m.
  void forget_removed(double x, double m) {
    if (x < x_in_) upstream_ -= m;
  }
  double section_x() const { return x_in_; }
  double mass_in() const { return mass_in_; }

 private:
  double upstream_mass(const ParticleSet& particles) const;
  double x_in_;
  double upstream_ = 0.0;
  double mass_in_ = 0.0;
};

}  // namespace hydrojump::sph
