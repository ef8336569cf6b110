// `hydrojump vof DIR`: run_vof_case as named stages over the runner's parts (runner_parts.hpp):
//   check       the case directory (case.toml, the dictionaries, not edited since `generate`), OpenFOAM,
//               and for a body_fitted mesh the non-orthogonal-face self-test;
//   start       where the run starts: a fresh start, --resume from the latest complete time (incomplete
//               ones moved aside), or --map-from another run; the end time (--end-time);
//   mesh        the mesh steps (blockMesh [topoSet subsetMesh] [topoSet sections]) and checkMesh;
//   initialise  0.orig -> 0, setFields, and mapFields with --map-from;
//   solve       interFoam in legs on the output grid, serial or decomposed (decomposePar, mpirun), with
//               the tailgate step after each leg under hold_toe;
//   finish      reconstructPar (parallel) and the summary line.
#include "reference/runner.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "cases/geometry.hpp"
#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "reference/case_writer.hpp"
#include "reference/foam_dictionary.hpp"
#include "reference/runner_parts.hpp"
#include "reference/solver_log.hpp"
#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"
#include "util/directory_lock.hpp"
#include "util/system_memory.hpp"
#include "util/time_directories.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

namespace detail {

namespace {

// The case a run runs: the resolved spec (one case, one resolution) and the OpenFOAM case built from it.
struct RunCase {
  const cases::Study& study;
  const cases::Case& c;
  const VofCase& vof;
};

// Where the run starts.
struct RunStart {
  int existing_ranks = 0;            // processor*/ of an earlier parallel run
  bool continue_decomposed = false;  // continue from processor*/ (parallel, and they are the newest)
  std::optional<double> time_s;      // the latest complete time; nothing: a fresh start
  bool mesh_exists = false;
  std::optional<MapSource> map_source;
};

// ------------------------------------------------------------------------------------------ check

// The resolved case of case.toml, checked: one case with one resolution that the VOF reference models,
// its dictionaries present, and (a fresh start) case.toml not edited since `generate` wrote them.
cases::Study load_run_case(const fs::path& dir, const fs::path& spec_file) {
  cases::Study study = cases::load_study(spec_file);
  if (study.cases.size() != 1 || study.cases.front().resolutions.size() != 1) {
    throw OpenFoamError(spec_file.string() + " must hold exactly one case with one resolution table "
                        "(the resolved case written by `hydrojump generate`)");
  }
  const cases::Case& c = study.cases.front();
  if (const auto reason = vof_unsupported_reason(c)) throw OpenFoamError(*reason);
  for (const char* f : {"system/controlDict", "system/blockMeshDict", "system/setFieldsDict", "0.orig/U"}) {
    if (!fs::exists(dir / f)) {
      throw OpenFoamError(dir.string() + " is not a complete OpenFOAM case: " + f +
                          " is missing (regenerate it with `hydrojump generate`)");
    }
  }
  // The dictionaries were written from the case.toml `generate` wrote (it rewrites both together): a
  // run starting afresh from an edited one would record settings its dictionaries do not have. (A
  // first run that failed before its first output starts afresh too; a resumed one is checked
  // against its record below.)
  const bool starts_afresh = !latest_time(dir) && !latest_time(dir / "processor0");
  if (const fs::path generated = dir / generated_case_file_name; starts_afresh && fs::exists(generated)) {
    const auto d = cases::first_setting_difference(util::read_text_file(generated), util::read_text_file(spec_file));
    if (d.any()) {
      throw OpenFoamError(spec_file.string() + " was edited after `hydrojump generate` wrote the OpenFOAM dictionaries "
                          "from it: it has '" + d.b + "' where they were written with '" + d.a +
                          "'. Run `hydrojump generate` again to rewrite them from it (or restore the line).");
    }
  }
  return study;
}

// OpenFOAM present (its line printed), and before a body_fitted mesh the self-test: a build that
// blows up on faces not aligned with the axes refuses the case (unless --force-body-fitted).
void check_installation(const fs::path& dir, const RunCase& rc, const RunOptions& options, std::ostream& out) {
  const VofCase& vof = rc.vof;
  const OpenFoamInstallation inst = check_openfoam(options.np > 1);
  out << "OpenFOAM " << (inst.version.empty() ? "?" : inst.version) << " (WM_PROJECT_DIR="
      << inst.project_dir.string() << "), case \"" << rc.c.id << "\", resolution \"" << vof.resolution << "\", "
      << cases::option_name(vof.mesh.strategy) << " mesh of " << vof.mesh.cell_count() << " cells, "
      << (options.np > 1 ? std::to_string(options.np) + " MPI ranks" : std::string("serial")) << "\n";
  if (vof.mesh.strategy != cases::MeshStrategy::body_fitted) return;
  out << "Self-test of interFoam on faces not aligned with the axes (body_fitted mesh)...\n" << std::flush;
  const SelfTestResult st = self_test_non_orthogonal(dir);
  if (!st.axis_aligned_ok) {
    throw OpenFoamError("interFoam does not keep still water at rest even on an axis-aligned mesh: " +
                        st.summary() + ". This OpenFOAM installation is not usable.");
  }
  if (!st.sheared_ok && options.force_body_fitted) {
    out << "  WARNING: " << st.summary() << "; running the body_fitted mesh anyway (--force-body-fitted): "
        << "expect divergence on this build\n";
  } else if (!st.sheared_ok) {
    throw OpenFoamError(
        "vof.mesh_strategy = \"body_fitted\" refused: this OpenFOAM build has the known defect of "
        "interFoam on faces not aligned with the coordinate axes (fvc::reconstruct returns wrong "
        "vertical velocities and the run diverges within a few steps); self-test: " + st.summary() +
        ". Use mesh_strategy = \"cartesian_cut\" (a staircase bed, every face axis-aligned), which runs "
        "correctly on this build.");
  }
  if (st.sheared_ok) out << "  " << st.summary() << "\n";
}

// The memory an interFoam run needs, measured as the peak resident size of a run's processes
// (blockMesh to interFoam, `/usr/bin/time -v hydrojump vof --end-time 0.002`) on run A: 215 MB at
// 49,232 cells (default), 511 MB at 194,112 cells (fine); and 166 MB for G5 at about 11,000 cells
// (quick). A line above each by at most 30 MB, with the fixed part counted once per MPI rank:
//   M = 145 MB x ranks + 2.04 kB x cells
double vof_memory_bytes(long cells, int ranks) {
  return 145.0e6 * std::max(1, ranks) + 2040.0 * static_cast<double>(cells);
}

// Refuses, before meshing, a run that needs more memory than the machine has available.
void check_memory(const RunCase& rc, const RunOptions& options) {
  const long cells = rc.vof.mesh.cell_count();
  std::ostringstream what, basis;
  what << "hydrojump vof: case \"" << rc.c.id << "\" at resolution \"" << rc.vof.resolution << "\"";
  basis << "145 MB x " << std::max(1, options.np) << " process(es) + 2.04 kB a cell x " << cells << " cells";
  util::check_memory_need(what.str(), vof_memory_bytes(cells, options.np), basis.str(),
                          "use a coarser resolution (larger vof_cell_size_bed_m and vof_cell_size_bulk_m), fewer "
                          "MPI ranks (--np), or free memory");
}

// ------------------------------------------------------------------------------------------ start

// Where to start: the decomposed results when continuing in parallel and they are the newest, else
// the reconstructed (or serial) ones; refused when results are there without --resume or with
// --map-from, or cannot be resumed with these options. A resume moves incomplete times aside.
RunStart find_start(const fs::path& dir, const cases::Case& c, const RunOptions& options, std::ostream& out) {
  RunStart s;
  // Processor directories from an earlier parallel run.
  s.existing_ranks = static_cast<int>(processor_directories(dir).size());
  const bool parallel = options.np > 1;
  const std::optional<double> start_decomposed =
      s.existing_ranks > 0 ? latest_time(dir / "processor0") : std::nullopt;
  const std::optional<double> start_serial = latest_time(dir);
  s.continue_decomposed = parallel && start_decomposed && (!start_serial || *start_decomposed >= *start_serial);
  s.time_s = s.continue_decomposed ? start_decomposed : start_serial;
  s.mesh_exists = fs::exists(dir / "constant/polyMesh/owner") || fs::exists(dir / "constant/polyMesh/owner.gz");
  const std::optional<double>& start = s.time_s;
  if (start && options.map_from) {
    throw OpenFoamError("--map-from starts a new run, but " + dir.string() + " already holds results up to t = " +
                        format_seconds(*start) + " s: generate a fresh case directory for the mapped run");
  }
  if (options.map_from) s.map_source = check_map_source(*options.map_from, dir, c.id);
  if (start && !options.resume) {
    throw OpenFoamError(dir.string() + " already holds results up to t = " + format_seconds(*start) +
                        " s: use --resume to continue from there, or delete the time directories to "
                        "start again");
  }
  if (!options.resume || !start) return s;
  // The dictionaries were written from the case the run started with: an edited case.toml would
  // describe other results (checked before anything is moved).
  cases::require_results_of(dir, dir / "case.toml");
  if (s.continue_decomposed && s.existing_ranks != options.np) {
    throw OpenFoamError(dir.string() + " was decomposed for " + std::to_string(s.existing_ranks) +
                        " MPI ranks: resume with --np " + std::to_string(s.existing_ranks));
  }
  if (!parallel && s.existing_ranks > 0 && latest_time(dir / "processor0").value_or(0.0) > *start + 1e-12) {
    throw OpenFoamError(dir.string() + " holds newer parallel results in processor*/: resume with --np " +
                        std::to_string(s.existing_ranks));
  }
  s.time_s = discard_incomplete_times(dir, s.continue_decomposed, out);
  return s;
}

// The end time: system/controlDict's endTime, which --end-time rewrites (to extend a run).
double settle_end_time(const fs::path& dir, const cases::Case& c, const RunOptions& options,
                       const std::optional<double>& start, std::ostream& out) {
  const fs::path spec_file = dir / "case.toml";
  double end_time_s = control_dict_end_time(dir);
  if (options.end_time_s) {
    if (*options.end_time_s > c.run.latest_end_time_s()) {
      throw OpenFoamError("--end-time " + format_seconds(*options.end_time_s) + " s is out of range for " +
                          spec_file.string() + ": must be <= " + format_seconds(c.run.latest_end_time_s()) +
                          " s (at most 100000 outputs, one every " + format_seconds(c.run.output_interval_s) +
                          " s, and at most 100000 s)");
    }
    if (!(*options.end_time_s > 0.0) || (start && *options.end_time_s <= *start + 1e-12)) {
      throw OpenFoamError("--end-time " + format_seconds(*options.end_time_s) + " s: must be after " +
                          (start ? "the latest time " + format_seconds(*start) + " s of " + dir.string()
                                 : std::string("t = 0")));
    }
    if (std::abs(*options.end_time_s - end_time_s) > 1e-12) {
      set_control_dict_end_time(dir, *options.end_time_s);
      out << "End time " << format_seconds(*options.end_time_s) << " s (was " << format_seconds(end_time_s)
          << " s; system/controlDict updated)\n";
      end_time_s = *options.end_time_s;
    }
  } else if (start && *start >= end_time_s - 1e-12) {
    out << "The run already reached its end time " << format_seconds(end_time_s)
        << " s (extend it with --resume --end-time T)\n";
  }
  return end_time_s;
}

// ------------------------------------------------------------------------------- mesh, initialise

// The mesh steps, then checkMesh: anything but "Mesh OK." stops the run with the failed checks.
void mesh(const StepPlace& place, const VofCase& vof) {
  place.out << "Meshing (" << cases::option_name(vof.mesh.strategy) << ")\n";
  std::map<std::string, int> used;
  for (const FoamStep& step : vof.mesh_steps) {
    std::vector<std::string> argv = {step.application};
    argv.insert(argv.end(), step.arguments.begin(), step.arguments.end());
    const int k = used[step.application]++;
    const std::string suffix = k > 0 ? std::string(".").append(std::to_string(k + 1)) : std::string();
    run_step(place, argv, "log." + step.application + suffix);
  }
  place.out << "Checking the mesh\n";
  run_step(place, {"checkMesh"}, "log.checkMesh");
  const std::string text = util::read_text_file(place.dir / "log.checkMesh");
  if (text.find("Mesh OK.") != std::string::npos) return;
  std::string report;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find("***") != std::string::npos || line.find("Failed") != std::string::npos) {
      report += "    " + line + "\n";
    }
  }
  throw OpenFoamError("checkMesh found a bad mesh in " + place.dir.string() + " (full report in log.checkMesh):\n" +
                      report);
}

