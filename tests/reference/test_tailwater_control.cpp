// The tailwater control that holds a jump's toe (reference/tailwater_control.hpp): the law against hand
// values and against a model basin whose answer is known, the toe on a sampled line, the rewrite of
// the outlet's Umean in a field file, the log, the legs and the generated dictionaries.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "reference/case_writer.hpp"
#include "reference/foam_dictionary.hpp"
#include "reference/runner.hpp"
#include "reference/tailwater_control.hpp"
#include "reference_test_specs.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump;
using reference::TailwaterControlLaw;
using reference::TailwaterControlStep;
using reference::testing::basin_spec;
using reference::testing::parse;
using reference::testing::tiny_hold_toe_spec;

namespace {

// Run B's numbers: q = 0.076 m^2/s, y1 = 25.4 mm, y2* = 0.2036 m, toe held at the basin start 0.2 m.
TailwaterControlLaw law_b() {
  TailwaterControlLaw law;
  law.discharge_m2_s = 0.076;
  law.gains.inflow_depth_m = 0.0254;
  law.gains.tailwater_depth_m = 0.2036;
  law.gains.target_toe_x_m = 0.2;
  law.toe_search_from_m = 0.1;
  law.gains.outlet_x_m = 2.49;
  law.interval_s = 0.5;
  law.volume_hold_time_s = 1.0;
  law.gains.toe_hold_time_s = 5.0;
  law.gains.toe_hold_gain = 0.5;  // the proportional part (off by default), so the hand values test it too
  return law;
}

const double no_toe = std::numeric_limits<double>::quiet_NaN();

// A model basin of length L with a jump: the supercritical stream of depth y1 up to the toe x, a level
// h behind it, so the water volume per unit width is V = y1 x + h (L - x). The toe moves upstream when
// the level exceeds the depth the jump needs, y2c (unknown to the control), at a speed of U1 per unit
// relative excess (a tailwater 1 % high moves the toe at 1 % of U1):
//
//   dx/dt = -U1 (h - y2c) / y2c,     dV/dt = q - Umean h   (the outlet lets out Umean h)
//
// integrated with explicit Euler steps of 1 ms, the control acting every interval_s on the mean of
// five toe samples per leg.
struct ModelBasin {
  double length_m = 2.49;
  double y1 = 0.0254;
  double u1 = 3.0;
  double y2c = 0.199;  // the depth this model's jump needs: 2.3 % below Belanger's y2*
  double x = 0.6;      // toe
  double volume = 0.0;
  double level() const { return (volume - y1 * x) / (length_m - x); }
};

struct ModelRun {
  double toe_end = 0.0, level_end = 0.0, toe_min = 1e9, toe_max = -1e9;
};

ModelRun run_model(ModelBasin b, const TailwaterControlLaw& law, bool control, double duration_s) {
  const double dt = 1e-3;
  const int steps_per_leg = static_cast<int>(std::lround(law.interval_s / dt));
  const int sample_every = steps_per_leg / 5;
  double umean = law.discharge_m2_s / law.gains.tailwater_depth_m;
  std::optional<double> target;
  std::vector<double> toes;
  ModelRun r;
  const int legs = static_cast<int>(std::lround(duration_s / law.interval_s));
  for (int leg = 0; leg < legs; ++leg) {
    toes.clear();
    for (int k = 1; k <= steps_per_leg; ++k) {
      const double h = b.level();
      b.x += dt * (-b.u1 * (h - b.y2c) / b.y2c);
      b.volume += dt * (law.discharge_m2_s - umean * h);
      if (b.x <= 0.0 || b.x >= b.length_m) return r;  // at the gate or out of the basin
      if (k % sample_every == 0) toes.push_back(b.x);
    }
    r.toe_min = std::min(r.toe_min, b.x);
    r.toe_max = std::max(r.toe_max, b.x);
    if (control) {
      const TailwaterControlStep s = reference::tailwater_control_step(law, target, (leg + 1) * law.interval_s, law.interval_s, toes, b.volume);
      target = s.volume_target_m2 - hydrojump::cases::toe_hold_proportional(law.gains, s.toe_x_m);  // I(n)
      umean = s.outlet_mean_velocity_m_s;
    }
  }
  r.toe_end = b.x;
  r.level_end = b.level();
  return r;
}

}  // namespace

