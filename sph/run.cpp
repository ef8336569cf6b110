#include "sph/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

#include "util/atomic_file.hpp"
#include "sph/density_outliers.hpp"
#include "sph/kernel.hpp"
#include "sph/particle_health.hpp"
#include "sph/vtk_output.hpp"

namespace hydrojump::sph {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--:--";
  const long t = static_cast<long>(s + 0.5);
  std::ostringstream o;
  o << std::setfill('0') << std::setw(2) << t / 3600 << ':' << std::setw(2) << (t / 60) % 60 << ':' << std::setw(2)
    << t % 60;
  return o.str();
}

std::string describe(const ParticleSet& ps, Eigen::Index i) {
  std::ostringstream o;
  const char* name = "unknown-type";
  switch (static_cast<ParticleType>(ps.type[i])) {
    case ParticleType::fluid: name = "fluid"; break;
    case ParticleType::boundary: name = "boundary"; break;
    case ParticleType::inflow: name = "inflow-buffer"; break;
    case ParticleType::outflow: name = "outflow-buffer"; break;
    case ParticleType::moving_wall: name = "moving-wall"; break;
    case ParticleType::retired: name = "retired"; break;
  }
  o << name << " particle id " << ps.id[i] << " at (x, z) = (" << ps.x[i] << ", "
    << ps.z[i] << ") m, velocity (" << ps.u[i] << ", " << ps.w[i] << ") m/s, density " << ps.rho[i] << " kg/m^3";
  return o.str();
}

class RunState {
 public:
  RunState(Solver& solver, const RunOptions& o) : solver_(solver), o_(o), series_(o.dir, "particles") {
    if (o.basin) basin_.emplace(*o.basin);
  }

  // `extending`: the run goes on past the checkpoint's time. An end-state output between two output
  // times (the last run's --end-time off the grid) is then dropped, so that the extended run's series,
  // logs and window means are those of an uninterrupted run (its .vtp is overwritten by the next output).
  void restore(const Checkpoint& c, bool extending) {
    next_output_ = c.next_output_time;
    auto series = c.series;
    auto log_rows = c.log_rows, gauge_rows = c.gauge_rows, basin_rows = c.basin_rows;
    const bool dropped = extending && c.last_output_is_end_state;
    if (dropped) {
      for (auto* rows : {&log_rows, &gauge_rows, &basin_rows})
        if (!rows->empty()) rows->pop_back();
      if (!series.empty()) series.pop_back();
    }
    end_state_output_ = c.last_output_is_end_state && !dropped;
    series_.restore(std::move(series));
    log_rows_ = std::move(log_rows);
    gauge_rows_ = std::move(gauge_rows);
    if (basin_) basin_->restore(basin_rows);
    if (dropped) {  // the files without it at once, not only at the next output
      series_.rewrite_pvd();
      write_tables();
    }
  }

  // The end state of a run that stops between two output times (not on the grid).
  void write_end_state_output() {
    write_output();
    end_state_output_ = true;
  }

