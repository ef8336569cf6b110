// Density diffusion terms added to the continuity equation, applied between fluid particles.
//
// Continuity (Monaghan 1994):   d rho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij  + D_i
//
// Molteni & Colagrossi (2009, Comput. Phys. Commun. 180:861-872):
//   D_i = delta h c0 sum_j psi_ij . grad_i W_ij V_j,   psi_ij = 2 (rho_j - rho_i) (r_j - r_i) / |r_ij|^2
// Fourtakas, Dominguez, Vacondio & Rogers (2019, Comput. Fluids 190:346-361): the same with the
// hydrostatic part removed,  rho_j - rho_i  ->  rho_j - rho_i - rho^H_ji,
//   rho^H_ji = rho0 ((1 + rho0 g.(r_j - r_i) / B)^(1/gamma) - 1).
// With grad_i W_ij = F (r_i - r_j) the pair term is  -2 F (rho_j - rho_i [- rho^H_ji]) V_j delta h c0.
//
// Usage:
//   | sph.density_diffusion | meaning                              | sph.density_diffusion_coefficient |
//   |-----------------------|--------------------------------------|-----------------------------------|
//   | "none"                | plain continuity                     | unused (an error if given)        |
//   | "molteni"             | Molteni & Colagrossi 2009            | delta in [0, 1], typically 0.1    |
//   | "fourtakas"           | Fourtakas et al. 2019 (default)      | delta in [0, 1], default 0.1      |
// Example (spec): `[sph]  density_diffusion = "fourtakas"   density_diffusion_coefficient = 0.1`
#pragma once

#include <stdexcept>
#include <string>

#include "cases/options.hpp"
#include "sph/equation_of_state.hpp"

namespace hydrojump::sph {

using cases::DensityDiffusion;  // sph.density_diffusion (cases/options.hpp)

// rho^H_ji = rho0 ((1 + x)^(1/gamma) - 1),  gamma = 7,  x = rho0 g.(r_j - r_i)/B = rho0 g_z (z_j - z_i) / B.
// x is O(rho0 g 2h / B) ~ 1e-3, so the power is replaced by its second-order Taylor expansion
// (the first term left out is a(a-1)(a-2)/6 x^3, a = 1/gamma: a relative error of about 0.27 x^2 ~ 3e-7),
// which keeps pow() out of the pair loop; rho0 g_z / B is made once, not once a pair.
class HydrostaticDensity {
 public:
  HydrostaticDensity(double rho0, double b, double gravity_z) : rho0_(rho0), scale_(rho0 * gravity_z / b) {}
  double difference(double zj_minus_zi) const {
    constexpr double a = 1.0 / TaitEquationOfState::gamma;
    const double x = scale_ * zj_minus_zi;
    return rho0_ * x * (a + 0.5 * a * (a - 1.0) * x);
  }

 private:
  double rho0_, scale_;
};

// Pair contribution to D_i:  delta h c0 (-2 F) (rho_j - rho_i - rho^H_ji) V_j
inline double density_diffusion_pair(double delta_h_c0, double gradient_factor, double density_jump,
                                     double volume_j) {
  return -2.0 * delta_h_c0 * gradient_factor * density_jump * volume_j;
}

}  // namespace hydrojump::sph
