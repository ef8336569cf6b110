// Tait equation of state of weakly compressible SPH (Monaghan 1994, J. Comput. Phys. 110:399-406;
// Batchelor 1967), as in DualSPHysics (Crespo et al. 2015, Comput. Phys. Commun. 187:204-216):
//
//   p = B ((rho / rho0)^gamma - 1),   B = c0^2 rho0 / gamma,   gamma = 7,
//   c0 = coefficient * sqrt(g H_max)  (or a speed given in the spec).
//
// Usage:
//   c0 = max(sound_speed_coefficient sqrt(g H_max), sound_speed_min_flow_ratio U_max)
//   unless sph.sound_speed_m_s > 0 gives it directly (H_max: the deepest water of the case; U_max:
//   its fastest inflow or initial flow). gamma is fixed at 7 (water).
//
// Usage:
//   | spec key                       | range        | default | meaning                                  |
//   |--------------------------------|--------------|---------|------------------------------------------|
//   | sph.sound_speed_coefficient    | [1, 1000]    | 10      | c0 / sqrt(g H_max)                       |
//   | sph.sound_speed_min_flow_ratio | [0, 1000]    | 10      | lower bound of c0 / U_max (Mach <= 0.1)  |
//   | sph.sound_speed_m_s            | [0, 1e5]     | 0       | c0 itself when > 0 (0: from the above)   |
// Example (spec): `[sph]  sound_speed_coefficient = 20.0`
// Example (code): `TaitEquationOfState eos(1000.0, 44.3);  double p = eos.pressure(1001.0);`
#pragma once

#include <cmath>

namespace hydrojump::sph {

struct TaitEquationOfState {
  double rho0 = 1000.0;
  double c0 = 1.0;
  static constexpr double gamma = 7.0;
  double b = 0.0;  // B

  TaitEquationOfState() = default;
  // B = c0^2 rho0 / gamma
  TaitEquationOfState(double rho0_kg_m3, double c0_m_s)
      : rho0(rho0_kg_m3), c0(c0_m_s), b(c0_m_s * c0_m_s * rho0_kg_m3 / gamma) {}

  // p = B ((rho/rho0)^7 - 1)   (gamma = 7: three multiplications instead of pow)
  double pressure(double rho) const {
    const double r = rho / rho0;
    const double r2 = r * r;
    static_assert(gamma == 7.0, "pressure() multiplies out (rho/rho0)^7");
    return b * (r2 * r2 * r2 * r - 1.0);
  }
  // rho = rho0 (1 + p/B)^(1/gamma)
  double density(double p) const { return rho0 * std::pow(1.0 + p / b, 1.0 / gamma); }
  // Hydrostatic density at depth d below a free surface: p = rho0 g d.
  double hydrostatic_density(double g, double depth) const { return density(rho0 * g * depth); }
};

}  // namespace hydrojump::sph
