#include "app/study.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <ctime>
#include <initializer_list>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <omp.h>
#include <sched.h>

#include "util/atomic_file.hpp"
#include "util/child_process.hpp"
#include "util/cli_checks.hpp"
#include "util/directory_lock.hpp"
#include "util/fingerprint.hpp"
#include "util/number_text.hpp"
#include "compare/record.hpp"
#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "util/stop_signals.hpp"
#include "app/generate.hpp"
#include "app/stage_info.hpp"
#include "app/stage_queue.hpp"
#include "app/study_report.hpp"
#include "compare/run_cost.hpp"
#include "reference/runner.hpp"
#include "hydrojump/version.hpp"
#include "sph/cli.hpp"

namespace hydrojump::app {
namespace {

// Stop requests to the study (Ctrl-C, SIGTERM, a hangup): the first one's signal number (0 while none
// came) and how many came. Lock-free atomics: safe in a signal handler and read by the worker threads.
std::atomic<int> study_stop_signal{0};
std::atomic<int> study_stop_requests{0};
static_assert(std::atomic<int>::is_always_lock_free);
void request_study_stop(int signal) {
  int none = 0;
  study_stop_signal.compare_exchange_strong(none, signal);
  study_stop_requests.fetch_add(1);
}

// The study's handlers for SIGINT, SIGTERM and SIGHUP (unless SIGHUP is ignored, as under nohup)
// while it runs. Its stages run in their own process groups, so a request reaches them once, from
// the study (a SIGTERM: the SPH run writes a checkpoint, the OpenFOAM run its current time), and no
// further stage starts; the next study resumes them. A second request stops them at once (SIGTERM,
// then SIGKILL to their process groups).
class StudyStopSignals {
 public:
  StudyStopSignals() {
    study_stop_signal = 0;
    study_stop_requests = 0;
  }

 private:
  util::StopSignalHandlers handlers_{request_study_stop, {.restart_interrupted_calls = true, .ignore_sigpipe = false}};
};

bool study_stopping() { return study_stop_signal != 0; }

std::string clock_now() {
  const auto t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&t, &tm);
  std::ostringstream s;
  s << std::put_time(&tm, "%H:%M:%S");
  return s.str();
}

// The fingerprint of case `c` at `resolution`: its resolved settings and a fingerprint of this
// program's code. The generate stamp holds it with `solver_fingerprint` (the code that writes and
// runs the solvers), the compare stamp with `source_fingerprint` (all of it), so a change to the
// comparator re-runs only the comparisons. The sph and vof stamps hold method_run_key.
std::string case_fingerprint(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                             const char* code) {
  std::string text = cases::resolved_case_text(study, c, resolution);
  text = text.substr(text.find('\n') + 1);  // the first line names the source file: not part of the case
  return util::fingerprint(text + "\ncode " + code);
}

// The fingerprint of the run that case `c` at `resolution` makes: the one its SPH checkpoint carries
// (sph::run_fingerprint: setting lines only, no comments, descriptive texts or run-control settings,
// and the solvers' code). The settings stamp holds it, so a reworded description or a relaxed
// stability limit keeps the solver results (and resumes an interrupted run).
std::string run_fingerprint_of(const cases::Study& study, const cases::Case& c, const std::string& resolution) {
  return sph::run_fingerprint(cases::resolved_case_text(study, c, resolution));
}

}  // namespace

std::string method_run_key(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                           const std::string& method) {
  std::string kept;
  for (const std::string& line : cases::method_setting_lines(cases::resolved_case_text(study, c, resolution), method))
    kept += line + '\n';
  return util::fingerprint(kept + "\ncode " + (method == "sph" ? sph_fingerprint : vof_fingerprint));
}

namespace {

// Locks the sph and vof directories under each of `tops` that exist, so that no run started by hand
// writes in them while the study rewrites or moves them (a run holding one makes this throw).
std::vector<std::unique_ptr<util::DirectoryLock>> lock_solver_directories(
    std::initializer_list<std::filesystem::path> tops, const std::string& holder) {
  std::vector<std::unique_ptr<util::DirectoryLock>> locks;
  for (const auto& top : tops)
    for (const char* method : {"sph", "vof"})
      if (std::filesystem::is_directory(top / method))
        locks.push_back(std::make_unique<util::DirectoryLock>(top / method, holder));
  return locks;
}

class StudyRunner {
 public:
  StudyRunner(const StudyOptions& options, const cases::Study& study, std::ostream& log)
      : options_(options),
        study_(study),
        log_(log),
        self_(options.executable.empty() ? std::filesystem::read_symlink("/proc/self/exe") : options.executable) {}