TEST_CASE("the tailwater control law: volume target and outlet Umean against hand values", "[reference][tailwater]") {
  const TailwaterControlLaw law = law_b();
  // First step: V* = V + (y2* - y1) / T_x (x - x_target) dt = 0.38 + 0.1782 / 5 * 0.1 * 0.5 (the
  // integral starts at V - P, so the proportional part k_p (y2* - y1) (x - x_target) adds nothing yet)
  const TailwaterControlStep first = reference::tailwater_control_step(law, std::nullopt, 10.5, 0.5, {0.25, 0.35, no_toe, 0.30}, 0.38);
  CHECK(first.toe_outputs == 3);
  CHECK(first.toe_x_m == Approx(0.30).epsilon(1e-12));
  CHECK(first.volume_target_m2 == Approx(0.38 + 0.1782 / 5.0 * 0.1 * 0.5).epsilon(1e-12));
  // Umean = (q + (V - V*) / T_V) / y2*
  CHECK(first.outlet_mean_velocity_m_s ==
        Approx((0.076 + (0.38 - first.volume_target_m2) / 1.0) / 0.2036).epsilon(1e-12));
  // With a previous target and the toe on target: the target stays, the volume error is drained.
  const TailwaterControlStep on = reference::tailwater_control_step(law, 0.381, 11.0, 0.5, {0.2}, 0.383);
  CHECK(on.volume_target_m2 == Approx(0.381).epsilon(1e-12));
  CHECK(on.outlet_mean_velocity_m_s == Approx((0.076 + 0.002) / 0.2036).epsilon(1e-12));
  // The toe 0.05 m downstream, from the integral 0.38: V* = I + P, I = 0.38 + 0.1782 / 5 * 0.05 * 0.5,
  // P = k_p (y2* - y1) (x - x_target) = 0.5 * 0.1782 * 0.05.
  const TailwaterControlStep near = reference::tailwater_control_step(law, 0.38, 11.0, 0.5, {0.25}, 0.38);
  CHECK(near.volume_target_m2 == Approx(0.38 + 0.1782 / 5.0 * 0.05 * 0.5 + 0.5 * 0.1782 * 0.05).epsilon(1e-12));
  CHECK(hydrojump::cases::toe_hold_proportional(law.gains, 0.25) == Approx(0.5 * 0.1782 * 0.05).epsilon(1e-12));
  // No toe on any output: counted at the outlet (the jump left the basin): more water.
  const TailwaterControlStep gone = reference::tailwater_control_step(law, 0.38, 11.5, 0.5, {no_toe, no_toe}, 0.38);
  CHECK(gone.toe_outputs == 0);
  CHECK(std::isnan(gone.toe_x_m));
  CHECK(gone.volume_target_m2 ==
        Approx(0.38 + 0.1782 / 5.0 * (2.49 - 0.2) * 0.5 + 0.5 * 0.1782 * (2.49 - 0.2)).epsilon(1e-12));
  // A short leg (an aligning leg of 0.05 s after a stop) moves the integral by its own length only.
  const TailwaterControlStep short_leg = reference::tailwater_control_step(law, 0.38, 10.1, 0.05, {0.3}, 0.38);
  CHECK(short_leg.volume_target_m2 == Approx(0.38 + 0.1782 / 5.0 * 0.1 * 0.05 + 0.5 * 0.1782 * 0.1).epsilon(1e-12));
  // Clamped to [1/4, 4] q / y2*.
  CHECK(reference::tailwater_control_step(law, 0.38, 12.0, 0.5, {0.2}, 0.0).outlet_mean_velocity_m_s ==
        Approx(0.25 * 0.076 / 0.2036).epsilon(1e-12));
  CHECK(reference::tailwater_control_step(law, 0.38, 12.0, 0.5, {0.2}, 1.38).outlet_mean_velocity_m_s ==
        Approx(4.0 * 0.076 / 0.2036).epsilon(1e-12));
}

