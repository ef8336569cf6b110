// The solver in legs on the output grid: plan_solver_legs and split_legs_for_control (runner.hpp), and
// one leg of interFoam (serial, or mpirun ... -parallel) run to its end time while its log is read:
// progress lines, divergence and crash detection (solver_log.hpp), a stop request that makes it
// write its current time and stop, and the message that says how to go on.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <sstream>
#include <thread>

#include <signal.h>
#include <unistd.h>

#include "reference/discharge_samples.hpp"
#include "reference/runner_parts.hpp"
#include "reference/solver_log.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

std::vector<SolverLeg> plan_solver_legs(double start_s, double end_s, std::optional<double> interval) {
  if (!(end_s > start_s)) return {};  // the run already reached its end time
  if (!interval) return {SolverLeg{end_s, std::nullopt}};
  const double dt = *interval, eps = 1e-6;
  const double first = std::ceil(start_s / dt - eps) * dt;
  const double last = std::floor(end_s / dt + eps) * dt;
  auto on = [&](double a, double b) { return std::abs(a - b) <= eps * dt; };
  if (first > last + eps * dt) return {SolverLeg{end_s, end_s - start_s}};  // no grid time in between
  std::vector<SolverLeg> legs;
  if (!on(first, start_s)) legs.push_back(SolverLeg{on(first, end_s) ? end_s : first, first - start_s});
  if (last > first + eps * dt) legs.push_back(SolverLeg{on(last, end_s) ? end_s : last, std::nullopt});
  if (!on(last, end_s)) legs.push_back(SolverLeg{end_s, end_s - last});
  return legs;
}

std::vector<SolverLeg> split_legs_for_control(const std::vector<SolverLeg>& legs, double start_s, double interval_s) {
  if (!(interval_s > 0.0)) return legs;
  std::vector<SolverLeg> out;
  double begin = start_s;
  for (const SolverLeg& leg : legs) {
    if (!leg.write_interval_s) {
      // at k interval from t = 0, so that a resumed run acts when an uninterrupted one would
      const double eps = 1e-6 * interval_s;
      for (double k = std::floor((begin + eps) / interval_s) + 1.0; k * interval_s < leg.end_s - eps; k += 1.0) {
        out.push_back(SolverLeg{k * interval_s, std::nullopt});
      }
    }
    out.push_back(leg);
    begin = leg.end_s;
  }
  return out;
}

namespace detail {

namespace {

// Appends the resume mark to the solver's log; returns the log's size after it, where this leg's
// reading starts.
std::uintmax_t mark_resumed_log(const fs::path& log_file, double start) {
  std::ofstream mark(log_file, std::ios::app);
  mark << "\n// ---- resumed by hydrojump from t = " << format_seconds(start) << " s ----\n";
  mark.close();
  std::error_code ec;
  const std::uintmax_t offset = fs::file_size(log_file, ec);
  return ec ? 0 : offset;
}

// The solver's log as it grows: each read hands the text written since the last one to `log`.
class LogFollower {
 public:
  LogFollower(fs::path file, std::uintmax_t offset, SolverLog& log)
      : file_(std::move(file)), offset_(offset), log_(log) {}
  void read_new() {
    std::ifstream in(file_, std::ios::binary);
    if (!in) return;
    in.seekg(static_cast<std::streamoff>(offset_));
    std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    offset_ += chunk.size();
    log_.add_text(chunk);
  }

 private:
  fs::path file_;
  std::uintmax_t offset_;
  SolverLog& log_;
};

// The progress lines of one leg: simulated time, time step, Courant number, wall time and
//   ETA = (t_end - t) wall / (t - t_begin)
// and, for a stilling basin, the water balance over the last simulated second of this run, or since it
// started (discharge_samples.hpp). On a terminal one line rewritten every second, else a line every
// progress_interval_s.
class SolverProgress {
 public:
  SolverProgress(const SolverRun& run, const SolverLog& log, double t_begin, std::ostream& out)
      : run_(run), log_(log), t_begin_(t_begin), out_(out),
        interactive_((&out == &std::cout) && ::isatty(STDOUT_FILENO)),
        begin_(std::chrono::steady_clock::now()), last_report_(begin_) {}
  bool interactive() const { return interactive_; }

