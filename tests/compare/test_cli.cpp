// The command line as a user runs it (the real executable, HYDROJUMP_EXECUTABLE):
// - `hydrojump sph`: SIGTERM, SIGINT and a hangup (SIGHUP) stop the run with a final checkpoint (exit
//   status 128 + signal, issue 3: "SIGINT/SIGTERM write a final checkpoint and exit cleanly"), and `--resume`
//   continues from it to the end (the dam break at the quick resolution, dx 0.02 m, 5,000 particles);
// - `hydrojump check` prints the derived hydraulics (hand values); `generate` refuses an invalid spec
//   and writes nothing; `bench --json` prints its figures.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <chrono>
#include <cstdlib>
#include <csignal>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <sstream>
#include <vector>

#include <signal.h>

#include "util/child_process.hpp"
#include "util/directory_lock.hpp"
#include "reference/runner.hpp"
#include "sph/checkpoint.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

// Starts `hydrojump args...` with stdout and stderr to `log` (truncated); returns its pid.
pid_t start(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> argv = {HYDROJUMP_EXECUTABLE};
  argv.insert(argv.end(), args.begin(), args.end());
  hydrojump::util::ChildCommand command(argv, log);
  command.append_to_log = false;
  return hydrojump::util::start_child(command);
}

int wait_exit_status(pid_t pid) {
  const hydrojump::util::ChildExit e = hydrojump::util::wait_child(pid);
  REQUIRE(e.exited);  // it exits by itself after the signal, not killed by it
  return e.exit_code;
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

// Runs `hydrojump args...` to the end; returns its exit status and leaves its output in `log`.
int run(const std::vector<std::string>& args, const fs::path& log) { return wait_exit_status(start(args, log)); }

// However a test that kills hydrojump outright ends, nothing it started runs on: `process` is killed
// and reaped (unless the test reaped it), and a process still holding `dir`'s lock is killed by the pid
// the lock file names after `holder_label` ("hydrojump sph, pid ", "its solver interFoam, pid ").
struct KillLeftovers {
  pid_t process;
  fs::path dir;
  std::string holder_label;
  bool reaped = false;
  ~KillLeftovers() {
    if (!reaped) {
      ::kill(process, SIGKILL);
      hydrojump::util::wait_child(process);
    }
    try {
      const hydrojump::util::DirectoryLock lock(dir, "the test");
    } catch (const std::exception&) {  // held (or unreadable): its holder runs on
      const std::string holder = read_text(dir / hydrojump::util::DirectoryLock::file_name);
      const auto at = holder.find(holder_label);
      if (at != std::string::npos) ::kill(static_cast<pid_t>(std::atol(holder.c_str() + at + holder_label.size())), SIGKILL);
    }
  }
};

}  // namespace

