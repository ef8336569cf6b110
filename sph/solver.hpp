// The SPH solver: particles, settings and the time step as a script.
//
//   symplectic:  interactions(); dt = time_step(); predictor(dt); interactions(); corrector(dt);
//   verlet:      interactions(); dt = time_step(); verlet(dt);
//
// interactions() sorts the particles by cell (the order of the neighbour search), computes the
// boundary densities (mDBC), pressures, SPS stresses and the rates. All loops gather per particle,
// so a step gives the same result with any number of OpenMP threads.
#pragma once

#include <cstdint>

#include "sph/cell_list.hpp"
#include "sph/interactions.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {

// The clock of a run, saved with checkpoints.
struct SolverClock {
  double time = 0.0;        // simulated time (s)
  double last_dt = 0.0;     // the last time step (s)
  std::int64_t steps = 0;   // completed steps
};

class Solver {
 public:
  Solver(SolverSettings settings, ParticleSet particles, SolverClock clock = {});

  // Advances the state by one time step.
  void step();

  const SolverSettings& settings() const { return settings_; }
  const ParticleSet& particles() const { return particles_; }
  const SolverClock& clock() const { return clock_; }
  double time() const { return clock_.time; }
  // Nominal acoustic time step CFL h / c0 (used to detect a collapsing time step).
  double acoustic_time_step() const { return settings_.cfl * settings_.h / settings_.eos.c0; }
  // Pressures of the current state (for output): recomputed from the densities.
  void update_pressure();

 private:
  InteractionSummary interactions();
  void sort_by_cell();

  SolverSettings settings_;
  ParticleSet particles_;
  SolverClock clock_;
  CellList cells_;
};

}  // namespace hydrojump::sph
