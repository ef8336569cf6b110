// The outflow level control (sph/outflow_level_control.hpp): the integral law against its closed
// form on a still lattice, its limits, its coupling to the outflow buffers, and the settings that
// select it.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "cases/geometry.hpp"
#include "sph/open_boundaries.hpp"
#include "sph/outflow_level_control.hpp"
#include "sph/settings.hpp"
#include "sph_test_support.hpp"

using namespace hydrojump;
using namespace hydrojump::sph;

namespace {

// Still water `rows` dx deep on a flat bed, columns from x0 to x0 + columns dx.
ParticleSet still_lattice(double dx, double x0, int columns, int rows) {
  ParticleSet p;
  p.resize(static_cast<Eigen::Index>(columns) * rows);
  Eigen::Index i = 0;
  std::int64_t id = 0;
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < rows; ++r, ++i)
      p.assign(i, ParticleType::fluid, x0 + (c + 0.5) * dx, (r + 0.5) * dx, 1000.0, 1000.0 * dx * dx, id++);
  return p;
}

const cases::Case& case_named(const cases::Study& study, const std::string& id) {
  for (const auto& c : study.cases)
    if (c.id == id) return c;
  FAIL("no case " << id);
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("the level control integrates the section's depth error at its control instants", "[sph][open_boundary][level_control]") {
  // A lattice 12 dx = 0.12 m deep around the section x = 0.5 m; target y2 = 0.10 m, T_c = 1 s. The
  // hat column of width 2 dx over a lattice reads its depth exactly (basin_monitor.hpp), so after n
  // control instants y_t = y2 - n (dt_c / T_c) (0.12 - 0.10) exactly (up to rounding).
  const double dx = 0.01, y2 = 0.10, time_constant = 1.0;
  const ParticleSet p = still_lattice(dx, 0.3, 40, 12);
  const OutflowLevelControl control(0.5, y2, time_constant, 2.0 * dx);
  double y_t = y2;
  int updates = 0;
  const double dt = 7e-4;  // steps not commensurate with dt_c = 0.01 s
  const int steps = 150;   // t from 0 to 0.105 s: instants 0.01 ... 0.10 s
  double t = 0.0;  // advanced as the solver's clock: t_next = t + dt
  for (int s = 0; s < steps; ++s, t += dt) {
    if (const auto next = control.update(p, t, dt, y_t)) {
      y_t = *next;
      ++updates;
    }
  }
  CHECK(updates == 10);
  const double expected = y2 - updates * OutflowLevelControl::control_interval_s / time_constant * (0.12 - y2);
  CHECK(y_t == Approx(expected).epsilon(1e-9));
  CHECK(y_t < y2);  // a section deeper than y2 lowers the outlet
  // A shallower section raises it; the outlet stays within [0.5, 1.5] y2 however large the error.
  CHECK(control.next_outlet_depth(y2, 0.08) == Approx(y2 + 0.01 * 0.02));
  CHECK(control.next_outlet_depth(1.49 * y2, 0.0) == Approx(1.5 * y2));
  CHECK(control.next_outlet_depth(0.51 * y2, 10.0) == Approx(0.5 * y2));
  CHECK_THROWS_WITH(OutflowLevelControl(0.5, y2, 0.0, 2.0 * dx), Catch::Contains("integral time"));
}

TEST_CASE("the level-controlled outlet drains at the characteristic state of its moved target depth", "[sph][open_boundary][level_control]") {
  // Geometry: outflow at x = 1 m with y2 = 0.10 m; the section at x = 0.5 m sits in still water
  // 0.12 m deep. After the open boundaries have moved the target to y_t, the absorbing buffer moves
  // at the characteristic outlet's u_B for the strip upstream of the outlet (depth h, at rest).
  const double dx = 0.01, y2 = 0.10, q = 0.05, g = 9.81;
  cases::CaseGeometry geometry;
  geometry.bed = cases::BedProfile::flat(0.0);
  geometry.inflows.push_back({0.0, 0.0254, q / 0.0254});
  geometry.outflows.push_back({1.0, y2});
  BufferParameters params;
  params.dx = dx;
  params.support = 2.0 * std::sqrt(2.0) * dx;
  params.eos = TaitEquationOfState(1000.0, 40.0);
  params.gravity = g;
  params.outflow = OutflowCondition::absorbing;
  params.level_at_section = true;
  params.level_section_x = 0.5;
  params.level_time = 0.5;
  OpenBoundaries open = OpenBoundaries::from_geometry(geometry, params);
  REQUIRE(open.outflow_target_depth() == Approx(y2));
  ParticleSet p = still_lattice(dx, 0.3, 70, 12);  // x from 0.3 to 1.0 m, 0.12 m deep
  // One step across the instant 0.01 s: y_t = y2 - (0.01 / 0.5) (0.12 - 0.10).
  open.advance(p, 0.0095, 0.001);
  const double y_t = y2 - 0.01 / 0.5 * (0.12 - y2);
  CHECK(open.outflow_target_depth() == Approx(y_t).epsilon(1e-9));
  // No instant in (0.0105, 0.0115]: unchanged.
  open.advance(p, 0.0105, 0.001);
  CHECK(open.outflow_target_depth() == Approx(y_t).epsilon(1e-9));
  // Fluid put past the outlet joins the buffer at the new target's velocity.
  const Eigen::Index n = p.size();
  p.resize(n + 12);
  for (int r = 0; r < 12; ++r) p.assign(n + r, ParticleType::fluid, 1.0 + 0.5 * dx, (r + 0.5) * dx, 1000.0, 0.1, 10000 + r);
  open.advance(p, 0.0115, 1e-4);
  const double h = 0.12;  // the strip upstream of the outlet, at rest
  // u_B = (R+ + R-) / 2, R+ = 0 + 2 sqrt(g h), R- = q / y_t - 2 sqrt(g y_t)
  const double expected = 0.5 * (2.0 * std::sqrt(g * h) + q / y_t - 2.0 * std::sqrt(g * y_t));
  int buffer = 0;
  for (Eigen::Index k = 0; k < p.size(); ++k)
    if (p.type[k] == static_cast<std::uint8_t>(ParticleType::outflow)) {
      ++buffer;
      CHECK(p.u[k] == Approx(expected).epsilon(1e-9));
    }
  CHECK(buffer == 12);
  // A resumed run restores the target (Solver: from SolverClock::outflow_target_depth).
  OpenBoundaries fresh = OpenBoundaries::from_geometry(geometry, params);
  fresh.set_outflow_target_depth(y_t);
  CHECK(fresh.outflow_target_depth() == Approx(y_t).epsilon(1e-12));
}

TEST_CASE("the level control is set from the spec, at the downstream section, and refused where it cannot work", "[sph][level_control][options]") {
  cases::Study study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  cases::Case a = case_named(study, "A");
  a.sph.outflow_level_reference = hydrojump::cases::OutflowLevelReference::downstream_section;  // a level held at the measuring section
  a.sph.outflow_level_time_s = 3.0;
  const auto geometry = solver_geometry(a, study.fluid, 0.005);
  const SolverSettings s = make_settings(a, study.fluid, geometry, 0.005);
  CHECK(s.open.level_at_section);
  CHECK(s.open.level_time == 3.0);
  double x_down = -1.0;
  for (const auto& sec : geometry.sections)
    if (sec.role == hydrojump::cases::SectionRole::downstream) x_down = sec.x_m;
  CHECK(s.open.level_section_x == x_down);
  CHECK(buffer_parameters(s).level_at_section);
  // The default holds the tailwater at the outlet (run B of the study file sets no level control).
  const cases::Case plain = case_named(study, "B");
  CHECK_FALSE(make_settings(plain, study.fluid, solver_geometry(plain, study.fluid, 0.005), 0.005).open.level_at_section);
  // A dam break has no outflow and no downstream section.
  cases::Study dam = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/dam_break.toml");
  cases::Case* dam_break = nullptr;
  for (auto& c : dam.cases)
    if (c.kind == "dam_break") dam_break = &c;
  REQUIRE(dam_break != nullptr);
  dam_break->sph.outflow_level_reference = hydrojump::cases::OutflowLevelReference::downstream_section;
  const auto dam_geometry = solver_geometry(*dam_break, dam.fluid, 0.01);
  CHECK_THROWS_WITH(make_settings(*dam_break, dam.fluid, dam_geometry, 0.01),
                    Catch::Contains("sph.outflow_level_reference = \"downstream_section\" needs an outflow buffer") &&
                        Catch::Contains("no outflow"));
}
