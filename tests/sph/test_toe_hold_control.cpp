// The toe-holding tailwater control (sph/toe_hold_control.hpp, [case.tailwater] control = "hold_toe"):
// - the law by hand: V*(0) = V(0) and y_t = y2*; one output with the toe 0.1 m downstream raises the
//   integral by (y2* - y1) / T_x * 0.1 m * dt, V* by that plus k_p (y2* - y1) 0.1 m, and the outlet by
//   V* - V over T_V S; no toe counts as a toe at
//   the outlet; the clamps; the law is refused for a case that does not hold its toe;
// - on a short smooth channel (A_smooth's inflow, dx 10 mm) with two basin starts 0.1 m apart and
//   everything else the same: each held toe goes to its own basin start;
// - a held run interrupted between two outputs and resumed from its checkpoint ends as the
//   uninterrupted one, bit for bit (particles, V*, the outlet's depth).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>

#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"
#include "sph/checkpoint.hpp"
#include "sph/open_boundaries.hpp"
#include "sph/run.hpp"
#include "sph/toe_hold_control.hpp"
#include "sph_test_support.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump;
using namespace hydrojump::sph;
namespace fs = std::filesystem;

namespace {

ToeHoldLaw hand_law() {
  ToeHoldLaw law;
  law.gains.inflow_depth_m = 0.0254;
  law.gains.tailwater_depth_m = 0.132;
  law.gains.target_toe_x_m = 0.2;
  law.gains.outlet_x_m = 1.0;
  // S = (c_t^2 - U_t^2) / (2 c_t): U_t = 0.0508 / 0.132 = 0.38485 m/s, c_t = 1.13794 m/s -> 0.50389 m/s
  law.outlet_gain_m_s = 0.50389;
  law.interval_s = 0.1;
  law.volume_hold_time_s = 1.0;
  law.gains.toe_hold_time_s = 5.0;
  law.gains.toe_hold_gain = 0.5;
  law.rho0 = 1000.0;
  return law;
}

// A_smooth on the short basin with its toe started `toe_offset_m` downstream of the basin start and
// the tailwater scaled by `tailwater_factor`, under `control`; an absorbing outlet (the study's).
sph_test::LoadedCase held_basin(const std::string& control, double toe_offset_m, double tailwater_factor) {
  return sph_test::short_smooth_basin(0.005, [&](cases::Case& c) {
    auto& b = std::get<cases::StillingBasinCase>(c.data);
    b.control.mode = hydrojump::cases::option_from_name<hydrojump::cases::TailwaterControlMode>("test", control);
    b.control.volume_hold_time_s = 0.5;
    b.control.toe_hold_time_s = 2.0;
    b.tailwater_depth_m *= tailwater_factor;
    b.initial_toe_x_m = b.upstream_length_m + toe_offset_m;
    c.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
    c.sph.sound_speed_coefficient = 20.0;
    c.sph.outflow_condition = hydrojump::cases::OutflowCondition::absorbing;
    c.run.output_interval_s = 0.05;
    c.sections = cases::default_stilling_basin_sections(b);
  });
}

RunOptions options_for(const sph_test::LoadedCase& c, const fs::path& dir, double end_time_s) {
  RunOptions o;
  o.dir = dir;
  o.end_time_s = end_time_s;
  o.output_interval_s = c.spec.run.output_interval_s;
  o.checkpoint_interval_wall_s = 1e9;
  o.fingerprint = "toe hold test";
  o.basin = BasinMonitorSetup::from_case(c.spec, c.geometry, c.settings.dx, c.settings.eos.rho0);
  if (c.spec.holds_toe()) o.toe_hold = ToeHoldLaw::from_case(c.spec, c.geometry, 9.81, c.settings.eos.rho0);
  return o;
}

OpenBoundaries open_of(const sph_test::LoadedCase& c) {
  return OpenBoundaries::from_geometry(c.geometry, buffer_parameters(c.settings));
}

// Mean toe over the outputs in [t0, t1] (a missing toe counts as at the outlet).
double mean_toe(const RunOptions& o, const Solver& solver, double t0, double t1) {
  const util::CsvTable table = util::read_csv_table(o.dir / "basin.csv");
  const auto t = table.column("t_s"), x = table.column("toe_x_m");
  REQUIRE(t);
  REQUIRE(x);
  double sum = 0.0;
  int n = 0;
  for (const auto& row : table.rows) {
    const double tv = util::csv_number(row[*t]);
    if (tv < t0 - 1e-9 || tv > t1 + 1e-9) continue;
    const double xv = util::csv_number(row[*x]);
    sum += std::isfinite(xv) ? xv : solver.settings().domain.x_max;
    ++n;
  }
  REQUIRE(n > 0);
  return sum / n;
}

}  // namespace

