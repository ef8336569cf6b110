#include "cases/child_process.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <csignal>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace hydrojump::cases {

namespace fs = std::filesystem;

namespace {

// What the child reports through the close-on-exec pipe when it fails before exec.
struct StartFailure {
  int stage = 0;  // 1: chdir, 2: exec
  int error = 0;  // errno
};

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
  return fd;
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
    const fs::path candidate = fs::path(dir) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

pid_t start_child(const ChildCommand& command) {
  if (command.argv.empty() || command.argv.front().empty()) throw std::runtime_error("start_child: no program given");
  const std::string& name = command.argv.front();
  fs::path program = name;
  if (name.find('/') == std::string::npos) {
    const auto found = find_on_path(name);
    if (!found) throw std::runtime_error("cannot start " + name + ": it is not on PATH");
    program = *found;
  }

  // Everything the child needs, built before fork.
  std::vector<std::string> args = command.argv;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env = child_environment(command.environment);
  std::vector<char*> envp;
  for (std::string& v : env) envp.push_back(v.data());
  envp.push_back(nullptr);
  const std::string dir = command.working_directory.string();

  const int log_fd = open_or_throw(command.log_file, O_WRONLY | O_CREAT | (command.append_to_log ? O_APPEND : O_TRUNC),
                                   name, "log file");
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  int report[2] = {-1, -1};
  if (::pipe2(report, O_CLOEXEC) != 0) {
    ::close(log_fd);
    if (null_fd >= 0) ::close(null_fd);
    throw std::runtime_error("cannot start " + name + ": pipe failed (" + std::strerror(errno) + ")");
  }

  const pid_t pid = ::fork();
  if (pid == 0) {
    // The child: async-signal-safe calls only.
    StartFailure failure;
    if (command.own_process_group) ::setpgid(0, 0);
    if (!dir.empty() && ::chdir(dir.c_str()) != 0) {
      failure = {1, errno};
    } else {
      ::dup2(log_fd, STDOUT_FILENO);
      ::dup2(log_fd, STDERR_FILENO);
      if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
      ::execve(program.c_str(), argv.data(), envp.data());
      failure = {2, errno};
    }
    [[maybe_unused]] const auto written = ::write(report[1], &failure, sizeof failure);
    ::_exit(127);
  }
  const int fork_error = errno;
  ::close(log_fd);
  if (null_fd >= 0) ::close(null_fd);
  ::close(report[1]);
  if (pid < 0) {
    ::close(report[0]);
    throw std::runtime_error("cannot start " + name + ": fork failed (" + std::strerror(fork_error) + ")");
  }
  // The pipe closes on a successful exec and carries a StartFailure otherwise.
  StartFailure failure;
  ssize_t n = 0;
  do {
    n = ::read(report[0], &failure, sizeof failure);
  } while (n < 0 && errno == EINTR);
  ::close(report[0]);
  if (n == static_cast<ssize_t>(sizeof failure)) {
    wait_child(pid);
    if (failure.stage == 1) {
      throw std::runtime_error("cannot start " + name + ": cannot enter its working directory " + dir + " (" +
                               std::strerror(failure.error) + ")");
    }
    throw std::runtime_error("cannot start " + name + " (" + program.string() + "): " + std::strerror(failure.error));
  }
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
  ::kill(pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (std::chrono::steady_clock::now() < deadline) {
    if (const auto e = poll_child(pid)) return *e;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid, SIGKILL);
  return wait_child(pid);
}

ChildExit run_child(const ChildCommand& command) { return wait_child(start_child(command)); }

}  // namespace hydrojump::cases