TEST_CASE("the tailwater control holds a model basin's toe at the target and finds the depth its jump needs",
          "[reference][tailwater]") {
  const TailwaterControlLaw law = law_b();
  ModelBasin b;
  b.volume = b.y1 * b.x + law.gains.tailwater_depth_m * (b.length_m - b.x);  // filled to y2*, 2.3 % too deep
  // Without the control the outlet lets out q at y2*: the basin keeps its too-deep water and the
  // jump runs upstream past the upstream section (0.1 m).
  const ModelRun free = run_model(b, law, false, 60.0);
  CHECK(free.toe_min < 0.1);
  // With it the toe comes to x_target and the level to the depth the jump needs (y2c, 0.199 m), within
  // 5 mm and 0.1 mm after 60 s, without leaving the basin on the way.
  const ModelRun held = run_model(b, law, true, 60.0);
  CHECK(held.toe_end == Approx(0.2).margin(0.005));
  CHECK(held.level_end == Approx(0.199).margin(1e-4));
  CHECK(held.toe_min > 0.1);
  // The same from a toe upstream of the target.
  b.x = 0.12;
  b.volume = b.y1 * b.x + 0.195 * (b.length_m - b.x);
  const ModelRun from_upstream = run_model(b, law, true, 60.0);
  CHECK(from_upstream.toe_end == Approx(0.2).margin(0.005));
  CHECK(from_upstream.level_end == Approx(0.199).margin(1e-4));
}

TEST_CASE("the toe on a free surface: the first persistent rise of its highest points", "[reference][tailwater]") {
  // Iso-surface points every 2 mm from 0 to 2 m: the supercritical stream at y1, a splash at 0.30-0.31 m
  // (with the running mean's 2 cm still shorter than the persistence 2 y1 = 5 cm), the roller's surface at 0.1 m from 0.6 m on, with an air
  // pocket's underside at 0.01 m below it (the highest point counts) and the jet's points at y1 below
  // the roller.
  std::vector<double> x, z;
  const double y1 = 0.0254;
  for (int i = 0; i <= 1000; ++i) {
    const double xi = 0.002 * i;
    const bool roller = xi >= 0.6 - 1e-9, splash = xi > 0.30 - 1e-9 && xi < 0.31 + 1e-9;
    x.push_back(xi);
    z.push_back(roller || splash ? 0.1 : y1);
    if (roller) {
      x.push_back(xi);
      z.push_back(0.01);
      x.push_back(xi);
      z.push_back(y1);
    }
  }
  // within the running mean's half width plus a station (y1/4)
  CHECK(reference::toe_on_surface(x, z, 0.1, 2.0, y1) == Approx(0.6).margin(0.011 + 0.25 * y1));
  CHECK(reference::toe_on_surface(x, z, 0.7, 2.0, y1) == Approx(0.7).margin(1e-12));  // searched from x_from
  // Searched only up to x_to: no toe before 0.5 m.
  CHECK(std::isnan(reference::toe_on_surface(x, z, 0.1, 0.5, y1)));
  // No rise, no points: no toe.
  std::vector<double> flat(z.size(), y1);
  CHECK(std::isnan(reference::toe_on_surface(x, flat, 0.1, 2.0, y1)));
  CHECK(std::isnan(reference::toe_on_surface({}, {}, 0.1, 2.0, y1)));
}

TEST_CASE("the free surface's points are read from an OpenFOAM .vtp file, and an unreadable one is named",
          "[reference][tailwater]") {
  const hydrojump::testing::TempDir tmp("tailwater-vtp");
  const fs::path file = tmp.path() / "alpha_0.5.vtp";
  // What OpenFOAM's surfaces function object writes, in ASCII: two points (x, y = vertical, z = span).
  util::write_file_atomically(file,
      "<?xml version='1.0'?>\n<VTKFile type='PolyData' version='0.1' byte_order='LittleEndian'>\n<PolyData>\n"
      "<Piece NumberOfPoints='2' NumberOfPolys='0'>\n<Points>\n"
      "<DataArray type='Float32' Name='Points' NumberOfComponents='3' format='ascii'>\n"
      "0.25 0.0381 0 0.5 0.2 0.001\n</DataArray>\n</Points>\n</Piece>\n</PolyData>\n</VTKFile>\n");
  std::vector<double> x, z;
  reference::read_surface_points(file, x, z);
  REQUIRE(x.size() == 2);
  CHECK(x[0] == Approx(0.25));
  CHECK(z[0] == Approx(0.0381));
  CHECK(x[1] == Approx(0.5));
  CHECK(z[1] == Approx(0.2));
  CHECK_THROWS_WITH(reference::read_surface_points(tmp.path() / "missing.vtp", x, z), Catch::Contains("missing.vtp"));
  // A file that is not VTK XML (here a half-written one) is named, not parsed.
  const fs::path broken = tmp.path() / "broken.vtp";
  util::write_file_atomically(broken, "<?xml version='1.0'?>\n<VTKF");
  CHECK_THROWS_WITH(reference::read_surface_points(broken, x, z),
                    Catch::Contains("broken.vtp") && Catch::Contains("not a VTK XML PolyData"));
}

