#include "util/child_process.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <csignal>
#include <fcntl.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace hydrojump::util {

namespace fs = std::filesystem;

namespace {

ChildExit decode(int status) {
  ChildExit e;
  if (WIFEXITED(status)) {
    e.exited = true;
    e.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    e.signal = WTERMSIG(status);
  }
  return e;
}

std::string variable_name(const std::string& entry) { return entry.substr(0, entry.find('=')); }

// This process's environment with the command's changes applied.
std::vector<std::string> child_environment(const std::vector<std::string>& changes) {
  std::vector<std::string> env;
  for (char** e = environ; e && *e; ++e) {
    const std::string entry = *e;
    bool changed = false;
    for (const std::string& c : changes) changed = changed || variable_name(c) == variable_name(entry);
    if (!changed) env.push_back(entry);
  }
  for (const std::string& c : changes)
    if (c.find('=') != std::string::npos) env.push_back(c);
  return env;
}

int open_or_throw(const fs::path& file, int flags, const std::string& program, const std::string& what) {
  const int fd = ::open(file.c_str(), flags | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot start " + program + ": cannot open its " + what + " " + file.string() +
                             " (" + std::strerror(errno) + ")");
  }
  if (fd > STDERR_FILENO) return fd;
  const int high = ::fcntl(fd, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
  const int error = errno;
  ::close(fd);
  if (high < 0) throw std::runtime_error("cannot start " + program + ": fcntl failed (" + std::strerror(error) + ")");
  return high;
}

// What the child is made of, prepared by start_child.
struct ChildSetup {
  const char* program;
  char* const* argv;
  char* const* envp;
  int log_fd;
  int null_fd;
  const std::vector<int>& inherited_descriptors;
  const char* working_directory;  // nullptr: this process's
  bool own_process_group;
  int parent_death_signal;  // 0: none
};

// posix_spawn: no copy of this process's memory, safe from a multi-threaded parent, the exec error
// returned. Returns 0 or the error number.
int spawn_and_exec(const ChildSetup& s, pid_t& pid) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, s.log_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, s.log_fd, STDERR_FILENO);
  posix_spawn_file_actions_adddup2(&actions, s.null_fd, STDIN_FILENO);
  // dup2 onto itself clears close-on-exec in the child (POSIX 2018; glibc >= 2.29).
  for (const int fd : s.inherited_descriptors)
    if (fd > STDERR_FILENO) posix_spawn_file_actions_adddup2(&actions, fd, fd);
  if (s.working_directory) posix_spawn_file_actions_addchdir_np(&actions, s.working_directory);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (s.own_process_group) {
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
  }
  const int rc = posix_spawn(&pid, s.program, &actions, &attributes, s.argv, s.envp);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return rc;
}

// For ChildCommand::parent_death_signal: fork, then in the child, before exec, ask Linux for that signal
// when the parent (the forking thread) ends, SIGKILL included (prctl PR_SET_PDEATHSIG; exec keeps the
// request). posix_spawn has no such attribute. Between fork and exec the child makes only
// async-signal-safe calls (the parent may be multi-threaded); an exec failure's error number comes back
// through a close-on-exec pipe, so the caller sees it as from posix_spawn. Returns 0 or the error number.
int fork_and_exec(const ChildSetup& s, pid_t& pid) {
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) return errno;
  const pid_t parent = ::getpid();
  pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(report[0]);
    ::close(report[1]);
    return error;
  }
  if (pid == 0) {
    const auto fail = [&](int error) {
      [[maybe_unused]] const ssize_t n = ::write(report[1], &error, sizeof error);
      ::_exit(127);
    };
    if (s.own_process_group && ::setpgid(0, 0) != 0) fail(errno);
    if (::dup2(s.log_fd, STDOUT_FILENO) < 0 || ::dup2(s.log_fd, STDERR_FILENO) < 0 ||
        ::dup2(s.null_fd, STDIN_FILENO) < 0)
      fail(errno);
    for (const int fd : s.inherited_descriptors)
      if (fd > STDERR_FILENO && ::fcntl(fd, F_SETFD, 0) != 0) fail(errno);
    if (s.working_directory && ::chdir(s.working_directory) != 0) fail(errno);
    if (::prctl(PR_SET_PDEATHSIG, s.parent_death_signal) != 0) fail(errno);
    if (::getppid() != parent) ::_exit(128 + s.parent_death_signal);  // the parent ended before the request
    ::execve(s.program, s.argv, s.envp);
    fail(errno);
  }
  ::close(report[1]);
  int error = 0;
  ssize_t n = 0;
  do {
    n = ::read(report[0], &error, sizeof error);
  } while (n < 0 && errno == EINTR);
  ::close(report[0]);
  if (n == static_cast<ssize_t>(sizeof error)) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return error;
  }
  return 0;
}

}  // namespace

