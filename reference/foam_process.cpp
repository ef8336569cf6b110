// The OpenFOAM processes of `hydrojump vof` (foam_process.hpp): spawning, the stop requests and
// waiting with them, and one utility as a step of the run.
#include "reference/foam_process.hpp"

#include <chrono>
#include <cstdio>
#include <deque>
#include <fstream>
#include <thread>

namespace hydrojump::reference::detail {

namespace fs = std::filesystem;

namespace {

// The stop requests (Ctrl-C, SIGTERM, a hangup) since the StopRequestGuard of this run was installed.
volatile std::sig_atomic_t stop_requests = 0;
void reference_runner_request_stop(int) { stop_requests = stop_requests + 1; }

}  // namespace

std::sig_atomic_t stop_request_count() { return stop_requests; }

// A progress line written to a pipe whose reader a hangup ended must not kill the runner before it has
// stopped the solver (the write fails instead).
StopRequestGuard::StopRequestGuard()
    : handlers_{reference_runner_request_stop, {.restart_interrupted_calls = false, .ignore_sigpipe = true}} {
  stop_requests = 0;
}

std::string tail_file(const fs::path& file, std::size_t n) {
  std::ifstream in(file);
  std::deque<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    lines.push_back(line);
    if (lines.size() > n) lines.pop_front();
  }
  std::string out;
  for (const std::string& l : lines) out += "    " + l + "\n";
  return out;
}

pid_t spawn(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& log, bool append,
            std::vector<int> inherited_descriptors) {
  try {
    util::ChildCommand command(argv, log);
    command.append_to_log = append;
    command.inherited_descriptors = std::move(inherited_descriptors);
    command.working_directory = cwd;
    command.own_process_group = true;
    command.parent_death_signal = write_and_stop_signal;  // hydrojump killed outright (SIGKILL) stops it too
    command.environment = {"PWD=" + cwd.string()};
    return util::start_child(command);
  } catch (const std::exception& e) {
    throw OpenFoamError(e.what());
  }
}

// The exit status (128 + signal when killed) of a child started by spawn.
int wait_for(pid_t pid) { return util::wait_child(pid).status(); }

std::string command_text(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

std::optional<util::ChildExit> wait_unless_stop_requested(pid_t pid, std::sig_atomic_t requests_before) {
  for (;;) {
    if (auto ended = util::poll_child(pid)) return ended;
    if (stop_request_count() != requests_before) {
      util::stop_child(pid);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void run_step(const StepPlace& place, const std::vector<std::string>& argv, const std::string& log_name,
              AfterStopRequest after_request) {
  const fs::path& dir = place.dir;
  std::ostream& out = place.out;
  const std::sig_atomic_t requests_before = after_request == AfterStopRequest::run ? stop_request_count() : 0;
  const std::string interrupted = "interrupted: " + argv.front() + " in " + dir.string() + " was stopped on request.";
  if (stop_request_count() != requests_before) throw StepStopped(interrupted);
  out << "  " << command_text(argv) << "  (log: " << log_name << ")\n" << std::flush;
  const fs::path log = dir / log_name;
  const auto ended =
      wait_unless_stop_requested(spawn(argv, dir, log, false, {place.lock.descriptor()}), requests_before);
  if (!ended) throw StepStopped(interrupted);
  if (ended->status() != 0) {
    throw OpenFoamError(argv.front() + " failed (it " + ended->describe() + ") in " + dir.string() +
                        "; last lines of " + log_name + ":\n" + tail_file(log));
  }
}

std::string format_seconds(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", t);
  return buffer;
}

}  // namespace hydrojump::reference::detail
