// Child processes (util/child_process.hpp) with /bin/sh as the child: exit codes, signals, the log
// file (appended or truncated), the working directory, environment changes, and programs that cannot
// be started (an exception naming them, not a status 127 that looks like the program's own); each both
// ways a child is made (posix_spawn, and fork for a parent_death_signal), and a child that gets its
// signal when its parent is killed outright.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <optional>
#include <thread>

#include <sys/prctl.h>
#include <unistd.h>

#include "util/child_process.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump::util;
namespace util = hydrojump::util;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A shell command; by_fork chooses how the child is made (fork, for a parent_death_signal, instead of
// posix_spawn).
util::ChildCommand shell(const std::string& script, const fs::path& log, bool by_fork = false) {
  ChildCommand c({"/bin/sh", "-c", script}, log);
  c.parent_death_signal = by_fork ? SIGTERM : 0;
  return c;
}

}  // namespace

TEST_CASE("A child's exit code and output reach the caller and its log file", "[cases][process]") {
  const bool by_fork = GENERATE(false, true);
  INFO("parent_death_signal (made by fork): " << by_fork);
  const hydrojump::testing::TempDir tmp("child");
  const fs::path& dir = tmp.path();
  const fs::path log = dir / "out.log";
  const util::ChildExit e = run_child(shell("echo to-stdout; echo to-stderr >&2; exit 3", log, by_fork));
  CHECK(e.exited);
  CHECK(e.exit_code == 3);
  CHECK(e.status() == 3);
  CHECK(e.describe() == "exited with code 3");
  CHECK(read(log) == "to-stdout\nto-stderr\n");

  // Appended by default, truncated on request.
  CHECK(util::run_child(shell("echo second", log, by_fork)).status() == 0);
  CHECK(read(log) == "to-stdout\nto-stderr\nsecond\n");
  util::ChildCommand truncate = shell("echo only", log, by_fork);
  truncate.append_to_log = false;
  CHECK(util::run_child(truncate).status() == 0);
  CHECK(read(log) == "only\n");

  // stdin is /dev/null: a child that reads it ends instead of waiting for a terminal.
  CHECK(util::run_child(shell("cat; echo read-done", log, by_fork)).status() == 0);
  CHECK(read(log) == "only\nread-done\n");
}

