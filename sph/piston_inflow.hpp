// Piston inflow: the set-up of the corrugated-bed SPH study (Bo et al. 2019) instead of an inflow
// buffer. A reservoir upstream of a sluice gate is pushed by a piston at U_p = q / H_r, so the gate
// passes q while the reservoir stands at H_r and the jet contracts to y1 below the gate. The level is
// not self-correcting: with L the reservoir length and Q(H) the gate's discharge,
//
//   L dH/dt = U_p H - Q(H),
//
// and U_p H_r = Q(H_r) only if the jet contracts as assumed (Cc = 0.611); even then the balance is
// unstable where U_p > dQ/dH (true at H_r: 0.224 vs 0.125 m/s for run A), so the level and the inflow
// drift on a time scale L / (dQ/dH - U_p) that shrinks as the piston advances. At dx = 5 mm the jet
// contracts to Cc = 0.86, the gate passes more than U_p H at every level and the inflow decays
// (sph/README.md). The inflow buffer holds q exactly; the piston is the published set-up. The
// geometry (reservoir, gate plate, piston, level H_r from E1, opening y1 / 0.611, length) is
// cases::add_piston_reservoir; the piston is a moving wall (sph/wall_motion.hpp). Nothing is created:
// the water that enters the basin is the water that crosses the inflow section x_in (the downstream
// face of the gate), measured as the decrease of the water upstream of it,
//
//   m_in(t) = M_up(0) - M_up(t),   M_up = sum of the fluid masses with x < x_in,
//
// which is exact bookkeeping (nothing else enters or leaves the reservoir). It is the run's inflow
// mass (run_log.csv, basin.csv, summary.json: the inflow discharge is its rate, to be compared with q).
//
// Usage
//   | key (section [sph])  | meaning                                                          |
//   |----------------------|------------------------------------------------------------------|
//   | inflow_condition     | "piston" (default "buffer")                                      |
//   | sluice_opening_m     | gate opening (m); 0: y1 / 0.611                                  |
//   | reservoir_length_m   | piston start to gate (m); 0: U_p T_end + 2 H_r                    |
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
  double section_x() const { return x_in_; }
  double mass_in() const { return mass_in_; }

 private:
  double upstream_mass(const ParticleSet& particles) const;
  double x_in_;
  double upstream_ = 0.0;
  double mass_in_ = 0.0;
};

}  // namespace hydrojump::sph