std::string ChildExit::describe() const {
  if (exited) return "exited with code " + std::to_string(exit_code);
  const char* name = ::strsignal(signal);
  return "was killed by signal " + std::to_string(signal) + " (" + (name ? name : "?") + ")";
}

std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path candidate = fs::absolute(fs::path(dir) / name);
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

pid_t start_child(const ChildCommand& command) {
  if (command.argv.empty() || command.argv.front().empty()) throw std::runtime_error("start_child: no program given");
  const std::string& name = command.argv.front();
  if (command.parent_death_signal < 0 || command.parent_death_signal >= NSIG)
    throw std::runtime_error("cannot start " + name + ": " + std::to_string(command.parent_death_signal) +
                             " is not a signal number");
  fs::path program = name;
  if (name.find('/') == std::string::npos) {
    const auto found = find_on_path(name);
    if (!found) throw std::runtime_error("cannot start " + name + ": it is not on PATH");
    program = *found;
  }  // a relative path with a '/' is taken relative to the working directory, as a shell there would
  const std::string dir = command.working_directory.string();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(command.working_directory, ec)) {
    throw std::runtime_error("cannot start " + name + ": cannot enter its working directory " + dir +
                             " (not a directory)");
  }

  // Everything the child needs, built here, before the child exists.
  std::vector<std::string> args = command.argv;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env = child_environment(command.environment);
  std::vector<char*> envp;
  for (std::string& v : env) envp.push_back(v.data());
  envp.push_back(nullptr);

  // Descriptors at 3 or above (a parent started with stdout closed would otherwise get 1 back), all
  // close-on-exec, so children started by other threads meanwhile do not inherit them.
  const int log_fd = open_or_throw(command.log_file, O_WRONLY | O_CREAT | (command.append_to_log ? O_APPEND : O_TRUNC),
                                   name, "log file");
  int null_fd = -1;
  try {
    null_fd = open_or_throw("/dev/null", O_RDONLY, name, "input");
  } catch (...) {
    ::close(log_fd);
    throw;
  }
  const ChildSetup setup{program.c_str(), argv.data(), envp.data(), log_fd, null_fd, command.inherited_descriptors,
                         dir.empty() ? nullptr : dir.c_str(), command.own_process_group,
                         command.parent_death_signal};
  pid_t pid = 0;
  const int rc = command.parent_death_signal != 0 ? fork_and_exec(setup, pid) : spawn_and_exec(setup, pid);
  ::close(log_fd);
  ::close(null_fd);
  if (rc != 0) throw std::runtime_error("cannot start " + name + " (" + program.string() + "): " + std::strerror(rc));
  return pid;
}

ChildExit wait_child(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("waitpid failed for process " + std::to_string(pid) + ": " +
                                                 std::strerror(errno));
  }
  return decode(status);
}

std::optional<ChildExit> poll_child(pid_t pid) {
  int status = 0;
  pid_t r = 0;
  do {
    r = ::waitpid(pid, &status, WNOHANG);
  } while (r < 0 && errno == EINTR);
  if (r == 0) return std::nullopt;
  if (r < 0) throw std::runtime_error("waitpid failed for process " + std::to_string(pid) + ": " + std::strerror(errno));
  return decode(status);
}

ChildExit stop_child(pid_t pid, std::chrono::milliseconds grace) {
  // A child leading its own process group (ChildCommand::own_process_group) is stopped with all it
  // started (mpirun's ranks, a shell's commands), which would otherwise go on running unowned.
  const pid_t target = ::getpgid(pid) == pid ? -pid : pid;
  ::kill(target, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (std::chrono::steady_clock::now() < deadline) {
    if (const auto e = poll_child(pid)) {
      if (target < 0) ::kill(target, SIGKILL);  // what the group's leader left behind
      return *e;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(target, SIGKILL);
  return wait_child(pid);
}

ChildExit run_child(const ChildCommand& command) { return wait_child(start_child(command)); }

}  // namespace hydrojump::util