TEST_CASE("A child killed by a signal reports it as 128 + the signal number", "[cases][process]") {
  const hydrojump::testing::TempDir tmp("child");
  const fs::path& dir = tmp.path();
  const util::ChildExit e = run_child(shell("kill -KILL $$", dir / "log"));
  CHECK_FALSE(e.exited);
  CHECK(e.signal == 9);
  CHECK(e.status() == 137);
  CHECK_THAT(e.describe(), Catch::StartsWith("was killed by signal 9"));

  // stop_child: SIGTERM first; a child that ignores it is killed after the grace period.
  const pid_t polite = util::start_child(shell("sleep 30", dir / "log"));
  CHECK_FALSE(util::poll_child(polite).has_value());  // still running
  const util::ChildExit stopped = stop_child(polite);
  CHECK(stopped.signal == 15);
  const pid_t stubborn = util::start_child(shell("trap '' TERM; echo ready; while :; do sleep 0.1; done", dir / "stubborn.log"));
  // Wait until the shell has installed its trap (it says so).
  const auto ready_by = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (read(dir / "stubborn.log").find("ready") == std::string::npos) {
    REQUIRE(std::chrono::steady_clock::now() < ready_by);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const auto t0 = std::chrono::steady_clock::now();
  const util::ChildExit killed = stop_child(stubborn, std::chrono::milliseconds(300));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(killed.signal == 9);
  CHECK(seconds < 5.0);
}

TEST_CASE("stop_child stops a process-group leader with everything it started", "[cases][process]") {
  const bool by_fork = GENERATE(false, true);
  INFO("parent_death_signal (made by fork): " << by_fork);
  const hydrojump::testing::TempDir tmp("child_group");
  const fs::path& dir = tmp.path();
  // As mpirun with its ranks: a shell in its own process group waiting for a command it started.
  util::ChildCommand command = shell("sleep 60 & echo $! > '" + (dir / "grandchild").string() + "'; wait", dir / "log", by_fork);
  command.own_process_group = true;
  const pid_t leader = util::start_child(command);
  const auto ready_by = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (read(dir / "grandchild").find('\n') == std::string::npos) {
    REQUIRE(std::chrono::steady_clock::now() < ready_by);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const pid_t grandchild = std::stoi(read(dir / "grandchild"));
  util::stop_child(leader);
  // The command it started is gone too (or a zombie waiting for init to reap it), not still running.
  const auto gone_by = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  const auto running = [grandchild] {
    const std::string stat = read("/proc/" + std::to_string(grandchild) + "/stat");
    if (stat.empty()) return false;
    const auto close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z';
  };
  while (running() && std::chrono::steady_clock::now() < gone_by) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK_FALSE(running());
  if (running()) ::kill(grandchild, SIGKILL);
}

TEST_CASE("A child runs in its working directory with the requested environment changes", "[cases][process]") {
  const bool by_fork = GENERATE(false, true);
  INFO("parent_death_signal (made by fork): " << by_fork);
  const hydrojump::testing::TempDir tmp("child");
  const fs::path& dir = tmp.path();
  fs::create_directories(dir / "work");
  ::setenv("HYDROJUMP_TEST_REMOVED", "present", 1);
  ::setenv("HYDROJUMP_TEST_REPLACED", "old", 1);
  util::ChildCommand c = shell("pwd; echo \"${HYDROJUMP_TEST_REMOVED:-unset} $HYDROJUMP_TEST_REPLACED $HYDROJUMP_TEST_ADDED\"",
                         dir / "log", by_fork);
  c.working_directory = dir / "work";
  c.environment = {"HYDROJUMP_TEST_REMOVED", "HYDROJUMP_TEST_REPLACED=new", "HYDROJUMP_TEST_ADDED=added"};
  REQUIRE(util::run_child(c).status() == 0);
  CHECK(read(dir / "log") == fs::canonical(dir / "work").string() + "\nunset new added\n");
  // The parent's environment is untouched.
  CHECK(std::string(std::getenv("HYDROJUMP_TEST_REMOVED")) == "present");
  CHECK(std::string(std::getenv("HYDROJUMP_TEST_REPLACED")) == "old");
  ::unsetenv("HYDROJUMP_TEST_REMOVED");
  ::unsetenv("HYDROJUMP_TEST_REPLACED");
}

TEST_CASE("A program that cannot be started is an error naming it and the reason", "[cases][process]") {
  const bool by_fork = GENERATE(false, true);
  INFO("parent_death_signal (made by fork): " << by_fork);
  const hydrojump::testing::TempDir tmp("child");
  const fs::path& dir = tmp.path();
  auto message = [by_fork](ChildCommand c) -> std::string {
    c.parent_death_signal = by_fork ? SIGTERM : 0;
    try {
      util::run_child(c);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no exception";
  };
  CHECK(message(util::ChildCommand({"hydrojump-no-such-program"}, dir / "log")) ==
        "cannot start hydrojump-no-such-program: it is not on PATH");
  CHECK_THAT(message(util::ChildCommand({(dir / "missing").string()}, dir / "log")),
             Catch::Contains("cannot start " + (dir / "missing").string()) &&
                 Catch::Contains("No such file or directory"));
  std::ofstream(dir / "not-executable") << "#!/bin/sh\n";
  CHECK_THAT(message(util::ChildCommand({(dir / "not-executable").string()}, dir / "log")), Catch::Contains("Permission denied"));
  util::ChildCommand no_dir = shell("true", dir / "log");
  no_dir.working_directory = dir / "absent";
  CHECK_THAT(message(no_dir), Catch::Contains("cannot enter its working directory " + (dir / "absent").string()));
  CHECK_THAT(message(shell("true", dir / "absent" / "log")),
             Catch::Contains("cannot open its log file " + (dir / "absent" / "log").string()));
  // A name on PATH is found.
  CHECK(util::find_on_path("sh").has_value());
  util::ChildCommand bad_signal = shell("true", dir / "log");
  bad_signal.parent_death_signal = 1000;
  CHECK_THROWS_WITH(util::run_child(bad_signal), "cannot start /bin/sh: 1000 is not a signal number");
  CHECK(util::run_child(util::ChildCommand({"sh", "-c", "exit 0"}, dir / "log")).status() == 0);
}

// ChildCommand::parent_death_signal: a parent killed outright (SIGKILL, no handler of its own runs)
// takes its child with it (SIGTERM here, SIGUSR2 as `hydrojump vof` asks); without one the child runs
// on. The parent here is a process forked by the test; the test takes in the orphan
// (PR_SET_CHILD_SUBREAPER) so that it can wait for it.
TEST_CASE("A child started with a parent_death_signal gets it when its parent is killed outright", "[cases][process]") {
  const int death_signal = GENERATE(SIGTERM, SIGUSR2, 0);
  INFO("parent_death_signal: " << death_signal);
  REQUIRE(::prctl(PR_SET_CHILD_SUBREAPER, 1) == 0);
  struct NoLongerSubreaper {
    ~NoLongerSubreaper() { ::prctl(PR_SET_CHILD_SUBREAPER, 0); }
  } restore;
  int channel[2];
  REQUIRE(::pipe(channel) == 0);
  const pid_t parent = ::fork();
  REQUIRE(parent >= 0);
  if (parent == 0) {  // the parent to be killed: starts `sleep 60`, tells its pid, waits
    ::close(channel[0]);
    pid_t child = 0;
    try {
      util::ChildCommand sleeper({"sleep", "60"});
      sleeper.parent_death_signal = death_signal;
      child = util::start_child(sleeper);
    } catch (...) {
      ::_exit(1);
    }
    if (::write(channel[1], &child, sizeof child) != static_cast<ssize_t>(sizeof child)) ::_exit(1);
    for (;;) ::pause();
  }
  ::close(channel[1]);
  pid_t child = 0;
  const ssize_t n = ::read(channel[0], &child, sizeof child);
  ::close(channel[0]);
  ::kill(parent, SIGKILL);
  CHECK(util::wait_child(parent).signal == SIGKILL);
  REQUIRE(n == static_cast<ssize_t>(sizeof child));
  // The orphan is this process's child now.
  std::optional<util::ChildExit> ended;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(death_signal != 0 ? 10 : 2);
  while (!(ended = util::poll_child(child)) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (death_signal != 0) {
    REQUIRE(ended.has_value());
    CHECK_FALSE(ended->exited);
    CHECK(ended->signal == death_signal);
  } else {
    CHECK_FALSE(ended.has_value());  // still running: stopped here
    if (!ended) util::stop_child(child);
  }
}