// 0.orig -> 0 and setFields; with --map-from, the source's state mapped over it.
void initialise(const StepPlace& place, const std::optional<MapSource>& map_source) {
  place.out << "Initial fields\n";
  std::error_code ec;
  fs::remove_all(place.dir / "0", ec);
  fs::copy(place.dir / "0.orig", place.dir / "0", fs::copy_options::recursive);
  run_step(place, {"setFields"}, "log.setFields");
  if (map_source) map_initial_state(place, *map_source);
}

// ------------------------------------------------------------------------------------------ solve

// The solver's command: interFoam, or (parallel) mpirun ... interFoam -parallel after decomposePar
// unless the case is still decomposed for these ranks.
std::vector<std::string> solver_command(const StepPlace& place, const RunOptions& options, const RunStart& start) {
  if (options.np <= 1) return {"interFoam"};
  const fs::path& dir = place.dir;
  const bool decomposed_current = start.time_s && start.continue_decomposed && start.existing_ranks == options.np;
  if (!decomposed_current) {
    util::write_file_atomically(
        dir / "system/decomposeParDict",
        foam::format_file({"dictionary", "system", "decomposeParDict"}, decompose_par_dict(options.np)));
    std::vector<std::string> argv = {"decomposePar", "-force"};
    if (start.time_s) argv.push_back("-latestTime");
    // Until it has finished, processor*/ are not a decomposition to resume from.
    if (stop_request_count() > 0) throw StepStopped("interrupted: stopped on request before decomposePar.");
    util::write_file_atomically(dir / decomposing_marker, "decomposePar started by hydrojump vof\n");
    run_step(place, argv, "log.decomposePar");
    fs::remove(dir / decomposing_marker);
  }
  std::vector<std::string> solver = {"mpirun"};
  if (::geteuid() == 0) solver.push_back("--allow-run-as-root");
  if (static_cast<unsigned>(options.np) > std::thread::hardware_concurrency()) solver.push_back("--oversubscribe");
  for (const std::string& a : {std::string("-np"), std::to_string(options.np), std::string("-x"),
                               std::string("WM_PROJECT_DIR"), std::string("interFoam"), std::string("-parallel")}) {
    solver.push_back(a);
  }
  return solver;
}

