// Viscous terms of the momentum equation.
//
// Artificial viscosity (Monaghan 1992, Annu. Rev. Astron. Astrophys. 30:543-574):
//   dv_i/dt += - sum_j m_j Pi_ij grad_i W_ij,
//   Pi_ij = -alpha c0 mu_ij / rho_ij   if v_ij . r_ij < 0, else 0,
//   mu_ij = h v_ij . r_ij / (r_ij^2 + eta^2),  rho_ij = (rho_i + rho_j)/2,  eta^2 = 0.01 h^2.
//
// Laminar viscosity (Lo & Shao 2002, Appl. Ocean Res. 24:275-286) plus sub-particle-scale (SPS)
// eddy viscosity (Dalrymple & Rogers 2006, Coast. Eng. 53:141-147):
//   dv_i/dt += sum_j m_j 4 nu0 (r_ij . grad_i W_ij) / ((rho_i + rho_j)(r_ij^2 + eta^2)) v_ij
//            + sum_j m_j (tau_i/rho_i^2 + tau_j/rho_j^2) . grad_i W_ij
//   tau_ab/rho = 2 nu_t S_ab - 2/3 nu_t S_kk delta_ab - 2/3 C_I Delta^2 |S|^2 delta_ab,
//   nu_t = (C_s Delta)^2 |S|,  |S| = sqrt(2 S_ab S_ab),  Delta = dx.
//
// Usage:
//   | sph.viscosity  | parameters                                                        |
//   |----------------|-------------------------------------------------------------------|
//   | "artificial"   | sph.artificial_viscosity_alpha (default 0.01), or instead          |
//   |                | sph.artificial_viscosity_nu_m2_s: alpha = 8 nu / (h c0), the same  |
//   |                | viscosity nu = alpha h c0 / 8 (2D) at every resolution;           |
//   |                | sph.artificial_viscosity_wall_factor (default 1): alpha times this|
//   |                | between fluid and wall particles (DualSPHysics' ViscoBoundFactor; |
//   |                | 0 = no viscous wall friction, e.g. a jump as Belanger assumes it) |
//   | "laminar_sps"  | fluid.kinematic_viscosity_m2_s, sph.sps_smagorinsky_constant 0.12,|
//   |                | sph.sps_blin_constant 0.0066 (both in [0, 1]; 0 and 0: laminar);  |
//   |                | or sph.sps_mixing_length_m l (0-1 m, default 0: l = C_s dx): the |
//   |                | eddy viscosity nu_t = l^2 |S| of Prandtl's mixing length, fixed  |
//   |                | in metres across resolutions, limited near walls to Prandtl's     |
//   |                | kappa d (mixing_length_near_wall; without the limit the full      |
//   |                | length braked a jump's inflow, sph/README.md);                    |
//   |                | sph.sps_wall_distance: "kernel_support" (default) measures d only |
//   |                | to wall particles within 2h, so l jumps from about 0.41 (2h -     |
//   |                | dx/2) to l_m there; "whole_domain" also beyond, from the fixed    |
//   |                | walls' distance table (wall_distance.hpp), as Prandtl's law has it|
//   |                | sph.viscous_wall_condition "no_slip" (default), "free_slip" or    |
//   |                | "wall_function" (mDBC only): the walls' velocity in both terms is |
//   |                | mDBC's no-slip or slip velocity (boundary_mdbc.hpp); free slip    |
//   |                | takes the wall shear of an unresolved boundary layer out, the    |
//   |                | wall function puts the log law's back (wall_function.hpp)        |
// Ranges: alpha and the wall factor in [0, 1]; nu in [0, 1] m^2/s. A parameter of the model not
// chosen is an error (cases/spec_reader.cpp).
// Example (spec): `[sph]  viscosity = "artificial"   artificial_viscosity_alpha = 0.1`
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cases/options.hpp"
#include "sph/wall_function.hpp"

