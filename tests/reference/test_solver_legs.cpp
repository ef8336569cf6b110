// The legs a VOF run is split into so that every output lies on the grid k dt_out and the end time is
// written (reference/runner.hpp, plan_solver_legs).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "reference/runner.hpp"

using hydrojump::reference::plan_solver_legs;
using hydrojump::reference::SolverLeg;

namespace {

// A leg as (end, write interval or 0 for the case's).
std::vector<std::pair<double, double>> summary(const std::vector<SolverLeg>& legs) {
  std::vector<std::pair<double, double>> out;
  for (const SolverLeg& leg : legs) out.emplace_back(leg.end_s, leg.write_interval_s.value_or(0.0));
  return out;
}

void check_legs(const std::vector<SolverLeg>& legs, const std::vector<std::pair<double, double>>& expected) {
  const auto got = summary(legs);
  REQUIRE(got.size() == expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    INFO("leg " << i);
    CHECK(got[i].first == Approx(expected[i].first).margin(1e-12));
    CHECK(got[i].second == Approx(expected[i].second).margin(1e-12));
  }
}

}  // namespace

TEST_CASE("a run from and to output times is one leg at the case's interval", "[reference][legs]") {
  check_legs(plan_solver_legs(0.0, 10.0, 0.1), {{10.0, 0.0}});
  // 4.4 s read from a time directory's name is not exactly 44 x 0.1: still on the grid.
  check_legs(plan_solver_legs(4.4, 8.4, 0.1), {{8.4, 0.0}});
  check_legs(plan_solver_legs(4.4 + 1e-9, 8.4 - 1e-9, 0.1), {{8.4 - 1e-9, 0.0}});
}

TEST_CASE("a start off the grid gets an aligning leg written once at the next output time", "[reference][legs]") {
  check_legs(plan_solver_legs(4.41491204, 8.4, 0.1), {{4.5, 4.5 - 4.41491204}, {8.4, 0.0}});
  // The next output time is the end time: the aligning leg is the whole run.
  check_legs(plan_solver_legs(4.41491204, 4.5, 0.1), {{4.5, 4.5 - 4.41491204}});
}

TEST_CASE("an end off the grid gets a closing leg that writes it", "[reference][legs]") {
  check_legs(plan_solver_legs(0.0, 0.015, 0.01), {{0.01, 0.0}, {0.015, 0.005}});
  // Start on the grid and no later grid time before the end: the closing leg only.
  check_legs(plan_solver_legs(0.01, 0.015, 0.01), {{0.015, 0.005}});
  // Both ends off the grid.
  check_legs(plan_solver_legs(0.015, 0.035, 0.01), {{0.02, 0.005}, {0.03, 0.0}, {0.035, 0.005}});
  check_legs(plan_solver_legs(0.015, 0.025, 0.01), {{0.02, 0.005}, {0.025, 0.005}});
  // No output time between start and end: one leg written at its end.
  check_legs(plan_solver_legs(0.012, 0.018, 0.01), {{0.018, 0.006}});
}

TEST_CASE("a run that already reached its end time has no leg", "[reference][legs]") {
  CHECK(plan_solver_legs(10.0, 10.0, 0.1).empty());
  CHECK(plan_solver_legs(10.05, 10.0, 0.1).empty());
  CHECK(plan_solver_legs(10.05, 10.0, std::nullopt).empty());
}

TEST_CASE("without a simulated-time output interval the run is one leg at the case's settings",
          "[reference][legs]") {
  check_legs(plan_solver_legs(0.015, 0.035, std::nullopt), {{0.035, 0.0}});
}

TEST_CASE("legs cover the run without gaps and every leg boundary is an output time or the end",
          "[reference][legs]") {
  const double dt = 0.1;
  for (double start : {0.0, 0.03, 0.1, 1.23456, 2.0, 2.09999}) {
    for (double end : {2.1, 2.15, 3.0, 3.05, 7.77}) {
      if (end <= start) continue;
      INFO("start " << start << ", end " << end);
      const auto legs = plan_solver_legs(start, end, dt);
      REQUIRE(!legs.empty());
      double t = start;
      for (const SolverLeg& leg : legs) {
        CHECK(leg.end_s > t);
        const double k = leg.end_s / dt;
        const bool on_grid = std::abs(k - std::round(k)) < 1e-6;
        CHECK((on_grid || leg.end_s == end));
        // A leg with its own interval writes once, at its end.
        if (leg.write_interval_s) CHECK(*leg.write_interval_s == Approx(leg.end_s - t).margin(1e-12));
        t = leg.end_s;
      }
      CHECK(t == end);
    }
  }
}

