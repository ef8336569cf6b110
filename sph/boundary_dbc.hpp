// Dynamic boundary conditions, DBC (Crespo, Gomez-Gesteira & Dalrymple 2007, CMC Comput. Mater.
// Continua 5(3):173-184), the default wall treatment of DualSPHysics.
//
// Boundary particles sit in layers behind the wall and do not move. They obey the continuity
// equation with their fluid neighbours and the equation of state,
//
//   d rho_b/dt = sum_j m_j (v_b - v_j) . grad_b W_bj     (fluid j, v_b = 0),   p_b = Tait(rho_b),
//
// and enter the fluid's momentum equation like any neighbour: a fluid particle approaching a wall
// compresses the boundary particles, whose pressure rises and pushes it back. Their density is
// never below rho0 (no suction by walls). The fluid stays about 1-1.5 dx from the first boundary
// layer; with the layout of the particle generator the wall line lies halfway between the first
// boundary layer and the outer fluid row.
//
// Usage:
//   | spec key            | values / range          | default | meaning                                    |
//   |---------------------|-------------------------|---------|--------------------------------------------|
//   | sph.boundary        | "dbc", "mdbc"           | "dbc"   | wall treatment (mdbc: boundary_mdbc.hpp)   |
//   | sph.boundary_layers | 0-20                    | 0       | layers of wall particles (0: ceil(2h/dx))  |
// Example (spec): `[sph]  boundary = "dbc"   boundary_layers = 0`
#pragma once

namespace hydrojump::sph {

// Pair term of the boundary particle's continuity equation:  m_j (v_b - v_j) . grad_b W_bj,
// with grad_b W_bj = F (r_b - r_j) = F (dx, dz); u_j, w_j are v_j - v_b (v_b = 0 for a fixed wall).
inline double dbc_density_rate_pair(double mass_j, double gradient_factor, double u_j, double w_j, double dx,
                                    double dz) {
  return mass_j * gradient_factor * (-u_j * dx - w_j * dz);
}

// A wall particle's integrated density, never below the reference:  rho_b = max(rho0, rho_b*)
// (walls push, they do not pull: no suction of the fluid towards a wall). A NaN stays NaN, so the
// run's checks see it.
inline double dbc_wall_density(double integrated_density, double rho0) {
  return integrated_density < rho0 ? rho0 : integrated_density;
}

}  // namespace hydrojump::sph