// After a parallel run stopped early (interrupted, diverged, or stopped by the tailwater control): the
// complete times the processors wrote reconstructed into `dir` (reconstructPar -newTimes), so that
// `compare`, ParaView and a serial resume see them; processor*/ stay for `--resume --np N`. Returns a
// sentence for the error message (empty when there was nothing to reconstruct).
std::string reconstruct_written_times(const StepPlace& place, int np) {
  const fs::path& dir = place.dir;
  auto times = util::time_directories(dir / "processor0", 0.0);
  while (!times.empty() && !time_directory_complete(times.back().path)) times.pop_back();
  const auto reconstructed = latest_time(dir);
  if (times.empty() || (reconstructed && *reconstructed >= times.back().time_s - 1e-12)) return "";
  const std::string last = times.back().path.filename().string();
  try {
    run_step(place, {"reconstructPar", "-newTimes", "-time", ":" + last}, "log.reconstructPar", AfterStopRequest::run);
  } catch (const OpenFoamError& e) {
    const std::string why = e.what();
    return "\nThe times written so far are only in processor*/: reconstructPar failed (" +
           why.substr(0, why.find('\n')) + ").";
  }
  return "\nThe times written up to t = " + last + " s were reconstructed into " + dir.string() +
         " (for `hydrojump compare` and ParaView); processor*/ are kept for `--resume --np " + std::to_string(np) +
         "`.";
}

