// Reading sampled lines: water depth by integrating alpha, and the surge front on the floor line.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include "reference/line_samples.hpp"

namespace fs = std::filesystem;
using hydrojump::reference::LineSample;

TEST_CASE("water depth is the integral of alpha along the line", "[reference][line_samples]") {
  // alpha = 1 below z = 0.1, a linear interface between 0.1 and 0.11, 0 above: depth 0.105.
  LineSample s;
  for (int i = 0; i <= 300; ++i) {
    const double z = i * 0.001;
    s.position_m.push_back(z);
    s.alpha.push_back(z <= 0.1 ? 1.0 : (z >= 0.11 ? 0.0 : (0.11 - z) / 0.01));
  }
  CHECK(hydrojump::reference::water_depth(s) == Approx(0.105).margin(1e-12));
}

TEST_CASE("the surge front ignores detached splashes", "[reference][line_samples]") {
  LineSample s;
  for (int i = 0; i <= 100; ++i) {
    const double x = i * 0.01;
    s.position_m.push_back(x);
    // Water up to x = 0.4 with a one-point dry hole at 0.2, a splash at x = 0.8.
    const bool wet = (x <= 0.4 + 1e-9 && std::abs(x - 0.2) > 1e-9) || std::abs(x - 0.8) < 1e-9;
    s.alpha.push_back(wet ? 0.9 : 0.1);
  }
  CHECK(*hydrojump::reference::surge_front(s, 0.05) == Approx(0.4));
  CHECK(*hydrojump::reference::surge_front(s, 0.5) == Approx(0.8));
  s.alpha.front() = 0.0;
  CHECK_FALSE(hydrojump::reference::surge_front(s, 0.05).has_value());
}

TEST_CASE("raw .xy files are read and bad ones rejected with the file name", "[reference][line_samples]") {
  const fs::path dir = fs::temp_directory_path() / ("hydrojump-line-samples-" + std::to_string(::getpid()));
  fs::create_directories(dir / "0.5");
  fs::create_directories(dir / "0.25");
  {
    std::ofstream f(dir / "0.5/line_alpha.water.xy");
    f << "# comment\n0 1\n0.01 1\n0.02 0.5\n0.03 0\n";
    std::ofstream bad(dir / "0.25/line_alpha.water.xy");
    bad << "0 x\n";
  }
  const LineSample s = hydrojump::reference::read_line_sample(dir / "0.5/line_alpha.water.xy");
  CHECK(s.position_m.size() == 4);
  CHECK(hydrojump::reference::water_depth(s) == Approx(0.02));
  CHECK_THROWS_WITH(hydrojump::reference::read_line_sample(dir / "0.25/line_alpha.water.xy"),
                    Catch::Contains("0.25/line_alpha.water.xy"));
  CHECK_THROWS_WITH(hydrojump::reference::read_line_sample(dir / "missing.xy"), Catch::Contains("missing.xy"));
  const auto times = hydrojump::reference::sample_times(dir);
  REQUIRE(times.size() == 2);
  CHECK(times[0].first == 0.25);
  CHECK(times[1].first == 0.5);
  fs::remove_all(dir);
}
