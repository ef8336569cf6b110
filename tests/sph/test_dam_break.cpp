// Dam break (verification case 4): water column L = 1 m wide, 2 m high, in a tank 4 m long
// (Koshizuka & Oka 1996 scaled to L = 1 m; cases/dam_break.toml). The surge front x_front/L (as
// defined by sph::surge_front_x, within 0.1 L of the floor) is compared with the measured points of
// cases/data/dam_break_front_koshizuka_oka_1996.csv by compare::compare_front
// (compare/dam_break_front.hpp), in the experiment's time origin: t_model = t_exp - 0.175 sqrt(L/(2g))
// (0.0395 s at L = 1 m: its clock started before the gate had let the water go), as published
// comparisons with this kind of data do.
// The unshifted errors are printed beside (the front then leads by about 0.2 L from t = 0.2 s on:
// mean 0.18 / max 0.24 at dx = 0.04 m, 0.23 / 0.29 at dx = 0.02 m).
//
// Asserted on the shifted comparison, at dx = 0.04 m (default suite) and dx = 0.02 and 0.01 m ([slow]):
//   - mean |x_sim - x_exp| / L <= 0.10 and max <= 0.20, over at least 10 of the 15 measured points;
//   - the late front speed (least-squares slope after t_exp = 0.4 s) within 5 % of the measured one.
// A measured point counts while the measured front and the simulated one are both short of the far
// wall (the simulated by dx).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "compare/dam_break_front.hpp"
#include "sph/run.hpp"
#include "sph_test_support.hpp"

namespace {

using hydrojump::compare::FrontComparison;

const std::vector<hydrojump::compare::MeasuredFrontPoint>& measured_front() {
  static const auto points = hydrojump::compare::read_measured_front(
      std::string(HYDROJUMP_SOURCE_DIR) + "/cases/data/dam_break_front_koshizuka_oka_1996.csv");
  return points;
}

// One run's front at every step, and what the lifted-gate test needs.
struct DamBreakRun {
  hydrojump::compare::FrontTrace trace;
  double released_at_02s = 0.0;  // fraction of the water past the gate (x > L) at t = 0.2 s
  double column_width = 0.0, tank_length = 0.0, gravity = 9.81, dx = 0.0;
  long steps = 0;
};

// Runs the dam break at spacing dx to the last measured time.
// gate_speed > 0: the gate is lifted at that speed (gate.type = "lifted"), otherwise removed at once.
// shifting: sph.particle_shifting.
DamBreakRun run_dam_break(double dx, double gate_speed = 0.0, const std::string& shifting = "none") {
  auto loaded = sph_test::load_case("dam_break.toml", dx, [&](hydrojump::cases::Case& c) {
    c.sph.time_integrator = hydrojump::cases::TimeIntegrator::symplectic;
    c.sph.particle_shifting = hydrojump::cases::option_from_name<hydrojump::cases::ParticleShifting>("test", shifting);
    auto& d = std::get<hydrojump::cases::DamBreakCase>(c.data);
    if (gate_speed > 0.0) {
      d.gate = hydrojump::cases::GateOpening::lifted;
      d.gate_lift_speed_m_s = gate_speed;
    } else {
      d.gate = hydrojump::cases::GateOpening::instant;
    }
  });
  DamBreakRun run;
  run.column_width = loaded.spec.dam_break()->column_width_m;
  run.tank_length = loaded.spec.dam_break()->tank_length_m;
  run.gravity = loaded.study.fluid.gravity_m_s2;
  run.dx = dx;
  const auto measured = measured_front();
  const double end = measured.back().t_s * std::sqrt(run.column_width / hydrojump::compare::measured_front_column_width_m);
  hydrojump::sph::Solver solver(loaded.settings, loaded.particles);
  const double layer = 0.1 * run.column_width;
  run.trace.t_s.push_back(solver.time());
  run.trace.x_m.push_back(hydrojump::sph::surge_front_x(solver.particles(), dx, layer));
  while (solver.time() < end) {
    solver.step();
    run.trace.t_s.push_back(solver.time());
    run.trace.x_m.push_back(hydrojump::sph::surge_front_x(solver.particles(), dx, layer));
    if (solver.time() >= 0.2 && run.released_at_02s == 0.0) {
      double past = 0.0, all = 0.0;
      const auto& ps = solver.particles();
      for (Eigen::Index i = 0; i < ps.size(); ++i) {
        if (!ps.is_fluid(i)) continue;
        all += ps.mass[i];
        if (ps.x[i] > run.column_width) past += ps.mass[i];
      }
      run.released_at_02s = past / all;
    }
  }
  run.steps = solver.clock().steps;
  return run;
}

// The run's front against the data with the time origin shifted by `shift_s`.
FrontComparison compare(const DamBreakRun& run, double shift_s) {
  return hydrojump::compare::compare_front(run.trace, measured_front(),
                                           {run.column_width, run.tank_length, run.dx, shift_s});
}

// Both comparisons, printed; returns the one in the experiment's time origin.
FrontComparison compare_and_print(const DamBreakRun& run, const std::string& label) {
  const double shift = hydrojump::compare::gate_opening_time_shift_s(run.column_width, run.gravity);
  const FrontComparison shifted = compare(run, shift), unshifted = compare(run, 0.0);
  std::cout << "dam break dx = " << run.dx << " (" << label << "): time origin shifted by " << shift
            << " s: mean |x_front/L difference| = " << shifted.mean_abs << ", max = " << shifted.max_abs << " over "
            << shifted.points << " of " << shifted.measured_points << " points, late front speed ratio "
            << shifted.late_speed_ratio << "; unshifted: mean " << unshifted.mean_abs << ", max " << unshifted.max_abs
            << ", first point " << unshifted.first_point_error << "; " << run.steps << " steps\n";
  return shifted;
}

// What is checked at every resolution, in the experiment's time origin.
void check_front(const FrontComparison& e) {
  CHECK(e.points >= 10);
  CHECK(e.mean_abs <= 0.10);
  CHECK(e.max_abs <= 0.20);
  CHECK(std::abs(e.late_speed_ratio - 1.0) <= 0.05);
}

}  // namespace

