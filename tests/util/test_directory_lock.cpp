// The run-directory lock (util/directory_lock.hpp): a second holder is refused with a message naming
// the first; the lock goes with its holder, including one killed by SIGKILL; children do not inherit it
// unless given its descriptor.
#include <catch2/catch.hpp>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include <csignal>
#include <unistd.h>

#include "util/child_process.hpp"
#include "util/directory_lock.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump::util;
namespace util = hydrojump::util;
namespace fs = std::filesystem;

namespace {

std::string busy_message(const fs::path& dir) {
  try {
    const util::DirectoryLock second(dir, "second");
  } catch (const DirectoryBusy& e) {
    return e.what();
  }
  return "not refused";
}

}  // namespace

TEST_CASE("A run directory is locked by one holder at a time", "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  {
    const util::DirectoryLock first(dir, "hydrojump sph");  // creates the directory
    CHECK(fs::is_directory(dir));
    const std::string message = busy_message(dir);
    CHECK_THAT(message, Catch::StartsWith(dir.string() + " is in use by another process (hydrojump sph, pid " +
                                          std::to_string(::getpid()) + ")"));
  }
  // Released with its holder: the next one gets it.
  { const util::DirectoryLock again(dir, "again"); }
}

TEST_CASE("A lock held by a process goes with it, even when it is killed", "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  fs::create_directories(dir);
  // flock(1) from util-linux (essential in Debian) takes the same kind of lock on the same file and,
  // with --no-fork, becomes the sleeping holder itself. It waits for the lock (no --nonblock): the
  // probe below holds it for an instant, and a non-blocking flock that met the probe gave up at once
  // and left the loop waiting for a holder that never came (seen on a loaded machine).
  const auto flock_program = util::find_on_path("flock");
  if (!flock_program) FAIL("flock(1) (util-linux) is needed for this test");
  const pid_t holder = util::start_child(util::ChildCommand(
      {flock_program->string(), "--no-fork", (dir / DirectoryLock::file_name).string(), "sleep", "30"}));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  std::string message;
  while ((message = busy_message(dir)) == "not refused") {
    REQUIRE(std::chrono::steady_clock::now() < deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  CHECK_THAT(message, Catch::Contains(dir.string() + " is in use by another process"));
  ::kill(holder, SIGKILL);
  CHECK(util::wait_child(holder).signal == SIGKILL);
  CHECK(busy_message(dir) == "not refused");  // no stale lock to delete by hand
}

TEST_CASE("A child started while the lock is held does not keep it", "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  pid_t child = 0;
  {
    const util::DirectoryLock lock(dir, "parent");
    child = util::start_child(util::ChildCommand({"/bin/sh", "-c", "sleep 5"}));
  }
  // The parent let go; the sleeping child must not hold the lock.
  CHECK(busy_message(dir) == "not refused");
  util::stop_child(child);
}

TEST_CASE("A child given the lock's descriptor holds the lock until it ends, also after its parent let go",
          "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  pid_t child = 0;
  {
    const util::DirectoryLock lock(dir, "hydrojump vof");
    REQUIRE(lock.descriptor() > 2);
    // sleep itself, in its own group (a shell could leave a forked sleep holding the lock after stop_child).
    util::ChildCommand solver({"/bin/sleep", "30"});
    solver.own_process_group = true;
    solver.inherited_descriptors = {lock.descriptor()};
    child = util::start_child(solver);
  }
  // As interFoam after its runner was killed: a second runner is refused while it runs.
  CHECK_THAT(busy_message(dir), Catch::Contains("in use by another process (hydrojump vof"));
  util::stop_child(child);
  CHECK(busy_message(dir) == "not refused");
}

TEST_CASE("The holder's note on the child it runs is shown, and taken back", "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  const util::DirectoryLock lock(dir, "hydrojump vof");
  const std::string holder = "hydrojump vof, pid " + std::to_string(::getpid());
  lock.set_note("its solver interFoam, pid 4242", "`kill -USR2 4242` stops it");
  // The holder runs: the hint for a child left running is not shown.
  const std::string message = busy_message(dir);
  CHECK_THAT(message, Catch::Contains("in use by another process (" + holder + "; its solver interFoam, pid 4242)"));
  CHECK_THAT(message, !Catch::Contains("kill"));
  lock.set_note("");
  CHECK_THAT(busy_message(dir), Catch::Contains("in use by another process (" + holder + ")"));
}

TEST_CASE("A lock held by the child of a holder that has ended says so and shows the note", "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  fs::create_directories(dir);
  // The solver a killed runner started, here flock(1) holding the lock as the inherited descriptor
  // would.
  const auto flock_program = util::find_on_path("flock");
  if (!flock_program) FAIL("flock(1) (util-linux) is needed for this test");
  const pid_t solver = util::start_child(util::ChildCommand(
      {flock_program->string(), "--no-fork", (dir / DirectoryLock::file_name).string(), "sleep", "30"}));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (busy_message(dir) == "not refused") {
    REQUIRE(std::chrono::steady_clock::now() < deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // The text the runner left (its pid above any pid_max, so no process has it), naming the solver
  // that runs on; written now, since a probe that got the lock before flock(1) did wrote its own.
  const std::string solver_pid = std::to_string(solver);
  std::ofstream(dir / util::DirectoryLock::file_name) << "hydrojump vof, pid 999999999\nits solver flock, pid " << solver_pid
                                                << "\n`kill -USR2 " << solver_pid << "` stops it\n";
  CHECK_THAT(busy_message(dir), Catch::StartsWith(dir.string() + " is in use: hydrojump vof, pid 999999999 has ended, "
                                                  "but its solver flock, pid " + solver_pid + " runs on and holds the "
                                                  "lock: `kill -USR2 " + solver_pid + "` stops it; or wait for it to finish"));
  // A note whose child has ended too (left by an earlier holder) is not believed: no hint to kill a pid
  // that may be another process's by now.
  std::ofstream(dir / util::DirectoryLock::file_name)
      << "hydrojump vof, pid 999999999\nits solver interFoam, pid 999999998\n`kill -USR2 999999998` stops it\n";
  const std::string stale = busy_message(dir);
  CHECK_THAT(stale, Catch::Contains("is in use by another process (hydrojump vof, pid 999999999; its solver "
                                    "interFoam, pid 999999998)"));
  CHECK_THAT(stale, !Catch::Contains("kill"));
  util::stop_child(solver);
}

TEST_CASE("A lock file that is a symbolic link, a hard link or a directory is refused, and its target left alone", "[cases][lock]") {
  const hydrojump::testing::TempDir tmp("lock");
  const fs::path dir = tmp.path() / "run";
  fs::create_directories(dir);
  const fs::path target = tmp.path() / "precious";
  std::ofstream(target) << "keep me\n";
  fs::create_symlink(target, dir / DirectoryLock::file_name);
  CHECK_THROWS_WITH(util::DirectoryLock(dir, "hydrojump sph"),
                    Catch::Contains((dir / DirectoryLock::file_name).string() + " is a symbolic link, a hard link or not a regular file"));
  std::string text;
  std::getline(std::ifstream(target), text);
  CHECK(text == "keep me");
  // A dangling link is not followed to create its target either.
  fs::remove(target);
  CHECK_THROWS(util::DirectoryLock(dir, "hydrojump sph"));
  CHECK_FALSE(fs::exists(target));
  fs::remove(dir / DirectoryLock::file_name);
  fs::create_directory(dir / DirectoryLock::file_name);
  CHECK_THROWS_WITH(util::DirectoryLock(dir, "hydrojump sph"), Catch::Contains("is a symbolic link, a hard link or not a regular file"));
  // A hard link to another file would write that file too.
  fs::remove(dir / DirectoryLock::file_name);
  std::ofstream(target) << "keep me\n";
  fs::create_hard_link(target, dir / DirectoryLock::file_name);
  CHECK_THROWS_WITH(util::DirectoryLock(dir, "hydrojump sph"), Catch::Contains("a hard link"));
  std::getline(std::ifstream(target), text);
  CHECK(text == "keep me");
}