TEST_CASE("the outlet's Umean is read and rewritten in a field file, nothing else changed", "[reference][tailwater]") {
  const hydrojump::testing::TempDir tmp("tailwater-u");
  const fs::path file = tmp.path() / "U";
  const std::string before =
      "FoamFile { version 2.0; format ascii; class volVectorField; object U; }\n"
      "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform (0 0 0);\nboundaryField\n{\n"
      "    // outlet: Umean = q / y2 (a comment)\n"
      "    outletPipe { type zeroGradient; }\n"
      "    inlet { type fixedValue; value uniform (2 0 0); }\n"
      "    outlet\n    {\n        type            outletPhaseMeanVelocity;\n        Umean           0.37434358;\n"
      "        alpha           alpha.water;\n        value           nonuniform List<vector> 2((0.3 0 0) (0.31 0 0));\n    }\n"
      "    atmosphere { type pressureInletOutletVelocity; value uniform (0 0 0); }\n}\n";
  util::write_file_atomically(file, before);
  CHECK(reference::read_outlet_mean_velocity(file) == 0.37434358);
  reference::write_outlet_mean_velocity(file, 0.4123456789);
  CHECK(reference::read_outlet_mean_velocity(file) == Approx(0.4123456789).epsilon(1e-9));
  std::string expected = before;
  expected.replace(expected.find("0.37434358"), 10, "0.4123456789");
  CHECK(util::read_text_file(file) == expected);
  // A file without the entry: an error naming the file.
  util::write_file_atomically(file, "boundaryField\n{\n    inlet { type fixedValue; }\n}\n");
  CHECK_THROWS_WITH(reference::read_outlet_mean_velocity(file),
                    Catch::Contains(file.string()) && Catch::Contains("no outlet entry"));
  util::write_file_atomically(file, "boundaryField\n{\n    outlet { type zeroGradient; }\n}\n");
  CHECK_THROWS_WITH(reference::write_outlet_mean_velocity(file, 0.3), Catch::Contains("the outlet entry has no Umean"));
}

TEST_CASE("the tailwater control log is appended and read back", "[reference][tailwater]") {
  const hydrojump::testing::TempDir tmp("tailwater-log");
  CHECK(reference::read_tailwater_control_log(tmp.path()).empty());
  TailwaterControlStep a{10.5, 0.3, 5, 0.378, 0.3797, 0.365};
  TailwaterControlStep b{11.0, no_toe, 0, 0.383, 0.3812, 0.3886};
  reference::append_tailwater_control_log(tmp.path(), a);
  reference::append_tailwater_control_log(tmp.path(), b);
  const auto rows = reference::read_tailwater_control_log(tmp.path());
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].time_s == 10.5);
  CHECK(rows[0].toe_x_m == 0.3);
  CHECK(rows[0].toe_outputs == 5);
  CHECK(rows[0].volume_target_m2 == 0.3797);
  CHECK(rows[1].outlet_mean_velocity_m_s == 0.3886);
  CHECK(std::isnan(rows[1].toe_x_m));
  CHECK(rows[1].water_volume_m2 == 0.383);
  // A run resumed from 10.5 s drops the later row; a fresh start drops the log.
  reference::truncate_tailwater_control_log(tmp.path(), 10.5);
  REQUIRE(reference::read_tailwater_control_log(tmp.path()).size() == 1);
  CHECK(reference::read_tailwater_control_log(tmp.path())[0].outlet_mean_velocity_m_s == 0.365);
  reference::truncate_tailwater_control_log(tmp.path(), std::nullopt);
  CHECK(!fs::exists(tmp.path() / reference::tailwater_control_log));
}

