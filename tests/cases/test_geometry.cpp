// The one geometry source: walls, initial water and boundaries derived from a case.
#include <catch2/catch.hpp>

#include <cmath>

#include "cases/geometry.hpp"
#include "cases/spec_reader.hpp"

using namespace hydrojump::cases;

TEST_CASE("Stilling-basin geometry of run A", "[cases][geometry]") {
  const Study s = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const auto geo = make_geometry(*s.find_case("A"), s.fluid);
  CHECK(geo.x_min_m == 0.0);
  CHECK(geo.x_max_m == Approx(0.2 + 20 * 0.068 + 0.2));
  CHECK(geo.z_min_m == Approx(-0.013));
  CHECK(geo.z_max_m == Approx(0.104 + 0.1));
  REQUIRE(geo.inflows.size() == 1);
  CHECK(geo.inflows[0].depth_m == Approx(0.0254));
  REQUIRE(geo.outflows.size() == 1);
  CHECK(geo.outflows[0].tailwater_depth_m == Approx(0.104));
  CHECK(geo.expected_toe_x_m == Approx(0.2));
  // Initial water: y1 upstream, tailwater downstream, never below the bed.
  CHECK(geo.initial_water.surface_at(0.1) == Approx(0.0254));
  CHECK(geo.initial_water.surface_at(1.7) == Approx(0.104));
  CHECK(geo.initial_water.discharge_m2_s == Approx(0.0508));
  // The bed wall has the fluid above it: left-hand normals point up.
  const auto& bed = geo.walls.at(0);
  CHECK(bed.name == "bed");
  for (std::size_t i = 1; i < bed.points.size(); ++i) {
    const Vec2 d = bed.points[i] - bed.points[i - 1];
    CHECK(-d.y() * 0.0 + d.x() > 0.0);
  }
  CHECK(geo.sections.size() == s.find_case("A")->sections.size());
  // The sluice gate reaches the domain top, or the energy line where that is higher (run B).
  for (const char* id : {"A", "B"}) {
    const auto g = make_geometry(*s.find_case(id), s.fluid);
    const auto* basin = s.find_case(id)->stilling_basin();
    const double e1 = basin->inflow_depth_m + basin->inflow_velocity_m_s * basin->inflow_velocity_m_s / (2 * 9.81);
    int gates = 0;
    for (const auto& w : g.walls)
      if (w.name == "inlet_gate") {
        ++gates;
        CHECK(w.points.front().y() == Approx(std::max(g.z_max_m, e1)));
      }
    CHECK(gates == 1);
  }
  CHECK(geo.max_flow_speed_m_s == Approx(2.0));
}

TEST_CASE("Closed-tank walls enclose the water with inward normals", "[cases][geometry]") {
  const Study s = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/still_water.toml");
  const auto geo = make_geometry(s.cases[0], s.fluid);
  const Vec2 centre(0.5, 0.25);
  for (const auto& wall : geo.walls) {
    for (std::size_t i = 1; i < wall.points.size(); ++i) {
      const Vec2 d = wall.points[i] - wall.points[i - 1];
      const Vec2 n(-d.y(), d.x());
      CHECK(n.dot(centre - wall.points[i - 1]) > 0.0);
    }
  }
}

TEST_CASE("Piston reservoir of run A: level from E1, piston speed from q, length from the run", "[cases][geometry]") {
  const Study s = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const Case& a = *s.find_case("A_smooth");
  CaseGeometry geo = make_geometry(a, s.fluid);
  const double t = 0.015, g = 9.81, y1 = 0.0254, q = 0.0254 * 2.0, end = 10.0;
  const PistonReservoir r = add_piston_reservoir(geo, *a.stilling_basin(), 0.0, 0.0, end, t, g);
  // H_r + q^2/(2 g H_r^2) = E1 = y1 + U1^2/(2 g) = 0.2293 m, subcritical (H_r > y_c = 0.064 m).
  CHECK(r.depth_m + q * q / (2 * g * r.depth_m * r.depth_m) == Approx(0.0254 + 4.0 / (2 * g)).epsilon(1e-10));
  CHECK(r.depth_m > std::cbrt(q * q / g));
  CHECK(r.piston_speed_m_s * r.depth_m == Approx(q).epsilon(1e-12));
  CHECK(r.opening_m == Approx(y1 / 0.611));
  CHECK(r.length_m == Approx(r.piston_speed_m_s * end + 2 * r.depth_m));
  CHECK(r.piston_x_m == Approx(-t - r.length_m));
  CHECK(geo.x_min_m == r.piston_x_m);
  CHECK(geo.z_max_m >= 1.5 * r.depth_m);
  CHECK(geo.max_water_height_m >= r.depth_m);
  REQUIRE(geo.moving_walls.size() == 1);
  CHECK(geo.moving_walls[0].velocity_m_s.x() == r.piston_speed_m_s);
  CHECK(geo.moving_walls[0].end_s == end);
  bool sluice = false, inlet = false;
  for (const auto& w : geo.walls) {
    sluice = sluice || w.name == "sluice_gate";
    inlet = inlet || w.name == "inlet_gate";
  }
  CHECK(sluice);
  CHECK_FALSE(inlet);
  CHECK(geo.initial_water.surface_at(r.piston_x_m + 0.01) == Approx(r.depth_m));
  CHECK(geo.initial_water.surface_at(0.1) == Approx(y1));
  // A reservoir too short for the run, an opening above the level.
  CaseGeometry g2 = make_geometry(a, s.fluid);
  CHECK_THROWS_WITH(add_piston_reservoir(g2, *a.stilling_basin(), 0.0, 1.0, end, t, g), Catch::Contains("too short"));
  CHECK_THROWS_WITH(add_piston_reservoir(g2, *a.stilling_basin(), 0.5, 0.0, end, t, g), Catch::Contains("not below the reservoir level"));
}