TEST_CASE("hydrojump sph stops on SIGTERM, SIGINT and SIGHUP with a checkpoint, and --resume finishes the run",
          "[compare][integration][restart]") {
  hydrojump::testing::TempDir tmp("signals");
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
  // A second process on the same directory stops at once, naming the running one (util/directory_lock.hpp).
  CHECK(wait_exit_status(start({"sph", run.string(), "--resume", "--quiet"}, tmp.path() / "second.log")) != 0);
  CHECK_THAT(read_text(tmp.path() / "second.log"),
             Catch::Contains("is in use by another process (hydrojump sph, pid " + std::to_string(pid) + ")"));
  REQUIRE(::kill(pid, SIGINT) == 0);
  CHECK(wait_exit_status(pid) == 128 + SIGINT);
  const auto second_stop = hydrojump::sph::read_checkpoint(checkpoint);
  CHECK(second_stop.clock.steps > first.clock.steps);
  CHECK(second_stop.clock.time < 0.8);

  // Resumed, then a hangup (the terminal closed): 128 + 1, a later checkpoint. The run is started
  // with SIGHUP at its default, as from a terminal (a test run under nohup would pass it on ignored).
  {
    struct sigaction default_hup {}, old_hup {};
    default_hup.sa_handler = SIG_DFL;
    sigemptyset(&default_hup.sa_mask);
    ::sigaction(SIGHUP, &default_hup, &old_hup);
    pid = start({"sph", run.string(), "--resume", "--quiet", "--threads", "1"}, tmp.path() / "run_hup.log");
    ::sigaction(SIGHUP, &old_hup, nullptr);
  }
  wait_for_rows(run / "run_log.csv", second_stop.log_rows.size() + 2);
  REQUIRE(::kill(pid, SIGHUP) == 0);
  CHECK(wait_exit_status(pid) == 128 + SIGHUP);
  CHECK_THAT(read_text(tmp.path() / "run_hup.log"), Catch::Contains("stopped by SIGHUP"));
  const auto second = hydrojump::sph::read_checkpoint(checkpoint);
  CHECK(second.clock.steps > second_stop.clock.steps);
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

// A study killed outright (SIGKILL: no handler of its own runs) must not leave its running stage going
// on unowned, holding its directory's lock: the stage asked Linux to be sent SIGTERM when the study
// ends (ChildCommand::parent_death_signal), so it stops as on `kill -TERM`, with a checkpoint.
TEST_CASE("hydrojump study killed by SIGKILL: its running SPH stage stops with a checkpoint", "[compare][integration][restart]") {
  hydrojump::testing::TempDir tmp("study_killed");
  const fs::path out = tmp.path() / "out";
  const pid_t study = start({"study", std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml", "--methods", "sph",
                             "--resolution", "quick", "--out", out.string()},
                            tmp.path() / "study.log");
  const fs::path run = out / "dam_break" / "sph";
  KillLeftovers leftovers{study, run, "hydrojump sph, pid "};
  wait_for_rows(run / "run_log.csv", 2);
  REQUIRE(::kill(study, SIGKILL) == 0);
  const hydrojump::util::ChildExit killed = hydrojump::util::wait_child(study);
  leftovers.reaped = true;
  CHECK(killed.signal == SIGKILL);

  // The stage (now nobody's child) ends by itself within a minute: its log says so, and the directory's
  // lock is free again.
  const fs::path stage_log = out / "dam_break" / "sph.log";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool stopped = false;
  bool unlocked = false;
  while (!(stopped && unlocked) && std::chrono::steady_clock::now() < deadline) {
    stopped = read_text(stage_log).find("checkpoint written") != std::string::npos;
    if (stopped) {
      try {
        const hydrojump::util::DirectoryLock lock(run, "the test");
        unlocked = true;
      } catch (const hydrojump::util::DirectoryBusy&) {
      }
    }
    if (!(stopped && unlocked)) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  INFO("study log:\n" << read_text(tmp.path() / "study.log") << "\nstage log:\n" << read_text(stage_log));
  CHECK_THAT(read_text(stage_log), Catch::Contains("stopped by SIGTERM"));
  REQUIRE(stopped);
  CHECK(unlocked);
  const auto checkpoint = hydrojump::sph::read_checkpoint(run / "checkpoint.bin");
  CHECK(checkpoint.clock.time > 0.0);
  CHECK(checkpoint.clock.time < 0.8);  // stopped before the end
}

// `hydrojump vof` killed outright (SIGKILL) while interFoam runs: the solver does not run on unowned to
// the end, holding the case's lock; it gets SIGUSR2 from Linux (ChildCommand::parent_death_signal),
// which its controlDict makes "write the current time and stop", so `--resume` can go on from there.
TEST_CASE("hydrojump vof killed by SIGKILL: interFoam writes the current time and stops", "[compare][integration][openfoam]") {
  hydrojump::testing::TempDir tmp("vof_killed");
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  REQUIRE(run({"generate", spec, "--out", tmp.path().string(), "--resolution", "quick"}, tmp.path() / "generate.log") == 0);
  const fs::path dir = tmp.path() / "dam_break" / "vof";
  const pid_t vof = start({"vof", dir.string()}, tmp.path() / "vof.log");
  KillLeftovers leftovers{vof, dir, "its solver interFoam, pid "};
  // A few time steps in (the run ends at 0.8 s and writes every 0.02 s).
  const auto started_by = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (read_text(dir / "log.interFoam").find("\nTime = 0.01") == std::string::npos) {
    INFO("vof log:\n" << read_text(tmp.path() / "vof.log"));
    REQUIRE(std::chrono::steady_clock::now() < started_by);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE(::kill(vof, SIGKILL) == 0);
  CHECK(hydrojump::util::wait_child(vof).signal == SIGKILL);
  leftovers.reaped = true;

  // The solver (now nobody's child) writes and ends within a minute, and the lock is free again.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool unlocked = false;
  while (!unlocked && std::chrono::steady_clock::now() < deadline) {
    try {
      const hydrojump::util::DirectoryLock lock(dir, "the test");
      unlocked = true;
    } catch (const hydrojump::util::DirectoryBusy&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  const std::string solver_log = read_text(dir / "log.interFoam");
  INFO("interFoam log, last part:\n" << solver_log.substr(solver_log.size() > 2000 ? solver_log.size() - 2000 : 0));
  REQUIRE(unlocked);
  // It stopped early, on the signal, with the time it had reached written (not an output time).
  const auto latest = hydrojump::reference::latest_time(dir);
  REQUIRE(latest.has_value());
  CHECK(*latest > 0.01);
  CHECK(*latest < 0.1);
  CHECK_THAT(solver_log, Catch::Contains("\nEnd"));
}

TEST_CASE("hydrojump sph keeps the outputs of a run that failed before its first checkpoint unless --restart",
          "[compare][integration][restart]") {
  hydrojump::testing::TempDir tmp("failed_run");
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  REQUIRE(run({"generate", spec, "--out", tmp.path().string(), "--resolution", "quick"}, tmp.path() / "generate.log") == 0);
  const fs::path dir = tmp.path() / "dam_break" / "sph";
  // What a run that went unstable before its first checkpoint leaves: a diagnosis, no checkpoint.
  std::ofstream(dir / "failure.txt") << "unstable at t = 0.1 s\n";

  CHECK(run({"sph", dir.string(), "--quiet", "--end-time", "0.01"}, tmp.path() / "plain.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "plain.log"),
             Catch::Contains("stopped before its first checkpoint (failure.txt, its diagnosis)") &&
                 Catch::Contains("--restart"));
  CHECK(read_text(dir / "failure.txt") == "unstable at t = 0.1 s\n");
  CHECK_FALSE(fs::exists(dir / "particles.pvd"));

  const int status = run({"sph", dir.string(), "--restart", "--quiet", "--threads", "1", "--end-time", "0.01"},
                         tmp.path() / "restart.log");
  INFO("restart log:\n" << read_text(tmp.path() / "restart.log"));
  CHECK(status == 0);
  CHECK_FALSE(fs::exists(dir / "failure.txt"));
  CHECK(fs::exists(dir / "particles.pvd"));
}

// `hydrojump sph DIR` with the environment change `env` (e.g. "HYDROJUMP_MEMORY_LIMIT_MB=20"); its exit status.
int run_sph_with(const fs::path& dir, const std::string& env, const fs::path& log) {
  hydrojump::util::ChildCommand command({HYDROJUMP_EXECUTABLE, "sph", dir.string(), "--quiet", "--threads", "1", "--end-time", "0.01"},
                                        log);
  command.append_to_log = false;
  command.environment = {env};
  return wait_exit_status(hydrojump::util::start_child(command));
}

TEST_CASE("hydrojump sph and vof refuse up front a run that needs more memory than is available, with the figures",
          "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("memory");
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  REQUIRE(run({"generate", spec, "--out", tmp.path().string(), "--resolution", "quick"}, tmp.path() / "generate.log") == 0);
  const fs::path dir = tmp.path() / "dam_break" / "sph";
  // The dam break at quick needs 25 MB + 0.52 kB a particle: more than 20 MB, less than 1000 MB.
  CHECK(run_sph_with(dir, "HYDROJUMP_MEMORY_LIMIT_MB=20", tmp.path() / "short.log") == 1);
  const std::string refused = read_text(tmp.path() / "short.log");
  CHECK_THAT(refused, Catch::Contains("hydrojump sph: case \"dam_break\" at dx = ") && Catch::Contains("needs about ") &&
                          Catch::Contains("(25 MB + 0.52 kB a particle x ") &&
                          Catch::Contains("but this machine has 20 MB available") && Catch::Contains("coarser resolution"));
  CHECK_FALSE(fs::exists(dir / "particles.pvd"));
  CHECK_FALSE(fs::exists(dir / "checkpoint.bin"));
  CHECK(run_sph_with(dir, "HYDROJUMP_MEMORY_LIMIT_MB=lots", tmp.path() / "bad.log") == 1);
  CHECK_THAT(read_text(tmp.path() / "bad.log"), Catch::Contains("HYDROJUMP_MEMORY_LIMIT_MB = \"lots\"") &&
                                                    Catch::Contains("positive number of MB"));
  CHECK(run_sph_with(dir, "HYDROJUMP_MEMORY_LIMIT_MB=1000", tmp.path() / "enough.log") == 0);
  CHECK(fs::exists(dir / "particles.pvd"));

  // interFoam: 145 MB a process + 2.04 kB a cell, refused before meshing.
  const fs::path vof = tmp.path() / "dam_break" / "vof";
  hydrojump::util::ChildCommand command({HYDROJUMP_EXECUTABLE, "vof", vof.string()}, tmp.path() / "vof.log");
  command.append_to_log = false;
  command.environment = {"HYDROJUMP_MEMORY_LIMIT_MB=100"};
  CHECK(wait_exit_status(hydrojump::util::start_child(command)) == 1);
  CHECK_THAT(read_text(tmp.path() / "vof.log"),
             Catch::Contains("hydrojump vof: case \"dam_break\" at resolution \"quick\" needs about ") &&
                 Catch::Contains("(145 MB x 1 process(es) + 2.04 kB a cell x ") &&
                 Catch::Contains("but this machine has 100 MB available") && Catch::Contains("coarser resolution"));
  CHECK_FALSE(fs::exists(vof / "log.blockMesh"));
}

TEST_CASE("hydrojump check prints run A's derived hydraulics", "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("check");
  REQUIRE(run({"check", std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml"}, tmp.path() / "check.log") == 0);
  // Run A by hand (y1 = 25.4 mm, U1 = 2 m/s, y2 = 0.104 m): q = 0.0508 m^2/s, Fr1 = 2/sqrt(9.81 y1) =
  // 4.01, y2* = y1/2 (sqrt(1 + 8 Fr1^2) - 1) = 0.132 m, E1 = y1 + q^2/(2 g y1^2) = 0.2293 m,
  // E2 = 0.104 + q^2/(2 g 0.104^2) = 0.1162 m, eta = 1 - E2/E1 = 49.34 %, eta* (at y2*) = 39.22 %.
  // Run A's row of the hydraulics table, then of the models table.
  std::string row_a, models_a;
  std::istringstream lines(read_text(tmp.path() / "check.log"));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("  A ", 0) == 0) (row_a.empty() ? row_a : models_a) = line;
  INFO(read_text(tmp.path() / "check.log"));
  REQUIRE_FALSE(row_a.empty());
  std::istringstream fields(row_a);
  std::vector<std::string> f;
  for (std::string x; fields >> x;) f.push_back(x);
  REQUIRE(f.size() == 14u);
  CHECK(f[2] == "0.0254");
  CHECK(f[4] == "0.0508");
  CHECK(f[5] == "4.01");
  CHECK(f[6] == "0.132");
  CHECK(f[8] == "0.2293");
  CHECK(f[9] == "0.1162");
  CHECK(f[10] == "49.34");
  CHECK(f[11] == "39.22");
  CHECK(f[12] == "48.43");  // the experiment's, from the spec
  CHECK(f[13] == "hold_toe");  // the flume's protocol, the default: y2 is predicted, 0.104 m the initial level
  // The rules by hand: l = 0.1 y2* = 0.0132 m; T_s = 2 (0.2 + 1.36 + 0.2) / sqrt(9.81 * 0.13178) = 3.096 s,
  // the window from 3 T_s = 9.29 s (up to the next 0.1 s output: 9.3) over one more T_s (3.1 s): 9.3 - 12.4 s.
  CHECK_THAT(models_a, Catch::Contains("SPS l 0.0132 m free_slip") && Catch::Contains("kEpsilon + nut_limiter") &&
                           Catch::Contains("9.3 - 12.4 (run 12.4)"));
}

// Exit statuses: 0 for --help and --version, 2 for a command-line mistake (as for an invalid spec),
// not CLI11's own 104-114.
TEST_CASE("hydrojump exits with 2 on a command-line mistake and 0 on --help", "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("exit_codes");
  CHECK(run({"--help"}, tmp.path() / "help.log") == 0);
  CHECK(run({"--version"}, tmp.path() / "version.log") == 0);
  CHECK(run({"no-such-command"}, tmp.path() / "unknown.log") == 2);
  CHECK(run({"compare", "--window", "1"}, tmp.path() / "window.log") == 2);
  CHECK(run({"bench", "--threads", "0"}, tmp.path() / "threads.log") == 2);
  CHECK(run({"sph", (tmp.path() / "absent").string()}, tmp.path() / "absent.log") == 2);
  CHECK_THAT(read_text(tmp.path() / "threads.log"), Catch::Contains("--threads"));
  CHECK_THAT(read_text(tmp.path() / "unknown.log"),
             Catch::Contains("unknown command \"no-such-command\"") && Catch::Contains("vof, compare, study"));
}

// `generate --case` takes ids comma-separated as `study --cases` does, and repeated.
TEST_CASE("hydrojump generate takes case ids comma-separated or repeated", "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("generate_cases");
  const fs::path out = tmp.path() / "out";
  REQUIRE(run({"generate", "default", "--out", out.string(), "--case", "A,B_smooth", "--case", "C"},
              tmp.path() / "generate.log") == 0);
  std::vector<std::string> written;
  for (const auto& entry : fs::directory_iterator(out)) written.push_back(entry.path().filename().string());
  std::sort(written.begin(), written.end());
  CHECK(written == std::vector<std::string>{"A", "B_smooth", "C"});
  CHECK(run({"generate", "default", "--out", (tmp.path() / "bad").string(), "--case", "A,Z"}, tmp.path() / "bad.log") == 2);
  CHECK_THAT(read_text(tmp.path() / "bad.log"), Catch::Contains("case \"Z\": no such case"));
  CHECK_FALSE(fs::exists(tmp.path() / "bad" / "A"));
}

// `check` writes every case into a scratch directory under TMPDIR and removes it again, also when it
// is stopped meanwhile (the stop request is held back until the directory is gone).
TEST_CASE("hydrojump check stopped by SIGTERM or SIGHUP leaves no scratch directory, and runs on under nohup", "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("check_stop");
  for (const int sig : {SIGTERM, SIGHUP}) {
    const fs::path scratch_parent = tmp.path() / ("tmp" + std::to_string(sig));
    fs::create_directories(scratch_parent);
    hydrojump::util::ChildCommand command({HYDROJUMP_EXECUTABLE, "check", std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml"},
                                           tmp.path() / "check.log");
    command.environment = {"TMPDIR=" + scratch_parent.string()};
    const pid_t pid = hydrojump::util::start_child(command);
    // Stopped once its scratch directory exists (within 60 s).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    bool made = false;
    while (!made && std::chrono::steady_clock::now() < deadline) {
      made = fs::directory_iterator(scratch_parent) != fs::directory_iterator();
      if (!made) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    REQUIRE(made);
    REQUIRE(::kill(pid, sig) == 0);
    const hydrojump::util::ChildExit e = hydrojump::util::wait_child(pid);
    INFO("signal " << sig << ": " << e.describe() << "\n" << read_text(tmp.path() / "check.log"));
    CHECK(e.status() != 0);
    CHECK(fs::directory_iterator(scratch_parent) == fs::directory_iterator());  // nothing left
  }
  // Under nohup (SIGHUP ignored) a hangup is no stop request: the check finishes.
  const fs::path scratch_parent = tmp.path() / "tmp_nohup";
  fs::create_directories(scratch_parent);
  hydrojump::util::ChildCommand command({HYDROJUMP_EXECUTABLE, "check", std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml"},
                                         tmp.path() / "nohup.log");
  command.environment = {"TMPDIR=" + scratch_parent.string()};
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGHUP, &ignore, &previous);
  const pid_t pid = hydrojump::util::start_child(command);  // inherits SIGHUP ignored, as under nohup
  ::sigaction(SIGHUP, &previous, nullptr);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (fs::directory_iterator(scratch_parent) == fs::directory_iterator() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  REQUIRE(::kill(pid, SIGHUP) == 0);
  const hydrojump::util::ChildExit e = hydrojump::util::wait_child(pid);
  INFO(read_text(tmp.path() / "nohup.log"));
  CHECK(e.status() == 0);
  CHECK_THAT(read_text(tmp.path() / "nohup.log"), Catch::Contains("every case generates at every resolution"));
  CHECK(fs::directory_iterator(scratch_parent) == fs::directory_iterator());
}

TEST_CASE("hydrojump generate refuses an invalid spec, names the key and writes nothing", "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("invalid");
  std::string spec = read_text(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml");
  const std::string good = "[case.column]\nwidth_m = 1.0";
  REQUIRE(spec.find(good) != std::string::npos);
  spec.replace(spec.find(good), good.size(), "[case.column]\nwidth_m = -1.0");
  {
    std::ofstream out(tmp.path() / "bad.toml");
    out << spec;
  }
  const fs::path out_dir = tmp.path() / "runs";
  CHECK(run({"generate", (tmp.path() / "bad.toml").string(), "--out", out_dir.string()}, tmp.path() / "generate.log") != 0);
  const std::string log = read_text(tmp.path() / "generate.log");
  CHECK_THAT(log, Catch::Contains("bad.toml:") && Catch::Contains("column.width_m = -1"));
  CHECK_FALSE(fs::exists(out_dir));
}

TEST_CASE("hydrojump generate and check refuse what only a solver's derivation finds, and generate writes nothing", "[compare][integration][cli]") {
  // A VOF bed cell of 2 cm leaves fewer than 2 cells across y1 = 25.4 mm: the spec's rules pass,
  // the OpenFOAM mesh plan refuses. It used to do so after DIR/A/sph had been written.
  hydrojump::testing::TempDir tmp("derived");
  std::string spec = read_text(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml");
  const std::string good = "vof_cell_size_bed_m = 0.005\nvof_cell_size_bulk_m = 0.01";
  REQUIRE(spec.find(good) != std::string::npos);
  spec.replace(spec.find(good), good.size(), "vof_cell_size_bed_m = 0.02\nvof_cell_size_bulk_m = 0.02");
  {
    std::ofstream out(tmp.path() / "coarse.toml");
    out << spec;
  }
  const fs::path out_dir = tmp.path() / "runs";
  CHECK(run({"generate", (tmp.path() / "coarse.toml").string(), "--out", out_dir.string(), "--case", "A"},
            tmp.path() / "generate.log") == 2);
  const std::string log = read_text(tmp.path() / "generate.log");
  INFO(log);
  CHECK_THAT(log, Catch::Contains("coarse.toml: case \"A\" at resolution \"quick\": resolution.quick.vof_cell_size_bed_m = 0.02 m") &&
                      Catch::Contains("inflow depth y1 = 0.0254 m"));
  CHECK_FALSE(fs::exists(out_dir));
  // `check` finds it too (it had said the spec was fine).
  CHECK(run({"check", (tmp.path() / "coarse.toml").string()}, tmp.path() / "check.log") == 2);
  CHECK_THAT(read_text(tmp.path() / "check.log"), Catch::Contains("coarse.toml: case \"A\" at resolution \"quick\": ") &&
                                                      Catch::Contains("inflow depth"));
}

TEST_CASE("hydrojump generate keeps a finished run's results only for the settings that made them", "[compare][integration][cli]") {
  // Regenerating over a run with other settings left its results in place, and `compare` reported
  // them under the new settings.
  hydrojump::testing::TempDir tmp("regenerate");
  const std::string original = read_text(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/poiseuille.toml");
  const auto write_spec = [&](const std::string& text) {
    std::ofstream out(tmp.path() / "spec.toml");
    out << text;
  };
  write_spec(original);
  const fs::path out_dir = tmp.path() / "runs";
  const std::vector<std::string> generate = {"generate", (tmp.path() / "spec.toml").string(), "--out", out_dir.string()};
  REQUIRE(run(generate, tmp.path() / "g1.log") == 0);
  const fs::path sph_dir = out_dir / "poiseuille" / "sph";
  { std::ofstream(sph_dir / "summary.json") << "{}\n"; }  // a finished run's product
  // The same settings (the spec file spelt another way): regenerated, the results kept.
  REQUIRE(run({"generate", (tmp.path() / "." / "spec.toml").string(), "--out", out_dir.string()}, tmp.path() / "g2.log") == 0);
  CHECK(fs::exists(sph_dir / "summary.json"));
  // Other settings: refused, nothing rewritten.
  const std::string before = read_text(sph_dir / "case.toml");
  const std::string end = "end_time_s = ";
  const auto at = original.find(end);
  REQUIRE(at != std::string::npos);
  write_spec(original.substr(0, at + end.size()) + "1" + original.substr(at + end.size()));  // 3.0 s -> 13.0 s
  CHECK(run(generate, tmp.path() / "g3.log") == 1);
  const std::string log = read_text(tmp.path() / "g3.log");
  INFO(log);
  CHECK_THAT(log, Catch::Contains(sph_dir.string() + " holds the results of a run of case \"poiseuille\" with other settings") &&
                      Catch::Contains("'end_time_s = 3.0' where the spec now gives 'end_time_s = 13.0'"));
  CHECK(read_text(sph_dir / "case.toml") == before);
  // Without results the directory is simply regenerated.
  fs::remove(sph_dir / "summary.json");
  CHECK(run(generate, tmp.path() / "g4.log") == 0);
  CHECK(read_text(sph_dir / "case.toml") != before);
}

TEST_CASE("hydrojump compare refuses results made with other settings than the case.toml it reads", "[compare][integration][cli]") {
  // A hand-edited case.toml beside finished results made `compare` report them under the edited
  // settings. Each solver now records the case its run started with (results_case.toml).
  hydrojump::testing::TempDir tmp("results_case");
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/poiseuille.toml";
  REQUIRE(run({"generate", spec, "--out", (tmp.path() / "runs").string()}, tmp.path() / "generate.log") == 0);
  const fs::path run_dir = tmp.path() / "runs" / "poiseuille";
  const fs::path sph_dir = run_dir / "sph";
  REQUIRE(run({"sph", sph_dir.string(), "--end-time", "0.01", "--threads", "1", "--quiet"}, tmp.path() / "sph.log") == 0);
  REQUIRE(read_text(sph_dir / "results_case.toml") == read_text(sph_dir / "case.toml"));
  const std::string original = read_text(sph_dir / "case.toml");
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = original;
    REQUIRE(text.find(from) != std::string::npos);
    return text.replace(text.find(from), from.size(), to);
  };
  // The results' own case: compare goes on (and stops later: it compares stilling basins only).
  CHECK(run({"compare", run_dir.string()}, tmp.path() / "c1.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "c1.log"), Catch::Contains("handles kind \"stilling_basin\" only"));
  // Another setting in the case.toml beside the SPH results: refused, naming both lines.
  { std::ofstream(sph_dir / "case.toml") << replaced("cfl_number = 0.2", "cfl_number = 0.1"); }
  CHECK(run({"compare", run_dir.string()}, tmp.path() / "c2.log") != 0);
  std::string log = read_text(tmp.path() / "c2.log");
  INFO(log);
  CHECK_THAT(log, Catch::Contains(sph_dir.string() + " holds results made with other settings") &&
                      Catch::Contains("results_case.toml has 'cfl_number = 0.2'") && Catch::Contains("has 'cfl_number = 0.1'"));
  // A relaxed stability limit (what a resumed run may change) is the same case.
  { std::ofstream(sph_dir / "case.toml") << replaced("max_density_variation = 0.05", "max_density_variation = 0.2"); }
  CHECK(run({"compare", run_dir.string()}, tmp.path() / "c3.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "c3.log"), Catch::Contains("handles kind \"stilling_basin\" only"));
  // OpenFOAM results are reported under the same case.toml: an OpenFOAM case run with other settings
  // (no record: a run of an earlier version, its own case.toml) is refused too.
  { std::ofstream(sph_dir / "case.toml") << original; }
  const fs::path vof_dir = run_dir / "vof";
  { std::ofstream(vof_dir / "case.toml") << replaced("end_time_s = 3.0", "end_time_s = 4.0"); }
  { std::ofstream(vof_dir / "log.interFoam") << "Time = 0.1\n"; }
  CHECK(run({"compare", run_dir.string()}, tmp.path() / "c4.log") != 0);
  log = read_text(tmp.path() / "c4.log");
  CHECK_THAT(log, Catch::Contains(vof_dir.string() + " holds results made with other settings") &&
                      Catch::Contains("case.toml has 'end_time_s = 4.0'"));
}

TEST_CASE("options refuse nan, inf, non-positive numbers, empty paths and the wrong directory, naming the option", "[compare][integration][cli]") {
  // CLI11's PositiveNumber lets "nan" through: `sph --end-time nan` then ran the case's whole end time.
  hydrojump::testing::TempDir tmp("numbers");
  const std::string study = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/poiseuille.toml";
  REQUIRE(run({"generate", study, "--out", (tmp.path() / "runs").string()}, tmp.path() / "generate.log") == 0);
  const fs::path dir = tmp.path() / "runs" / "poiseuille" / "sph";
  for (const std::string value : {"nan", "inf", "0", "-1", "1x"}) {
    INFO("--end-time " << value);
    CHECK(run({"sph", dir.string(), "--end-time", value, "--quiet"}, tmp.path() / "sph.log") != 0);
    CHECK_THAT(read_text(tmp.path() / "sph.log"), Catch::Contains("--end-time") && Catch::Contains("must be a finite number > 0"));
  }
  // Finite but past what a case may run (it would never end): refused with the limit.
  CHECK(run({"sph", dir.string(), "--end-time", "1e308", "--quiet"}, tmp.path() / "sph.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "sph.log"), Catch::Contains("--end-time 1e+308 s is out of range") &&
                                                    Catch::Contains("must be <= "));
  CHECK_FALSE(fs::exists(dir / "checkpoint.bin"));
  // An empty --out wrote into the current directory.
  for (const std::string command : {"generate", "study"}) {
    INFO(command);
    CHECK(run({command, study, "--out", ""}, tmp.path() / "out.log") != 0);
    CHECK_THAT(read_text(tmp.path() / "out.log"), Catch::Contains("--out") && Catch::Contains("must not be empty"));
  }
  // The OpenFOAM case beside the SPH directory holds the same case.toml; sph refuses it by name.
  const std::string tank = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/still_water.toml";
  REQUIRE(run({"generate", tank, "--out", (tmp.path() / "tank").string()}, tmp.path() / "generate_tank.log") == 0);
  const fs::path vof_dir = tmp.path() / "tank" / "still_water" / "vof";
  REQUIRE(fs::exists(vof_dir / "system" / "controlDict"));
  CHECK(run({"sph", vof_dir.string(), "--quiet"}, tmp.path() / "vof_dir.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "vof_dir.log"),
             Catch::Contains("is an OpenFOAM case") && Catch::Contains((vof_dir.parent_path() / "sph").string()));
  CHECK_FALSE(fs::exists(vof_dir / "run_log.csv"));
  CHECK(run({"bench", "--steps", "0"}, tmp.path() / "bench.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "bench.log"), Catch::Contains("--steps: Value 0 not in range 1 to 1000000000"));
  // compare --window: "nan" was refused as "T1 must be >= T0", and "inf" accepted.
  for (const auto& window : {std::pair<std::string, std::string>{"nan", "10"}, {"6", "nan"}, {"0", "inf"}}) {
    INFO("--window " << window.first << " " << window.second);
    CHECK(run({"compare", (tmp.path() / "runs" / "poiseuille").string(), "--no-plots", "--window", window.first, window.second},
              tmp.path() / "window.log") != 0);
    CHECK_THAT(read_text(tmp.path() / "window.log"), Catch::Contains("--window") && Catch::Contains("must be finite times >= 0 s"));
  }
  // validation-doc --not-run: a resolution the study does not define is named with those it does; nothing is written.
  const fs::path doc = tmp.path() / "validation.md";
  CHECK(run({"validation-doc", "--records", (tmp.path() / "no_records").string(), "--out", doc.string(), "--not-run",
             std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml", "quick", "fast"},
            tmp.path() / "doc.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "doc.log"), Catch::Contains("--not-run: \"fast\" is not a resolution of") &&
                                                    Catch::Contains("(it has: default, fine, quick)"));
  CHECK_FALSE(fs::exists(doc));
}

TEST_CASE("hydrojump bench --json prints particles, steps, threads, speed and memory", "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("bench");
  REQUIRE(run({"bench", "--steps", "3", "--threads", "1", "--json"}, tmp.path() / "bench.log") == 0);
  const std::string log = read_text(tmp.path() / "bench.log");
  INFO(log);
  // 20,000 fluid particles (1 m x 2 m at dx 0.01 m) plus the tank's walls
  CHECK_THAT(log, Catch::Contains("\"steps\": 3") && Catch::Contains("\"threads\": 1") &&
                      Catch::Contains("\"particle_steps_per_second\": ") && Catch::Contains("\"peak_memory_bytes\": "));
  const auto at = log.find("\"particles\": ");
  REQUIRE(at != std::string::npos);
  CHECK(std::stol(log.substr(at + 13)) > 20000);
  CHECK_THAT(log, Catch::Contains("\"model\": \"dualsphysics\""));
}

TEST_CASE("hydrojump bench --model jump runs a study's SPH model, costliest every costly path, and unknown models are refused",
          "[compare][integration][cli]") {
  hydrojump::testing::TempDir tmp("bench_jump");
  REQUIRE(run({"bench", "--model", "jump", "--steps", "2", "--threads", "1"}, tmp.path() / "bench.log") == 0);
  const std::string log = read_text(tmp.path() / "bench.log");
  INFO(log);
  CHECK_THAT(log, Catch::Contains("(model jump)") && Catch::Contains("2 steps") &&
                      Catch::Contains("model: the [sph] of case \"A\" in the embedded study"));
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/bed_matters.toml";
  REQUIRE(run({"bench", "--model", "jump", "--spec", spec, "--steps", "2", "--threads", "1"}, tmp.path() / "spec.log") == 0);
  CHECK_THAT(read_text(tmp.path() / "spec.log"), Catch::Contains("in " + spec));
  REQUIRE(run({"bench", "--model", "costliest", "--steps", "2", "--threads", "1", "--json"}, tmp.path() / "costliest.log") == 0);
  CHECK_THAT(read_text(tmp.path() / "costliest.log"), Catch::Contains("\"model\": \"costliest\"") && Catch::Contains("\"steps\": 2"));
  // A study without a stilling basin has no jump model; --spec belongs to --model jump.
  const std::string dam = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  CHECK(run({"bench", "--model", "jump", "--spec", dam, "--steps", "2"}, tmp.path() / "dam.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "dam.log"), Catch::Contains("has no stilling-basin case"));
  CHECK(run({"bench", "--spec", spec, "--steps", "2"}, tmp.path() / "spec_alone.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "spec_alone.log"), Catch::Contains("--spec is only used with --model jump"));
  CHECK(run({"bench", "--model", "verlet"}, tmp.path() / "bad.log") != 0);
  CHECK_THAT(read_text(tmp.path() / "bad.log"), Catch::Contains("--model") && Catch::Contains("verlet"));
}

TEST_CASE("hydrojump compare on a dam break: the surge front in the experiment's time origin and unshifted",
          "[compare][integration][cli][dam_break]") {
  hydrojump::testing::TempDir tmp("compare_dam_break");
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  REQUIRE(run({"generate", spec, "--out", (tmp.path() / "runs").string(), "--resolution", "quick"},
              tmp.path() / "generate.log") == 0);
  const fs::path run_dir = tmp.path() / "runs" / "dam_break";
  // An SPH front that is the measured one 0.0395 s early (t_model = t_exp - 0.175 sqrt(L/(2g)) with
  // L = 1 m): one output at each measured time less the shift, at the measured position.
  {
    std::ofstream g(run_dir / "sph" / "gauges.csv");
    g << "t_s,front_x_m\n0,1\n";
    std::ifstream data(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/data/dam_break_front_koshizuka_oka_1996.csv");
    for (std::string line; std::getline(data, line);) {
      if (line.empty() || line[0] == '#' || line[0] == 't') continue;
      const double t = std::stod(line.substr(0, line.find(','))), x = std::stod(line.substr(line.find(',') + 1));
      g << std::setprecision(12) << t - 0.175 * std::sqrt(1.0 / (2.0 * 9.81)) << ',' << x << '\n';
    }
  }
  CHECK(run({"compare", run_dir.string(), "--window", "0", "1"}, tmp.path() / "w.log") == 2);
  CHECK_THAT(read_text(tmp.path() / "w.log"), Catch::Contains("--window"));
  REQUIRE(run({"compare", run_dir.string()}, tmp.path() / "c.log") == 0);
  const std::string log = read_text(tmp.path() / "c.log");
  INFO(log);
  CHECK_THAT(log, Catch::Contains("sph: front vs the experiment, time origin shifted by 0.0395 s: mean 0.000 L, max 0.000 L"));
  CHECK_THAT(log, Catch::Contains("vof: not available"));
  const std::string json = read_text(run_dir / "comparison.json");
  CHECK_THAT(json, Catch::Contains("\"kind\": \"dam_break\"") && Catch::Contains("\"time_shift_s\": 0.03950831859"));
  CHECK_THAT(json, Catch::Contains("\"shifted\": {\"time_shift_s\": 0.03950831859, \"points\": 14"));
  CHECK_THAT(read_text(run_dir / "csv" / "front.csv"), Catch::StartsWith("t_exp_s,measured_x_over_L,sph_shifted_x_over_L"));
  CHECK_THAT(read_text(run_dir / "report.md"), Catch::Contains("| SPH | experiment's (shifted) | 14 of 15 | 0.000 | 0.000 |"));
  CHECK(fs::file_size(run_dir / "figures" / "front.png") > 1000);
}
