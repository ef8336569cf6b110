// OpenFOAM time-directory names: which names are times, and the sorted listing with its lower bound.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "util/time_directories.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using hydrojump::util::parse_time_name;
using hydrojump::util::time_directories;

TEST_CASE("time names are OpenFOAM's decimal times and nothing else", "[cases][time_directories]") {
  CHECK(parse_time_name("0") == 0.0);
  CHECK(parse_time_name("0.05") == 0.05);
  CHECK(parse_time_name("12.5") == 12.5);
  CHECK(parse_time_name("1e-05") == 1e-05);
  CHECK(parse_time_name("2.5E+01") == 25.0);
  CHECK(parse_time_name(".5") == 0.5);
  for (const char* not_a_time : {"", "0.orig", "0.05.incomplete", "4.5.abandoned.2", "processor0", "constant", "-1",
                                 "+1", " 1", "1 ", "nan", "inf", "infinity", "0x10", "1e", "1e999", "e5", "."}) {
    INFO(not_a_time);
    CHECK_FALSE(parse_time_name(not_a_time).has_value());
  }
}

TEST_CASE("time directories are listed sorted by time, files and other names left out", "[cases][time_directories]") {
  const hydrojump::testing::TempDir tmp("time-directories");
  const fs::path& dir = tmp.path();
  for (const char* name : {"10", "2", "0", "0.5", "1e-05", "0.orig", "2.incomplete", "constant", "processor0"})
    fs::create_directories(dir / name);
  std::ofstream(dir / "3") << "a file named like a time\n";

  const auto all = time_directories(dir);
  REQUIRE(all.size() == 5);
  const double expected[] = {0.0, 1e-05, 0.5, 2.0, 10.0};
  for (std::size_t k = 0; k < all.size(); ++k) {
    CHECK(all[k].time_s == expected[k]);
    CHECK(all[k].path == dir / all[k].path.filename());
  }
  CHECK(all[3].path.filename() == "2");

  // Only the times after a bound (here the start, t = 0), as the runner and the results check ask.
  const auto later = time_directories(dir, 0.0);
  REQUIRE(later.size() == 4);
  CHECK(later.front().time_s == 1e-05);
  CHECK(time_directories(dir, 10.0).empty());
  CHECK(time_directories(dir / "missing").empty());
  CHECK(time_directories(dir / "3").empty());  // a file, not a directory
}
