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

#include <vector>

#include <Eigen/Core>

#include "sph/cell_list.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {

// The fluid-side particles near each wall particle's ghost node, a Verlet list as neighbour_list.hpp's:
// for every wall particle b, the fluid and buffer particles j closer than `reach` to b's ghost node
// at the positions (x, z) it is built from (periodic images with their shift). It serves while no
// particle has moved more than (reach - support)/2 since: a wall's ghost node moves with it (fixed
// offset), so a pair within the support then was within the reach when listed. Built with the pair
// list, it spares every interaction the scan of the 3 x 3 cells around each ghost node.
class GhostNeighbourList {
 public:
  // `cells` built from (x, z) with cells of at least `reach`; `type`, ghost offsets from `ps`.
  void build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const ParticleSet& ps, const CellList& cells, const SolverSettings& s,
             double reach);
  // Particle b's listed neighbours: entries [begin(b), end(b)), neighbour(k) seen at x + shift(k).
  int begin(Eigen::Index b) const { return start_[static_cast<std::size_t>(b)]; }
  int end(Eigen::Index b) const { return end_[static_cast<std::size_t>(b)]; }
  int neighbour(int k) const { return j_[static_cast<std::size_t>(k)]; }
  double shift(int k) const { return shift_.empty() ? 0.0 : shift_[static_cast<std::size_t>(k)]; }
  const int* neighbours() const { return j_.data(); }
  bool periodic() const { return !shift_.empty(); }
  const double* shifts() const { return shift_.data(); }  // periodic lists only
  // What brings b's ghost node x_b + ghost_dx_b into the periodic domain as listed (0 if not periodic).
  double ghost_wrap(Eigen::Index b) const { return wrap_.empty() ? 0.0 : wrap_[static_cast<std::size_t>(b)]; }
  Eigen::Index particles() const { return static_cast<Eigen::Index>(end_.size()); }

 private:
  std::vector<int> start_, end_;  // per particle (walls only non-empty); slots of the candidates' size
  std::vector<int> j_;
  std::vector<double> shift_, wrap_;  // periodic domains only
};

// Sets rho (and the no-slip wall velocity wall_u, wall_w) of every boundary particle from its ghost
// node, over the ghost list's neighbours.
void mdbc_boundary_density(ParticleSet& ps, const GhostNeighbourList& list, const SolverSettings& s);
// The same with a list built now from `cells` (the particles at the positions `cells` was built from).
void mdbc_boundary_density(ParticleSet& ps, const CellList& cells, const SolverSettings& s);

}  // namespace hydrojump::sph