  // A line when one is due.
  void report_if_due() {
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_report_).count();
    if (interactive_ ? since >= 1.0 : since >= run_.options.progress_interval_s) {
      show(false);
      last_report_ = now;
    }
  }

  void show(bool final_line) const {
    const std::string line = text();
    if (interactive_) {
      out_ << "\r" << line << "    " << (final_line ? "\n" : "") << std::flush;
    } else {
      out_ << line << "\n" << std::flush;
    }
  }

 private:
  std::string text() const {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
    const double t = log_.time_s().value_or(t_begin_);
    const double done = t - t_begin_;
    const double eta = done > 0 ? (run_.run_end_s - t) * wall / done : std::nan("");
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "  t = %.4g / %.4g s (%.1f %%), dt = %.3g s, Co max %.3g, wall %s, ETA %s",
                  t, run_.run_end_s, 100.0 * t / run_.run_end_s, log_.time_step_s().value_or(0.0),
                  log_.courant_max().value_or(0.0), format_duration(wall).c_str(),
                  format_duration(eta).c_str());
    return std::string(buffer) + water_balance(t);
  }

  // ", q_in .., q_out .. [+ top ..] m2/s (last .. s)", or nothing (no basin, no samples yet).
  std::string water_balance(double t) const {
    const double balance_from = std::max(t_begin_, t - 1.0);
    if (!run_.c.stilling_basin() || !(t > balance_from)) return "";
    try {
      if (const auto q = patch_discharges(run_.dir, balance_from, t, run_.thickness_m)) {
        std::ostringstream balance;
        balance << std::setprecision(4) << ", q_in " << q->inflow_m2_s << ", q_out " << q->outflow_m2_s;
        if (q->top_outflow_m2_s > 0.001 * q->inflow_m2_s) balance << " + top " << q->top_outflow_m2_s;
        balance << " m2/s (last " << t - balance_from << " s)";
        return balance.str();
      }
    } catch (const std::exception&) {
      // a sample file being written: the next progress line reads it again
    }
    return "";
  }

  const SolverRun& run_;
  const SolverLog& log_;
  double t_begin_;
  std::ostream& out_;
  bool interactive_;
  std::chrono::steady_clock::time_point begin_, last_report_;
};

// How the solver ended, and whether this run asked it to write and stop.
struct SolverEnd {
  util::ChildExit exit;
  bool stop_sent = false;
};

// Waits for the solver while reading its log: a stop request makes it write its current time and stop
// (it is killed 120 s later if it has not), a failure the log shows (divergence, a crash) stops it.
SolverEnd watch_solver(pid_t pid, LogFollower& follower, const SolverLog& log, SolverProgress& progress,
                       std::ostream& out) {
  std::optional<util::ChildExit> ended;  // how interFoam ended; nullopt while it runs
  bool stop_sent = false;
  std::chrono::steady_clock::time_point stop_time;
  while (!ended) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ended = util::poll_child(pid);
    if (stop_request_count() > 0 && !ended && !stop_sent) {
      ::kill(pid, write_and_stop_signal);  // first: the message may go to a pipe a hangup has closed
      out << (progress.interactive() ? "\n" : "") << "Stop requested: interFoam writes the current time and stops...\n"
          << std::flush;
      stop_sent = true;
      stop_time = std::chrono::steady_clock::now();
    }
    if (stop_sent && !ended &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - stop_time).count() > 120.0) {
      ended = util::stop_child(pid);
    }
    follower.read_new();
    if (log.failed() && !ended) {
      ended = util::stop_child(pid);
      follower.read_new();
    }
    if (!ended) progress.report_if_due();
  }
  return SolverEnd{*ended, stop_sent};
}