  void write_output() {
    end_state_output_ = false;
    solver_.drop_retired();  // outputs hold only the particles in the run
    solver_.update_pressure();
    const ParticleSet& ps = solver_.particles();
    const double t = solver_.time();
    series_.write(ps, t);
    // Run log.
    const auto& s = solver_.settings();
    // The water mass with the outflow buffers' particles, which the outflow total counts only when
    // they are removed; the energies and the density variation of the fluid.
    const double mass = ps.water_mass();
    double kinetic = 0.0, potential = 0.0, max_var = 0.0;
    for (Eigen::Index i = 0; i < ps.size(); ++i) {
      if (!ps.is_fluid(i)) continue;
      kinetic += 0.5 * ps.mass[i] * (ps.u[i] * ps.u[i] + ps.w[i] * ps.w[i]);
      potential += -ps.mass[i] * s.body_force_z * ps.z[i];
      max_var = std::max(max_var, std::abs(ps.rho[i] / s.eos.rho0 - 1.0));
    }
    std::ostringstream row;
    row << std::setprecision(10) << t << ',' << solver_.clock().steps << ',' << solver_.clock().last_dt << ',' << mass
        << ',' << kinetic << ',' << potential << ',' << max_var << ',' << ps.fluid_count() << ','
        << solver_.clock().inflow_mass << ',' << solver_.clock().outflow_mass << ',' << solver_.clock().outlier_mass;
    log_rows_.push_back(row.str());
    // Gauges.
    std::ostringstream g;
    g << std::setprecision(10) << t;
    for (const auto& gauge : o_.gauges) {
      const double surface = surface_elevation_at(ps, gauge.x_m, s.dx);
      const auto [u, w] = velocity_at(ps, s, gauge.x_m, 0.5 * (o_.bed_elevation(gauge.x_m) + surface));
      g << ',' << surface << ',' << u << ',' << w;
    }
    if (o_.record_front) g << ',' << surge_front_x(ps, s.dx, o_.front_layer_m);
    gauge_rows_.push_back(g.str());
    // Stilling basins: toe, discharges, sections, summary.
    if (basin_) {
      const double y_t = solver_.open_boundaries().outflows().empty() ? std::numeric_limits<double>::quiet_NaN()
                                                                      : solver_.open_boundaries().outflow_target_depth();
      basin_->record(ps, t, solver_.clock().inflow_mass, solver_.clock().outflow_mass, y_t, solver_.clock().outlier_mass);
    }
    write_tables();
  }

  // run_log.csv, gauges.csv and (stilling basins) basin.csv and summary.json from the rows so far.
  void write_tables() const {
    util::write_file_atomically(
        o_.dir / "run_log.csv",
        join("t_s,step,dt_s,fluid_mass_kg_per_m,kinetic_energy_J_per_m,potential_energy_J_per_m,max_density_variation,"
             "fluid_particles,inflow_mass_kg_per_m,outflow_mass_kg_per_m,outlier_mass_kg_per_m",
             log_rows_));
    std::string header = "t_s";
    for (const auto& gauge : o_.gauges)
      header += ",surface_z_" + gauge.name + "_m,u_" + gauge.name + "_m_s,w_" + gauge.name + "_m_s";
    if (o_.record_front) header += ",front_x_m";
    util::write_file_atomically(o_.dir / "gauges.csv", join(header, gauge_rows_));
    if (basin_) {
      util::write_file_atomically(o_.dir / "basin.csv", basin_->csv());
      util::write_file_atomically(o_.dir / "summary.json", basin_->summary_json());
    }
  }

  // The toe-holding control's step at an output on the grid, from the sample just recorded
  // (toe_hold_control.hpp); an end-state output between two grid times does not steer.
  void steer_tailwater() {
    if (!basin_ || !o_.toe_hold || basin_->samples().empty()) return;
    const BasinSample& s = basin_->samples().back();
    const ToeHoldState next = toe_hold_step(*o_.toe_hold, solver_.clock().held_volume_m2, s.fluid_mass, s.toe_x);
    solver_.set_tailwater_control(next.outlet_depth_m, next.volume_integral_m2);
  }

  std::string status() const { return basin_ ? basin_->status_line() : std::string(); }
  // What the run monitor knew when a run failed: a jump swept out of the basin or drowned at the
  // inflow explains most "particle left the domain" stops of stilling basins (a bad tailwater).
  std::string jump_note() const {
    if (!basin_) return {};
    const std::string state = basin_->jump_state();
    if (state == "swept_downstream")
      return "\n  Before this, the run monitor had found the jump swept downstream (" + basin_->status_line() +
             "): the tailwater holds no jump here, and the supercritical stream reaching the outlet makes splashes.";
    if (state == "at_inflow")
      return "\n  Before this, the run monitor had found the jump drowned at the inflow (" + basin_->status_line() +
             "): the tailwater is too high for this inflow.";
    return {};
  }

