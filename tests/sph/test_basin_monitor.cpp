// The stilling-basin run monitor (sph/basin_monitor.hpp) on particle sets built by hand, where the
// answers are known: water columns of a lattice, the toe of a step, the discharges from the buffer mass
// totals, the steady-state verdict and the summary, and the restore of a resumed run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "basin_fixture.hpp"
#include "util/csv_table.hpp"
#include "sph/basin_monitor.hpp"

using namespace hydrojump;

using namespace basin_fixture;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("water columns of a lattice give its depth and discharge", "[sph][basin]") {
  const sph::ParticleSet ps = step_particles(0.5);
  // The hat weights sum to w/dx over a lattice whatever its offset: exact depth and discharge for
  // stations on, between and anywhere near the particle columns, for w = dx and w = 2 dx.
  for (const double width : {dx, 2.0 * dx}) {
    const auto c = sph::BasinMonitor::columns(ps, {0.2525, 0.25, 0.2513, 0.7525, 0.7547}, width);
    for (int k = 0; k < 3; ++k) {
      CHECK(c[k].depth == Approx(depth1).epsilon(1e-12));
      CHECK(c[k].discharge == Approx(q).epsilon(1e-12));
    }
    for (int k = 3; k < 5; ++k) {
      CHECK(c[k].depth == Approx(depth2).epsilon(1e-12));
      CHECK(c[k].discharge == Approx(q).epsilon(1e-12));
    }
  }
}

TEST_CASE("the monitor finds the toe of a step and reads the sections", "[sph][basin]") {
  sph::BasinMonitor monitor(setup());
  monitor.record(step_particles(0.5), 0.0, 0.0, 0.0);
  const sph::BasinSample& s = monitor.samples().back();
  // Running mean over 0.8 depth1 = 4 stations: the step shows half-way at most 2 stations early.
  CHECK(s.toe_x == Approx(0.5).margin(2.5 * dx));
  CHECK(s.depth[0] == Approx(depth1).epsilon(1e-9));
  CHECK(s.depth[1] == Approx(depth2).epsilon(1e-9));
  CHECK(s.discharge[1] == Approx(q).epsilon(1e-9));
  CHECK(std::isnan(s.q_in));  // no interval before the first sample
  CHECK(monitor.jump_state() == "in_basin");
  // The terminal line says when q will be known instead of printing NaN.
  CHECK_THAT(monitor.status_line(), Catch::Contains("from the second output on"));
  CHECK_THAT(monitor.status_line(), !Catch::Contains("nan"));
  // No rise anywhere: the jump has left the basin; a rise from the upstream section on: drowned.
  monitor.record(step_particles(2.0), 0.1, 0.0, 0.0);
  CHECK(monitor.jump_state() == "swept_downstream");
  CHECK(std::isnan(monitor.samples().back().toe_x));
  // A toe past the "downstream" section (0.8025 m), where y2 is read: swept as well.
  monitor.record(step_particles(0.9), 0.15, 0.0, 0.0);
  CHECK(monitor.samples().back().toe_x == Approx(0.9).margin(2.5 * dx));
  CHECK(monitor.jump_state() == "swept_downstream");
  CHECK_THAT(monitor.status_line(), Catch::Contains("past the downstream section"));
  CHECK_THAT(monitor.status_line(), Catch::Contains("q_in 0.0000"));
  monitor.record(step_particles(0.0), 0.2, 0.0, 0.0);
  CHECK(monitor.jump_state() == "at_inflow");
  CHECK_THAT(monitor.summary_json(), Catch::Contains("\"jump_state\": \"at_inflow\""));
}