  // A case's first stage: its records imported (--records) or its directories generated where the case
  // changed. Returns the case's result when nothing is left to run (imported, or failed: a failure is
  // recorded, so the other cases go on); none when its solver stages are to run. Never throws.
  std::optional<CaseResult> prepare_case(const cases::Case& c) {
    try {
      return prepare_case_directories(c);
    } catch (const std::exception& e) {
      say(c.id + ": FAILED: " + e.what());
      return CaseResult{c.id, {{"setup", "failed", 0.0, 1, e.what()}}};
    } catch (...) {
      return CaseResult{c.id, {{"setup", "failed", 0.0, 1, "unknown error"}}};
    }
  }

  // Whether a solver stage of a prepared case is cached (its stamp holds its run key; not with --force).
  bool stage_current(const cases::Case& c, const std::string& method) const {
    return stamp_current(options_.out / c.id, method, method_run_key(study_, c, options_.resolution, method));
  }

  // Whether stage `stage` of the case directory `dir` finished with `fingerprint` (its stamp), so it is
  // not run again (always false with --force).
  bool stamp_current(const std::filesystem::path& dir, const std::string& stage, const std::string& fingerprint) const {
    return !options_.force && util::read_text_file(dir / (stage + ".stamp")) == fingerprint;
  }

  // One solver stage ("sph" or "vof") of a prepared case, resumed where an earlier one stopped. Never
  // throws. The two solvers of a case may run at once: they write only their own files.
  StageResult run_solver_stage(const cases::Case& c, const std::string& method) {
    try {
      return run_solver(c, method);
    } catch (const std::exception& e) {
      say(c.id + ": " + method + " FAILED: " + e.what());
      return {method, "failed", 0.0, 1, e.what()};
    } catch (...) {
      return {method, "failed", 0.0, 1, "unknown error"};
    }
  }

  // The case's comparison, once its solver stages (`solvers`, in the order of --methods) have ended;
  // its result. Never throws.
  CaseResult finish_case(const cases::Case& c, std::vector<StageResult> solvers) {
    CaseResult result{c.id, std::move(solvers)};
    try {
      bool any_solver_ok = false, any_solver_ran = false;
      for (const auto& stage : result.stages) {
        any_solver_ok = any_solver_ok || stage.state == "done" || stage.state == "cached";
        // A stopped run wrote new outputs too: the comparison is stale.
        any_solver_ran = any_solver_ran || stage.state == "done" || stage.state == "failed" || stage.state == "stopped";
      }
      const auto dir = options_.out / c.id;
      // A comparison is only as current as the solver results it read.
      if (any_solver_ran) std::filesystem::remove(dir / "compare.stamp");
      if (any_solver_ok && !study_stopping()) {
        const std::string compare_fingerprint = case_fingerprint(study_, c, options_.resolution, source_fingerprint);
        result.stages.push_back(run_stage(c.id, "compare", {self_.string(), "compare", dir.string()}, dir,
                                          compare_fingerprint, {}));
      } else {
        result.stages.push_back({"compare", "skipped", 0.0, 0, {}});
      }
    } catch (const std::exception& e) {
      say(c.id + ": compare FAILED: " + e.what());
      result.stages.push_back({"compare", "failed", 0.0, 1, e.what()});
    } catch (...) {
      result.stages.push_back({"compare", "failed", 0.0, 1, "unknown error"});
    }
    return result;
  }

