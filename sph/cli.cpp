#include "sph/cli.hpp"

#include "util/atomic_file.hpp"
#include "util/cli_checks.hpp"
#include "util/directory_lock.hpp"
#include "util/fingerprint.hpp"
#include "cases/results_case.hpp"
#include "util/stop_signals.hpp"
#include "util/system_memory.hpp"
#include "hydrojump/version.hpp"

#include <atomic>
#include <csignal>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <omp.h>
#include <unistd.h>

#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "cases/spec_reader.hpp"
#include "sph/bench.hpp"
#include "sph/checkpoint.hpp"
#include "sph/particle_generator.hpp"
#include "sph/run.hpp"
#include "sph/settings.hpp"
#include "sph/solver.hpp"
#include "sph/vtk_output.hpp"

namespace hydrojump::sph {

// The fingerprint that ties a checkpoint to its case: the case's setting lines and the solver code
// (solver_fingerprint, cmake/write_version.cmake: a comparator change keeps checkpoints). Setting
// lines (cases/results_case.hpp) leave out comments and descriptive texts, which a regenerated
// case.toml may word differently, and the run-control settings that never change the trajectory
// (the stability limit checked after each step and the checkpoint interval), so a run stopped at the
// density limit can be resumed from its last good checkpoint with a relaxed limit.
std::string run_fingerprint(const std::string& case_text) {
  std::string kept;
  for (const std::string& line : cases::setting_lines(case_text)) {
    kept += line;
    kept += '\n';
  }
  return util::fingerprint(kept + "\ncode " + solver_fingerprint);
}

namespace {

// Set by SIGINT, SIGTERM or SIGHUP; the run loop polls it, writes a checkpoint and returns. (A signal handler
// can only reach static storage; this flag is the one such object and only the handler writes it.)
std::atomic<bool> g_stop_requested{false};
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void request_stop(int sig) {
  g_stop_signal.store(sig);
  g_stop_requested.store(true);
}

}  // namespace

namespace {

// DIR must be an SPH run directory written by `generate`, not the OpenFOAM case beside it.
void check_run_directory(const std::filesystem::path& dir, const std::filesystem::path& case_file) {
  if (!std::filesystem::exists(case_file))
    throw std::runtime_error("'" + case_file.string() +
                             "' not found: DIR must be a directory written by `hydrojump generate` (DIR/<case>/sph)");
  // generate writes the same case.toml into DIR/<case>/vof: an OpenFOAM case is not an SPH run directory.
  if (std::filesystem::exists(dir / "system" / "controlDict")) {
    const auto named = dir.has_filename() ? dir : dir.parent_path();  // "runs/A/vof/" names runs/A/vof
    throw std::runtime_error("'" + dir.string() + "' is an OpenFOAM case (it has system/controlDict; run it with `hydrojump vof`): " +
                             "`hydrojump sph` runs the SPH directory beside it, " + (named.parent_path() / "sph").string());
  }
}

// The resolved case of a run directory: exactly one case at exactly one resolution.
cases::Study load_run_study(const std::filesystem::path& case_file) {
  cases::Study study = cases::load_study(case_file);
  if (study.cases.size() != 1)
    throw std::runtime_error("'" + case_file.string() + "' holds " + std::to_string(study.cases.size()) +
                             " cases; a run directory holds exactly one (write it with `hydrojump generate`)");
  if (study.cases.front().resolutions.size() != 1)
    throw std::runtime_error("'" + case_file.string() + "' defines " + std::to_string(study.cases.front().resolutions.size()) +
                             " resolutions; a run directory holds exactly one");
  return study;
}

// The run's end time: --end-time within what the case allows, else the case's own.
double run_end_time(const SphOptions& opt, const cases::Case& c, const std::filesystem::path& case_file) {
  if (opt.end_time > c.run.latest_end_time_s()) {
    std::ostringstream e;
    e << "--end-time " << opt.end_time << " s is out of range for '" << case_file.string() << "': must be <= "
      << c.run.latest_end_time_s() << " s (at most " << cases::max_outputs_per_run << " outputs, one every "
      << c.run.output_interval_s << " s, and at most " << cases::max_end_time_s << " s)";
    throw std::runtime_error(e.str());
  }
  const double end = opt.end_time > 0.0 ? opt.end_time : c.run.end_time_s;
  if (c.sph.inflow_condition == cases::InflowCondition::piston && end > c.run.end_time_s)
    throw std::runtime_error("'" + case_file.string() + "': --end-time " + std::to_string(end) +
                             " s runs past case.run.end_time_s = " + std::to_string(c.run.end_time_s) +
                             " s, for which the piston's stroke and the reservoir's length were made (sph.inflow_condition = "
                             "\"piston\"): the piston would stop and the inflow die. Raise case.run.end_time_s and "
                             "generate the case again.");
  return end;
}

RunOptions run_options(const SphOptions& opt, const cases::Study& study, const cases::CaseGeometry& geometry,
                       const SolverSettings& settings, const std::filesystem::path& case_file) {
  const cases::Case& c = study.cases.front();
  RunOptions ro;
  ro.dir = opt.dir;
  ro.end_time_s = run_end_time(opt, c, case_file);
  ro.output_interval_s = c.run.output_interval_s;
  ro.checkpoint_interval_wall_s = c.sph.checkpoint_interval_wall_s;
  // The resolved case and the program version: a checkpoint only resumes the run it was written for.
  ro.fingerprint = run_fingerprint(util::read_text_file(case_file));
  for (const auto& section : geometry.sections) ro.gauges.push_back({section.name, section.x_m});
  if (ro.gauges.empty()) ro.gauges.push_back({"centre", 0.5 * (geometry.x_min_m + geometry.x_max_m)});
  ro.bed_elevation = [bed = geometry.bed](double x) { return bed.elevation(x); };
  if (c.stilling_basin() != nullptr)
    ro.basin = BasinMonitorSetup::from_case(c, geometry, settings.dx, settings.eos.rho0);
  if (c.holds_toe()) ro.toe_hold = ToeHoldLaw::from_case(c, geometry, study.fluid.gravity_m_s2, settings.eos.rho0);
  if (const auto* d = c.dam_break()) {  // its gauges are among the geometry's sections
    ro.record_front = true;
    ro.front_layer_m = 0.1 * d->column_width_m;
  }
  if (!opt.quiet) {
    ro.progress = &std::cerr;
    ro.progress_is_terminal = ::isatty(STDERR_FILENO) != 0;
  }
  ro.stop_requested = &g_stop_requested;
  return ro;
}

// The checkpoint to resume (--resume), or nothing for a fresh start; refuses to overwrite a run that
// was neither resumed nor explicitly restarted.
std::optional<Checkpoint> previous_run(const SphOptions& opt, const std::filesystem::path& case_file, const RunOptions& ro) {
  const std::filesystem::path& dir = opt.dir;
  const auto ck = checkpoint_path(dir);
  if (opt.resume) {
    if (!std::filesystem::exists(ck))
      throw std::runtime_error("--resume: no checkpoint '" + ck.string() + "' to resume from");
    Checkpoint checkpoint = read_checkpoint(ck);
    if (checkpoint.fingerprint != ro.fingerprint)
      throw std::runtime_error("--resume: '" + case_file.string() +
                               "' changed since the checkpoint was written (beyond descriptive texts, the laboratory's "
                               "values and sph.max_density_variation and sph.checkpoint_interval_wall_s, which may "
                               "change); run with --restart to start over");
    if (checkpoint.clock.time >= ro.end_time_s - 1e-12)
      std::cerr << "hydrojump sph: the checkpoint is at t = " << checkpoint.clock.time
                << " s, already at or past the end time " << ro.end_time_s
                << " s: nothing to run (give a later --end-time to go on)\n";
    return checkpoint;
  }
  if (std::filesystem::exists(ck) && !opt.restart)
    throw std::runtime_error("'" + dir.string() +
                             "' already holds a run (checkpoint.bin): use --resume to continue it or --restart to "
                             "start over (overwriting its outputs)");
  if (!opt.restart) {
    // A run that stopped before its first checkpoint (a failure, a kill) left outputs but nothing to
    // resume: a plain start would delete them, the failure's diagnosis among them.
    for (const char* name : {"failure.txt", "particles.pvd"})
      if (std::filesystem::exists(dir / name))
        throw std::runtime_error("'" + dir.string() + "' already holds the outputs of a run that stopped before its first checkpoint (" +
                                 name + (std::string(name) == "failure.txt" ? ", its diagnosis" : "") +
                                 "): nothing to resume; use --restart to start over (deleting them)");
  }
  return std::nullopt;
}

// The memory an SPH run needs, measured with `hydrojump bench --model costliest --steps 3` at dx = 0.01,
// 0.005 and 0.0025 m (23k, 86k, 332k particles: peaks 34.9, 67.1, 195.7 MB), a line within 3 MB of
// each:  M = 25 MB + 0.52 kB N.
double run_memory_bytes(std::size_t particles) { return 25.0e6 + 520.0 * static_cast<double>(particles); }

// Refuses a run whose particles need more memory than the machine has available, before the solver
// allocates its neighbour lists and step arrays.
void check_run_memory(const cases::Case& c, const SolverSettings& settings, std::size_t particles) {
  std::ostringstream what, basis;
  what << "hydrojump sph: case \"" << c.id << "\" at dx = " << settings.dx << " m";
  basis << "25 MB + 0.52 kB a particle x " << particles << " particles";
  util::check_memory_need(what.str(), run_memory_bytes(particles), basis.str(),
                          "use a coarser resolution (a larger particle_spacing_m) or free memory");
}

// A fresh start removes the outputs of an earlier run in DIR, so that the new series is not mixed
// with stale snapshots, and records the case the results belong to.
void start_afresh(const std::filesystem::path& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const bool snapshot = name.rfind("particles_", 0) == 0 && entry.path().extension() == ".vtp";
    if (snapshot || name == "failure.txt" || name == "failure_state.vtp" || name == "checkpoint.bin")
      std::filesystem::remove(entry.path());
  }
  // What `compare` and `generate` check these results against.
  cases::record_results_case(dir);
}

std::unique_ptr<Solver> make_solver(const cases::Case& c, const cases::CaseGeometry& geometry, const SolverSettings& settings,
                                    std::optional<Checkpoint>& checkpoint, const std::filesystem::path& dir) {
  OpenBoundaries boundaries = OpenBoundaries::from_geometry(geometry, buffer_parameters(settings));
  if (checkpoint) {
    check_run_memory(c, settings, static_cast<std::size_t>(checkpoint->particles.size()));
    auto solver = std::make_unique<Solver>(settings, checkpoint->particles, checkpoint->clock, std::move(boundaries));
    checkpoint->particles = ParticleSet{};
    return solver;
  }
  ParticleSet particles = generate_particles(geometry, settings, c.sph.boundary_layers);
  check_run_memory(c, settings, static_cast<std::size_t>(particles.size()));
  auto solver = std::make_unique<Solver>(settings, std::move(particles), SolverClock{}, std::move(boundaries));
  // Not before the particles exist: a case the generator refuses leaves the earlier results beside
  // the record that made them.
  start_afresh(dir);
  return solver;
}

void print_run_header(const cases::Case& c, const cases::CaseGeometry& geometry, const SolverSettings& settings,
                      const Solver& solver, bool resumed) {
  std::cerr << "hydrojump sph: case \"" << c.id << "\" (" << c.kind << "), dx = " << settings.dx << " m, "
            << solver.particles().fluid_count() << " fluid + "
            << solver.particles().size() - solver.particles().fluid_count() << " boundary and buffer particles, "
            << omp_get_max_threads() << " thread(s), c0 = " << settings.eos.c0 << " m/s, "
            << (resumed ? "resuming at t = " + std::to_string(solver.time()) + " s" : std::string("from t = 0"))
            << "\n";
  if (settings.open.inflow == InflowCondition::piston) {
    const auto& piston = geometry.moving_walls.front();
    double opening = 0.0;
    for (const auto& wall : geometry.walls)
      if (wall.name == "sluice_gate") opening = wall.points[1].y();
    std::cerr << "hydrojump sph: piston inflow: reservoir from x = " << geometry.x_min_m << " m, level H_r = "
              << geometry.initial_water.surface_z_m.front() << " m, piston at " << piston.velocity_m_s.x()
              << " m/s until t = " << piston.end_s << " s, sluice gate opening " << opening << " m\n";
  }
  for (const Tailgate& gate : solver.open_boundaries().tailgates()) {
    // The design head over the crest and Rehbock's range (tailgate.hpp).
    const double q = cases::inflow_discharge(geometry);
    const double gravity = std::abs(settings.body_force_z);
    const double head = cases::rehbock_weir_head(q, gate.crest_height(), gravity);
    std::cerr << "hydrojump sph: tailgate at x = " << gate.section_x() << " m, crest " << gate.crest_height()
              << " m above the bed; Rehbock's weir passes q = " << q << " m^2/s with a head of " << head
              << " m (upstream depth " << gate.crest_height() + head << " m, H/P = " << head / gate.crest_height()
              << ")\n";
    if (head / gate.crest_height() > cases::rehbock_valid_head_ratio)
      std::cerr << "hydrojump sph: warning: H/P = " << head / gate.crest_height() << " is beyond Rehbock's range (<= "
                << cases::rehbock_valid_head_ratio
                << "): the gate is a low sill and the tailwater it holds may differ; see y2 in summary.json\n";
  }
}

}  // namespace

