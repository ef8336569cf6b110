// The one geometry source: walls, initial water and boundaries derived from a case.
#include <catch2/catch.hpp>

#include "cases/geometry.hpp"
#include "cases/spec_reader.hpp"

using namespace hydrojump::cases;

TEST_CASE("Stilling-basin geometry of run A", "[cases][geometry]") {
  const Study s = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml");
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
