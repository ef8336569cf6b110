// The toe-holding control's volume target shared by both solvers (cases/toe_hold_law.hpp), against
// hand-computed values, and its gains from a case.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "cases/geometry.hpp"
#include "cases/spec_reader.hpp"
#include "cases/toe_hold_law.hpp"

using namespace hydrojump::cases;

namespace {

// y1 = 25.4 mm, y2* = 0.132 m (y2* - y1 = 0.1066 m), basin start 0.2 m, outlet 1.76 m, T_x 5 s, k_p 0.5.
ToeHoldGains hand_gains() {
  ToeHoldGains g;
  g.inflow_depth_m = 0.0254;
  g.tailwater_depth_m = 0.132;
  g.target_toe_x_m = 0.2;
  g.outlet_x_m = 1.76;
  g.toe_hold_time_s = 5.0;
  g.toe_hold_gain = 0.5;
  return g;
}

}  // namespace

TEST_CASE("The toe-holding law moves the volume target by the water the toe's displacement stands for",
          "[cases][toe_hold]") {
  const ToeHoldGains g = hand_gains();
  // P = 0.5 * 0.1066 * 0.05 = 0.002665 m^2
  CHECK(toe_hold_proportional(g, 0.25) == Approx(0.002665).epsilon(1e-12));
  // I = 0.2 + 0.1066 / 5 * 0.05 * 0.5 = 0.200533 m^2; V* = I + P = 0.203198 m^2
  const VolumeTarget t = toe_hold_volume_target(g, 0.2, 0.25, 0.5);
  CHECK(t.integral_m2 == Approx(0.200533).epsilon(1e-12));
  CHECK(t.volume_target_m2 == Approx(0.203198).epsilon(1e-12));
  // A toe upstream of the target asks for less water.
  CHECK(toe_hold_volume_target(g, 0.2, 0.15, 0.5).volume_target_m2 < 0.2);
  // No toe (the jump has left the basin): a toe at the outlet, 1.56 m downstream of the target.
  const double none = std::numeric_limits<double>::quiet_NaN();
  CHECK(toe_hold_proportional(g, none) == Approx(0.5 * 0.1066 * 1.56).epsilon(1e-12));
  CHECK(toe_hold_volume_target(g, 0.2, none, 0.5).integral_m2 == Approx(0.2 + 0.1066 / 5.0 * 1.56 * 0.5).epsilon(1e-12));
}

TEST_CASE("The toe-holding gains come from the case and its geometry, and other cases are refused", "[cases][toe_hold]") {
  const Study s = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml");
  const Case& a = s.cases.front();
  REQUIRE(a.holds_toe());
  const CaseGeometry geo = make_geometry(a, s.fluid);
  const ToeHoldGains g = toe_hold_gains(a, geo);
  CHECK(g.inflow_depth_m == geo.inflows.front().depth_m);
  CHECK(g.tailwater_depth_m == geo.outflows.front().tailwater_depth_m);
  CHECK(g.target_toe_x_m == a.stilling_basin()->upstream_length_m);
  CHECK(g.outlet_x_m == geo.x_max_m);
  CHECK(g.toe_hold_time_s == a.stilling_basin()->control.toe_hold_time_s);
  CHECK(g.toe_hold_gain == 0.0);
  const Study tank = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/still_water.toml");
  CHECK_THROWS_AS(toe_hold_gains(tank.cases.front(), make_geometry(tank.cases.front(), tank.fluid)), std::invalid_argument);
}