  void write_checkpoint_now() {
    // Dropped in the solver itself, not only in the copy saved: the run then renews its neighbour
    // search at the next step as a run resumed from this checkpoint does, and both go on alike.
    solver_.drop_retired();
    Checkpoint c;
    c.fingerprint = o_.fingerprint;
    c.clock = solver_.clock();
    c.particles = solver_.particles();
    c.next_output_time = next_output_;
    c.last_output_is_end_state = end_state_output_;
    c.series = series_.entries();
    c.log_rows = log_rows_;
    c.gauge_rows = gauge_rows_;
    if (basin_) c.basin_rows = basin_->csv_rows();
    write_checkpoint(c, checkpoint_path(o_.dir));
  }

  double last_output_time() const { return series_.entries().empty() ? -1.0 : series_.entries().back().first; }

  double next_output_ = 0.0;

 private:
  bool end_state_output_ = false;  // the last output is an off-grid end state (Checkpoint)
  static std::string join(const std::string& header, const std::vector<std::string>& rows) {
    std::string out = header + "\n";
    for (const auto& r : rows) out += r + "\n";
    return out;
  }
  Solver& solver_;
  const RunOptions& o_;
  ParticleSeries series_;
  std::vector<std::string> log_rows_, gauge_rows_;
  std::optional<BasinMonitor> basin_;
};

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& dir) { return dir / "checkpoint.bin"; }

double surface_elevation_at(const ParticleSet& ps, double x, double dx) {
  double top = std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && std::abs(ps.x[i] - x) < dx && !(ps.z[i] + 0.5 * dx <= top)) top = ps.z[i] + 0.5 * dx;
  return top;
}

double surge_front_x(const ParticleSet& ps, double dx, double layer_m) {
  std::vector<double> xs;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && ps.z[i] < layer_m) xs.push_back(ps.x[i]);
  if (xs.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(xs.begin(), xs.end());
  double front = xs.front();
  for (const double x : xs) {
    if (x - front > 2.0 * dx) break;
    front = x;
  }
  return front + 0.5 * dx;
}

std::pair<double, double> velocity_at(const ParticleSet& ps, const SolverSettings& s, double x, double z) {
  const Kernel kernel = Kernel::make(std::string(cases::option_name(s.kernel)), s.h);
  double sum_w = 0.0, sum_u = 0.0, sum_v = 0.0;
  const double period = s.domain.x_max - s.domain.x_min;
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    if (!ps.is_fluid(i)) continue;
    double dx = x - ps.x[i];
    if (s.domain.periodic_x) dx -= period * std::round(dx / period);
    const double r = std::hypot(dx, z - ps.z[i]);
    if (r >= 2.0 * s.h) continue;
    const double vw = ps.mass[i] / ps.rho[i] * kernel.value(r);
    sum_w += vw;
    sum_u += vw * ps.u[i];
    sum_v += vw * ps.w[i];
  }
  if (!(sum_w > 0.0) || !std::isfinite(z)) return {std::nan(""), std::nan("")};
  return {sum_u / sum_w, sum_v / sum_w};
}