// interFoam from the start to `end_time_s` in legs that keep every output on the case's grid
// (plan_solver_legs: usually one), split for the tailgate step under hold_toe. A parallel run that
// stops early leaves its written times where compare and ParaView look. Returns the time reached.
double solve(const StepPlace& place, const RunCase& rc, const RunStart& start, double end_time_s,
             const RunOptions& options, const util::DirectoryLock& lock) {
  const fs::path& dir = place.dir;
  std::ostream& out = place.out;
  const bool parallel = options.np > 1;
  const SolverRun run{dir, rc.c, rc.vof.mesh.thickness_m, solver_command(place, options, start), parallel, options,
                      end_time_s, lock};
  const double t_begin = start.time_s.value_or(0.0);
  std::optional<double> leg_start = start.time_s;
  double reached = t_begin;
  std::vector<SolverLeg> legs = plan_solver_legs(t_begin, end_time_s, output_grid_interval(dir));
  std::optional<TailwaterControlLaw> control;
  if (rc.c.holds_toe()) {
    control = tailwater_control_law(rc.c, cases::make_geometry(rc.c, rc.study.fluid));
    legs = split_legs_for_control(legs, t_begin, control->interval_s);
    // The log describes this run: rows of an abandoned later part or of an earlier run go.
    truncate_tailwater_control_log(dir, start.time_s);
    std::ostringstream line;
    line << "Tailwater control (hold_toe): every " << format_seconds(control->interval_s)
         << " s the outlet's Umean is reset to hold the water volume, and the volume moved to bring the toe to x = "
         << control->gains.target_toe_x_m << " m (log: " << tailwater_control_log << ")\n";
    out << line.str();
  }
  // Between two steps (after a leg, during the control step) a stop request ends the run here.
  const auto stop_if_requested = [&]() {
    if (stop_request_count() == 0) return;
    const auto written = latest_time(parallel ? dir / "processor0" : dir);
    throw OpenFoamError("interrupted: stopped on request with the latest time directory at " +
                        (written ? "t = " + format_seconds(*written) + " s" : std::string("none")) +
                        ". Continue with `hydrojump vof " + dir.string() + " --resume" +
                        (parallel ? " --np " + std::to_string(options.np) : std::string()) + "`.");
  };
  try {
    for (const SolverLeg& leg : legs) {
      stop_if_requested();
      std::optional<ControlDictOverride> leg_control;
      if (leg.write_interval_s || std::abs(leg.end_s - end_time_s) > 1e-12) {
        if (leg_start && leg.write_interval_s && leg.end_s < end_time_s) {
          out << "Aligning with the output times: t = " << format_seconds(*leg_start)
              << " s lies between two of them, so interFoam first runs to t = " << format_seconds(leg.end_s)
              << " s (it counts its write times from where it starts)\n";
        } else if (leg.write_interval_s) {
          out << "The end time " << format_seconds(end_time_s)
              << " s lies between two output times: interFoam runs to the last one, then to the end time "
                 "in a closing leg that writes it\n";
        }
        leg_control.emplace(dir, leg);
      }
      reached = run_solver(run, leg_start, leg.end_s, out);
      if (leg_control) leg_control->restore(&out);
      if (control) {
        tailwater_control_after_leg(dir, *control, rc.vof.mesh.thickness_m, parallel, leg_start.value_or(0.0), leg.end_s, out);
      }
      leg_start = leg.end_s;
    }
  } catch (const OpenFoamError& e) {
    if (!parallel) throw;
    throw OpenFoamError(e.what() + reconstruct_written_times(place, options.np));
  }
  return reached;
}

