// The jump-toe criterion shared by the SPH run monitor and the comparator (cases/jump_toe.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "cases/jump_toe.hpp"
#include "cases/output_times.hpp"

using namespace hydrojump::cases;

namespace {

// Stations every ds from 0 to length; surface zeta = y1 up to x_jump, then a linear rise to y2 over
// `rise` (a schematic jump).
struct Profile {
  std::vector<double> x, zeta;
};

Profile schematic_jump(double y1, double y2, double x_jump, double rise, double ds, double length) {
  Profile p;
  for (double x = 0.0; x <= length + 1e-12; x += ds) {
    p.x.push_back(x);
    const double s = std::clamp((x - x_jump) / rise, 0.0, 1.0);
    p.zeta.push_back(y1 + s * (y2 - y1));
  }
  return p;
}

}  // namespace

TEST_CASE("running mean over a centred window skips NaN", "[cases][toe]") {
  const std::vector<double> v{1.0, 2.0, std::nan(""), 4.0, 5.0};
  const std::vector<double> m = running_mean(v, 1);
  CHECK(m[0] == Approx(1.5));
  CHECK(m[1] == Approx(1.5));   // (1 + 2) / 2, the NaN skipped
  CHECK(m[2] == Approx(3.0));   // (2 + 4) / 2
  CHECK(m[4] == Approx(4.5));
  CHECK(std::isnan(running_mean({std::nan("")}, 2)[0]));
}

TEST_CASE("the toe of a schematic jump is where the surface passes 1.5 y1", "[cases][toe]") {
  const double y1 = 0.025, y2 = 0.13, ds = 0.005;
  // Surface reaches 1.5 y1 at x_jump + rise (0.5 y1)/(y2 - y1).
  const Profile p = schematic_jump(y1, y2, 0.4, 0.3, ds, 1.5);
  const std::size_t i = find_jump_toe(p.x, p.zeta, 0.1, y1, ToeCriterion{});
  REQUIRE(i < p.x.size());
  const double expected = 0.4 + 0.3 * (0.5 * y1) / (y2 - y1);
  // The running mean over 0.8 y1 of a linear rise is the rise itself: found within one station.
  CHECK(std::abs(p.x[i] - expected) <= ds + 1e-12);
}

TEST_CASE("a splash thinner than the persistence length does not trip the toe", "[cases][toe]") {
  const double y1 = 0.025, ds = 0.005;
  Profile p = schematic_jump(y1, 0.13, 0.8, 0.3, ds, 1.5);
  // A 1 cm spike of 4 y1 at x = 0.3 m (a droplet or an air pocket).
  for (std::size_t k = 0; k < p.x.size(); ++k)
    if (std::abs(p.x[k] - 0.3) < 0.006) p.zeta[k] = 4.0 * y1;
  const std::size_t i = find_jump_toe(p.x, p.zeta, 0.1, y1, ToeCriterion{});
  REQUIRE(i < p.x.size());
  CHECK(p.x[i] > 0.8);
  // Searching starts at x_from; no rise at all gives "none".
  const Profile flat = schematic_jump(y1, y1, 0.8, 0.3, ds, 1.5);
  CHECK(find_jump_toe(flat.x, flat.zeta, 0.1, y1, ToeCriterion{}) == flat.x.size());
}

TEST_CASE("steadiness rule: the least-squares slope of a toe track, the verdict on the means and the drift tolerance", "[cases][toe]") {
  using hydrojump::cases::least_squares_slope;
  using hydrojump::cases::toe_drift_tolerance_m;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A straight track x = 0.4 + 0.02 t: the slope exactly; frames without a toe (NaN) are skipped.
  CHECK(least_squares_slope({6.0, 7.0, 8.0, 9.0}, {0.52, 0.54, 0.56, 0.58}) == Approx(0.02).margin(1e-12));
  CHECK(least_squares_slope({6.0, 7.0, 8.0, 9.0}, {0.52, nan, 0.56, 0.58}) == Approx(0.02).margin(1e-12));
  // Scatter about a fixed toe: sum (t - 2.5)(x - 0.5) / sum (t - 2.5)^2 = -0.02 / 5.
  CHECK(least_squares_slope({1.0, 2.0, 3.0, 4.0}, {0.50, 0.52, 0.48, 0.50}) == Approx(-0.004).margin(1e-12));
  // Fewer than three frames with a toe, or no spread in time: no slope.
  CHECK(std::isnan(least_squares_slope({1.0, 2.0, 3.0}, {0.5, nan, 0.6})));
  CHECK(std::isnan(least_squares_slope({2.0, 2.0, 2.0}, {0.5, 0.6, 0.7})));
  // The verdict on a window's means: both conditions strictly, NaN is not steady.
  using hydrojump::cases::steady_by_means;
  CHECK(steady_by_means(0.019, 0.06, 0.068));
  CHECK(steady_by_means(-0.019, -0.06, 0.068));
  CHECK_FALSE(steady_by_means(0.02, 0.0, 0.068));
  CHECK_FALSE(steady_by_means(0.0, 0.068, 0.068));
  CHECK_FALSE(steady_by_means(nan, 0.0, 0.068));
  CHECK_FALSE(steady_by_means(0.0, nan, 0.068));
  // The tolerance: a bed wavelength on a corrugated bed, 2 y1 on a smooth one.
  CHECK(toe_drift_tolerance_m(hydrojump::cases::BedShape::sinusoidal, 0.068, 0.0254) == 0.068);
  CHECK(toe_drift_tolerance_m(hydrojump::cases::BedShape::smooth, 0.0, 0.0254) == Approx(0.0508));
}