TEST_CASE("a leg's controlDict sets its own write interval only where the interval counts simulated time",
          "[reference][legs]") {
  // A hand-edited case whose output interval is 1 s, with function objects that also write every 1 s
  // of simulated time and one that writes every time step (writeInterval 1 under timeStep, also when
  // timeStep is the unstated default). The leg writes every 0.5 s, to t = 3 s.
  const std::string text = "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
                           "endTime         10;\n"
                           "writeControl    adjustable;\n"
                           "writeInterval   1;\n"
                           "functions\n{\n"
                           "    sampled\n    {\n        type sets;\n        writeControl adjustableRunTime;\n"
                           "        writeInterval 1;\n        sets ( line { type lineUniform; nPoints 10; } );\n    }\n"
                           "    stepwise\n    {\n        type volFieldValue;\n        writeControl timeStep;\n"
                           "        writeInterval 1;\n    }\n"
                           "    by_default\n    {\n        type surfaceFieldValue;\n        writeInterval 1;\n"
                           "        nested { writeControl runTime; }\n    }\n"
                           "}\n";
  hydrojump::reference::SolverLeg leg;
  leg.end_s = 3.0;
  leg.write_interval_s = 0.5;
  const std::string got = hydrojump::reference::leg_control_dict(text, "system/controlDict", leg);
  std::string expected = text;
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto pos = expected.find(from);
    REQUIRE(pos != std::string::npos);
    expected.replace(pos, from.size(), to);
  };
  replace("endTime         10;", "endTime         3;");
  replace("writeInterval   1;", "writeInterval   0.5;");
  replace("adjustableRunTime;\n        writeInterval 1;", "adjustableRunTime;\n        writeInterval 0.5;");
  CHECK(got == expected);
  // A leg at the case's interval changes only the end time.
  leg.write_interval_s.reset();
  std::string end_only = text;
  end_only.replace(end_only.find("endTime         10;"), 19, "endTime         3;");
  CHECK(hydrojump::reference::leg_control_dict(text, "system/controlDict", leg) == end_only);
}

TEST_CASE("a controlDict edited by hand during a leg keeps the edit, with the case's endTime back",
          "[reference][legs]") {
  using hydrojump::reference::control_dict_after_leg;
  const std::string original = "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
                               "endTime         10; // endTime = run.end_time_s\n"
                               "writeInterval   0.1;\n"
                               "maxCo           0.8;\n";
  hydrojump::reference::SolverLeg leg;
  leg.end_s = 4.5;
  const std::string leg_text = hydrojump::reference::leg_control_dict(original, "system/controlDict", leg);
  REQUIRE(leg_text != original);
  // Untouched: the case's text comes back as it was.
  CHECK(control_dict_after_leg(original, leg_text, leg_text, "system/controlDict", leg) == original);
  // maxCo lowered by hand while interFoam ran the leg: kept, and endTime is the case's again.
  std::string edited = leg_text;
  edited.replace(edited.find("maxCo           0.8;"), 20, "maxCo           0.5;");
  const auto back = control_dict_after_leg(original, leg_text, edited, "system/controlDict", leg);
  REQUIRE(back.has_value());
  std::string expected = original;
  expected.replace(expected.find("maxCo           0.8;"), 20, "maxCo           0.5;");
  CHECK(*back == expected);
  // A leg that also set its own write interval: the edit cannot be separated from the leg's changes.
  leg.write_interval_s = 0.05;
  const std::string aligning = hydrojump::reference::leg_control_dict(original, "system/controlDict", leg);
  std::string edited_aligning = aligning;
  edited_aligning.replace(edited_aligning.find("maxCo           0.8;"), 20, "maxCo           0.5;");
  CHECK_FALSE(control_dict_after_leg(original, aligning, edited_aligning, "system/controlDict", leg).has_value());
  CHECK(control_dict_after_leg(original, aligning, aligning, "system/controlDict", leg) == original);
}
