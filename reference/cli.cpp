#include "reference/cli.hpp"

#include <iostream>
#include <memory>

#include "util/atomic_file.hpp"
#include "util/cli_checks.hpp"
#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "reference/case_writer.hpp"
#include "reference/runner.hpp"

namespace hydrojump::reference {

namespace {

struct VofOptions {
  std::string dir;
  int np = 1;
  bool resume = false;
  double end_time_s = 0.0;  // 0: the controlDict's endTime
  std::string map_from;     // empty: setFields' initial state
  bool self_test = false;
  bool force_body_fitted = false;
  double progress_interval_s = 30.0;
};

}  // namespace

void register_commands(CLI::App& app) {
  auto options = std::make_shared<VofOptions>();
  CLI::App* vof = app.add_subcommand(
      "vof",
      "Mesh and run the OpenFOAM interFoam (VOF) reference case in DIR (DIR/<case>/vof written by "
      "`hydrojump generate`).\n"
      "Steps: check that OpenFOAM is usable; blockMesh (+ topoSet/subsetMesh for the staircase bed);\n"
      "checkMesh (a bad mesh stops the run with its report); setFields (initial water); interFoam,\n"
      "serial or with MPI (--np N: decomposePar, mpirun, reconstructPar). Shows the simulated time and\n"
      "an ETA, stops a diverging run (Courant blow-up, NaN, crash) with the last lines of its log, and\n"
      "continues an interrupted run with --resume. Ctrl-C (SIGINT), SIGTERM or a hangup (SIGHUP) makes\n"
      "interFoam write the current time and stop, ready for --resume; so does this command's end in any\n"
      "other way (killed: Linux sends interFoam SIGUSR2). Outputs stay on the case's output times (a run\n"
      "resumed between two of them first runs to the next one; an end time between two is written by a\n"
      "short closing run). Logs: DIR/log.<application>. The case can also be run by hand with DIR/Allrun.\n"
      "A case with [case.tailwater] control = \"hold_toe\" (the default) runs in legs; after each the outlet's Umean\n"
      "is reset like a tailgate to hold the jump's toe at the basin start (DIR/tailwater_control.csv).\n"
      "Needs OpenFOAM v1912 (WM_PROJECT_DIR, default /usr/share/openfoam).\n"
      "One process per DIR: a second one started on it stops at once, naming the first.");
  vof->add_option("DIR", options->dir,
                  "case directory (holds case.toml, system/, constant/, 0.orig/); required unless --self-test");
  vof->add_option("--np", options->np, "MPI ranks (1 = serial; >1 runs decomposePar + mpirun)")
      ->check(CLI::Range(1, 1024));
  vof->add_flag("--resume", options->resume,
                "continue from the latest complete time directory instead of refusing to overwrite");
  vof->add_flag("--self-test", options->self_test,
                "only check OpenFOAM and run the self-test for faces not aligned with the axes "
                "(decides whether mesh_strategy = \"body_fitted\" can run on this build)");
  vof->add_flag("--force-body-fitted", options->force_body_fitted,
                "run a body_fitted mesh even when the self-test shows the defect (for patched builds)");
  vof->add_option("--end-time", options->end_time_s,
                  "run to this simulated time in s instead of the case's end time (written into "
                  "system/controlDict; with --resume it extends a finished run)")
      ->check(util::positive_finite_number());
  vof->add_option("--map-from", options->map_from,
                  "start from the latest time of another run of the same case (its vof directory, e.g. a "
                  "settled `quick` run), interpolated onto this mesh by OpenFOAM's mapFields -consistent, "
                  "instead of setFields' initial water; a fresh start only, the time still starts at 0")
      ->check(CLI::ExistingDirectory);
  vof->add_option("--progress-interval", options->progress_interval_s,
                  "seconds between progress lines when the output is not a terminal (default 30)")
      ->check(util::positive_finite_number());
  vof->callback([options]() {
    if (options->self_test) {
      const OpenFoamInstallation inst = check_openfoam(false);
      std::cout << "OpenFOAM " << inst.version << " at " << inst.project_dir.string() << "\n";
      const SelfTestResult r =
          self_test_non_orthogonal(std::filesystem::temp_directory_path());
      std::cout << r.summary() << "\n"
                << (r.sheared_ok ? "body_fitted meshes can run on this build\n"
                                 : "body_fitted meshes are refused on this build (use cartesian_cut)\n");
      return;
    }
    if (options->dir.empty()) throw CLI::RequiredError("DIR");
    // On a fresh directory --resume --map-from silently started a mapped run.
    if (options->resume && !options->map_from.empty())
      throw CLI::ValidationError("--map-from", "starts a new run, and --resume continues one: give one of them");
    RunOptions run;
    run.np = options->np;
    run.resume = options->resume;
    run.progress_interval_s = options->progress_interval_s;
    run.force_body_fitted = options->force_body_fitted;
    if (options->end_time_s > 0.0) run.end_time_s = options->end_time_s;
    if (!options->map_from.empty()) run.map_from = std::filesystem::path(options->map_from);
    run_vof_case(options->dir, run, std::cout);
  });
}

void write_vof_case(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                    const std::filesystem::path& dir) {
  if (const auto reason = vof_unsupported_reason(c)) {
    // Not an error for `generate`: a study may hold cases only the SPH solver runs.
    std::filesystem::create_directories(dir);
    util::write_file_atomically(dir / "README.txt", "No OpenFOAM case was written: " + *reason +
                                                         ".\n`hydrojump vof` refuses this directory.\n");
    cases::write_resolved_case(study, c, resolution, dir / "case.toml");
    return;
  }
  const VofCase vof = build_vof_case(study, c, resolution);
  std::filesystem::create_directories(dir);
  write_vof_files(vof, dir);
  cases::write_resolved_case(study, c, resolution, dir / "case.toml");
  util::write_file_atomically(dir / generated_case_file_name, util::read_text_file(dir / "case.toml"));
}

}  // namespace hydrojump::reference