TEST_CASE("a stationary jump with balanced discharges is steady, a drifting one is not", "[sph][basin]") {
  const double dt = 0.1;
  SECTION("stationary") {
    sph::BasinMonitor monitor(setup());
    const sph::ParticleSet ps = step_particles(0.5);
    for (int k = 0; k <= 30; ++k) {
      const double t = k * dt;
      monitor.record(ps, t, rho0 * q * t, rho0 * q * t);  // in = out = q
    }
    CHECK(monitor.samples().back().q_in == Approx(q).epsilon(1e-9));
    CHECK(monitor.steady_from() == Approx(1.0).margin(1e-9));  // the first time with 1 s of history
    const std::string json = monitor.summary_json();
    CHECK(contains(json, "\"steady_over_window\": true"));
    CHECK(contains(json, "\"inflow_discharge_relative_error\": 0,"));
    CHECK(contains(json, "\"y2_over_y1\": 5.2,"));
  }
  SECTION("steady, then 30 % short over (1.5, 2] s, then balanced: steady again from the latest steady stretch") {
    sph::BasinMonitor monitor(setup());
    const sph::ParticleSet ps = step_particles(0.5);
    for (int k = 0; k <= 40; ++k) {
      const double t = k * dt;
      // mass out = rho0 q (t - 0.3 * (the part of [1.5, 2] before t))
      const double short_s = std::clamp(t - 1.5, 0.0, 0.5);
      monitor.record(ps, t, rho0 * q * t, rho0 * q * (t - 0.3 * short_s));
      if (k == 15) CHECK(monitor.steady_from() == Approx(1.0).margin(1e-9));
      if (k == 25) CHECK(std::isnan(monitor.steady_from()));  // one short interval in the last second: 3 %
    }
    // The last second holds no short interval from t = 3 s on (one output later if the window's start
    // is closed): not the first steady time, 1 s.
    CHECK(monitor.steady_from() == Approx(3.0).margin(0.1 + 1e-9));
  }
  SECTION("drifting downstream at 0.1 m/s") {
    sph::BasinMonitor monitor(setup());
    for (int k = 0; k <= 30; ++k) {
      const double t = k * dt;
      monitor.record(step_particles(0.3 + 0.1 * t), t, rho0 * q * t, rho0 * q * t);
    }
    // 0.1 m of drift per second is above the 0.068 m tolerance.
    CHECK(std::isnan(monitor.steady_from()));
    CHECK(contains(monitor.summary_json(), "\"steady_over_window\": false"));
  }
  SECTION("outflow 5 % short of the inflow") {
    sph::BasinMonitor monitor(setup());
    const sph::ParticleSet ps = step_particles(0.5);
    for (int k = 0; k <= 30; ++k) {
      const double t = k * dt;
      monitor.record(ps, t, rho0 * q * t, 0.95 * rho0 * q * t);
    }
    CHECK(std::isnan(monitor.steady_from()));
    const std::string json = monitor.summary_json();
    CHECK(contains(json, "\"steady_by_window_means\": false"));
    CHECK(contains(json, "\"window_outflow_minus_inflow_over_q\": -0.05"));
  }
  SECTION("outflow swinging by 10 % with the window's period: the 1 s test fails, the window means balance") {
    sph::BasinMonitor monitor(setup());
    const sph::ParticleSet ps = step_particles(0.5);
    const double omega = 2.0 * std::acos(-1.0) / 1.5;  // one period = the window [1.5, 3] s
    for (int k = 0; k <= 30; ++k) {
      const double t = k * dt;
      // q_out = q (1 + 0.1 sin(omega t)): mass out = rho0 q (t + 0.1 (1 - cos(omega t)) / omega); its
      // 1 s means are 3.6 % below q at t = 3 s, its mean over the window is q.
      const double out = rho0 * q * (t + 0.1 * (1.0 - std::cos(omega * t)) / omega);
      monitor.record(ps, t, rho0 * q * t, out);
    }
    CHECK(std::isnan(monitor.steady_from()));
    const std::string json = monitor.summary_json();
    CHECK(contains(json, "\"steady_over_window\": false"));
    CHECK(contains(json, "\"steady_by_window_means\": true"));
  }
}

TEST_CASE("outputs a time step late still make up the averaging window", "[sph][basin]") {
  // The solver writes each output at the first step at or after its nominal time. Outputs every 0.1 s,
  // each 6.8e-6 s late; in = out except over the last interval (2.9, 3] s of the window [1.5, 3] s,
  // when nothing leaves: the window's outflow - inflow is -0.1 q / (1.5 q) = -1/15. Without the
  // tolerance (cases/output_times.hpp) the output of 3 s fell out of the window and the balance read 0.
  sph::BasinMonitorSetup s = setup();
  s.output_interval_s = 0.1;
  sph::BasinMonitor monitor(s);
  const sph::ParticleSet ps = step_particles(0.5);
  const double late = 6.8e-6;
  for (int k = 0; k <= 30; ++k) {
    const double t = 0.1 * k + late;
    const double out = rho0 * q * std::min(t, 2.9 + late);
    monitor.record(ps, t, rho0 * q * t, out);
  }
  const std::string json = monitor.summary_json();
  INFO(json);
  const std::string key = "\"window_outflow_minus_inflow_over_q\": ";
  const auto at = json.find(key);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(json.substr(at + key.size(), 24)) == Approx(-1.0 / 15.0).epsilon(1e-6));
  CHECK(contains(json, "\"steady_by_window_means\": false"));
  // The last second's balance (the same rule) is -0.1 q / (1 s q) = -10 % at the last output: not steady.
  CHECK(std::isnan(monitor.steady_from()));
}

TEST_CASE("a resumed monitor continues from the checkpoint's rows", "[sph][basin]") {
  sph::BasinMonitor first(setup());
  const sph::ParticleSet ps = step_particles(0.5);
  for (int k = 0; k <= 5; ++k) first.record(ps, 0.1 * k, rho0 * q * 0.1 * k, 0.0);
  sph::BasinMonitor resumed(setup());
  resumed.restore(first.csv_rows());
  CHECK(resumed.csv() == first.csv());
  // The checkpoint's own time is recorded again on resume: replaced, not duplicated.
  resumed.record(ps, 0.5, rho0 * q * 0.5, 0.0);
  CHECK(resumed.samples().size() == first.samples().size());
  // ... with its discharges over the interval from the sample before it, as first recorded.
  CHECK(std::isfinite(resumed.samples().back().q_in));
  CHECK(resumed.csv() == first.csv());
  CHECK_THROWS(resumed.restore({"0,1,2"}));
}