// The time the solver reached; a stop request, a failure or an end before `end_time_s` throws
// OpenFoamError with the last lines of its log and how to go on.
double solver_time_reached(const SolverRun& run, const SolverLog& log, const SolverEnd& end, double t_begin,
                           double end_time_s) {
  const std::string np_option = run.parallel ? " --np " + std::to_string(run.options.np) : std::string();
  if (end.stop_sent) {
    const auto written = latest_time(run.parallel ? run.dir / "processor0" : run.dir);
    throw OpenFoamError("interrupted: interFoam stopped at t = " + format_seconds(log.time_s().value_or(t_begin)) +
                        " s; latest time directory " + (written ? format_seconds(*written) + " s" : std::string("none")) +
                        ". Continue with `hydrojump vof " + run.dir.string() + " --resume" + np_option + "`.");
  }
  const auto last_written = latest_time(run.parallel ? run.dir / "processor0" : run.dir);
  const std::string resume_hint =
      last_written ? " The last time directory written is t = " + format_seconds(*last_written) +
                         " s (inspect it; a run that diverged may have written non-physical fields just "
                         "before stopping). To retry, lower maxCo/maxAlphaCo in system/controlDict, delete the "
                         "bad time directories and run `hydrojump vof DIR --resume`."
                   : std::string();
  if (log.failed() || end.exit.status() != 0) {
    const std::string why = log.failed() ? log.failure() : "the solver " + end.exit.describe();
    throw OpenFoamError("interFoam stopped in " + run.dir.string() + ": " + why + "." + resume_hint +
                        "\nLast lines of log.interFoam" + (log.failed() ? " up to the failure" : "") + ":\n" +
                        (log.failed() ? log.failure_context() : log.tail()));
  }
  const double reached = log.time_s().value_or(t_begin);
  if (reached < end_time_s * (1.0 - 1e-6) - 1e-12) {
    throw OpenFoamError("interFoam ended at t = " + format_seconds(reached) + " s before the end time " +
                        format_seconds(end_time_s) + " s." + resume_hint + "\nLast lines of log.interFoam:\n" +
                        log.tail());
  }
  return reached;
}

}  // namespace

double run_solver(const SolverRun& run, std::optional<double> start, double end_time_s, std::ostream& out) {
  const fs::path& dir = run.dir;
  const fs::path log_file = dir / "log.interFoam";
  const std::uintmax_t offset = start ? mark_resumed_log(log_file, *start) : 0;
  out << "Running " << command_text(run.command) << " to t = " << format_seconds(end_time_s)
      << " s (log: log.interFoam)\n" << std::flush;
  // The solver holds the directory's lock too: if this runner dies (SIGKILL, out of memory) while
  // interFoam goes on, a second `hydrojump vof DIR` is refused until that solver has ended.
  const pid_t pid = spawn(run.command, dir, log_file, start.has_value(), {run.lock.descriptor()});
  // What a second runner is shown, also when this one was killed and the solver runs on.
  run.lock.set_note("its solver " + run.command.front() + ", pid " + std::to_string(pid),
                    "`kill -USR2 " + std::to_string(pid) + "` makes it write its current time and stop (then `hydrojump vof " +
                        dir.string() + " --resume" + (run.parallel ? " --np " + std::to_string(run.options.np) : std::string()) +
                        "`)");
  struct NoteCleared {
    const util::DirectoryLock& lock;
    ~NoteCleared() { lock.set_note(""); }
  } note_cleared{run.lock};
  SolverLog log(DivergenceLimits{run.c.vof.max_courant, 25.0, 1e-9});
  const double t_begin = start.value_or(0.0);
  SolverProgress progress(run, log, t_begin, out);
  LogFollower follower(log_file, offset, log);
  const SolverEnd end = watch_solver(pid, follower, log, progress, out);
  progress.show(true);
  return solver_time_reached(run, log, end, t_begin, end_time_s);
}

}  // namespace detail

}  // namespace hydrojump::reference
