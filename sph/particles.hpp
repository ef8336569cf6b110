// Particle storage of the SPH solver: structure of arrays, one Eigen vector per quantity
// (SPlisHSPlasH style), so the interaction loop streams through memory and the neighbour search can
// reorder every array by cell with one permutation.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace hydrojump::sph {

// What a particle is. Stored as one byte per particle; written to VTK as "type".
// inflow and outflow are the open-boundary buffers (sph/open_boundaries.hpp): neighbours of the fluid
// with imposed velocity and density, moved by their buffer rather than by the integrator.
// moving_wall: a wall particle moved by a prescribed motion (sph/wall_motion.hpp), e.g. a lifted
// dam-break gate; otherwise a boundary particle like the others.
// retired: taken out of the run (past an outflow buffer, or spilled there) but kept in the arrays, at
// rest with mass 0, until the next neighbour search drops it, so that leaving water does not renew
// the search by itself. Every pair term carries m_j or V_j = m_j/rho_j, so it acts on nothing; it is
// never written (outputs and checkpoints drop it first).
enum class ParticleType : std::uint8_t { fluid = 0, boundary = 1, inflow = 2, outflow = 3, moving_wall = 4, retired = 5 };

// Fixed and moving walls: the particles of the boundary conditions (DBC, mDBC).
inline bool is_wall_type(std::uint8_t t) {
  return t == static_cast<std::uint8_t>(ParticleType::boundary) || t == static_cast<std::uint8_t>(ParticleType::moving_wall);
}

using Vector = Eigen::VectorXd;
using IdVector = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1>;
using TypeVector = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>;

// All particles of a 2D run (x horizontal, z vertical). Fluid and boundary particles share the
// arrays; `type` tells them apart. Every array has size() entries.
struct ParticleSet {
  // State integrated in time.
  Vector x, z;        // position (m)
  Vector u, w;        // velocity (m/s)
  Vector rho;         // density (kg/m^3)
  // Constant per particle.
  Vector mass;        // kg per metre of width (2D)
  IdVector id;        // stable identity, survives reordering and restarts
  TypeVector type;    // ParticleType
  Vector ghost_dx, ghost_dz;  // boundary particles: mirror (ghost node) minus position, for mDBC
  Vector wall_u, wall_w;      // boundary particles: velocity seen by the viscous terms (mDBC no-slip)
  // Integrator storage: state at the start of the step (symplectic) or at the previous step (Verlet).
  Vector x_old, z_old, u_old, w_old, rho_old;
  // Derived and rates, recomputed by every interaction.
  Vector p;           // pressure (Pa)
  Vector ax, az;      // acceleration (m/s^2)
  Vector drho;        // density rate (kg/m^3/s)
  // Sub-particle-scale stress over density tau/rho (m^2/s^2), laminar_sps only.
  Vector tau_xx, tau_xz, tau_zz;
  // Where the solver's last neighbour search saw each particle (its Verlet list, neighbour_list.hpp);
  // NaN after a change of the particle count (the list no longer fits). Saved with checkpoints, so a
  // resumed run rebuilds the very list it left.
  Vector x_search, z_search;

  Eigen::Index size() const { return x.size(); }
  bool is_fluid(Eigen::Index i) const { return type[i] == static_cast<std::uint8_t>(ParticleType::fluid); }
  Eigen::Index fluid_count() const;
  // The water in the domain (kg/m): fluid and outflow-buffer particles. An inflow buffer's total
  // counts a particle when it becomes fluid, an outflow buffer's or a tailgate's when it is removed, so
  // with such boundaries water_mass(t) - water_mass(0) = inflow - outflow. (A piston reservoir's water
  // is fluid before its gate crossing counts it.)
  double water_mass() const;

  // Resizes every array to n (new entries are zero); a new count voids the neighbour search (NaN).
  void resize(Eigen::Index n);
  // Sets particle i to rest at (px, pz) with the given density and mass (i < size()).
  void assign(Eigen::Index i, ParticleType t, double px, double pz, double density, double particle_mass,
              std::int64_t particle_id);
  // Retires particle i (type retired, mass 0, at rest); remove_retired (open_boundaries.hpp) drops it.
  void retire(Eigen::Index i);
  // Reorders every array so that new[k] = old[order[k]].
  void permute(const std::vector<int>& order);
  // Visits every double array (for checkpoints and permutation), in a fixed order.
  void for_each_real_array(const std::function<void(Vector&)>& f);
  void for_each_real_array(const std::function<void(const Vector&)>& f) const;
};

}  // namespace hydrojump::sph
