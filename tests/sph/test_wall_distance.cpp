// The fixed walls' distance table (sph/wall_distance.hpp) against a brute-force oracle, and the
// mixing length it gives (sph.sps_wall_distance = "whole_domain") against Prandtl's l = min(l_m,
// kappa d) in a simple shear over a floor, where "kernel_support" gives l_m beyond the kernel support.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sph/boundary_mdbc.hpp"
#include "sph/cell_list.hpp"
#include "sph/interactions.hpp"
#include "sph/wall_distance.hpp"
#include "sph_test_support.hpp"

using namespace hydrojump;

namespace {

// min over fixed wall particles of |p - x_b| (with images one period away), capped at `reach`.
double brute_force_distance(const sph::ParticleSet& ps, double x, double z, double reach, double period = 0.0) {
  double best = reach;
  for (Eigen::Index b = 0; b < ps.size(); ++b) {
    if (ps.type[b] != static_cast<std::uint8_t>(sph::ParticleType::boundary)) continue;
    for (const double shift : {0.0, -period, period})
      best = std::min(best, std::hypot(x - ps.x[b] - shift, z - ps.z[b]));
  }
  return best;
}

// A sinusoidal bed of fixed wall particles in two layers, a vertical end wall, a moving gate and a few
// fluid particles (the table ignores the last two).
sph::ParticleSet mixed_walls() {
  std::vector<std::tuple<sph::ParticleType, double, double>> parts;
  for (int k = 0; k < 200; ++k) {
    const double x = 0.01 * k;
    for (int layer = 0; layer < 2; ++layer)
      parts.emplace_back(sph::ParticleType::boundary, x, -0.011 * (1.0 - std::cos(2.0 * M_PI * x / 0.068)) - 0.01 * layer);
  }
  for (int k = 0; k < 30; ++k) parts.emplace_back(sph::ParticleType::boundary, 2.0, 0.01 * k);
  for (int k = 0; k < 10; ++k) parts.emplace_back(sph::ParticleType::moving_wall, 0.5, 0.1 + 0.01 * k);
  for (int k = 0; k < 10; ++k) parts.emplace_back(sph::ParticleType::fluid, 1.0, 0.05 + 0.01 * k);
  sph::ParticleSet ps;
  ps.resize(static_cast<Eigen::Index>(parts.size()));
  for (std::size_t i = 0; i < parts.size(); ++i)
    ps.assign(static_cast<Eigen::Index>(i), std::get<0>(parts[i]), std::get<1>(parts[i]), std::get<2>(parts[i]), 1000.0, 0.1, static_cast<std::int64_t>(i));
  return ps;
}

}  // namespace

TEST_CASE("wall distance table: within spacing/sqrt(2) of the brute-force distance to the fixed walls, capped at the reach",
          "[sph][wall_distance]") {
  const sph::ParticleSet ps = mixed_walls();
  const double reach = 0.08, spacing = 0.005;
  const auto table = sph::WallDistanceTable::tabulate(ps, reach, spacing);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> ux(-0.2, 2.3), uz(-0.2, 0.5);
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double x = ux(gen), z = uz(gen);
    const double exact = brute_force_distance(ps, x, z, reach);
    const double err = std::abs(table.at(x, z) - exact);
    worst = std::max(worst, err);
    REQUIRE(err <= spacing / std::sqrt(2.0) + 1e-12);
  }
  INFO("worst error " << worst << " m");
  CHECK(worst > 0.0);  // the oracle and the table are different computations
  // At a node the table is exact; the moving gate and the fluid are not walls of the table.
  CHECK(table.at(0.5, 0.15) == Approx(brute_force_distance(ps, 0.5, 0.15, reach)).margin(spacing / std::sqrt(2.0)));
  CHECK(table.at(0.5, 0.15) == Approx(reach));
  // Far from every wall, and outside the table: the reach.
  CHECK(table.at(1.0, 0.4) == reach);
  CHECK(table.at(-5.0, 0.0) == reach);
  CHECK(table.at(0.0, std::numeric_limits<double>::quiet_NaN()) == reach);
}

