// Particle interactions of one evaluation of the right-hand side: pressure from the equation of
// state, the continuity equation with density diffusion, the momentum equation with the chosen
// viscosity, and the boundary treatment. Each particle sums its own terms over its neighbours
// (pair_terms.hpp, neighbour_list.hpp), in a fixed order whatever the number of threads, so results
// do not depend on the thread count.
//
// The particle arrays must be in the order of `cells` (ParticleSet::permute(cells.order())).
#pragma once

#include "sph/cell_list.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"
#include "sph/wall_distance.hpp"

namespace hydrojump::sph {

// What the time-step conditions need from an interaction.
struct InteractionSummary {
  double max_acceleration = 0.0;   // max |a_i| over fluid particles (m/s^2)
  double max_viscous_rate = 0.0;   // max over approaching pairs of h |v_ij.r_ij| / (r_ij^2 + eta^2) (m/s)
  double max_eddy_viscosity = 0.0; // max nu_t of the SPS stress computed in this call (m^2/s; 0 without SPS)
};

// p_i = Tait(rho_i) for every particle.
void compute_pressure(ParticleSet& ps, const SolverSettings& s);

// Fills ax, az, drho of every particle (boundary particles: drho only, DBC) and returns the
// quantities of the time-step conditions. laminar_sps: uses the SPS stress tau/rho of the previous
// call and leaves the new one (from this call's velocity gradients) in tau_xx, tau_xz, tau_zz.
// `wall_distances` (sph.sps_wall_distance = "whole_domain"): the fixed walls' distance table, used for
// the mixing length of fluid particles with no wall particle within the kernel support.
// The pairs are those of `list`, built with a reach of at least the support on the particles in
// their present order, no particle having moved more than (reach - support)/2 since.
InteractionSummary compute_interactions(ParticleSet& ps, const NeighbourList& list, const SolverSettings& s,
                                        const WallDistanceTable* wall_distances = nullptr);
// The same with a list built now on `cells` (the particles at the positions `cells` was built from).
InteractionSummary compute_interactions(ParticleSet& ps, const CellList& cells, const SolverSettings& s,
                                        const WallDistanceTable* wall_distances = nullptr);

}  // namespace hydrojump::sph
