// Prescribed wall motion (sph/wall_motion.hpp) and the lifted dam-break gate: the exact displacement
// of a piecewise-constant motion across its interval's ends, the wall-normal velocity the fluid
// sees, the gate plate of the generator, and a short run in which the gate rises at its speed while
// the water escapes only under it.
#include <catch2/catch.hpp>

#include <cmath>

#include "sph/run.hpp"
#include "sph/wall_motion.hpp"
#include "sph_test_support.hpp"

using namespace hydrojump;

namespace {

sph_test::LoadedCase lifted_dam_break(double dx, double speed) {
  return sph_test::load_case("dam_break.toml", dx, [&](cases::Case& c) {
    auto& d = std::get<cases::DamBreakCase>(c.data);
    d.gate = hydrojump::cases::GateOpening::lifted;
    d.gate_lift_speed_m_s = speed;
  });
}

}  // namespace

TEST_CASE("wall motion: exact displacement over its interval, wall-normal velocity", "[sph][wall_motion]") {
  const sph::WallMotion m{0.0, 2.0, 0.1, 0.5};
  CHECK(m.any());
  CHECK(m.moving_time(0.0, 0.05) == 0.0);
  CHECK(m.moving_time(0.0, 0.2) == Approx(0.1));
  CHECK(m.moving_time(0.2, 0.3) == Approx(0.1));
  CHECK(m.moving_time(0.45, 0.7) == Approx(0.05));
  CHECK(m.moving_time(0.6, 0.7) == 0.0);
  CHECK_FALSE(sph::WallMotion{}.any());

  sph::ParticleSet p;
  p.resize(3);
  p.assign(0, sph::ParticleType::moving_wall, 1.0, 0.5, 1000.0, 1.0, 0);  // a gate: normal along -x
  p.ghost_dx[0] = -0.02;
  p.assign(1, sph::ParticleType::moving_wall, 2.0, 0.5, 1000.0, 1.0, 1);  // a plate facing up
  p.ghost_dz[1] = 0.02;
  p.assign(2, sph::ParticleType::boundary, 3.0, 0.5, 1000.0, 1.0, 2);     // a fixed wall
  // Steps across the start and the end: the sum of the pieces is v (end - start).
  double t = 0.0;
  for (const double dt : {0.07, 0.07, 0.2, 0.2, 0.2}) {
    sph::move_walls(p, m, t, t + dt);
    t += dt;
  }
  CHECK(p.z[0] == Approx(0.5 + 2.0 * 0.4).epsilon(1e-12));
  CHECK(p.z[1] == Approx(0.5 + 2.0 * 0.4).epsilon(1e-12));
  CHECK(p.x[0] == 1.0);
  CHECK(p.z[2] == 0.5);
  // Inside the interval: the gate slides (no normal velocity), the plate facing up moves the fluid.
  sph::move_walls(p, sph::WallMotion{0.0, 2.0, 0.0, 10.0}, 0.0, 0.01);
  CHECK(p.u[0] == 0.0);
  CHECK(p.w[0] == 0.0);
  CHECK(p.u[1] == 0.0);
  CHECK(p.w[1] == Approx(2.0));
  CHECK(p.w[2] == 0.0);
  // The viscous terms' no-slip velocity (used as is with DBC; mDBC mirrors it) is the wall's too.
  CHECK(p.wall_w[1] == Approx(2.0));
  CHECK(p.wall_u[0] == 0.0);
  CHECK(p.wall_w[2] == 0.0);
}

TEST_CASE("lifted dam-break gate: a plate of moving wall particles behind the column", "[sph][wall_motion]") {
  const double dx = 0.04, speed = 5.0;
  const auto c = lifted_dam_break(dx, speed);
  const double L = c.spec.dam_break()->column_width_m, H = c.spec.dam_break()->column_height_m;
  REQUIRE(c.geometry.moving_walls.size() == 1);
  CHECK(c.settings.wall_motion.w_m_s == speed);
  CHECK(c.settings.wall_motion.end_s == Approx(1.05 * H / speed));
  int gate = 0;
  for (Eigen::Index i = 0; i < c.particles.size(); ++i) {
    if (c.particles.type[i] != static_cast<std::uint8_t>(sph::ParticleType::moving_wall)) continue;
    ++gate;
    CHECK(c.particles.x[i] > L);
    CHECK(c.particles.x[i] < L + 3 * dx + 1e-9);
    CHECK(c.particles.z[i] > 0.0);
    CHECK(c.particles.z[i] < 1.05 * H);
    CHECK(c.particles.ghost_dx[i] == Approx(2.0 * (L - c.particles.x[i])));
  }
  // 3 layers (ceil(2h/dx) = ceil(2.83)) of the rows centred at (k + 1/2) dx below 1.05 H.
  int rows = 0;
  while ((rows + 0.5) * dx < 1.05 * H) ++rows;
  CHECK(gate == 3 * rows);
  // The instant gate has none.
  const auto instant = sph_test::load_case("dam_break.toml", dx);
  for (Eigen::Index i = 0; i < instant.particles.size(); ++i)
    CHECK(instant.particles.type[i] != static_cast<std::uint8_t>(sph::ParticleType::moving_wall));
}

TEST_CASE("lifted dam-break gate: rises at its speed, the water leaves only under it", "[sph][wall_motion]") {
  const double dx = 0.04, speed = 2.0;
  auto c = lifted_dam_break(dx, speed);
  const double L = c.spec.dam_break()->column_width_m;
  sph::Solver solver(c.settings, c.particles);
  double lowest0 = 1e9;
  for (Eigen::Index i = 0; i < c.particles.size(); ++i)
    if (c.particles.type[i] == static_cast<std::uint8_t>(sph::ParticleType::moving_wall))
      lowest0 = std::min(lowest0, c.particles.z[i]);
  std::string problem;
  while (solver.time() < 0.15 && problem.empty()) {
    solver.step();
    problem = sph::diagnose(solver);
    const auto& ps = solver.particles();
    double lowest = 1e9;
    for (Eigen::Index i = 0; i < ps.size(); ++i)
      if (ps.type[i] == static_cast<std::uint8_t>(sph::ParticleType::moving_wall)) lowest = std::min(lowest, ps.z[i]);
    REQUIRE(lowest == Approx(lowest0 + speed * solver.time()).epsilon(1e-9));
    // Past the gate's face, water only below its lower edge (the gap), up to a particle spacing.
    for (Eigen::Index i = 0; i < ps.size(); ++i)
      if (ps.is_fluid(i) && ps.x[i] > L + 0.5 * dx) REQUIRE(ps.z[i] < lowest + dx);
  }
  INFO(problem);
  CHECK(problem.empty());
  int escaped = 0;
  for (Eigen::Index i = 0; i < solver.particles().size(); ++i)
    if (solver.particles().is_fluid(i) && solver.particles().x[i] > L + 4 * dx) ++escaped;
  CHECK(escaped > 0);  // the surge has started under the gate
}