TEST_CASE("wall distance table: a periodic channel sees the walls across the period, and bad arguments are refused",
          "[sph][wall_distance]") {
  // Two walls of a periodic channel of period 1 m: floor z = 0 at 0.005 <= x < 0.5 only, so that the
  // nearest wall of a point near x = 1 is the image of the floor's start.
  sph::ParticleSet ps;
  ps.resize(50);
  for (int k = 0; k < 50; ++k) ps.assign(k, sph::ParticleType::boundary, 0.005 + 0.01 * k, 0.0, 1000.0, 0.1, k);
  const double reach = 0.1, spacing = 0.004;
  const auto table = sph::WallDistanceTable::tabulate(ps, reach, spacing, true, 0.0, 1.0);
  for (const double x : {0.97, 0.99, 1.0, 1.02, -0.03, 2.99}) {
    for (const double z : {0.01, 0.03, 0.06}) {
      INFO("x = " << x << ", z = " << z);
      const double x_in = x - std::floor(x);
      CHECK(table.at(x, z) == Approx(brute_force_distance(ps, x_in, z, reach, 1.0)).margin(spacing / std::sqrt(2.0)));
    }
  }
  CHECK(table.at(0.99, 0.01) < 0.03);  // the image of the wall start at x = 1.005
  CHECK_THROWS_AS(sph::WallDistanceTable::tabulate(ps, 0.0, spacing), std::invalid_argument);
  CHECK_THROWS_AS(sph::WallDistanceTable::tabulate(ps, reach, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(sph::WallDistanceTable::tabulate(ps, reach, 1e-7), std::invalid_argument);  // 1e12 nodes
  // No fixed wall at all: every point is at least the reach from one.
  sph::ParticleSet fluid_only;
  fluid_only.resize(1);
  fluid_only.assign(0, sph::ParticleType::fluid, 0.0, 0.0, 1000.0, 0.1, 0);
  CHECK(sph::WallDistanceTable::tabulate(fluid_only, reach, spacing).at(0.0, 0.0) == reach);
}

namespace {

// The mixing length l = sqrt(tau_xz) / S that the SPS stress of a simple shear u = S (z - z_bed)
// implies (tau_xz = nu_t du/dz = l^2 S^2), for each fluid particle of the still-water tank (dx 0.02
// m, mDBC floor) with 0.35 < x < 0.65 m and 0.02 < z < 0.3 m, beside the brute-force distance to the
// nearest fixed wall particle.
struct ShearSample {
  double d, length;
};
std::vector<ShearSample> mixing_lengths_in_shear(const std::string& wall_distance) {
  const double dx = 0.02, lm = 0.05, S = 1.0;
  auto c = sph_test::load_case("still_water.toml", dx, [&](cases::Case& k) {
    k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
    k.sph.sps_mixing_length_m = lm;
    k.sph.sps_wall_distance = hydrojump::cases::option_from_name<hydrojump::cases::SpsWallDistance>("test", wall_distance);
    k.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
  });
  REQUIRE(c.settings.viscosity.sps_wall_distance_table == (wall_distance == "whole_domain"));
  sph::ParticleSet ps = c.particles;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i)) ps.u[i] = S * (ps.z[i] - c.geometry.bed.elevation(ps.x[i]));
  // As the solver makes it: from the particles at the start, reach l_m / kappa + dx, nodes at dx/2.
  const auto table = sph::WallDistanceTable::tabulate(ps, sph::mixing_length_wall_reach(lm, dx), 0.5 * dx);
  sph::CellList cells;
  cells.build(ps.x, ps.z, sph::CellGrid::enclosing(ps.x, ps.z, c.settings.support()));
  ps.permute(cells.order());
  cells.mark_sorted();
  sph::mdbc_boundary_density(ps, cells, c.settings);
  sph::compute_pressure(ps, c.settings);
  sph::compute_interactions(ps, cells, c.settings, c.settings.viscosity.sps_wall_distance_table ? &table : nullptr);
  std::vector<ShearSample> out;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && ps.x[i] > 0.35 && ps.x[i] < 0.65 && ps.z[i] > 0.02 && ps.z[i] < 0.3)
      out.push_back({brute_force_distance(ps, ps.x[i], ps.z[i], 1.0), std::sqrt(std::max(0.0, ps.tau_xz[i])) / S});
  REQUIRE(out.size() > 20);
  return out;
}

}  // namespace

TEST_CASE("sps_wall_distance: whole_domain gives Prandtl's l = min(l_m, kappa d) beyond the kernel support, kernel_support gives l_m there",
          "[sph][viscosity][wall_distance]") {
  const double dx = 0.02, lm = 0.05, kappa = 0.41;
  const double support = 2.0 * std::sqrt(2.0) * dx;  // 2h at coef_h = 1
  int beyond_support_below_lm = 0;
  for (const auto& sample : mixing_lengths_in_shear("whole_domain")) {
    const double prandtl = std::min(lm, kappa * (sample.d - 0.5 * dx));
    INFO("d = " << sample.d << " m: l = " << sample.length << ", Prandtl " << prandtl);
    // 2 %: the SPH velocity gradient of a linear field on the lattice (kernel sums), and the table's
    // interpolation (spacing dx/2) for the particles beyond the support; 5 % within it, where the
    // wall particles' (mDBC) velocities enter the gradient (the same there with either rule).
    CHECK(sample.length == Approx(prandtl).epsilon(sample.d < support ? 0.05 : 0.02).margin(1e-4));
    if (sample.d > support && prandtl < 0.9 * lm) ++beyond_support_below_lm;
  }
  CHECK(beyond_support_below_lm >= 4);  // the rows the old rule gave l_m
  for (const auto& sample : mixing_lengths_in_shear("kernel_support")) {
    INFO("d = " << sample.d << " m: l = " << sample.length);
    const double expected = sample.d < support ? std::min(lm, kappa * (sample.d - 0.5 * dx)) : lm;
    CHECK(sample.length == Approx(expected).epsilon(sample.d < support ? 0.05 : 0.02).margin(1e-4));
  }
}
