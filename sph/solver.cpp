#include "sph/solver.hpp"

#include <utility>

#include "sph/boundary_mdbc.hpp"
#include "sph/particle_health.hpp"
#include "sph/time_integration.hpp"

namespace hydrojump::sph {

Solver::Solver(SolverSettings settings, ParticleSet particles, SolverClock clock, OpenBoundaries open)
    : settings_(std::move(settings)), particles_(std::move(particles)), clock_(clock), open_(std::move(open)) {
  settings_.validate();
  if (settings_.viscosity.sps_wall_distance_table) {
    // Far enough for l = min(l_m, kappa d) to reach l_m; nodes at dx/2.
    wall_distances_ = WallDistanceTable::tabulate(particles_, mixing_length_wall_reach(settings_.viscosity.sps_length, settings_.dx),
                                                  0.5 * settings_.dx, settings_.domain.periodic_x, settings_.domain.x_min, settings_.domain.x_max);
  }
  open_.start(particles_);
  if (clock_.outflow_target_depth > 0.0) open_.set_outflow_target_depth(clock_.outflow_target_depth);
  update_pressure();
}

CellGrid::Box Solver::grid_limit() const {
  const double pad = settings_.domain.margin + 3.0 * settings_.support();
  return {settings_.domain.x_min - pad, settings_.domain.x_max + pad, settings_.domain.z_min - pad, settings_.domain.z_max + pad};
}

void Solver::sort_by_cell() {
  const CellGrid grid = settings_.domain.periodic_x
                            ? CellGrid::periodic_x(settings_.domain.x_min, settings_.domain.x_max, particles_.z, settings_.support())
                            : CellGrid::enclosing(particles_.x, particles_.z, settings_.support(), grid_limit());
  cells_.build(particles_.x, particles_.z, grid);
  bool identity = true;
  const auto& order = cells_.order();
  for (std::size_t k = 0; k < order.size() && identity; ++k) identity = order[k] == static_cast<int>(k);
  if (!identity) {
    particles_.permute(order);
    cells_.mark_sorted();
  }
}

InteractionSummary Solver::interactions() {
  sort_by_cell();
  if (settings_.boundary == BoundaryMethod::mdbc) mdbc_boundary_density(particles_, cells_, settings_);
  compute_pressure(particles_, settings_);
  return compute_interactions(particles_, cells_, settings_, settings_.viscosity.sps_wall_distance_table ? &wall_distances_ : nullptr);
}

void Solver::step() {
  const InteractionSummary start = interactions();
  const double dt = variable_time_step(start, settings_);
  const double t = clock_.time;
  const WallMotion walls = settings_.wall_motion.for_step(particles_);
  if (settings_.time.integrator == TimeIntegrator::symplectic) {
    symplectic_predictor(particles_, settings_, dt);
    move_walls(particles_, walls, t, t + 0.5 * dt);
    interactions();
    const bool shifting = settings_.shifting.model != ParticleShifting::none;
    if (shifting) concentration_gradients(particles_, cells_, settings_, shifting_gradients_);
    symplectic_corrector(particles_, settings_, dt);
    if (shifting) shift_particles(particles_, shifting_gradients_, settings_, dt, &cells_);
    move_walls(particles_, walls, t + 0.5 * dt, t + dt);
  } else {
    const bool euler = clock_.steps % settings_.time.verlet_euler_interval == 0;
    verlet_update(particles_, settings_, dt, euler);
    move_walls(particles_, walls, t, t + dt);
  }
  // Not after a step that left a fluid particle unhealthy: the buffers would reset or remove it as
  // outflow before the run's check sees it (sph/particle_health.hpp); the run stops on it instead.
  const OpenBoundaryTotals crossed =
      all_fluid_healthy(particles_, settings_) ? open_.advance(particles_, t, dt) : OpenBoundaryTotals{};
  clock_.outflow_target_depth = open_.outflow_target_depth();
  clock_.inflow_mass += crossed.mass_in;
  clock_.outflow_mass += crossed.mass_out;
  clock_.time += dt;
  clock_.last_dt = dt;
  ++clock_.steps;
}

void Solver::update_pressure() { compute_pressure(particles_, settings_); }

void Solver::set_tailwater_control(double outflow_target_depth_m, double held_volume_m2) {
  open_.set_outflow_target_depth(outflow_target_depth_m);
  clock_.outflow_target_depth = open_.outflow_target_depth();
  clock_.held_volume_m2 = held_volume_m2;
}

}  // namespace hydrojump::sph