std::string diagnose(const Solver& solver) {
  const ParticleSet& ps = solver.particles();
  const SolverSettings& s = solver.settings();
  const double t = solver.time();
  std::ostringstream out;
  int reported = 0;
  auto report = [&](const std::string& what, Eigen::Index i) {
    if (reported < 5) out << "  " << what << ": " << describe(ps, i) << "\n";
    ++reported;
  };
  // Fluid first (where an instability starts), then the walls it spread to (sph/particle_health.hpp).
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    if (!ps.is_fluid(i)) continue;
    switch (fluid_health(ps, i, s)) {
      case FluidHealth::ok:
        break;
      case FluidHealth::non_finite:
        report("non-finite state (NaN/Inf)", i);
        break;
      case FluidHealth::below_bed:
        // Below every wall: it went through the boundary particles, not over them.
        report("left the domain through the bottom (it passed through the bed's boundary particles: look for a gap in "
               "the wall near this x in initial_particles.vtp, or a wall too soft for the impact: a larger "
               "sph.sound_speed_coefficient or sph.boundary_layers)",
               i);
        break;
      case FluidHealth::outside:
        report("left the domain", i);
        break;
      case FluidHealth::density: {
        std::ostringstream w;
        w << "|rho/rho0 - 1| = " << std::abs(ps.rho[i] / s.eos.rho0 - 1.0) << " above the limit "
          << s.density.max_variation << " (sph.max_density_variation)";
        report(w.str(), i);
        break;
      }
    }
  }
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    if (!ps.is_fluid(i) && !std::isfinite(ps.rho[i])) report("non-finite density", i);
  }
  // Density outliers removed (sph/density_outliers.hpp): beyond a small share the water itself is unhealthy.
  const SolverClock& clock = solver.clock();
  const double water = ps.water_mass();
  if (clock.outlier_mass > kOutlierMassShareLimit * water) {
    out << "  " << clock.outlier_particles << " fluid particles (" << clock.outlier_mass << " kg/m, "
        << 100.0 * clock.outlier_mass / water << " % of the water's " << water
        << " kg/m) have been removed since t = 0 because their density left [" << kOutlierDensityLow << ", "
        << kOutlierDensityHigh << "] rho0: more than " << 100.0 * kOutlierMassShareLimit
        << " % of the water. Try a smaller sph.cfl_number or a finer resolution.\n";
    ++reported;
  }
  const double dt = solver.clock().last_dt;
  if (solver.clock().steps > 0 && !(dt >= 1e-3 * solver.acoustic_time_step())) {
    out << "  time step collapsed: dt = " << dt << " s, below 1e-3 of the acoustic step CFL h/c0 = "
        << solver.acoustic_time_step() << " s (a particle is being accelerated without bound)\n";
    ++reported;
  }
  if (reported == 0) {
    // A level-holding piston that has nearly reached the gate: the reservoir is used up.
    const WallMotion& piston = s.wall_motion;
    if (piston.holds_level()) {
      const double face = moving_face_x(ps);
      if (piston.reservoir_end_x_m - face < piston.held_level_m) {
        std::ostringstream e;
        e << "the piston reservoir is used up at t = " << t << " s: the piston face is at x = " << face
          << " m, less than H_r = " << piston.held_level_m << " m before the gate (x = " << piston.reservoir_end_x_m
          << " m). Holding the level, the piston pushes what the gate passes; when that is more than q the jet "
             "contracts less than the opening assumes (Cc = 0.611): give a smaller sph.sluice_opening_m (y1/Cc with "
             "the Cc this resolution gives) or a longer sph.reservoir_length_m.";
        return e.str();
      }
    }
    return {};
  }
  std::ostringstream head;
  head << "the SPH run went unstable at t = " << t << " s (step " << solver.clock().steps << "); " << reported
       << " problem(s)" << (reported > 5 ? ", the first 5:" : ":") << "\n"
       << out.str();
  head << "  domain box [" << s.domain.x_min << ", " << s.domain.x_max << "] x [" << s.domain.z_min << ", " << s.domain.fluid_ceiling << "] m (margin " << s.domain.margin
       << " m). Try a smaller sph.cfl_number, a finer resolution, or check the geometry.";
  return head.str();
}

