// The dam-break front comparison (compare/dam_break_front.hpp) against hand-built traces with known
// answers: a trace that is the measured front moved by the gate's opening time compares exactly in
// the experiment's time origin; a trace ahead by a constant distance gives that distance; the wall,
// the trace's end and the Froude scaling of the measured times decide which points count.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "compare/dam_break_front.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump::compare;
using hydrojump::testing::TempDir;

namespace {

const std::vector<MeasuredFrontPoint> measured = {
    {0.1, 1.2}, {0.2, 1.5}, {0.3, 2.0}, {0.45, 2.8}, {0.55, 3.4}, {0.65, 3.9}};

// x(t) = L * (the measured front, linearly interpolated, at t + lead_s) + offset_m: a model whose
// water leaves lead_s earlier than the experiment's; sampled every 1 ms from 0 to 0.8 s.
FrontTrace trace_of(double l, double lead_s, double offset_m) {
  FrontTrace tr;
  for (int k = 0; k <= 800; ++k) {
    const double t = 0.001 * k, te = t + lead_s;
    double x = measured.front().x_over_l;
    for (std::size_t j = 0; j + 1 < measured.size(); ++j)
      if (te >= measured[j].t_s && te <= measured[j + 1].t_s)
        x = measured[j].x_over_l + (measured[j + 1].x_over_l - measured[j].x_over_l) * (te - measured[j].t_s) /
                                       (measured[j + 1].t_s - measured[j].t_s);
    if (te > measured.back().t_s) x = measured.back().x_over_l + 5.0 * (te - measured.back().t_s);
    tr.t_s.push_back(t);
    tr.x_m.push_back(l * x + offset_m);
  }
  return tr;
}

}  // namespace

TEST_CASE("the gate-opening time shift is 0.175 sqrt(L / (2 g))", "[compare][dam_break]") {
  CHECK(gate_opening_time_shift_s(1.0, 9.81) == Approx(0.0395083).epsilon(1e-5));
  CHECK(gate_opening_time_shift_s(0.25, 9.81) == Approx(0.5 * 0.0395083).epsilon(1e-5));
  CHECK_THROWS_AS(gate_opening_time_shift_s(0.0, 9.81), std::invalid_argument);
}

TEST_CASE("a front that leads by the gate's opening time compares exactly in the experiment's time origin",
          "[compare][dam_break]") {
  const double shift = gate_opening_time_shift_s(1.0, 9.81);
  const FrontTrace tr = trace_of(1.0, shift, 0.0);
  const FrontComparison shifted = compare_front(tr, measured, {1.0, 4.0, 0.02, shift});
  CHECK(shifted.points == 6);
  CHECK(shifted.measured_points == 6);
  // Exact up to the linear interpolation between the 1 ms samples across the data's kinks: at most
  // (slope jump, < 6 L/s) x 1 ms / 4 = 1.5e-3 L.
  CHECK(shifted.mean_abs < 1.5e-3);
  CHECK(shifted.max_abs < 1.5e-3);
  CHECK(shifted.late_speed_ratio == Approx(1.0).epsilon(1e-3));
  // Unshifted, the same model leads: at t = 0.3 s it is where the data is at 0.3395 s.
  const FrontComparison unshifted = compare_front(tr, measured, {1.0, 4.0, 0.02, 0.0});
  CHECK(unshifted.simulated[2] == Approx(2.0 + (2.8 - 2.0) * shift / 0.15).epsilon(1e-3));
  CHECK(unshifted.mean_abs > 0.1);
}

TEST_CASE("a front ahead by a constant distance gives that distance over L and the wall and the trace's end drop points",
          "[compare][dam_break]") {
  // Ahead by 0.15 m on L = 0.5 m: |dx| / L = 0.3 at every point; the measured times scale with
  // sqrt(0.5), and the trace moved by that scale's shift compares every point it reaches.
  const double l = 0.5, scale = std::sqrt(l);
  FrontTrace tr;
  const FrontTrace unit = trace_of(1.0, 0.0, 0.0);
  for (std::size_t k = 0; k < unit.t_s.size(); ++k) {
    tr.t_s.push_back(unit.t_s[k] * scale);
    tr.x_m.push_back(l * unit.x_m[k] + 0.15);
  }
  const FrontComparison c = compare_front(tr, measured, {l, 4.0 * l, 0.01, 0.0});
  // The point at x/L = 3.9 is compared only while x_sim = 1.95 + 0.15 = 2.1 m < 2.0 - 0.01 m: it is not.
  CHECK(c.points == 5);
  CHECK(c.mean_abs == Approx(0.3).epsilon(1e-9));
  CHECK(c.max_abs == Approx(0.3).epsilon(1e-9));
  CHECK(c.t_exp_s[0] == Approx(0.1 * scale).epsilon(1e-12));
  // A trace that ends at 0.25 s (in L = 1 m time) compares only the points before it.
  FrontTrace short_trace = trace_of(1.0, 0.0, 0.0);
  short_trace.t_s.resize(251);
  short_trace.x_m.resize(251);
  const FrontComparison s = compare_front(short_trace, measured, {1.0, 4.0, 0.02, 0.0});
  CHECK(s.points == 2);
  CHECK(std::isnan(s.late_speed_ratio));  // no point after 0.4 s
}

TEST_CASE("the measured front table is read with its comments, and a damaged one is refused naming the file",
          "[compare][dam_break]") {
  const TempDir tmp("front-table");
  const auto good = tmp.path() / "front.csv";
  std::ofstream(good) << "# Koshizuka & Oka\n# scaled\nt_s,x_front_over_L\n0.1,1.1\n0.2,1.3\n";
  const auto points = read_measured_front(good);
  REQUIRE(points.size() == 2);
  CHECK(points[1].t_s == 0.2);
  CHECK(points[1].x_over_l == 1.3);
  const auto bad = tmp.path() / "bad.csv";
  std::ofstream(bad) << "t_s,x_front_over_L\n0.1,1.1\n0.2,abc\n";
  CHECK_THROWS_WITH(read_measured_front(bad), Catch::Contains("bad.csv") && Catch::Contains("0.2,abc"));
  CHECK_THROWS_WITH(read_measured_front(tmp.path() / "none.csv"), Catch::Contains("none.csv"));
}
