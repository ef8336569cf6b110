// The SPH solver: particles, settings and the time step as a script.
//
//   symplectic:  interactions(); dt = time_step(); predictor(dt); move_walls(t, t + dt/2);
//                interactions(); [concentration_gradients();] corrector(dt); [shift_particles(dt);]
//                move_walls(t + dt/2, t + dt);
//   verlet:      interactions(); dt = time_step(); verlet(dt); move_walls(t, t + dt);
//   both then:   remove_density_outliers(); open_boundaries(t, dt);
//
// remove_density_outliers() takes out the fluid particles whose density left [0.7, 1.3] rho0
// (sph/density_outliers.hpp), counted in the clock.
// move_walls() moves the moving_wall particles by their prescribed motion (sph/wall_motion.hpp).
//
// open_boundaries() advances the inflow/outflow buffers (sph/open_boundaries.hpp) of a stilling
// basin: it moves the buffer particles, turns inflow particles into fluid and fluid into outflow
// particles, and moves the outlet's target depth at the level control's instants
// (sph/outflow_level_control.hpp); nothing for closed cases.
//
// concentration_gradients() and shift_particles() (sph.particle_shifting = "fickian", particle_shifting.hpp):
// the concentration gradient from the corrector's interaction (at the predictor's half-step
// positions), then the fluid particles' displacement down it after the corrector.
//
// interactions() renews the neighbour search when a particle has moved too far since the last one
// (Verlet lists with a skin: the particles sorted by cell, the pairs closer than the support plus the
// skin listed, and with mDBC each wall particle's ghost-node neighbours), then computes the boundary densities (mDBC), pressures, SPS stresses and the rates. Every loop adds to a particle in a
// fixed order (the pair loop: each particle over its own full neighbour list),
// so a step gives the same result with any number of OpenMP threads.
#pragma once

#include <cstdint>

#include "sph/boundary_mdbc.hpp"
#include "sph/cell_list.hpp"
#include "sph/interactions.hpp"
#include "sph/open_boundaries.hpp"
#include "sph/particle_shifting.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"
#include "sph/wall_distance.hpp"

namespace hydrojump::sph {

// The clock of a run, saved with checkpoints.
struct SolverClock {
  double time = 0.0;        // simulated time (s)
  double last_dt = 0.0;     // the last time step (s)
  std::int64_t steps = 0;   // completed steps
  // Open boundaries: mass injected at the inflows and removed at the outflows since t = 0 (kg/m).
  double inflow_mass = 0.0;
  double outflow_mass = 0.0;
  // The outflow buffers' target depth y_t (m), moved by a level control (outflow_level_control.hpp);
  // 0: the case's tailwater depth (a run not yet started, or no outflow buffers).
  double outflow_target_depth = 0.0;
  // The integral part I of the toe-holding control's water volume target V* (m^2,
  // toe_hold_control.hpp); 0: none, or not started.
  double held_volume_m2 = 0.0;
  // Fluid particles removed as density outliers since t = 0 (sph/density_outliers.hpp): count, mass (kg/m).
  std::int64_t outlier_particles = 0;
  double outlier_mass = 0.0;
};

class Solver {
 public:
  Solver(SolverSettings settings, ParticleSet particles, SolverClock clock = {}, OpenBoundaries open = {});

  // Advances the state by one time step.
  void step();

  const SolverSettings& settings() const { return settings_; }
  // The particles; water that left through an outflow buffer stays among them, retired
  // (ParticleType::retired), until the next neighbour search or drop_retired().
  const ParticleSet& particles() const { return particles_; }
  // Drops the retired particles now (before outputs and checkpoints); the next step then renews the
  // neighbour search.
  void drop_retired() { remove_retired(particles_); }
  const SolverClock& clock() const { return clock_; }
  // The inflow/outflow buffers and their mass totals since this solver was made.
  const OpenBoundaries& open_boundaries() const { return open_; }
  double time() const { return clock_.time; }
  // Nominal acoustic time step CFL h / c0 (used to detect a collapsing time step).
  double acoustic_time_step() const { return settings_.time.cfl * settings_.h / settings_.eos.c0; }
  // Pressures of the current state (for output): recomputed from the densities.
  void update_pressure();
  // The toe-holding control's step (toe_hold_control.hpp): the outflow buffers' new target depth and
  // V*, both kept in the clock (and so in checkpoints).
  void set_tailwater_control(double outflow_target_depth_m, double held_volume_m2);

 private:
  InteractionSummary interactions();
  // The neighbour search (a Verlet list, neighbour_list.hpp): current while every particle is within
  // skin/2 of where it saw them (x_search, z_search); search_neighbours() sorts the particles by the
  // cells of those positions and lists the pairs closer than support + skin there.
  static double search_skin(const SolverSettings& s);
  bool search_current() const;
  bool search_positions_current() const;  // every particle within skin/2 of x_search, z_search
  void remember_search_positions();
  void search_neighbours();
  // The cell grid's extent: the domain box plus the tolerated margin and three kernel supports (the
  // boundary particles' layers); fluid beyond it is stopped by the run's checks after the step.
  CellGrid::Box grid_limit() const;

  SolverSettings settings_;
  ParticleSet particles_;
  SolverClock clock_;
  OpenBoundaries open_;
  CellList cells_;           // of the last search's positions, cells of support + skin
  NeighbourList neighbours_;
  GhostNeighbourList ghosts_;  // mDBC: the fluid side of each wall particle's ghost node
  double skin_ = 0.0;
  // sph.sps_wall_distance = "whole_domain": the fixed walls' distance table (wall_distance.hpp).
  WallDistanceTable wall_distances_;
  // sph.particle_shifting: the last concentration gradients (storage reused from step to step).
  ConcentrationGradients shifting_gradients_;
};

}  // namespace hydrojump::sph