 private:
  std::optional<CaseResult> prepare_case_directories(const cases::Case& c) {
    const auto dir = options_.out / c.id;
    const std::string fingerprint = case_fingerprint(study_, c, options_.resolution, solver_fingerprint);
    const std::string run_fingerprint = run_fingerprint_of(study_, c, options_.resolution);
    const std::string compare_fingerprint = case_fingerprint(study_, c, options_.resolution, source_fingerprint);

    // Records of this case and code (--records) stand in for a run, unless this directory's own
    // comparison is current.
    if (util::read_text_file(dir / "compare.stamp") != compare_fingerprint)
      if (auto imported = import_records(c, dir)) return *imported;
    // Regenerate the case directories only when the case changed (keeps finished results).
    const auto generated_stamp = dir / "generate.stamp";
    const auto run_stamp = dir / "settings.stamp";
    if (!options_.force && util::read_text_file(generated_stamp) != fingerprint &&
        util::read_text_file(run_stamp) == run_fingerprint) {
      // Only descriptive texts or run-control settings changed: the results still belong to the case.
      // Rewrite its inputs in place (generate keeps results whose setting lines agree); the solver
      // stamps stay valid, and the comparison runs again with the new texts.
      auto runs_idle = lock_solver_directories({dir}, "hydrojump study (regenerating it)");
      std::ostringstream generated;
      generate_cases(study_, {&c}, options_.resolution, options_.out, generated);
      runs_idle.clear();
      say(c.id + ": only descriptive texts or run-control settings changed: inputs rewritten, results kept");
      util::write_file_atomically(generated_stamp, fingerprint);
      std::filesystem::remove(dir / "compare.stamp");
    }
    if (options_.force || util::read_text_file(generated_stamp) != fingerprint) {
      // The results of a changed case are stale: start its directory afresh, keeping the previous
      // results (hours of runs) as <case>.previous (replacing an older one) instead of deleting them.
      // Not while a run started by hand is still writing in it (that run keeps its directory).
      const auto previous = options_.out / (c.id + ".previous");
      auto runs_idle = lock_solver_directories({dir, previous}, "hydrojump study (moving it)");
      // Results in a directory the study did not make (no stamp: `generate` and `sph` run by hand)
      // are kept the same way. A directory whose solvers never ran (a study stopped after preparing
      // it) holds nothing to keep, and must not replace an older <case>.previous.
      if (solvers_ran_in(dir)) {
        std::filesystem::remove_all(previous);
        std::filesystem::rename(dir, previous);
        say(c.id + ": the case or the program changed: its previous results are kept in " + previous.string());
      } else {
        std::filesystem::remove_all(dir);
      }
      runs_idle.clear();
      std::ostringstream generated;
      generate_cases(study_, {&c}, options_.resolution, options_.out, generated);
      say(c.id + ": " + generated.str().substr(0, generated.str().find_last_not_of('\n') + 1));
      util::write_file_atomically(generated_stamp, fingerprint);
      util::write_file_atomically(run_stamp, run_fingerprint);
    }
    return std::nullopt;
  }

  StageResult run_solver(const cases::Case& c, const std::string& method) {
    const auto dir = options_.out / c.id;
    if (study_stopping()) return {method, "skipped", 0.0, 0, "the study was stopped"};
    std::vector<std::string> args = {self_.string(), method, (dir / method).string()};
    if (method == "sph" && options_.sph_threads > 0) {
      args.push_back("--threads");
      args.push_back(std::to_string(options_.sph_threads));
    }
    if (method == "vof" && options_.mpi_ranks > 1) {
      args.push_back("--np");
      args.push_back(std::to_string(options_.mpi_ranks));
    }
    // Resume an interrupted solver from what it left: the SPH checkpoint, or OpenFOAM's mesh and
    // time directories.
    const auto started = dir / (method + ".started");
    const bool resumable = method == "sph" ? std::filesystem::exists(dir / "sph" / "checkpoint.bin")
                                           : std::filesystem::exists(dir / "vof" / "constant" / "polyMesh");
    if (std::filesystem::exists(started) && resumable) args.push_back("--resume");
    // An SPH run of this study that stopped before its first checkpoint (its outputs and failure.txt
    // are the study's own) starts over; `hydrojump sph` refuses to overwrite them otherwise.
    else if (std::filesystem::exists(started) && method == "sph") args.push_back("--restart");
    // A run that starts from the beginning has no earlier legs.
    if (args.back() != "--resume") std::filesystem::remove(dir / (method + ".legs"));
    return run_stage(c.id, method, args, dir, method_run_key(study_, c, options_.resolution, method), started);
  }

