// The piston inflow (sph/piston_inflow.hpp, cases::add_piston_reservoir): a reservoir behind a sluice
// gate pushed by a piston, the set-up of the corrugated-bed SPH study. Case A_smooth on a shortened
// basin (0.1 + 0.3 + 0.1 m), a run of 0.6 s (so a short reservoir), dx = 5 mm, simulated to 0.4 s.
// Checks: the generated reservoir, gate and piston; the piston advancing U_p t; no water lost or
// created (reservoir + basin + outflow buffer + what left over the outlet); the water entering the
// basin under the gate; and the contraction of the jet implied by its rate over 0.2-0.4 s,
//   q_gate = Cc a sqrt(2 g (H - Cc a))      (Torricelli below a sluice gate, H the reservoir level),
// which must lie between the sharp-edged gate's 0.611 (less contraction is possible, more is not)
// and 1 (no contraction): 0.55 < Cc < 1.0. Measured: Cc = 0.86 at dx = 5 mm (an opening of 8 particle
// spacings contracts less than the laboratory's), so the default opening y1/0.611 passes ~30 % more
// than q at first (0.067 vs 0.0508 m^2/s over 0.2-0.4 s), until the reservoir level has dropped.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>
#include <set>
#include <string>

#include "sph/run.hpp"
#include "sph_test_support.hpp"

using namespace hydrojump;

namespace {

sph_test::LoadedCase piston_basin() {
  return sph_test::short_smooth_basin(0.005, [](cases::Case& c) {
    c.run.end_time_s = 0.6;
    c.sph.inflow_condition = "piston";
  });
}

// Fluid and outflow-buffer particles (the outlet has not removed those yet).
double water_mass(const sph::ParticleSet& ps) {
  double m = 0.0;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) || ps.type[i] == static_cast<std::uint8_t>(sph::ParticleType::outflow)) m += ps.mass[i];
  return m;
}

// The reservoir level: the highest fluid particle over the middle of the reservoir, plus dx/2.
double reservoir_level(const sph::ParticleSet& ps, double x0, double x1, double dx) {
  double top = 0.0;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && ps.x[i] > x0 && ps.x[i] < x1) top = std::max(top, ps.z[i]);
  return top + 0.5 * dx;
}

