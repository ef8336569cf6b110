// Still water (issue 3, verification case 3; cases/still_water.toml): a tank 1 m long with water
// H = 0.5 m deep at rest. After 2 s: max |v| < 1 % of sqrt(g H), the bottom pressure within 3 % of
// rho g H with mDBC (the spec's boundary), and the free surface within one particle spacing of its
// initial level. The same checks run with DBC.
//
// Bottom pressure: a least-squares line p(z) through the fluid particles of the central half of the
// tank (0.25 m < x < 0.75 m), evaluated at the bed z = 0. Free surface: in every column of width dx,
// the highest fluid particle plus dx/2.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>

#include "sph_test_support.hpp"

namespace {

struct StillWaterResult {
  double max_speed = 0.0, bottom_pressure = 0.0, max_surface_error = 0.0, rho_g_h = 0.0, sqrt_gh = 0.0;
  double dx = 0.0;
};

StillWaterResult run_still_water(double dx, const std::string& boundary, double end_time,
                                 const std::string& shifting = "none") {
  auto loaded = sph_test::load_case("still_water.toml", dx, [&](hydrojump::cases::Case& c) {
    c.sph.boundary = hydrojump::cases::option_from_name<hydrojump::cases::BoundaryMethod>("test", boundary);
    c.sph.particle_shifting = hydrojump::cases::option_from_name<hydrojump::cases::ParticleShifting>("test", shifting);
  });
  const double depth = loaded.spec.still_water()->water_depth_m;
  const double g = loaded.study.fluid.gravity_m_s2;
  hydrojump::sph::Solver solver(loaded.settings, loaded.particles);
  while (solver.time() < end_time) solver.step();
  solver.update_pressure();
  const auto& ps = solver.particles();
  StillWaterResult r;
  r.dx = dx;
  r.max_speed = sph_test::max_fluid_speed(ps);
  r.rho_g_h = loaded.study.fluid.density_kg_m3 * g * depth;
  r.sqrt_gh = std::sqrt(g * depth);
  // Least-squares line p = a + b z over the central fluid particles.
  double n = 0, sz = 0, szz = 0, sp = 0, szp = 0;
  std::map<long, double> top;  // column -> highest particle
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    if (!ps.is_fluid(i)) continue;
    const long col = std::lround(std::floor(ps.x[i] / dx));
    top[col] = std::max(top.count(col) ? top[col] : -1e9, ps.z[i] + 0.5 * dx);
    if (ps.x[i] < 0.25 || ps.x[i] > 0.75) continue;
    n += 1;
    sz += ps.z[i];
    szz += ps.z[i] * ps.z[i];
    sp += ps.p[i];
    szp += ps.z[i] * ps.p[i];
  }
  const double slope = (n * szp - sz * sp) / (n * szz - sz * sz);
  r.bottom_pressure = (sp - slope * sz) / n;
  for (const auto& [col, z] : top) r.max_surface_error = std::max(r.max_surface_error, std::abs(z - depth));
  std::cout << "still water dx = " << dx << " (" << boundary << ", shifting " << shifting << "), t = " << solver.time() << " s: max |v| = " << r.max_speed
            << " m/s = " << 100.0 * r.max_speed / r.sqrt_gh << " % of sqrt(gH); bottom pressure " << r.bottom_pressure
            << " Pa = " << 100.0 * (r.bottom_pressure / r.rho_g_h - 1.0) << " % off rho g H; surface error "
            << r.max_surface_error / dx << " dx\n";
  return r;
}

}  // namespace

TEST_CASE("still water stays at rest with hydrostatic pressure (dx 0.02 m)", "[sph][still_water][long]") {
  for (const std::string boundary : {"mdbc", "dbc"}) {
    INFO(boundary);
    const StillWaterResult r = run_still_water(0.02, boundary, 2.0);
    CHECK(r.max_speed < 0.01 * r.sqrt_gh);
    CHECK(std::abs(r.bottom_pressure / r.rho_g_h - 1.0) < 0.03);
    CHECK(r.max_surface_error < r.dx);
  }
}

// Particle shifting (sph/particle_shifting.hpp) must not stir water at rest: its displacement scales
// with |v|, and the free surface is not shifted, so the same limits hold.
TEST_CASE("still water stays at rest with particle shifting (mDBC dx 0.02 m)", "[sph][still_water][shifting][long]") {
  const StillWaterResult r = run_still_water(0.02, "mdbc", 2.0, "fickian");
  CHECK(r.max_speed < 0.01 * r.sqrt_gh);
  CHECK(std::abs(r.bottom_pressure / r.rho_g_h - 1.0) < 0.03);
  CHECK(r.max_surface_error < r.dx);
}

TEST_CASE("still water stays at rest with hydrostatic pressure (mDBC dx 0.01 m)", "[sph][still_water][slow]") {
  const StillWaterResult r = run_still_water(0.01, "mdbc", 2.0);
  CHECK(r.max_speed < 0.01 * r.sqrt_gh);
  CHECK(std::abs(r.bottom_pressure / r.rho_g_h - 1.0) < 0.03);
  CHECK(r.max_surface_error < r.dx);
}
