// A failed stage's diagnosis (app/stage_info.hpp): failure.txt counts only when this leg wrote it, judged
// on the file system's own timestamps.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <string>

#include "app/stage_info.hpp"
#include "tests/temp_dir.hpp"
#include "util/atomic_file.hpp"

namespace fs = std::filesystem;
using hydrojump::app::failure_text;
using hydrojump::app::leg_start_time;

TEST_CASE("Stage info: a diagnosis written as the leg starts is this leg's, an older one is not", "[study]") {
  const hydrojump::testing::TempDir tmp("stage_info");
  const fs::path& dir = tmp.path();
  fs::create_directories(dir / "sph");
  const fs::path marker = dir / "sph.started";
  const fs::path diagnosis = dir / "sph" / "failure.txt";
  hydrojump::util::write_file_atomically(marker, "key\n");
  hydrojump::util::write_file_atomically(diagnosis, "went unstable at t = 0.5 s\n  details\n");
  hydrojump::util::write_file_atomically(dir / "sph.log", "step 10\nlast words\n");
  const auto started = fs::last_write_time(marker);

  // The marker's own timestamp is the leg's start.
  CHECK(leg_start_time(marker) == started);
  // Written in the same timestamp tick as the marker (coarse file-system clocks): still this leg's.
  fs::last_write_time(diagnosis, started);
  CHECK(failure_text(dir, "sph", dir / "sph.log", 3, leg_start_time(marker)) == "went unstable at t = 0.5 s");
  // A diagnosis older than the leg is an earlier leg's: the log's last line and the exit status.
  fs::last_write_time(diagnosis, started - std::chrono::seconds(1));
  CHECK(failure_text(dir, "sph", dir / "sph.log", 3, leg_start_time(marker)) == "exit status 3: last words");
  // Without a marker the leg starts now.
  CHECK(leg_start_time(dir / "absent.started") >= started);
  CHECK(leg_start_time(fs::path()) >= started);
}