TEST_CASE("the toe-holding law by hand: the first output, a toe downstream, no toe, the clamps", "[sph][toe_hold]") {
  const ToeHoldLaw law = hand_law();
  const double mass = 120.0;  // kg/m: V = 0.12 m^2
  // The first output: V* = V, the integral starts at V - P with P = 0.5 * 0.1066 * 0.15 = 7.995e-3 m^2.
  const ToeHoldState first = toe_hold_step(law, 0.0, mass, 0.35);
  CHECK(first.volume_target_m2 == Approx(0.12).epsilon(1e-15));
  CHECK(first.volume_integral_m2 == Approx(0.12 - 7.995e-3).epsilon(1e-12));
  CHECK(first.outlet_depth_m == 0.132);
  // The toe 0.1 m downstream of the target: I += (0.132 - 0.0254) / 5 * 0.1 * 0.1 = 2.132e-4 m^2,
  // V* = I + 0.5 * 0.1066 * 0.1, and with V unchanged the outlet rises by V* - V over T_V S.
  const ToeHoldState second = toe_hold_step(law, first.volume_integral_m2, mass, 0.3);
  const double dv = (0.132 - 0.0254) / 5.0 * 0.1 * 0.1;
  CHECK(second.volume_integral_m2 - first.volume_integral_m2 == Approx(dv).epsilon(1e-9));
  CHECK(second.volume_target_m2 == Approx(second.volume_integral_m2 + 0.5 * 0.1066 * 0.1).epsilon(1e-12));
  CHECK(second.outlet_depth_m == Approx(0.132 + (second.volume_target_m2 - 0.12) / law.outlet_gain_m_s).epsilon(1e-12));
  // The toe moving back does not overshoot the volume: at 0.25 m the proportional part has halved.
  const ToeHoldState back = toe_hold_step(law, second.volume_integral_m2, mass, 0.25);
  CHECK(back.volume_target_m2 - back.volume_integral_m2 == Approx(0.5 * 0.1066 * 0.05).epsilon(1e-9));
  // More water than the target: the outlet drops below y2* to let it out.
  const ToeHoldState drain = toe_hold_step(law, 0.12, mass + 1.0, 0.2);
  CHECK(drain.outlet_depth_m == Approx(0.132 - 0.001 / law.outlet_gain_m_s).epsilon(1e-12));
  // No toe: the jump has left the basin, a toe at the outlet (0.8 m downstream).
  const ToeHoldState gone = toe_hold_step(law, first.volume_integral_m2, mass, std::numeric_limits<double>::quiet_NaN());
  CHECK(gone.volume_integral_m2 - first.volume_integral_m2 == Approx(8.0 * dv).epsilon(1e-9));
  CHECK(gone.volume_target_m2 - gone.volume_integral_m2 == Approx(0.5 * 0.1066 * 0.8).epsilon(1e-9));
  // The clamps: y2*/2 and 3 y2*/2.
  CHECK(toe_hold_step(law, 0.12, mass + 1000.0, 0.2).outlet_depth_m == Approx(0.066));
  CHECK(toe_hold_step(law, 0.12, mass - 110.0, 0.2).outlet_depth_m == Approx(0.198));
  // The law of a case: its basin start and outlet; a fixed-depth case has none.
  const auto held = held_basin("hold_toe", 0.0, 1.0);
  const ToeHoldLaw from_case = ToeHoldLaw::from_case(held.spec, held.geometry, 9.81, 1000.0);
  CHECK(from_case.gains.target_toe_x_m == held.geometry.expected_toe_x_m);
  CHECK(from_case.gains.outlet_x_m == held.geometry.x_max_m);
  CHECK(from_case.interval_s == 0.05);
  {  // its gain S = (c_t^2 - U_t^2) / (2 c_t) from the case's q and tailwater depth, by hand
    const auto& in = held.geometry.inflows.front();
    const double u_t = in.depth_m * in.velocity_m_s / held.geometry.outflows.front().tailwater_depth_m;
    const double c_t = std::sqrt(9.81 * held.geometry.outflows.front().tailwater_depth_m);
    CHECK(from_case.outlet_gain_m_s == Approx(0.5 * (c_t - u_t * u_t / c_t)).epsilon(1e-12));
  }
  const auto fixed = held_basin("fixed_depth", 0.0, 1.0);
  CHECK_THROWS_WITH(ToeHoldLaw::from_case(fixed.spec, fixed.geometry, 9.81, 1000.0), Catch::Contains("hold_toe"));
}

