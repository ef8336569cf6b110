// `hydrojump study`: a whole side-by-side study from one spec. For every selected case it generates
// the case directories, runs the SPH solver and the OpenFOAM reference, compares them, and finally
// writes the study-level report.
//
// Each stage of each case runs as a child process of this executable (`hydrojump sph DIR`,
// `hydrojump vof DIR`, `hydrojump compare DIR`) with its output in OUT/<case>/<stage>.log, so one
// failing or crashing case is reported and does not stop the others.
//
// Caching: a stage that finished writes OUT/<case>/<stage>.stamp holding a hash of the resolved case
// and of the program's code (solver_fingerprint for the generate, sph and vof stages, source_fingerprint
// for compare; cmake/write_version.cmake); a re-run skips stages whose stamp matches, so only what changed runs
// again, and an interrupted study resumes where it stopped (solvers resume from their checkpoints).
// The study report covers the cases run now and every other case of the spec whose comparison in OUT
// is current (stamp = its fingerprint), so a long study can be run a few cases at a time.
#pragma once

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cases/spec.hpp"

namespace hydrojump::app {

struct StudyOptions {
  std::string spec = "default";              // file, or "default" for the embedded study
  std::string resolution = "quick";
  std::vector<std::string> cases;            // empty: all
  std::filesystem::path out = "study";
  int jobs = 1;                              // solver stages run at the same time (largest cases first);
                                             // 0: one per core (stage_jobs; the command's default)
  int mpi_ranks = 1;                         // --np for the OpenFOAM runs
  int sph_threads = 0;                       // --threads for the SPH runs; 0: all cores with one job, the
                                             // cores shared out with several (sph_threads_per_job)
  std::vector<std::string> methods = {"sph", "vof"};  // which solvers to run
  bool force = false;                        // ignore the stamps and run everything again
  std::filesystem::path records;             // validation records to import (compare/record.hpp); empty: none
  std::filesystem::path executable;          // the hydrojump binary run for each stage
                                             // (empty: this process's own executable)
};

// The solver stages the study runs at once: `jobs` (--jobs), or with 0 one per `cores_per_stage` cores
// (the larger of --np and --threads, one without them: two single-threaded runs side by side do more
// than one run on two threads, and no more runs than cores); at most `stages` (the solver stages that
// will run, not the cached ones), at least one.
int stage_jobs(int jobs, int cores_per_stage, int cores, std::size_t stages);

// The OpenMP threads each SPH run gets: `requested` if > 0; else, with several jobs, the `cores` shared
// out among them (at least one each), so that two stages side by side do not put four spinning threads
// on two cores; else 0 (the solver's own default: OMP_NUM_THREADS or all cores).
int sph_threads_per_job(int requested, int jobs, int cores);

// The key of one method's results of case `c` at `resolution` ("sph" or "vof"): a hash of the case's
// setting lines for that method (cases::method_setting_lines: no comments, descriptive texts,
// run-control settings or the other method's model table) and that solver's code (sph_fingerprint or
// vof_fingerprint, cmake/write_version.cmake). The study's sph and vof stamps hold it and validation
// records carry it as their run key, so a change to one solver, or to its [sph] or [vof] settings,
// leaves the other method's records current. (A study directory's generate and settings stamps hold
// both solvers' code: there such a change still re-runs both methods.)
std::string method_run_key(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                           const std::string& method);

// Runs the study; returns the number of cases with a failed stage (0: all good; at most 127), or 128 + the signal
// number when a stop request (SIGINT, SIGTERM, SIGHUP) stopped it: the running stages are stopped
// with their state written and no other stage starts.
int run_study(const StudyOptions& options, std::ostream& log);

// Adds `study` to `app`.
void register_study_command(CLI::App& app);

}  // namespace hydrojump::app
