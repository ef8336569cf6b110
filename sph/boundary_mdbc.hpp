// Modified dynamic boundary conditions, mDBC (English, Dominguez, Vacondio, Crespo, Stansby, Lind,
// Chiapponi & Gomez-Gesteira 2022, Comp. Part. Mech. 9:911-925).
//
// Each boundary particle b has a ghost node g mirrored across the wall (g = b + 2 (q - b), q the
// nearest wall point, so corners mirror through the corner). The fluid density and its gradient at
// g are found with a first-order consistent SPH interpolation,
//
//   [ sum V_j W_gj          sum V_j (x_j - x_g) W_gj        sum V_j (z_j - z_g) W_gj      ] [rho_g    ]   [ sum m_j W_gj    ]
//   [ sum V_j dW_gj/dx      sum V_j (x_j - x_g) dW_gj/dx    sum V_j (z_j - z_g) dW_gj/dx  ] [drho/dx  ] = [ sum m_j dW/dx   ]
//   [ sum V_j dW_gj/dz      sum V_j (x_j - x_g) dW_gj/dz    sum V_j (z_j - z_g) dW_gj/dz  ] [drho/dz  ]   [ sum m_j dW/dz   ]
//
// (fluid neighbours j, V_j = m_j / rho_j), and extrapolated back to the boundary particle:
//   rho_b = rho_g + (r_b - r_g) . grad rho_g.
// Where the matrix is singular (|det| < 1e-3; e.g. a ghost node with few fluid neighbours near the
// free surface) the Shepard value sum m_j W / sum V_j W is used without the gradient, and where the
// ghost node lies mostly outside the fluid (Shepard sum sum_j V_j W_gj < 0.5) rho_b = rho0. rho_b is never below rho0, so walls do not pull
// on the fluid. Boundary particles do not move; for the viscous terms (laminar_sps) they carry the
// no-slip velocity mirrored about the fixed wall, v_b = 2 v_wall - v_g = -v_g, with v_g interpolated at
// the ghost node with the same first-order correction (English et al. 2022, no-slip variant). With
// sph.viscous_wall_condition = "free_slip" they carry the ghost velocity with its wall-normal part
// reversed instead (the slip variant), v_b = v_wall + v_rel - 2 (v_rel . n) n, v_rel = v_g - v_wall,
// n along the ghost offset: the eddy and laminar viscosity then see no shear at the wall.
//
// Usage:
//   | spec key            | values / range | default | meaning                                       |
//   |---------------------|----------------|---------|-----------------------------------------------|
//   | sph.boundary        | "mdbc"         | "dbc"   | this wall treatment (needs ghost offsets)      |
//   | sph.boundary_layers | 0-20           | 0       | layers of wall particles (0: ceil(2h/dx))     |
//   | sph.viscous_wall_condition | "no_slip", "free_slip", "wall_function" | "no_slip" | wall velocity of the viscous terms (laminar_sps; wall_function: slip) |
// Boundary particles need ghost offsets, which the particle generator computes from the
// CaseGeometry walls. Example (spec): `[sph]  boundary = "mdbc"`
#pragma once

#include "sph/cell_list.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {

// Sets rho (and the no-slip wall velocity wall_u, wall_w) of every boundary particle from its ghost node.
void mdbc_boundary_density(ParticleSet& ps, const CellList& cells, const SolverSettings& s);

}  // namespace hydrojump::sph