  // Whether a solver ran in the case directory `dir`: its stamp or started marker, or its results.
  static bool solvers_ran_in(const std::filesystem::path& dir) {
    for (const std::string method : {"sph", "vof"})
      if (std::filesystem::exists(dir / (method + ".stamp")) || std::filesystem::exists(dir / (method + ".started")) ||
          cases::holds_results(dir / method))
        return true;
    return false;
  }

  // The case from its validation records (--records) when every method asked for has one whose key is
  // this case's key for that method (method_run_key): the study report reads them instead of a run. A
  // record with another key is stale (other settings or other solver code) and is said so; the case
  // then runs.
  std::optional<CaseResult> import_records(const cases::Case& c, const std::filesystem::path& dir) {
    if (options_.records.empty() || options_.force) return std::nullopt;
    std::vector<compare::ValidationRecord> found;
    for (const auto& method : options_.methods) {
      const auto file = compare::record_file(options_.records, study_.name, c.id, method, options_.resolution);
      const auto record = compare::read_record_if_present(file);
      if (!record) return std::nullopt;
      if (record->failed()) {
        say(c.id + ": record " + file.string() + " is of a run that failed (" + record->failure + "): running it");
        return std::nullopt;
      }
      const std::string key = method_run_key(study_, c, options_.resolution, method);
      if (record->run_key != key) {
        say(c.id + ": record " + file.string() + " is stale (made with run key " + record->run_key +
            "; this case and code give " + key + "): running instead");
        return std::nullopt;
      }
      found.push_back(*record);
    }
    if (found.empty()) return std::nullopt;
    // A directory of results that are not these records' is kept aside, as for a changed case.
    if (cases::holds_results(dir / "sph") || cases::holds_results(dir / "vof")) {
      const auto previous = options_.out / (c.id + ".previous");
      auto runs_idle = lock_solver_directories({dir, previous}, "hydrojump study (moving it)");
      std::filesystem::remove_all(previous);
      std::filesystem::rename(dir, previous);
      say(c.id + ": its earlier results are kept in " + previous.string());
    }
    std::filesystem::remove_all(dir);
    compare::write_imported_comparison(dir, found);
    CaseResult result{c.id, {}};
    std::string files;
    for (const auto& r : found) {
      const auto file = compare::record_file(options_.records, r.study, r.case_id, r.method, r.resolution);
      files += (files.empty() ? "" : ", ") + file.string();
      result.stages.push_back({r.method, "imported", 0.0, 0, "record of " + r.recorded_on});
    }
    say(c.id + ": imported from " + files + " (not run)");
    return result;
  }

  // The threads (SPH) or MPI ranks (VOF) a solver stage runs on. Without --threads `hydrojump sph` takes
  // OpenMP's default (OMP_NUM_THREADS, else the cores of the affinity mask), which it inherits from
  // this process.
  int stage_threads(const std::string& stage) const {
    if (stage == "sph") return options_.sph_threads > 0 ? options_.sph_threads : std::max(1, omp_get_max_threads());
    return options_.mpi_ranks;
  }