int run_sph_directory(const SphOptions& opt) {
  const std::filesystem::path dir = opt.dir;
  const std::filesystem::path case_file = dir / "case.toml";
  check_run_directory(dir, case_file);
  // One process per run directory (a second one stops here, naming the first).
  const util::DirectoryLock lock(dir, "hydrojump sph");
  // What a run killed outright left half-written (its complete files are all in place).
  util::remove_orphaned_temporaries(dir);
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const cases::Study study = load_run_study(case_file);
  const cases::Case& c = study.cases.front();
  const cases::Resolution& resolution = c.resolutions.begin()->second;
  const cases::CaseGeometry geometry = solver_geometry(c, study.fluid, resolution.particle_spacing_m);
  const SolverSettings settings = make_settings(c, study.fluid, geometry, resolution.particle_spacing_m);
  const RunOptions ro = run_options(opt, study, geometry, settings, case_file);
  std::optional<Checkpoint> checkpoint = previous_run(opt, case_file, ro);
  const bool resumed = checkpoint.has_value();
  const std::unique_ptr<Solver> solver = make_solver(c, geometry, settings, checkpoint, dir);
  print_run_header(c, geometry, settings, *solver, resumed);

  g_stop_requested.store(false);
  RunStatus status;
  {
    // Ctrl-C, SIGTERM or a hangup (unless ignored, as under nohup) stop the run at the next step
    // with a checkpoint. An interrupted write is restarted: a signal arriving while the progress line
    // goes to a pipe would otherwise fail that write (EINTR) and leave std::cerr in a failed state,
    // silencing the messages that follow ("checkpoint written"). SIGPIPE is ignored, so that a reader
    // of the progress that goes away (a closed `| tee`) cannot kill the run before its checkpoint.
    const util::StopSignalHandlers handlers(request_stop, {.restart_interrupted_calls = true, .ignore_sigpipe = true});
    status = run_case(*solver, ro, checkpoint);
  }
  if (status == RunStatus::interrupted) {
    const int sig = g_stop_signal.load();
    std::cerr << "hydrojump sph: stopped by " << util::stop_signal_name(sig) << " at t = " << solver->time()
              << " s; checkpoint written to " << checkpoint_path(dir).string() << " (continue with --resume)\n";
    return 128 + sig;
  }
  std::cerr << "hydrojump sph: finished at t = " << solver->time() << " s after " << solver->clock().steps
            << " steps; outputs in " << dir.string() << " (particles.pvd, run_log.csv, gauges.csv" << (c.stilling_basin() ? ", basin.csv, summary.json" : "") << ", results_case.toml)\n";
  return 0;
}

