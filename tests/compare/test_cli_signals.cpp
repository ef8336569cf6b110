// `hydrojump sph` as a user runs it: SIGTERM and SIGINT stop the run with a final checkpoint (exit
// status 128 + signal, issue 3: "SIGINT/SIGTERM write a final checkpoint and exit cleanly"), and
// `--resume` continues from it to the end. The executable under test is the real one
// (HYDROJUMP_EXECUTABLE), on the dam break at the quick resolution (dx 0.02 m, ~5,000 particles).
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sph/checkpoint.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

// Starts `hydrojump args...` with stdout and stderr to `log`; returns its pid.
pid_t start(const std::vector<std::string>& args, const fs::path& log) {
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
    std::vector<char*> argv;
    std::string exe = HYDROJUMP_EXECUTABLE;
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

int wait_exit_status(pid_t pid) {
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));  // it exits by itself after the signal, not killed by it
  return WEXITSTATUS(status);
}

std::size_t lines_in(const fs::path& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// Waits (up to 120 s) until the run has logged `rows` data rows past its header.
void wait_for_rows(const fs::path& run_log, std::size_t rows) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (lines_in(run_log) < rows + 1) {
    REQUIRE(std::chrono::steady_clock::now() < deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("hydrojump sph stops on SIGTERM and SIGINT with a checkpoint, and --resume finishes the run",
          "[compare][integration][restart]") {
  hydrojump::compare::testing::TempDir tmp("signals");
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  REQUIRE(wait_exit_status(start({"generate", spec, "--out", tmp.path().string(), "--resolution", "quick"},
                                 tmp.path() / "generate.log")) == 0);
  const fs::path run = tmp.path() / "dam_break" / "sph";
  const fs::path checkpoint = run / "checkpoint.bin";

  // SIGTERM after a few outputs: exit status 128 + 15, a checkpoint at the time reached.
  pid_t pid = start({"sph", run.string(), "--quiet", "--threads", "1"}, tmp.path() / "run1.log");
  wait_for_rows(run / "run_log.csv", 3);
  REQUIRE(::kill(pid, SIGTERM) == 0);
  CHECK(wait_exit_status(pid) == 128 + SIGTERM);
  REQUIRE(fs::exists(checkpoint));
  const auto first = hydrojump::sph::read_checkpoint(checkpoint);
  INFO("run 1 log:\n" << read_text(tmp.path() / "run1.log"));
  CHECK(first.clock.time > 0.0);
  CHECK(first.clock.time < 0.8);  // stopped before the end
  CHECK_THAT(read_text(tmp.path() / "run1.log"), Catch::Contains("stopped by SIGTERM"));

  // Resumed, then SIGINT (Ctrl-C): 128 + 2, a later checkpoint.
  pid = start({"sph", run.string(), "--resume", "--quiet", "--threads", "1"}, tmp.path() / "run2.log");
  wait_for_rows(run / "run_log.csv", first.log_rows.size() + 2);
  REQUIRE(::kill(pid, SIGINT) == 0);
  CHECK(wait_exit_status(pid) == 128 + SIGINT);
  const auto second = hydrojump::sph::read_checkpoint(checkpoint);
  CHECK(second.clock.steps > first.clock.steps);
  CHECK(second.clock.time < 0.8);

  // Resumed to the case's end (0.8 s, past the surge's impact on the far wall at 0.68 s: the README
  // tutorial's run): exit 0, the end reached, the log continuous (one row per output).
  const int status = wait_exit_status(
      start({"sph", run.string(), "--resume", "--quiet", "--threads", "2"}, tmp.path() / "run3.log"));
  INFO("run 3 log:\n" << read_text(tmp.path() / "run3.log"));
  CHECK(status == 0);
  const auto last = hydrojump::sph::read_checkpoint(checkpoint);
  CHECK(last.clock.time >= 0.8 - 1e-9);
  CHECK(last.clock.steps > second.clock.steps);
  CHECK(lines_in(run / "run_log.csv") == last.log_rows.size() + 1);
}
