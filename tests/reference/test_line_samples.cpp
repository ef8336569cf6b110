// Reading sampled lines: water depth by integrating alpha, and the surge front on the floor line.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "reference/discharge_samples.hpp"
#include "reference/line_samples.hpp"
#include "tests/temp_dir.hpp"

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
  const hydrojump::testing::TempDir tmp("line-samples");
  const fs::path& dir = tmp.path();
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
}

TEST_CASE("patch discharges: window means per unit width, outward fluxes, restarts and missing samples",
          "[reference][samples]") {
  using hydrojump::reference::patch_discharges;
  const hydrojump::testing::TempDir tmp("discharges");
  const fs::path dir = tmp.path() / "case";  // not there yet, as a case without samples
  auto write = [&](const std::string& function, const std::string& start, const std::string& rows) {
    fs::create_directories(dir / "postProcessing" / function / start);
    std::ofstream(dir / "postProcessing" / function / start / "surfaceFieldValue.dat")
        << "# Time\tsum(alphaPhi0.water)\tsum(phi)\n" << rows;
  };
  const double thickness = 0.005;
  // Nothing sampled (a case written before these function objects): nothing to say.
  CHECK_FALSE(patch_discharges(dir, 0.0, 1.0, thickness).has_value());
  // Inflow 0.1 m^2/s (an inward flux is negative), outflow 0.08 then 0.12: mean 0.1 over [1, 2].
  write("discharge_inlet", "0", "1\t-5e-4\t0\n1.5\t-5e-4\t0\n2\t-5e-4\t0\n3\t-1\t0\n");
  write("discharge_outlet", "0", "1\t4e-4\t0\n1.5\t5e-4\t0\n2\t6e-4\t0\n3\t1\t0\n");
  auto q = patch_discharges(dir, 1.0, 2.0, thickness);
  REQUIRE(q.has_value());
  CHECK(q->inflow_m2_s == Approx(0.1).epsilon(1e-12));
  CHECK(q->outflow_m2_s == Approx(0.1).epsilon(1e-12));
  CHECK_FALSE(q->top_sampled);
  CHECK(q->top_outflow_m2_s == 0.0);
  // The top, restarted at 1.5 s: the restart's rows replace the first run's from 1.5 s on.
  write("discharge_atmosphere", "0", "1\t0\t0\n1.5\t9\t0\n2\t9\t0\n");
  write("discharge_atmosphere", "1.5", "1.5\t1.5e-5\t0\n2\t1.5e-5\t0\n");
  q = patch_discharges(dir, 1.0, 2.0, thickness);
  REQUIRE(q.has_value());
  CHECK(q->top_sampled);
  CHECK(q->top_outflow_m2_s == Approx(0.002).epsilon(1e-12));  // (0 + 3e-3 + 3e-3) / 3
  // Started again from 1.5 s (the first restart crashed before its next output): OpenFOAM finds
  // 1.5/surfaceFieldValue.dat and writes 1.5/surfaceFieldValue_1.5.dat. The retry's rows replace the
  // crashed attempt's, also the row at 2.5 s the retry has not reached yet.
  write("discharge_atmosphere", "1.5", "1.5\t1.5e-5\t0\n2\t1.5e-5\t0\n2.5\t7\t0\n");
  std::ofstream(dir / "postProcessing" / "discharge_atmosphere" / "1.5" / "surfaceFieldValue_1.5.dat")
      << "# Time\tsum(alphaPhi0.water)\tsum(phi)\n2\t3e-5\t0\n";
  const auto rows = hydrojump::reference::read_surface_field_value(dir / "postProcessing" / "discharge_atmosphere");
  REQUIRE(rows.size() == 3u);
  CHECK(rows[0] == std::make_pair(1.0, 0.0));
  CHECK(rows[1] == std::make_pair(1.5, 1.5e-5));
  CHECK(rows[2] == std::make_pair(2.0, 3e-5));
  q = patch_discharges(dir, 1.0, 2.0, thickness);
  REQUIRE(q.has_value());
  CHECK(q->top_outflow_m2_s == Approx(0.003).epsilon(1e-12));  // (0 + 3e-3 + 6e-3) / 3
  // A window without rows, or no thickness: nothing.
  CHECK_FALSE(patch_discharges(dir, 5.0, 6.0, thickness).has_value());
  CHECK_FALSE(patch_discharges(dir, 1.0, 2.0, 0.0).has_value());
}