TEST_CASE("the monitor's mass balance counts the density outliers removed as water leaving", "[sph][basin][density_outliers]") {
  // Water in the domain constant; 1 kg/m injected, 0.75 kg/m out at the outlet and 0.25 kg/m removed as
  // outliers over the run: the balance closes only with the outliers counted.
  sph::BasinMonitor monitor(setup());
  const sph::ParticleSet ps = step_particles(0.5);
  monitor.record(ps, 0.0, 0.0, 0.0, 0.1, 0.0);
  monitor.record(ps, 1.0, 1.0, 0.75, 0.1, 0.25);
  const std::string json = monitor.summary_json();
  CHECK(contains(json, "\"inflow_minus_outflow_kg_per_m\": 0,") );
  CHECK(contains(json, "\"density_outliers_kg_per_m\": 0.25"));
  CHECK(contains(json, "\"relative_to_injected\": 0}"));
  CHECK(contains(monitor.csv(), "outlet_target_depth_m,outlier_mass_kg_per_m,"));
  sph::BasinMonitor resumed(setup());
  resumed.restore(monitor.csv_rows());
  CHECK(resumed.samples().back().mass_removed == 0.25);
}

TEST_CASE("the water in the basin: all fluid with an inflow buffer, not a piston reservoir's", "[sph][basin]") {
  // One particle of the step pushed back upstream of the inflow section (x_in = 0): with an inflow
  // buffer it is still basin water (it entered and has not left); upstream of a piston's gate the
  // water is the reservoir's.
  hydrojump::sph::ParticleSet ps = step_particles(0.5);
  ps.x[0] = -0.01;
  const double total = ps.mass.sum();
  auto fluid_mass = [&](bool reservoir_upstream) {
    auto s = setup();
    s.reservoir_upstream = reservoir_upstream;
    hydrojump::sph::BasinMonitor monitor(s);
    monitor.record(ps, 0.0, 0.0, 0.0);
    const std::string row = monitor.csv_rows().back();
    std::vector<double> v;
    for (const auto& cell : hydrojump::util::split_csv_line(row)) v.push_back(hydrojump::util::csv_number(cell));
    REQUIRE(v.size() > 6);
    return v[6];  // t, toe, q_in, q_out, mass_in, mass_out, fluid_mass, ...
  };
  CHECK(fluid_mass(false) == Approx(total).epsilon(1e-12));
  CHECK(fluid_mass(true) == Approx(total - ps.mass[0]).epsilon(1e-12));
}

TEST_CASE("the monitor records the outlet's target depth and where the tailwater was held", "[sph][basin][level_control]") {
  sph::BasinMonitorSetup held = setup();
  held.tailwater_held_at = "downstream_section";
  sph::BasinMonitor monitor(held);
  const sph::ParticleSet ps = step_particles(0.5);
  // A level control lowering the outlet's target from 0.20 m by 0.01 m per output, t = 1.0 ... 3.0 s;
  // the summary's window mean is that of the outputs in [1.5, 3.0] s.
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k <= 10; ++k) {
    const double t = 1.0 + 0.2 * k, y_t = 0.20 - 0.01 * k;
    monitor.record(ps, t, rho0 * q * t, rho0 * q * t, y_t);
    if (t >= held.average_start_s - 1e-9 && t <= held.average_end_s + 1e-9) {
      sum += y_t;
      ++count;
    }
  }
  REQUIRE(count == 8);  // t = 1.6 ... 3.0
  CHECK(monitor.samples().back().outlet_target_depth == Approx(0.10));
  CHECK(contains(monitor.csv(), "fluid_mass_kg_per_m,outlet_target_depth_m,"));
  const std::string summary = monitor.summary_json();
  INFO(summary);
  CHECK(contains(summary, "\"tailwater_held_at\": \"downstream_section\""));
  const std::string key = "\"outlet_target_depth_m\": {\"mean\": ";
  const auto at = summary.find(key);
  REQUIRE(at != std::string::npos);
  CHECK(std::strtod(summary.c_str() + at + key.size(), nullptr) == Approx(sum / count).epsilon(1e-9));
  CHECK_THAT(monitor.status_line(), Catch::Contains("outlet y_t 0.1000 m"));
  // Held at the outlet (the default), the line does not repeat the constant y2.
  sph::BasinMonitor plain(setup());
  plain.record(ps, 1.0, 0.0, 0.0, 0.2);
  CHECK_THAT(plain.status_line(), !Catch::Contains("outlet y_t"));
  // A resumed run restores the column from the checkpoint's rows.
  sph::BasinMonitor resumed(held);
  resumed.restore(monitor.csv_rows());
  CHECK(resumed.csv() == monitor.csv());
  CHECK(resumed.samples().back().outlet_target_depth == monitor.samples().back().outlet_target_depth);
}