RunStatus run_case(Solver& solver, const RunOptions& o, const std::optional<Checkpoint>& resume) {
  std::filesystem::create_directories(o.dir);
  RunState state(solver, o);
  if (resume) {
    state.restore(*resume, o.end_time_s > solver.time() + 1e-12);
  } else {
    state.write_output();
    state.steer_tailwater();
    state.next_output_ = o.output_interval_s;
  }
  const auto t_start = Clock::now();
  auto last_checkpoint = t_start, last_progress = t_start;
  const double t0 = solver.time();
  std::int64_t steps_here = 0;
  auto progress = [&](bool final_line) {
    if (o.progress == nullptr) return;
    const double wall = seconds_since(t_start);
    const double rate = static_cast<double>(steps_here) / std::max(wall, 1e-9);
    const double done = solver.time() - t0;
    const double eta = done > 0 ? wall * (o.end_time_s - solver.time()) / done : -1.0;
    std::ostringstream line;
    line << std::fixed << std::setprecision(4) << "t = " << solver.time() << " / " << o.end_time_s << " s  step "
         << solver.clock().steps << "  dt " << std::scientific << std::setprecision(2) << solver.clock().last_dt
         << " s  " << std::fixed << std::setprecision(1) << rate << " steps/s  ETA " << format_duration(eta);
    const std::string basin = state.status();
    if (!basin.empty()) line << "  |  " << basin;
    if (o.progress_is_terminal) *o.progress << '\r' << line.str() << "   " << (final_line ? "\n" : "") << std::flush;
    else *o.progress << line.str() << "\n" << std::flush;
  };

  while (solver.time() < o.end_time_s - 1e-12) {
    if (o.stop_requested != nullptr && o.stop_requested->load()) {
      state.write_checkpoint_now();
      progress(true);
      return RunStatus::interrupted;
    }
    if (o.max_steps >= 0 && steps_here >= o.max_steps) {
      state.write_checkpoint_now();
      return RunStatus::step_limit;
    }
    const std::int64_t outliers_before = solver.clock().outlier_particles;
    solver.step();
    ++steps_here;
    if (solver.clock().outlier_particles > outliers_before && o.progress != nullptr)
      *o.progress << (o.progress_is_terminal ? "\n" : "") << "t = " << solver.time() << " s: removed "
                  << solver.clock().outlier_particles - outliers_before << " fluid particle(s) whose density left ["
                  << kOutlierDensityLow << ", " << kOutlierDensityHigh << "] rho0 (" << solver.clock().outlier_particles
                  << " since t = 0, " << solver.clock().outlier_mass << " kg/m; see sph/density_outliers.hpp)\n";
    const std::string problem = diagnose(solver);
    if (!problem.empty()) {
      std::string kept = std::filesystem::exists(checkpoint_path(o.dir))
                             ? "the last good checkpoint " + checkpoint_path(o.dir).string() + " is kept"
                             : "no checkpoint had been written yet";
      const std::string message = problem + state.jump_note() + "\n  The failing state is in " + (o.dir / "failure_state.vtp").string() +
                                  "; " + kept + ", with the outputs written before.";
      try {
        Solver copy = solver;
        copy.drop_retired();
        copy.update_pressure();
        write_particles_vtp(copy.particles(), o.dir / "failure_state.vtp");
        util::write_file_atomically(o.dir / "failure.txt", message + "\n");
      } catch (const std::exception&) {
        // The diagnosis itself is what matters.
      }
      if (o.progress && o.progress_is_terminal) *o.progress << "\n";
      throw SimulationFailure(message);
    }
    if (solver.time() >= state.next_output_ - 1e-12) {
      state.write_output();
      state.steer_tailwater();
      // The next output time: one interval on, or the first multiple of the interval past t when a
      // step has passed several (a loop adding the interval stalls once it is below t's round-off).
      const double next_multiple = (std::floor((solver.time() + 1e-12) / o.output_interval_s) + 1.0) * o.output_interval_s;
      state.next_output_ = std::max(state.next_output_ + o.output_interval_s, next_multiple);
    }
    if (seconds_since(last_checkpoint) >= o.checkpoint_interval_wall_s) {
      state.write_checkpoint_now();
      last_checkpoint = Clock::now();
    }
    const double since = seconds_since(last_progress);
    if (since >= (o.progress_is_terminal ? 1.0 : 10.0)) {
      progress(false);
      last_progress = Clock::now();
    }
  }
  if (state.last_output_time() < solver.time() - 1e-12) state.write_end_state_output();  // the final state
  state.write_checkpoint_now();
  progress(true);
  return RunStatus::finished;
}

}  // namespace hydrojump::sph
