// The OpenFOAM processes of `hydrojump vof` (internal to reference/): starting a utility or the solver
// in its own process group, the stop requests (Ctrl-C, SIGTERM, a hangup) and waiting with them, and
// one utility run as a step of the run, logged to DIR/log.<application>.
//
// A stop request during a step stops the utility (the solver instead writes its current time and stops,
// solver_legs.cpp), and no further step starts. If hydrojump itself dies, the child gets SIGUSR2
// (PR_SET_PDEATHSIG): interFoam writes its current time and stops, the utilities end.
#pragma once

#include <csignal>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <sys/types.h>

#include "reference/runner.hpp"
#include "util/child_process.hpp"
#include "util/directory_lock.hpp"
#include "util/stop_signals.hpp"

namespace hydrojump::reference::detail {

// The signal the generated controlDict tells interFoam to treat as "write now and stop"
// (OptimisationSwitches/stopAtWriteNowSignal); SIGUSR2 is forwarded to the ranks by mpirun.
inline constexpr int write_and_stop_signal = SIGUSR2;

// A scratch directory removed when the scope ends, also when a step inside it fails (errors while
// removing are ignored: they must not replace the step's own error).
class ScratchDirectory {
 public:
  explicit ScratchDirectory(std::filesystem::path path) : path_(std::move(path)) {}
  ~ScratchDirectory() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The number of stop requests (Ctrl-C, SIGTERM, a hangup) since the StopRequestGuard of this run was
// installed.
std::sig_atomic_t stop_request_count();

// Installs SIGINT/SIGTERM handlers for its lifetime (one run of `hydrojump vof`), and a SIGHUP one
// unless SIGHUP is ignored (nohup): a closed terminal stops the solver with its state written, instead
// of leaving it running unowned (it runs in its own process group, which the hangup does not reach).
// The run stops at the next safe point: the solver writes its current time and stops, a utility
// (blockMesh, decomposePar, reconstructPar, ...) is stopped, and no further step starts.
class StopRequestGuard {
 public:
  StopRequestGuard();

 private:
  util::StopSignalHandlers handlers_;
};

// The last `n` lines of a text file, indented.
std::string tail_file(const std::filesystem::path& file, std::size_t n = 20);

// Starts `argv` in `cwd` with stdout and stderr going to `log` (appended or truncated), in its own
// process group: Ctrl-C reaches hydrojump, which asks the solver to write and stop; when hydrojump ends
// in any way, SIGKILL included, the child gets SIGUSR2 (interFoam writes its current time and stops;
// mpirun passes it to the ranks; the utilities end). OpenFOAM warns when PWD differs from the working
// directory.
pid_t spawn(const std::vector<std::string>& argv, const std::filesystem::path& cwd, const std::filesystem::path& log,
            bool append, std::vector<int> inherited_descriptors = {});

// The exit status (128 + signal when killed) of a child started by spawn.
int wait_for(pid_t pid);

// The command line of `argv`, its words separated by blanks.
std::string command_text(const std::vector<std::string>& argv);

// A time in seconds with 4 significant digits, as the runner's messages write it.
std::string format_seconds(double t);

// Waits for a child started by spawn; a stop request made since `requests_before` stops it instead
// (nothing is returned then).
std::optional<util::ChildExit> wait_unless_stop_requested(pid_t pid, std::sig_atomic_t requests_before);

// Whether a step runs after a stop request made before it started: a step of the run does not
// start; the reconstruction of what an interrupted parallel run wrote does (a new request stops it).
enum class AfterStopRequest { skip, run };

// Thrown by run_step when a stop request stopped its utility or kept it from starting; the run adds
// how to go on.
class StepStopped : public OpenFoamError {
 public:
  using OpenFoamError::OpenFoamError;
};

// Where a run's utilities run: the case directory, the stream their command lines are shown on, and
// the directory's lock, which each utility inherits, so that one still writing when hydrojump dies
// (killed) keeps the directory from a second run until it ends, as the solver does.
struct StepPlace {
  const std::filesystem::path& dir;
  std::ostream& out;
  const util::DirectoryLock& lock;
};

// Runs one utility to completion; a non-zero exit stops the run with the tail of its log. A stop
// request stops it (what it wrote is not used: the next run starts the step again).
void run_step(const StepPlace& place, const std::vector<std::string>& argv, const std::string& log_name,
              AfterStopRequest after_request = AfterStopRequest::skip);

}  // namespace hydrojump::reference::detail