TEST_CASE("the held toe goes to the basin start: two basins starting 0.1 m apart hold their toes 0.1 m apart",
          "[sph][toe_hold][toe_hold_steering][long]") {
  // The same 0.5-m smooth channel and the same initial water (the toe ramp at x = 0.2 m, the tailwater
  // 0.8 y2*, so the jump first runs downstream to about 0.4 m), the basin starting at 0.15 m or at
  // 0.25 m: only the control's target differs (and the sections). Without the control both runs would
  // be the same run. Measured (dx 0.01 m, T_V 0.5 s, T_x 1.5 s, 3 s, the characteristic outlet): the toes
  // come back to 0.178 and 0.245 m over the last second (0.183 and 0.235 m with k_p = 0.5), still
  // settling; asserted:
  // each within 0.06 m (2.4 y1) of its target, and 0.1 m of target apart gives at least 0.05 m of toe.
  const double end = 3.0, dx = 0.01;
  double toe[2] = {0.0, 0.0}, target[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const double upstream = 0.15 + 0.1 * k;
    const auto c = sph_test::short_smooth_basin(dx, [&](cases::Case& spec) {
      auto& b = std::get<cases::StillingBasinCase>(spec.data);
      b.upstream_length_m = upstream;
      b.basin_length_m = 0.45 - upstream;
      b.initial_toe_x_m = 0.2;
      b.tailwater_depth_m *= 0.8;
      b.control.volume_hold_time_s = 0.5;
      b.control.toe_hold_time_s = 1.5;
      spec.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
      spec.sph.sound_speed_coefficient = 20.0;
      spec.sph.outflow_condition = hydrojump::cases::OutflowCondition::absorbing;
      spec.run.output_interval_s = 0.05;
      spec.sections = cases::default_stilling_basin_sections(b);
    });
    const hydrojump::testing::TempDir tmp("toe_hold_target_" + std::to_string(k));
    const RunOptions o = options_for(c, tmp.path(), end);
    Solver solver(c.settings, c.particles, {}, open_of(c));
    REQUIRE(run_case(solver, o) == RunStatus::finished);
    target[k] = c.geometry.expected_toe_x_m;
    toe[k] = mean_toe(o, solver, end - 1.0, end);
    std::cout << "short basin dx " << dx << " m, basin start " << target[k] << " m, toe every 0.25 s:";
    for (double t0 = 0.0; t0 < end - 1e-9; t0 += 0.25) std::cout << ' ' << mean_toe(o, solver, t0, t0 + 0.25);
    std::cout << "; mean over the last 1 s " << toe[k] << " m, outlet depth " << solver.clock().outflow_target_depth
              << " m\n";
  }
  CHECK(std::abs(toe[0] - target[0]) < 0.06);
  CHECK(std::abs(toe[1] - target[1]) < 0.06);
  CHECK(toe[1] - toe[0] > 0.05);
}

TEST_CASE("a held run resumed from its checkpoint ends as the uninterrupted one", "[sph][toe_hold][restart][long]") {
  const auto c = held_basin("hold_toe", 0.05, 0.9);
  const double end = 0.3;
  const hydrojump::testing::TempDir tmp_a("toe_hold_whole"), tmp_b("toe_hold_resumed");
  Solver whole(c.settings, c.particles, {}, open_of(c));
  REQUIRE(run_case(whole, options_for(c, tmp_a.path(), end)) == RunStatus::finished);
  {
    Solver first(c.settings, c.particles, {}, open_of(c));
    RunOptions o = options_for(c, tmp_b.path(), end);
    o.max_steps = 2345;  // between two outputs, after several control steps
    REQUIRE(run_case(first, o) == RunStatus::step_limit);
  }
  const Checkpoint ck = read_checkpoint(checkpoint_path(tmp_b.path()));
  REQUIRE(ck.clock.held_volume_m2 > 0.0);  // the integral I
  Solver resumed(c.settings, ck.particles, ck.clock, open_of(c));
  REQUIRE(run_case(resumed, options_for(c, tmp_b.path(), end), ck) == RunStatus::finished);
  // The control has moved the outlet (the basin starts 10 % low and its toe downstream).
  CHECK(whole.clock().outflow_target_depth != c.geometry.outflows.front().tailwater_depth_m);
  CHECK(resumed.clock().steps == whole.clock().steps);
  CHECK(resumed.clock().held_volume_m2 == whole.clock().held_volume_m2);
  CHECK(resumed.clock().outflow_target_depth == whole.clock().outflow_target_depth);
  const auto& pa = whole.particles();
  const auto& pb = resumed.particles();
  REQUIRE(pa.size() == pb.size());
  CHECK(pa.id == pb.id);
  CHECK(pa.x == pb.x);
  CHECK(pa.z == pb.z);
  CHECK(pa.u == pb.u);
  CHECK(pa.rho == pb.rho);
  CHECK(util::read_text_file(tmp_a.path() / "basin.csv") == util::read_text_file(tmp_b.path() / "basin.csv"));
}