  StageResult run_stage(const std::string& id, const std::string& stage, const std::vector<std::string>& args,
                        const std::filesystem::path& dir, const std::string& fingerprint,
                        const std::filesystem::path& started_marker) {
    const auto stamp = dir / (stage + ".stamp");
    if (stamp_current(dir, stage, fingerprint)) {
      say(id + ": " + stage + " up to date (cached)");
      return {stage, "cached", 0.0, 0, {}};
    }
    const auto log_file = dir / (stage + ".log");
    // A request that came since the caller looked: nothing starts (a child stopped before its own
    // handlers are set would die without writing its state).
    if (study_stopping()) return {stage, "skipped", 0.0, 0, "the study was stopped"};
    if (!started_marker.empty()) {
      util::write_file_atomically(started_marker, fingerprint);
      std::filesystem::remove(dir / (stage + ".failed"));  // this run may end otherwise
    }
    say(id + ": " + stage + " started (log: " + log_file.string() + ")");
    const auto t0 = std::chrono::steady_clock::now();
    // On the file system's clock, as the diagnosis' timestamp is (leg_start_time).
    const auto leg_start = leg_start_time(started_marker);
    int status = 127;
    std::string start_error;
    bool stopped = false;
    try {
      util::ChildCommand command(args, log_file);
      command.own_process_group = true;  // a stop request reaches it from the study, once
      command.parent_death_signal = SIGTERM;  // and a study killed outright (SIGKILL) stops it too
      const pid_t pid = util::start_child(command);
      std::optional<util::ChildExit> ended;
      while (!(ended = util::poll_child(pid))) {
        if (study_stopping() && !stopped) {
          ::kill(-pid, SIGTERM);  // its process group: it stops with its state written
          stopped = true;
        }
        if (study_stop_requests.load() >= 2) {
          ended = util::stop_child(pid, std::chrono::seconds(2));  // asked again: at once
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      status = ended->status();
    } catch (const std::exception& e) {
      start_error = e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!start_error.empty()) {
      say(id + ": " + stage + " FAILED: " + start_error);
      return {stage, "failed", seconds, status, start_error};
    }
    if (status != 0 && !started_marker.empty()) add_leg(dir, stage, seconds);
    if (stopped && status != 0) {
      say(id + ": " + stage + " stopped on request after " + duration_text(seconds) + " (the next study resumes it)");
      return {stage, "stopped", seconds, status, {}};
    }
    if (status != 0) {
      say(id + ": " + stage + " FAILED (exit status " + std::to_string(status) + ") after " +
          duration_text(seconds) + "; last lines of " + log_file.string() + ":\n" + tail(log_file, 8));
      // A failed run is a result: `hydrojump record` keeps what stopped it.
      if (!started_marker.empty())
        write_stage_failure(dir, stage, fingerprint, failure_text(dir, stage, log_file, status, leg_start), stage_threads(stage));
      return {stage, "failed", seconds, status, {}};
    }
    if (!started_marker.empty()) write_stage_info(dir, stage, seconds, stage_threads(stage));
    util::write_file_atomically(stamp, fingerprint);
    if (!started_marker.empty()) std::filesystem::remove(started_marker);
    say(id + ": " + stage + " finished in " + duration_text(seconds));
    return {stage, "done", seconds, 0, {}};
  }

  static std::string tail(const std::filesystem::path& file, int lines) {
    const std::string text = util::read_text_file(file);
    std::size_t at = text.size();
    for (int n = 0; n <= lines && at > 0; ++n) {
      const auto p = text.rfind('\n', at - 1);
      if (p == std::string::npos) {
        at = 0;
        break;
      }
      at = p;
      if (n == lines) ++at;
    }
    std::string out;
    std::istringstream in(text.substr(at));
    for (std::string line; std::getline(in, line);) out += "    | " + line + "\n";
    return out;
  }

  void say(const std::string& message) {
    std::lock_guard lock(mutex_);
    log_ << "[" << clock_now() << "] " << message << std::endl;
  }

  const StudyOptions& options_;
  const cases::Study& study_;
  std::ostream& log_;
  std::filesystem::path self_;
  std::mutex mutex_;
};

// The cases of the report: the ones run now, and, in the spec's order among them, every other case of
// the study whose comparison in options.out is current (its compare stamp matches the case's
// fingerprint: same settings, same resolution, same code), so that a long study run a few cases at a
// time (`--cases A,B`, then `--cases C`) ends with one report across all of them.
std::vector<CaseResult> with_earlier_runs(const StudyOptions& options, const cases::Study& study,
                                          const std::vector<CaseResult>& run_now) {
  std::vector<CaseResult> out;
  for (const auto* c : select_cases(study, {})) {
    const auto now = std::find_if(run_now.begin(), run_now.end(), [&](const CaseResult& r) { return r.id == c->id; });
    if (now != run_now.end()) {
      out.push_back(*now);
      continue;
    }
    std::string fingerprint;
    try {
      fingerprint = case_fingerprint(study, *c, options.resolution, source_fingerprint);  // the compare stamp's
    } catch (const std::exception&) {
      continue;  // not valid at this resolution: it cannot have run
    }
    if (util::read_text_file(options.out / c->id / "compare.stamp") == fingerprint)
      out.push_back(CaseResult{c->id, {{"compare", "earlier run", 0.0, 0, {}}}});
  }
  return out;
}

}  // namespace

int stage_jobs(int jobs, int cores_per_stage, int cores, std::size_t stages) {
  if (jobs <= 0) jobs = std::max(1, cores / std::max(1, cores_per_stage));
  return std::max(1, std::min<int>(jobs, static_cast<int>(std::max<std::size_t>(1, stages))));
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

int sph_threads_per_job(int requested, int jobs, int cores) {
  if (requested > 0) return requested;
  if (jobs <= 1) return 0;
  return std::max(1, cores / jobs);
}

namespace {

// Every selected case: prepared one after the other (records imported, directories generated), then
// the solver stages of all of them --jobs at a time (stage_jobs, counting the stages that will run:
// not the cached ones), the largest case's first (run_work: size x simulated time x U1 / dx), each
// case's comparison on the worker that ended its last solver stage. Sets options.jobs and
// options.sph_threads (the runner reads them); the results in the order of `selected`.
std::vector<CaseResult> run_cases(StudyRunner& runner, StudyOptions& options, const std::vector<const cases::Case*>& selected,
                                  std::ostream& log) {
  std::vector<CaseResult> results(selected.size());
  std::vector<std::vector<StageResult>> solvers(selected.size(), std::vector<StageResult>(options.methods.size()));
  std::vector<std::atomic<std::size_t>> left(selected.size());
  struct Stage {
    std::size_t case_index, method_index;
  };
  std::vector<Stage> stages;
  std::vector<double> work;
  std::size_t to_run = 0;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    std::optional<CaseResult> done = study_stopping() ? CaseResult{selected[i]->id, {{"setup", "skipped", 0.0, 0, "the study was stopped"}}}
                                                      : runner.prepare_case(*selected[i]);
    if (done) {
      results[i] = *done;
      continue;
    }
    if (options.methods.empty()) results[i] = runner.finish_case(*selected[i], {});
    left[i] = options.methods.size();
    for (std::size_t m = 0; m < options.methods.size(); ++m) {
      stages.push_back({i, m});
      work.push_back(compare::run_work(*selected[i], options.resolution, "sph"));
      to_run += runner.stage_current(*selected[i], options.methods[m]) ? 0 : 1;
    }
  }
  const int cores = available_cores();
  options.jobs = stage_jobs(options.jobs, std::max(options.mpi_ranks, options.sph_threads), cores, to_run);
  options.sph_threads = sph_threads_per_job(options.sph_threads, options.jobs, cores);
  // Several OpenFOAM runs on several ranks each: Open MPI would bind each run's ranks to the same
  // first cores.
  if (options.jobs > 1 && options.mpi_ranks > 1) ::setenv("OMPI_MCA_hwloc_base_binding_policy", "none", 0);
  log << to_run << " solver stage(s) to run, " << options.jobs << " at a time, the largest case's first"
      << (options.sph_threads > 0 ? ", " + std::to_string(options.sph_threads) + " SPH thread(s) each" : std::string())
      << std::endl;
  run_largest_first(work, options.jobs, [&](std::size_t k) {
    const auto [i, m] = stages[k];
    solvers[i][m] = runner.run_solver_stage(*selected[i], options.methods[m]);
    if (left[i].fetch_sub(1) == 1) results[i] = runner.finish_case(*selected[i], solvers[i]);
  });
  return results;
}

}  // namespace

int run_study(const StudyOptions& given, std::ostream& log) {
  const cases::Study study = load_spec_argument(given.spec);
  const auto selected = select_cases(study, given.cases);
  StudyOptions options = given;
  // Each method once, in the order given (two runs of one solver in one directory would collide).
  std::vector<std::string> methods;
  for (const auto& m : given.methods)
    if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
  options.methods = methods;
  // Validate every selected case first, with what only the solvers' derivations find: nothing runs
  // (and no earlier results are moved aside) while one is invalid.
  check_cases(study, selected, options.resolution);
  // Before hours of SPH runs: an OpenFOAM run could not start in this directory.
  if (std::find(options.methods.begin(), options.methods.end(), "vof") != options.methods.end()) {
    if (const auto problem = reference::openfoam_path_problem(options.out))
      throw std::runtime_error("--out " + options.out.string() + ": " + *problem + " (or --methods sph)");
  }
  {
    std::error_code ec;
    std::filesystem::create_directories(options.out, ec);
    if (ec || !std::filesystem::is_directory(options.out))
      throw std::runtime_error("--out " + options.out.string() + ": cannot be made a study directory (" +
                               (std::filesystem::exists(options.out) ? std::string("a file of that name is there")
                                                                     : ec.message()) +
                               ")");
  }
  // One study per output directory (its case runs lock their own directories too).
  const util::DirectoryLock lock(options.out, "hydrojump study " + options.spec);
  // What a study or comparison killed outright left half-written in the study's own directories (the
  // solvers clean theirs, under their own locks).
  util::remove_orphaned_temporaries(options.out);
  for (const cases::Case* c : selected)
    for (const auto& sub : {options.out / c->id, options.out / c->id / "csv", options.out / c->id / "figures"})
      if (std::filesystem::is_directory(sub)) util::remove_orphaned_temporaries(sub);
  log << "study \"" << study.name << "\": " << selected.size() << " case(s) at resolution \""
      << options.resolution << "\" into " << options.out.string() << std::endl;

  StudyRunner runner(options, study, log);
  const StudyStopSignals stop_signals;
  const std::vector<CaseResult> results = run_cases(runner, options, selected, log);

  write_study_report(options, study, with_earlier_runs(options, study, results), log);
  int failed = 0;
  for (const auto& r : results) failed += r.failed() ? 1 : 0;
  log << "study report: " << (options.out / "study_report.md").string() << "; " << failed << " of "
      << results.size() << " case(s) had a failed stage" << std::endl;
  if (study_stopping()) {
    const int signal = study_stop_signal.load();
    log << "study stopped by " << util::stop_signal_name(signal)
        << ": the stages that were running stopped with their state written, no other stage started; run the "
           "same command again to go on from there"
        << std::endl;
    return 128 + signal;
  }
  return std::min(failed, 127);  // 128 and above: stopped by a signal
}

void register_study_command(CLI::App& app) {
  auto options = std::make_shared<StudyOptions>();
  options->jobs = 0;  // stage_jobs: one stage per core
  auto* cmd = app.add_subcommand(
      "study",
      "Run a whole study: generate every case, run the SPH solver and the OpenFOAM reference, compare "
      "them on common sections, plot, and write OUT/study_report.md. Finished stages are cached by a "
      "hash of the resolved case and of the program's code, so a re-run only runs what changed and an "
      "interrupted study resumes. One failed case is reported and does not stop the others. One study per OUT "
      "at a time: a second one stops at once, naming the first.");
  cmd->add_option("SPEC", options->spec, "study file (TOML), or \"default\" for the embedded ead2002 study")
      ->capture_default_str();
  cmd->add_option("--resolution,-r", options->resolution, "resolution level (quick, default, fine)")
      ->capture_default_str();
  cmd->add_option("--cases", options->cases, "case ids, comma-separated or repeated, or \"all\" (the default: every case)")->delimiter(',');
  cmd->add_option("--out,-o", options->out, "study directory")->capture_default_str()->check(util::non_empty_path());
  cmd->add_option("--jobs,-j", options->jobs, "solver stages (SPH or OpenFOAM runs) run at the same time, the largest cases' first, each case's "
                  "comparison after its last solver stage (default: one per core, one per --np cores with "
                  "--np)")->check(CLI::Range(1, 64));
  cmd->add_option("--np", options->mpi_ranks, "MPI ranks for each OpenFOAM run")->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--threads", options->sph_threads,
                  "OpenMP threads for each SPH run (default: the cores shared out among the stages run at once; "
                  "all of them when one runs)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--methods", options->methods, "solvers to run: sph,vof")
      ->delimiter(',')
      ->check(CLI::IsMember({"sph", "vof"}));
  cmd->add_flag("--force", options->force, "ignore cached results and run every stage again");
  cmd->add_option("--records", options->records,
                  "validation records (`hydrojump record`, e.g. validation/records): a case whose records for every "
                  "method asked for match its settings and the solvers' code is imported instead of run; a stale "
                  "record is named and the case runs")
      ->check(CLI::ExistingDirectory);
  cmd->callback([options] {
    const int status = run_study(*options, std::cout);
    if (status >= 128) throw CLI::RuntimeError(status);  // stopped by a signal: 128 + its number
    if (status > 0) throw CLI::RuntimeError(1);
  });
}

}  // namespace hydrojump::app
