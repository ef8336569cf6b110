// Child processes: start a program with its output in a log file, wait for it, stop it.
//
// One implementation for everything hydrojump starts: the study runner's `hydrojump generate/sph/vof/
// compare` stages, the matplotlib scripts, OpenFOAM's utilities and solvers, and the tests that run the
// real executable.
//
// Everything is prepared before the child exists (the program looked up on PATH, the log file opened,
// the environment built) and the child is made by posix_spawn, which is safe from a multi-threaded
// parent and does not copy its memory (by fork, making only async-signal-safe calls before exec, when
// it is to be signalled at its parent's end); a program that cannot be started is an exception naming
// it and the reason instead of an exit status 127 that looks like the program's own.
//
// Usage
//   | field               | meaning                                                  | default        |
//   |---------------------|----------------------------------------------------------|----------------|
//   | argv                | argv[0] is a path, or a name looked up on PATH           | (required)     |
//   | log_file            | receives stdout and stderr                               | /dev/null      |
//   | append_to_log       | append (true) or truncate (false)                        | true           |
//   | working_directory   | the child's working directory                            | this process's |
//   | own_process_group   | Ctrl-C in the terminal reaches the parent only           | false          |
//   | environment         | "NAME=value" sets NAME, "NAME" removes it                | unchanged      |
//   | parent_death_signal | sent to the child when this process ends in any way      | 0 (none)       |
//
// Example
//   ChildCommand mesh({"blockMesh"}, case_dir / "log.blockMesh");
//   mesh.working_directory = case_dir;
//   const ChildExit e = run_child(mesh);
//   if (e.status() != 0) throw std::runtime_error("blockMesh " + e.describe());
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <sys/types.h>

namespace hydrojump::util {

struct ChildCommand {
  ChildCommand(std::vector<std::string> argv_, std::filesystem::path log_file_ = "/dev/null")
      : argv(std::move(argv_)), log_file(std::move(log_file_)) {}

  std::vector<std::string> argv;
  std::filesystem::path log_file;
  bool append_to_log = true;
  std::filesystem::path working_directory;
  bool own_process_group = false;
  std::vector<std::string> environment;
  // Descriptors the child keeps open under the same numbers (all others are close-on-exec): a
  // directory lock it must hold while it runs, even if its parent dies before it (DirectoryLock).
  std::vector<int> inherited_descriptors;
  // A signal (SIGTERM, SIGUSR2, ...) the child gets when this process ends in any way, SIGKILL included
  // (prctl PR_SET_PDEATHSIG, asked for between fork and exec), instead of running on unowned: a study's
  // stage stops as on `kill -TERM`, its state written and its directory lock released; interFoam, told
  // by its controlDict, writes its current time on SIGUSR2 (mpirun passes it to the ranks). 0: none. The
  // thread that starts the child must outlive it (Linux sends the signal when that thread ends).
  int parent_death_signal = 0;
};

// How a child ended.
struct ChildExit {
  bool exited = false;  // it called exit (false: a signal killed it)
  int exit_code = 0;    // when exited
  int signal = 0;       // when killed

  // The shell's convention: the exit code, or 128 + the signal number when a signal killed it.
  int status() const { return exited ? exit_code : 128 + signal; }
  // "exited with code 3", "was killed by signal 9 (Killed)"
  std::string describe() const;
};

// The first executable `name` in the directories of PATH.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

// Starts the command and returns its process id. Throws std::runtime_error naming the program and the
// reason when it cannot be started (not found, not executable, log file or working directory unusable).
pid_t start_child(const ChildCommand& command);

// Waits for the child to end (retrying when a signal interrupts the wait).
ChildExit wait_child(pid_t pid);

// The child's exit when it has ended, nullopt while it runs (does not block).
std::optional<ChildExit> poll_child(pid_t pid);

// Stops a child: SIGTERM, then SIGKILL if it has not ended after `grace`. Returns how it ended.
ChildExit stop_child(pid_t pid, std::chrono::milliseconds grace = std::chrono::seconds(5));

// start_child + wait_child.
ChildExit run_child(const ChildCommand& command);

}  // namespace hydrojump::util