TEST_CASE("a damaged tailwater control log is named with its line, not read past", "[reference][tailwater]") {
  const hydrojump::testing::TempDir tmp("tailwater-log-damaged");
  const fs::path file = tmp.path() / reference::tailwater_control_log;
  const std::string header = "time_s,toe_x_m,toe_outputs,water_volume_m2,volume_target_m2,outlet_mean_velocity_m_s\n";
  const std::string good = "0.5,0.3,5,0.378,0.3797,0.365\n";
  const auto error_of = [&](const std::string& text) {
    util::write_file_atomically(file, text);
    try {
      reference::read_tailwater_control_log(tmp.path());
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK_THAT(error_of(header + "garbage\n" + good), Catch::Contains(file.string() + ":2: 1 columns where the header has 6"));
  CHECK_THAT(error_of(header + good + "1.0,0.3,5,0.378,0.3797,nan\n"),
             Catch::Contains(file.string() + ":3: a row with a value that is not a finite number"));
  CHECK_THAT(error_of(header + good + "1.0,0.3,5,0.378,0.3797,abc\n"), Catch::Contains(":3: a row with a value"));
  CHECK_THAT(error_of(header + good + good), Catch::Contains(":3: time_s = 0.5 does not follow the previous row's 0.5"));
  // A leg without a toe (nan) is a valid row.
  CHECK(error_of(header + good + "1.0,nan,0,0.378,0.3797,0.37\n") == "(no error)");
}

TEST_CASE("the legs of a controlled run end every control interval, aligning and closing legs stay whole",
          "[reference][tailwater][legs]") {
  const auto ends = [](const std::vector<reference::SolverLeg>& legs) {
    std::vector<double> e;
    for (const auto& leg : legs) e.push_back(leg.end_s);
    return e;
  };
  using Catch::Matchers::Approx;
  CHECK_THAT(ends(reference::split_legs_for_control(reference::plan_solver_legs(10.0, 12.0, 0.1), 10.0, 0.5)),
             Approx(std::vector<double>{10.5, 11.0, 11.5, 12.0}).margin(1e-9));
  // From 10.05 s (a run stopped there): an aligning leg to 10.1 s, then legs ending at the multiples of
  // 0.5 s from t = 0, as in an uninterrupted run, the grid's last time 11.2 s, and a closing leg to 11.23 s.
  const auto legs = reference::split_legs_for_control(reference::plan_solver_legs(10.05, 11.23, 0.1), 10.05, 0.5);
  CHECK_THAT(ends(legs), Approx(std::vector<double>{10.1, 10.5, 11.0, 11.2, 11.23}).margin(1e-9));
  CHECK(legs.front().write_interval_s.has_value());
  CHECK(!legs[1].write_interval_s.has_value());
  CHECK(legs.back().write_interval_s.has_value());
  CHECK(ends(reference::split_legs_for_control(reference::plan_solver_legs(0.0, 1.0, 0.1), 0.0, 0.0)) ==
        std::vector<double>{1.0});
}

TEST_CASE("a hold_toe basin's case samples the free surface and the water volume, uncompressed, and other cases do not",
          "[reference][tailwater]") {
  const auto control_dict = [](const std::string& spec) {
    const cases::Study study = parse(spec);
    const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
    return reference::foam::format_file(vof.headers.at("system/controlDict"), vof.files.at("system/controlDict"));
  };
  const std::string held = control_dict(tiny_hold_toe_spec());
  CHECK_THAT(held, Catch::Contains("freeSurface") && Catch::Contains("alpha_0.5") && Catch::Contains("water_volume") &&
                       Catch::Contains("volIntegrate") && Catch::Contains("writeCompression off;"));
  // The volume every time step, with no writeInterval that a leg's controlDict could rewrite.
  const std::string volume = held.substr(held.find("water_volume"), held.find("}", held.find("water_volume")) - held.find("water_volume"));
  CHECK_THAT(volume, Catch::Contains("timeStep") && !Catch::Contains("writeInterval"));
  const std::string plain = control_dict(basin_spec("", 0.02, 0.01, "smooth"));
  CHECK_THAT(plain, !Catch::Contains("water_volume") && Catch::Contains("writeCompression on;"));
  // A dam break has no tailwater to steer: its case has no [case.tailwater] table.
  std::string dam = reference::testing::dam_break_spec();
  dam += "[case.tailwater]\ncontrol = \"hold_toe\"\n";
  CHECK_THROWS_WITH(parse(dam), Catch::Contains("tailwater"));
}