TEST_CASE("dam break surge front against Koshizuka and Oka at dx 0.04 m in the experiment's time origin",
          "[sph][dam_break]") {
  check_front(compare_and_print(run_dam_break(0.04), "instant gate"));
}

// Particle shifting (sph/particle_shifting.hpp) keeps the surge front: the same checks.
TEST_CASE("dam break surge front with particle shifting at dx 0.04 m", "[sph][dam_break][shifting][long]") {
  check_front(compare_and_print(run_dam_break(0.04, 0.0, "fickian"), "instant gate, fickian shifting"));
}

TEST_CASE("dam break surge front against Koshizuka and Oka at dx 0.02 m and 0.01 m in the experiment's time origin",
          "[sph][dam_break][slow]") {
  for (const double dx : {0.02, 0.01}) {
    INFO("dx = " << dx);
    check_front(compare_and_print(run_dam_break(dx), "instant gate"));
  }
}

// The lifted gate (sph/wall_motion.hpp), the physical alternative to the time shift: a gate lifted at
// 5.16 m/s (2.0 m/s at 0.3 m, the gate of the MPM study in shared/reference/study-notes.md,
// Froude-scaled to the 2 m column) holds water back, so less of it has passed the gate at t = 0.2 s
// than with the instant release (its front, a jet shot under the gate, may run slightly ahead early
// on); a gate lifted at 1000 m/s (out of the column in 2 ms) releases the column as the instant gate
// does (front within 0.03 L at every measured point, released water within 3 %). A lifted gate models
// the opening itself, so it is compared in the unshifted time origin.
TEST_CASE("dam break: a lifted gate delays the surge, a very fast one releases it at once", "[sph][dam_break][wall_motion][long]") {
  const DamBreakRun instant_run = run_dam_break(0.04);
  const DamBreakRun lifted_run = run_dam_break(0.04, 5.16);
  const DamBreakRun fast_run = run_dam_break(0.04, 1000.0);
  const FrontComparison instant = compare(instant_run, 0.0), lifted = compare(lifted_run, 0.0),
                        fast = compare(fast_run, 0.0);
  const std::size_t n = std::min({instant.simulated.size(), lifted.simulated.size(), fast.simulated.size()});
  REQUIRE(n >= 10);
  for (std::size_t k = 0; k < n; ++k) {
    INFO("measured point " << k);
    CHECK(std::abs(fast.simulated[k] - instant.simulated[k]) < 0.03);
  }
  INFO("water past the gate at 0.2 s: instant " << instant_run.released_at_02s << ", lifted "
       << lifted_run.released_at_02s << ", fast " << fast_run.released_at_02s);
  CHECK(lifted_run.released_at_02s < 0.8 * instant_run.released_at_02s);
  // The fast gate frees the column's foot ~1 ms later than the instant one; at the release rate of
  // ~0.9 of the water per second near 0.2 s that is ~2 % of the released fraction.
  CHECK(fast_run.released_at_02s == Approx(instant_run.released_at_02s).epsilon(0.03));
  WARN("dam break dx 0.04 m, gate lifted at 5.16 m/s, unshifted: mean |x_front/L difference| " << lifted.mean_abs
       << ", max " << lifted.max_abs << " (instant gate unshifted: " << instant.mean_abs << " / " << instant.max_abs
       << ")");
}

// The lifted gate at dx = 0.02 m (unshifted time origin): it removes part of the instant gate's lead
// (mean 0.16 against 0.23, max 0.26 against 0.29 as last measured), not all of it.
TEST_CASE("dam break at dx 0.02 m: the gate lifted at 5.16 m/s removes part of the lead (unshifted)",
          "[sph][dam_break][slow]") {
  const FrontComparison instant = compare(run_dam_break(0.02), 0.0);
  const FrontComparison lifted = compare(run_dam_break(0.02, 5.16), 0.0);
  REQUIRE(lifted.points >= 10);
  WARN("dam break dx 0.02 m, unshifted: gate lifted at 5.16 m/s mean " << lifted.mean_abs << ", max " << lifted.max_abs
       << ", late speed ratio " << lifted.late_speed_ratio << "; instant gate mean " << instant.mean_abs << ", max "
       << instant.max_abs);
  CHECK(lifted.mean_abs < instant.mean_abs);
}
