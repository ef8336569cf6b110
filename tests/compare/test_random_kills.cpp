// Kill-and-resume at random moments: `hydrojump sph` killed outright (SIGKILL: no handler, no final
// checkpoint) at random times, some of them while it writes a checkpoint, and resumed each time, ends
// with the uninterrupted run's checkpoint and outputs byte for byte, and no file it wrote is torn.
//
// The run: the dam break at the quick resolution (dx 0.02 m, 5,000 particles) to 0.15 s on one thread,
// a checkpoint every 0.05 s of wall time so that kills land before, between and during checkpoint
// writes. The kill times are drawn from a seed printed with any failure (HYDROJUMP_KILL_SEED repeats
// a sequence).
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>

#include "util/child_process.hpp"
#include "sph/checkpoint.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

constexpr const char* end_time = "0.15";

pid_t start(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> argv = {HYDROJUMP_EXECUTABLE};
  argv.insert(argv.end(), args.begin(), args.end());
  hydrojump::util::ChildCommand command(argv, log);
  command.append_to_log = true;
  return hydrojump::util::start_child(command);
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The run's files by name (the case's own inputs and the lock aside), with their bytes.
std::vector<std::pair<std::string, std::string>> outputs_of(const fs::path& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "case.toml" || name.rfind(".hydrojump", 0) == 0) continue;
    files.emplace_back(name, read_bytes(e.path()));
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The size of a file (0 if it is missing).
std::uintmax_t size_of(const fs::path& file) {
  std::error_code ec;
  const auto n = fs::file_size(file, ec);
  return ec ? 0 : n;
}

// Whether a temporary file of a checkpoint being written (util/atomic_file.hpp) is there now.
bool checkpoint_being_written(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(".checkpoint.bin.tmp.", 0) == 0) return true;
  return false;
}

// A fresh dam-break run directory under `top` whose run checkpoints every 0.05 s of wall time.
fs::path generated_run(const fs::path& top) {
  const std::string spec = std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml";
  fs::create_directories(top);
  const pid_t g = start({"generate", spec, "--out", top.string(), "--resolution", "quick"}, top / "generate.log");
  REQUIRE(hydrojump::util::wait_child(g).exit_code == 0);
  const fs::path dir = top / "dam_break" / "sph";
  std::string text = read_bytes(dir / "case.toml");
  const std::string key = "checkpoint_interval_wall_s = 300.0";
  const auto at = text.find(key);
  REQUIRE(at != std::string::npos);
  text.replace(at, key.size(), "checkpoint_interval_wall_s = 0.05");
  std::ofstream(dir / "case.toml", std::ios::binary | std::ios::trunc) << text;
  return dir;
}

}  // namespace

TEST_CASE("hydrojump sph killed at random moments and resumed each time ends as the uninterrupted run byte for byte",
          "[compare][integration][restart][kills]") {
  hydrojump::testing::TempDir tmp("random_kills");
  const fs::path reference = generated_run(tmp.path() / "reference");
  const fs::path killed = generated_run(tmp.path() / "killed");

  const pid_t r = start({"sph", reference.string(), "--quiet", "--threads", "1", "--end-time", end_time},
                        tmp.path() / "reference.log");
  REQUIRE(hydrojump::util::wait_child(r).exit_code == 0);

  const char* fixed_seed = std::getenv("HYDROJUMP_KILL_SEED");
  const unsigned seed = fixed_seed ? static_cast<unsigned>(std::strtoul(fixed_seed, nullptr, 10)) : std::random_device{}();
  INFO("kill seed " << seed << " (HYDROJUMP_KILL_SEED repeats it); log " << (tmp.path() / "killed.log").string());
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> delay_ms(30, 400);
  int kills = 0, kills_while_writing = 0, finished_early = 0;
  // A run killed before its first checkpoint starts over (--restart), as a user would.
  const auto resume_or_restart = [&] { return fs::exists(killed / "checkpoint.bin") ? "--resume" : "--restart"; };
  for (int attempt = 0; kills < 24 && attempt < 200; ++attempt) {
    const auto log_before = size_of(tmp.path() / "killed.log");
    const pid_t pid = start({"sph", killed.string(), resume_or_restart(), "--quiet", "--threads", "1",
                             "--end-time", end_time},
                            tmp.path() / "killed.log");
    // The kill time counts from the run's first line (its case read, its particles made), so that a
    // loaded machine's slow start-up does not leave every kill before the first checkpoint.
    const auto started_by = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (size_of(tmp.path() / "killed.log") == log_before && std::chrono::steady_clock::now() < started_by)
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    // Every third kill waits for a checkpoint write to begin and kills the run inside it.
    const bool during_write = kills % 3 == 2;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(during_write ? 3000 : delay_ms(random));
    bool writing = false;
    while (std::chrono::steady_clock::now() < deadline) {
      if (during_write && checkpoint_being_written(killed)) { writing = true; break; }
      std::this_thread::sleep_for(std::chrono::microseconds(during_write ? 200 : 2000));
    }
    ::kill(pid, SIGKILL);
    const hydrojump::util::ChildExit e = hydrojump::util::wait_child(pid);
    if (e.exited) {  // it ended (the end reached, or an error) before the kill
      REQUIRE(e.exit_code == 0);
      ++finished_early;
      break;
    }
    REQUIRE(e.signal == SIGKILL);
    ++kills;
    if (writing) ++kills_while_writing;
    // Whatever it left is whole: the checkpoint (if any) reads back and its checksum holds.
    if (fs::exists(killed / "checkpoint.bin")) CHECK_NOTHROW(hydrojump::sph::read_checkpoint(killed / "checkpoint.bin"));
  }
  CHECK(kills >= 20);
  CHECK(kills_while_writing >= 3);
  // The rest of the run, resumed once more to its end.
  const pid_t last = start({"sph", killed.string(), resume_or_restart(), "--quiet", "--threads", "1", "--end-time", end_time},
                           tmp.path() / "killed.log");
  REQUIRE(hydrojump::util::wait_child(last).exit_code == 0);

  const auto expected = outputs_of(reference);
  const auto got = outputs_of(killed);
  std::vector<std::string> expected_names, got_names;
  for (const auto& f : expected) expected_names.push_back(f.first);
  for (const auto& f : got) got_names.push_back(f.first);
  INFO("kills " << kills << ", during a checkpoint write " << kills_while_writing << ", run finished before a kill "
                << finished_early);
  REQUIRE(got_names == expected_names);  // no temporary left behind, nothing missing
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO(expected[i].first);
    CHECK(got[i].second == expected[i].second);
  }
}