TEST_CASE("window balance: interval discharges weighted by their intervals, over the outputs in the window", "[cases][toe]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Uneven outputs; q = 0.05. Each row's q_in, q_out cover the interval before it.
  const std::vector<double> t{0.0, 1.0, 1.5, 3.0, 4.0, 6.0};
  const std::vector<double> q_in{nan, 0.05, 0.05, 0.05, 0.05, 0.05};
  const std::vector<double> q_out{nan, 0.07, 0.06, 0.04, 0.05, 0.05};
  const std::vector<double> toe{0.50, 0.51, nan, 0.53, 0.54, 0.70};  // the last one off the line
  // [1, 4]: outputs 1, 1.5, 3, 4; sum (q_out - q_in) dt = 0.01 * 0.5 - 0.01 * 1.5 + 0 = -0.01 over
  // q * 3 s = 0.15: -1/15 (filling); the first output's own interval (0, 1] lies outside.
  const auto b = window_balance(t, q_in, q_out, toe, 1.0, 4.0, 1e-9, 0.05);
  CHECK(b.outputs == 4);
  CHECK(b.toe_missing == 1);
  CHECK(b.first_output_s == 1.0);
  CHECK(b.last_output_s == 4.0);
  CHECK(b.outflow_minus_inflow_over_q == Approx(-1.0 / 15.0).epsilon(0).margin(1e-12));
  CHECK(b.reaches_window_end);
  // Toe trend over (1, 0.51), (3, 0.53), (4, 0.54) only: exactly 0.01 m/s.
  CHECK(b.toe_trend_m_per_s == Approx(0.01).epsilon(0).margin(1e-12));
  // A window between outputs, or with only one, has no balance.
  CHECK(std::isnan(window_balance(t, q_in, q_out, toe, 4.5, 5.5, 1e-9, 0.05).outflow_minus_inflow_over_q));
  CHECK(std::isnan(window_balance(t, q_in, q_out, toe, 3.5, 5.5, 1e-9, 0.05).outflow_minus_inflow_over_q));
  // The whole run: (0.02 * 1 + 0.01 * 0.5 - 0.01 * 1.5) / (0.05 * 6) = 0.01 / 0.3.
  CHECK(window_balance(t, q_in, q_out, toe, 0.0, 6.0, 1e-9, 0.05).outflow_minus_inflow_over_q ==
        Approx(0.01 / 0.3).epsilon(0).margin(1e-12));
  // A window past the last output is not complete.
  CHECK_FALSE(window_balance(t, q_in, q_out, toe, 4.0, 7.0, 1e-9, 0.05).reaches_window_end);
  // A discharge missing after the window's first output: no balance.
  std::vector<double> q_gap = q_out;
  q_gap[3] = nan;
  CHECK(std::isnan(window_balance(t, q_in, q_gap, toe, 1.0, 4.0, 1e-9, 0.05).outflow_minus_inflow_over_q));
  // A repeated output time (a torn resume) is skipped, not counted as an interval.
  const std::vector<double> t_rep{0.0, 1.0, 1.5, 1.5, 3.0, 4.0};
  CHECK(window_balance(t_rep, q_in, q_out, toe, 1.0, 4.0, 1e-9, 0.05).outputs == 4);
  // Every output a little late (as the SPH solver writes them: the first step at or after the nominal
  // time): within 1 % of a 0.5 s output interval the window [1, 4] is the same four outputs; with only
  // 1e-9 s it loses the output of 4 s.
  std::vector<double> t_late = t;
  for (double& v : t_late) v += 6.8e-6;
  const double tolerance = output_time_tolerance_s(0.5);
  CHECK(tolerance == Approx(0.005).epsilon(1e-12));
  const auto late = window_balance(t_late, q_in, q_out, toe, 1.0, 4.0, tolerance, 0.05);
  CHECK(late.outputs == 4);
  CHECK(late.last_output_s == Approx(4.0 + 6.8e-6).epsilon(1e-12));
  CHECK(late.outflow_minus_inflow_over_q == Approx(-1.0 / 15.0).epsilon(1e-9));
  CHECK(late.reaches_window_end);
  CHECK(window_balance(t_late, q_in, q_out, toe, 1.0, 4.0, 1e-9, 0.05).outputs == 3);
  // The tolerance never takes in a neighbouring output: [1.5, 3] holds 1.5 and 3 only.
  CHECK(window_balance(t_late, q_in, q_out, toe, 1.5, 3.0, tolerance, 0.05).outputs == 2);
  CHECK(in_output_window(2.0 - 0.004, 2.0, 3.0, tolerance));
  CHECK_FALSE(in_output_window(2.0 - 0.006, 2.0, 3.0, tolerance));
  CHECK(output_time_tolerance_s(0.0) == 1e-9);
}