// Cc from q = Cc a sqrt(2 g (H - Cc a)) by bisection on (0, 1] (q grows with Cc there while Cc a < 2H/3).
double contraction(double q, double a, double h, double g) {
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mid * a * std::sqrt(2.0 * g * (h - mid * a)) < q ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("piston inflow: reservoir, gate and piston are generated", "[sph][piston]") {
  const auto c = piston_basin();
  CHECK(c.settings.inflow == sph::InflowCondition::piston);
  const auto open = sph::OpenBoundaries::from_geometry(c.geometry, sph::buffer_parameters(c.settings));
  CHECK(open.inflows().empty());  // no buffer
  int piston = 0, inflow = 0, reservoir_water = 0;
  const double x_p = c.geometry.moving_walls.front().face.points.front().x();
  for (Eigen::Index i = 0; i < c.particles.size(); ++i) {
    const auto t = static_cast<sph::ParticleType>(c.particles.type[i]);
    if (t == sph::ParticleType::moving_wall) {
      ++piston;
      CHECK(c.particles.x[i] < x_p);  // the plate behind the piston's face
      CHECK(c.particles.ghost_dx[i] > 0.0);
    }
    if (t == sph::ParticleType::inflow) ++inflow;
    if (t == sph::ParticleType::fluid && c.particles.x[i] < -0.05) ++reservoir_water;
  }
  CHECK(piston > 0);
  CHECK(inflow == 0);
  CHECK(reservoir_water > 1000);
  CHECK(c.settings.x_min == Approx(x_p));
  // The sluice gate is a solid plate: every lattice column across its thickness holds boundary
  // particles (an odd layer count once left the middle column out: its two faces' normals cancel).
  const cases::WallPolyline* gate = nullptr;
  for (const auto& w : c.geometry.walls)
    if (w.name == "sluice_gate") gate = &w;
  REQUIRE(gate != nullptr);
  const double thickness = -gate->points[2].x(), opening = gate->points[1].y(), dx = c.settings.dx;
  std::set<long> columns;
  for (Eigen::Index i = 0; i < c.particles.size(); ++i)
    if (c.particles.type[i] == static_cast<std::uint8_t>(sph::ParticleType::boundary) && c.particles.x[i] < 0.0 &&
        c.particles.x[i] > -thickness && c.particles.z[i] > opening + 3.0 * dx)
      columns.insert(std::lround(c.particles.x[i] / dx - 0.5));
  CHECK(static_cast<double>(columns.size()) == Approx(thickness / dx));
}

TEST_CASE("piston inflow: an opening of fewer than 5 particle spacings is refused", "[sph][piston]") {
  auto study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml");
  REQUIRE(study.find_case("A_smooth") != nullptr);
  cases::Case c = *study.find_case("A_smooth");
  c.sph.inflow_condition = "piston";
  c.sph.sluice_opening_m = 0.012;  // 2.4 dx at dx = 5 mm
  CHECK_THROWS_WITH(sph::solver_geometry(c, study.fluid, 0.005),
                    Catch::Contains("sph.sluice_opening_m") && Catch::Contains("5 particle spacings"));
  c.sph.sluice_opening_m = 0.03;   // 6 dx
  CHECK_NOTHROW(sph::solver_geometry(c, study.fluid, 0.005));
}

TEST_CASE("piston inflow: a short run pushes water under the gate, contracting as a jet does", "[sph][piston]") {
  auto c = piston_basin();
  const double q = 0.0254 * 2.0, rho0 = c.settings.eos.rho0;
  const double u_p = c.geometry.moving_walls.front().velocity_m_s.x();
  double x_plate0 = 1e9;
  for (Eigen::Index i = 0; i < c.particles.size(); ++i)
    if (c.particles.type[i] == static_cast<std::uint8_t>(sph::ParticleType::moving_wall))
      x_plate0 = std::min(x_plate0, c.particles.x[i]);
  sph::Solver solver(c.settings, c.particles, {}, sph::OpenBoundaries::from_geometry(c.geometry, sph::buffer_parameters(c.settings)));
  const double m0 = water_mass(solver.particles());
  const double x_p = c.geometry.moving_walls.front().face.points.front().x();
  std::string problem;
  double in_at_020 = -1.0;
  while (solver.time() < 0.4 && problem.empty()) {
    solver.step();
    problem = sph::diagnose(solver);
    if (in_at_020 < 0.0 && solver.time() >= 0.2) in_at_020 = solver.clock().inflow_mass;
  }
  INFO(problem);
  REQUIRE(problem.empty());
  const auto& ps = solver.particles();
  double x_plate = 1e9;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.type[i] == static_cast<std::uint8_t>(sph::ParticleType::moving_wall)) x_plate = std::min(x_plate, ps.x[i]);
  CHECK(x_plate - x_plate0 == Approx(u_p * solver.time()).epsilon(1e-9));
  // Nothing created: the water now in the domain plus what left over the outlet is the initial water.
  const double m1 = water_mass(ps);
  CHECK(std::abs(m1 + solver.clock().outflow_mass - m0) <= 1e-9 * m0);
  const double q_gate = (solver.clock().inflow_mass - in_at_020) / rho0 / (solver.time() - 0.2);
  double opening = 0.0;
  for (const auto& wall : c.geometry.walls)
    if (wall.name == "sluice_gate") opening = wall.points[1].y();
  const double level = reservoir_level(ps, x_p + 0.2 * (0.0 - x_p) + u_p * solver.time(), 0.5 * x_p, c.settings.dx);
  const double cc = contraction(q_gate, opening, level, 9.81);
  std::cout << "piston inflow A_smooth (short): U_p " << u_p << " m/s, t = " << solver.time()
            << " s, water under the gate " << solver.clock().inflow_mass << " kg/m, q over 0.2-0.4 s " << q_gate
            << " m^2/s (q = " << q << "), reservoir level " << level << " m, opening " << opening << " m: Cc = " << cc << "\n";
  CHECK(solver.clock().inflow_mass > 0.0);
  CHECK(cc > 0.55);
  CHECK(cc < 1.0);
}