namespace hydrojump::sph {

using cases::Viscosity;  // sph.viscosity (cases/options.hpp)

// The pair loop shares one division a pair among these terms:
//   approach_ij = v_ij.r_ij / ((r_ij^2 + eta^2)(rho_i + rho_j))  for approaching particles (v.r < 0), else 0,
//   inv_ij = 1 / ((r_ij^2 + eta^2)(rho_i + rho_j)).

// Pi_ij (m^2/s^2 per kg/m^3 scaled) with  dv_i/dt += -m_j Pi_ij grad_i W_ij  (and j alike):
//   Pi_ij = -alpha c0 mu_ij / rho_ij = -2 alpha c0 h approach_ij,  mu_ij = h v.r/(r^2 + eta^2),
//   rho_ij = (rho_i + rho_j)/2.
inline double artificial_viscosity_pair(double alpha_c0_h, double approach) { return -2.0 * alpha_c0_h * approach; }

// Laminar factor L with  dv_i/dt += m_j L v_ij  (and dv_j/dt += -m_i L v_ij):
//   L = 4 nu0 (r_ij . grad_i W_ij) / ((rho_i + rho_j)(r_ij^2 + eta^2)) = 4 nu0 F r^2 inv_ij,  r.gradW = F r^2.
inline double laminar_viscosity_pair(double nu0, double gradient_factor, double r2, double inv) {
  return 4.0 * nu0 * gradient_factor * r2 * inv;
}

// Prandtl's mixing length near a wall: l = min(l_m, kappa d), kappa = 0.41, d the distance from the
// wall, here from the centre of the nearest wall particle less dx/2 (the wall line lies halfway
// between the first boundary layer and the outer fluid row). d_centre = infinity: l_m (no wall
// within the kernel support and no distance table, sph.sps_wall_distance = "kernel_support").
inline double mixing_length_near_wall(double length, double wall_centre_distance, double dx) {
  const double d = wall_centre_distance - 0.5 * dx;
  return std::min(length, kVonKarman * std::max(0.0, d));
}

// The wall-centre distance beyond which mixing_length_near_wall gives l_m whatever the distance:
// l_m / kappa + dx/2, plus dx/2 of margin for an interpolated distance (wall_distance.hpp).
inline double mixing_length_wall_reach(double length, double dx) { return length / kVonKarman + dx; }

struct SpsStress {
  double xx = 0.0, xz = 0.0, zz = 0.0;  // tau/rho (m^2/s^2)
  double eddy_viscosity = 0.0;          // nu_t (m^2/s), for the time-step bound
};

// tau/rho from the strain rate (du/dx, dw/dz and the shear du/dz + dw/dx: the velocity gradient's
// rotation does not enter), Dalrymple & Rogers (2006):
//   S_ab = (d_a v_b + d_b v_a)/2,  |S| = sqrt(2 S_ab S_ab),  nu_t = l^2 |S|,
//   tau_ab/rho = 2 nu_t S_ab - 2/3 nu_t S_kk delta_ab - 2/3 C_I dx^2 |S|^2 delta_ab,
// with the length l = C_s dx (Smagorinsky) or a mixing length given in metres (Prandtl).
inline SpsStress sps_stress(double dudx, double dwdz, double shear, double length, double blin, double dx) {
  const double sxx = dudx, szz = dwdz, sxz = 0.5 * shear;
  const double s2 = 2.0 * (sxx * sxx + szz * szz + 2.0 * sxz * sxz);  // |S|^2
  const double nu_t = length * length * std::sqrt(s2);
  const double iso = -(2.0 / 3.0) * nu_t * (sxx + szz) - (2.0 / 3.0) * blin * dx * dx * s2;
  return {2.0 * nu_t * sxx + iso, 2.0 * nu_t * sxz, 2.0 * nu_t * szz + iso, nu_t};
}

}  // namespace hydrojump::sph
