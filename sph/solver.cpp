#include "sph/solver.hpp"

#include <cmath>
#include <utility>

#include "sph/boundary_mdbc.hpp"
#include "sph/density_outliers.hpp"
#include "sph/parallel.hpp"
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
  skin_ = search_skin(settings_);
  // A resumed run's particles remember the search it left: rebuild that one, not a new one.
  if (!search_positions_current()) remember_search_positions();
  search_neighbours();
  update_pressure();
}

// The Verlet list's skin: a tenth of the support, so that the list lasts while the fastest particle
// moves 0.05 support (about ten interactions in a jump run at CFL 0.2 with c0 = 10 U). None on a
// periodic domain too short for cells of support + skin (CellGrid::periodic_x needs three, counted
// as it counts them, so that a tie falls back to no skin rather than failing there).
double Solver::search_skin(const SolverSettings& s) {
  const double skin = 0.1 * s.support();
  if (s.domain.periodic_x && std::floor((s.domain.x_max - s.domain.x_min) / (s.support() + skin)) < 3.0) return 0.0;
  return skin;
}

bool Solver::search_current() const { return neighbours_.particles() == particles_.size() && search_positions_current(); }

bool Solver::search_positions_current() const {
  const ParticleSet& ps = particles_;
  const Eigen::Index n = ps.size();
  if (ps.x_search.size() != n || ps.z_search.size() != n) return false;
  const double limit2 = 0.25 * skin_ * skin_;
  bool current = true;
#pragma omp parallel for schedule(static) reduction(&& : current) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dx = ps.x[i] - ps.x_search[i], dz = ps.z[i] - ps.z_search[i];
    current = current && dx * dx + dz * dz <= limit2;  // NaN: not current
  }
  return current;
}

void Solver::remember_search_positions() {
  particles_.x_search = particles_.x;
  particles_.z_search = particles_.z;
}

CellGrid::Box Solver::grid_limit() const {
  const double pad = settings_.domain.margin + 3.0 * settings_.support();
  return {settings_.domain.x_min - pad, settings_.domain.x_max + pad, settings_.domain.z_min - pad, settings_.domain.z_max + pad};
}

void Solver::search_neighbours() {
  const ParticleSet& ps = particles_;
  const double reach = settings_.support() + skin_;
  const CellGrid grid = settings_.domain.periodic_x
                            ? CellGrid::periodic_x(settings_.domain.x_min, settings_.domain.x_max, ps.z_search, reach)
                            : CellGrid::enclosing(ps.x_search, ps.z_search, reach, grid_limit());
  cells_.build(ps.x_search, ps.z_search, grid);
  bool identity = true;
  const auto& order = cells_.order();
  for (std::size_t k = 0; k < order.size() && identity; ++k) identity = order[k] == static_cast<int>(k);
  if (!identity) {
    particles_.permute(order);
    cells_.mark_sorted();
  }
  neighbours_.build(ps.x_search, ps.z_search, ps.type, cells_, reach, settings_.boundary == BoundaryMethod::dbc);
  if (settings_.boundary == BoundaryMethod::mdbc) ghosts_.build(ps.x_search, ps.z_search, ps, cells_, settings_, reach);
}

InteractionSummary Solver::interactions() {
  if (!search_current()) {
    remove_retired(particles_);  // a search is due: drop what left the run since the last one
    remember_search_positions();
    search_neighbours();
  }
  if (settings_.boundary == BoundaryMethod::mdbc) mdbc_boundary_density(particles_, ghosts_, settings_);
  compute_pressure(particles_, settings_);
  return compute_interactions(particles_, neighbours_, settings_,
                              settings_.viscosity.sps_wall_distance_table ? &wall_distances_ : nullptr);
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
  const DensityOutliers outliers = remove_density_outliers(particles_, settings_);
  clock_.outlier_particles += outliers.particles;
  clock_.outlier_mass += outliers.mass;
  open_.forget_removed(outliers.x_m, outliers.mass_kg);
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