// ----------------------------------------------------------------------------------------- finish

// reconstructPar after a parallel run, and the summary line.
void finish(const StepPlace& place, const cases::Case& c, const RunOptions& options, const RunStart& start,
            double reached, std::chrono::steady_clock::time_point wall_begin) {
  if (options.np > 1) {
    std::vector<std::string> argv = {"reconstructPar"};
    if (start.time_s) argv.push_back("-newTimes");
    run_step(place, argv, "log.reconstructPar");
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_begin).count();
  place.out << "Done: case \"" << c.id << "\" reached t = " << format_seconds(reached) << " s in "
            << format_duration(wall) << " of wall time; fields in the time directories, section samples in "
            << (place.dir / "postProcessing").string() << "\n";
}

// ------------------------------------------------------------------------------------- the stages

void run_vof_case_steps(const fs::path& dir, const RunOptions& options, std::ostream& out) {
  if (options.np < 1) throw OpenFoamError("--np must be >= 1");
  const fs::path spec_file = dir / "case.toml";
  if (!fs::exists(spec_file)) {
    throw OpenFoamError(dir.string() + " is not a generated OpenFOAM case: " + spec_file.string() +
                        " is missing (write it with `hydrojump generate SPEC --out DIR`)");
  }
  // One process per case directory (a second one stops here, naming the first).
  const util::DirectoryLock lock(dir, "hydrojump vof");
  // What a run killed outright left half-written (its complete files are all in place).
  util::remove_orphaned_temporaries(dir);
  util::remove_orphaned_temporaries(dir / "system");
  const StepPlace place{dir, out, lock};
  // Ctrl-C, SIGTERM or a hangup from here on stop the run at its next safe point.
  const StopRequestGuard stop_guard;
  restore_control_dict_left_behind(dir, out);
  remove_cut_short_decomposition(dir, out);

  const cases::Study study = load_run_case(dir, spec_file);
  const cases::Case& c = study.cases.front();
  const VofCase vof = build_vof_case(study, c, c.resolutions.begin()->first);
  const RunCase rc{study, c, vof};
  check_installation(dir, rc, options, out);
  check_memory(rc, options);

  const RunStart start = find_start(dir, c, options, out);
  const double end_time_s = settle_end_time(dir, c, options, start.time_s, out);

  const auto wall_begin = std::chrono::steady_clock::now();
  if (!start.time_s) {
    // What `compare` and `generate` check these results against.
    cases::record_results_case(dir);
    mesh(place, vof);
    initialise(place, start.map_source);
  } else {
    out << "Resuming from t = " << format_seconds(*start.time_s) << " s"
        << (start.mesh_exists ? "" : " (no mesh found: run without --resume)") << "\n";
    if (!start.mesh_exists) throw OpenFoamError("cannot resume " + dir.string() + ": constant/polyMesh is missing");
  }
  const double reached = solve(place, rc, start, end_time_s, options, lock);
  finish(place, c, options, start, reached, wall_begin);
}

}  // namespace

}  // namespace detail

void run_vof_case(const fs::path& dir_in, const RunOptions& options, std::ostream& out) {
  const fs::path dir = fs::absolute(dir_in);
  if (const auto problem = openfoam_path_problem(dir)) throw OpenFoamError(*problem);
  try {
    detail::run_vof_case_steps(dir, options, out);
  } catch (const detail::StepStopped& e) {
    // A utility stopped on request (meshing, decomposing, reconstructing): how to go on depends on
    // what the run has written.
    const bool written = latest_time(dir).has_value() || latest_time(dir / "processor0").has_value();
    const std::string np = options.np > 1 ? " --np " + std::to_string(options.np) : std::string();
    throw OpenFoamError(std::string(e.what()) +
                        (written ? " Continue with `hydrojump vof " + dir.string() + " --resume" + np + "`."
                                 : " Nothing was computed yet: run the same `hydrojump vof` command again to start "
                                   "over."));
  }
}

}  // namespace hydrojump::reference