void register_commands(CLI::App& app) {
  auto opt = std::make_shared<SphOptions>();
  CLI::App* sph = app.add_subcommand(
      "sph",
      "Run the weakly compressible SPH solver on a case directory written by `generate` (DIR/<case>/sph).\n"
      "Reads DIR/case.toml; writes DIR/particles.pvd with one .vtp per output time (open it in ParaView),\n"
      "DIR/run_log.csv (mass, energies, max density variation, dt), DIR/gauges.csv (free-surface elevation\n"
      "at the sections and gauges), for stilling basins DIR/basin.csv (jump toe, inflow/outflow discharge,\n"
      "depth and discharge at every section per output) and DIR/summary.json (averages over the averaging\n"
      "window, y2/y1 against Belanger, mass balance, steady-state verdict), DIR/results_case.toml (the case.toml\n"
      "the run started with) and DIR/checkpoint.bin (every sph.checkpoint_interval_wall_s seconds and at exit). Ctrl-C (SIGINT), SIGTERM or a hangup (SIGHUP) writes a checkpoint and stops; continue with --resume. An unstable\n"
      "run stops with a diagnosis in DIR/failure.txt and keeps its last good checkpoint. One process per DIR:\n"
      "a second one started on it stops at once, naming the first (DIR/.hydrojump.lock).");
  sph->add_option("DIR", opt->dir, "case directory holding case.toml")->required()->check(CLI::ExistingDirectory);
  sph->add_flag("--resume", opt->resume, "continue from DIR/checkpoint.bin");
  sph->add_flag("--restart", opt->restart, "start over even if DIR holds a previous run (overwrites its outputs)");
  sph->add_option("--threads", opt->threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)")
      ->check(CLI::Range(1, 1024));
  sph->add_option("--end-time", opt->end_time, "stop at this simulated time in s instead of the case's end_time_s")
      ->check(util::positive_finite_number());
  sph->add_flag("--quiet", opt->quiet, "no progress line");
  sph->callback([opt]() {
    if (opt->resume && opt->restart) throw CLI::ValidationError("--resume and --restart", "choose one of them");
    const int code = run_sph_directory(*opt);
    if (code != 0) throw CLI::RuntimeError(code);
  });

  auto bench_opt = std::make_shared<BenchmarkOptions>();
  auto json = std::make_shared<bool>(false);
  CLI::App* bench = app.add_subcommand(
      "bench",
      "SPH benchmark: 2D dam break (column 1 m x 2 m, tank 4 m), dx = 0.01 m (20,000 fluid particles), Wendland\n"
      "C2, h = sqrt(2) dx, artificial viscosity 0.02, Fourtakas diffusion 0.1, DBC, Verlet, CFL 0.2,\n"
      "c0 = 20 sqrt(g 2 m), 0.3 s of physical time. Prints particle-steps per second (all particles times\n"
      "steps over the wall time of the time loop) and the peak memory. --model jump runs the same dam break with\n"
      "exactly the SPH model of a study's stilling basins (the [sph] of its first basin after the rules, open\n"
      "boundaries left out; --spec, default the embedded study); --model costliest with every costly path at\n"
      "once: symplectic, mDBC, laminar + SPS (mixing length, whole-domain wall distance, log-law wall function)\n"
      "and Fickian particle shifting.");
  bench->add_option("--steps", bench_opt->max_steps, "stop after N steps (a quick figure)")->check(CLI::Range(std::int64_t{1}, std::int64_t{1000000000}));
  bench->add_option("--threads", bench_opt->threads, "OpenMP threads")->check(CLI::Range(1, 1024));
  bench->add_option("--end-time", bench_opt->end_time_s, "physical time to simulate in s (default 0.3)")
      ->check(util::positive_finite_number());
  bench->add_option("--dx", bench_opt->particle_spacing_m, "particle spacing in m (default 0.01)")
      ->check(CLI::Range(0.002, 0.1));
  bench->add_option("--model", bench_opt->model,
                    "\"dualsphysics\" (default: DualSPHysics-comparable settings), \"jump\" (a study's SPH model) or "
                    "\"costliest\"")
      ->check(CLI::IsMember(benchmark_models()));
  bench->add_option("--spec", bench_opt->spec_file, "--model jump: the study file whose [sph] model runs (default: the embedded one)")
      ->check(CLI::ExistingFile);
  bench->add_flag("--json", *json, "print the result as one JSON object");
  bench->callback([bench_opt, json]() {
    const BenchmarkResult r = run_benchmark(*bench_opt);
    if (*json) {
      std::cout << to_json(r) << "\n";
      return;
    }
    std::cout << "hydrojump bench (model " << r.model << "): dam break dx = " << bench_opt->particle_spacing_m << " m, " << r.particles
              << " particles (" << r.fluid_particles << " fluid), " << r.threads << " thread(s)\n"
              << "  " << r.steps << " steps to t = " << r.simulated_time_s << " s in " << r.seconds << " s wall, "
              << r.cpu_seconds << " s CPU (a CPU time well above threads x wall, or a wall time well above the CPU\n"
              << "  time on one thread, means the machine was busy with other work)\n"
              << "  " << std::fixed << std::setprecision(3) << r.particle_steps_per_second / 1e6
              << " M particle-steps/s (" << r.particle_steps_per_second * static_cast<double>(r.fluid_particles) /
                                                  static_cast<double>(r.particles) / 1e6
              << " M counting fluid particles only)\n"
              << "  peak memory " << static_cast<double>(r.peak_memory_bytes) / 1048576.0 << " MiB\n";
    if (!r.model_source.empty()) std::cout << "  model: the " << r.model_source << "\n";
  });
}

void write_sph_input(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                     const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  cases::write_resolved_case(study, c, resolution, dir / "case.toml");
  const double dx = c.resolution(resolution).particle_spacing_m;
  const cases::CaseGeometry geometry = solver_geometry(c, study.fluid, dx);
  const SolverSettings settings = make_settings(c, study.fluid, geometry, dx);
  ParticleSet ps = generate_particles(geometry, settings, c.sph.boundary_layers);
  for (Eigen::Index i = 0; i < ps.size(); ++i) ps.p[i] = settings.eos.pressure(ps.rho[i]);
  write_particles_vtp(ps, dir / "initial_particles.vtp");
}

}  // namespace hydrojump::sph
