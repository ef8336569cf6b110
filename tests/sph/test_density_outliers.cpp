// Density outliers (sph/density_outliers.hpp): fluid particles whose density left [0.7, 1.3] rho0 are
// removed by the step and counted (DualSPHysics' RhopOut); a run that loses more than 1 % of its water
// this way stops with a diagnosis; the count survives a checkpoint.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "sph/checkpoint.hpp"
#include "sph/density_outliers.hpp"
#include "sph/open_boundaries.hpp"
#include "sph/piston_inflow.hpp"
#include "sph/run.hpp"
#include "sph_test_support.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump::sph;

namespace {

// Indices of the first `count` fluid particles.
std::vector<Eigen::Index> fluid_indices(const ParticleSet& ps, std::size_t count) {
  std::vector<Eigen::Index> out;
  for (Eigen::Index i = 0; i < ps.size() && out.size() < count; ++i)
    if (ps.is_fluid(i)) out.push_back(i);
  return out;
}

bool has_id(const ParticleSet& ps, std::int64_t id) {
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.id[i] == id) return true;
  return false;
}

}  // namespace

TEST_CASE("fluid particles whose density left [0.7, 1.3] rho0 are removed and counted, the rest kept in order",
          "[sph][density_outliers]") {
  auto loaded = sph_test::load_case("dam_break.toml", 0.05);
  ParticleSet ps = loaded.particles;
  const double rho0 = loaded.settings.eos.rho0;
  const auto f = fluid_indices(ps, 5);
  REQUIRE(f.size() == 5);
  Eigen::Index wall = 0;
  while (ps.is_fluid(wall)) ++wall;
  ps.rho[f[0]] = 0.69 * rho0;  // outlier, low
  ps.rho[f[1]] = 1.31 * rho0;  // outlier, high
  ps.rho[f[2]] = 0.71 * rho0;  // inside the range: kept (the run's own limit judges it)
  ps.rho[f[3]] = 1.29 * rho0;  // inside
  ps.rho[f[4]] = std::numeric_limits<double>::quiet_NaN();  // left to the run's check (non-finite)
  ps.rho[wall] = 0.5 * rho0;   // walls are never removed
  const std::int64_t gone_a = ps.id[f[0]], gone_b = ps.id[f[1]];
  const double mass = ps.mass[f[0]] + ps.mass[f[1]];
  std::vector<std::int64_t> kept_ids;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.id[i] != gone_a && ps.id[i] != gone_b) kept_ids.push_back(ps.id[i]);

  const double x_a = ps.x[f[0]], x_b = ps.x[f[1]];
  const DensityOutliers out = remove_density_outliers(ps, loaded.settings);
  CHECK(out.particles == 2);
  CHECK(out.mass == Approx(mass).epsilon(1e-15));
  CHECK(out.x_m == std::vector<double>{x_a, x_b});
  REQUIRE(ps.size() == static_cast<Eigen::Index>(kept_ids.size()));
  for (Eigen::Index i = 0; i < ps.size(); ++i) CHECK(ps.id[i] == kept_ids[static_cast<std::size_t>(i)]);
  CHECK_FALSE(has_id(ps, gone_a));
  CHECK_FALSE(has_id(ps, gone_b));
  // Nothing left to remove.
  CHECK(remove_density_outliers(ps, loaded.settings).particles == 0);
}

TEST_CASE("a density outlier that is also non-finite, below the bed or out of the domain is left to the run's check",
          "[sph][density_outliers][robustness]") {
  // A particle squeezed through a wall gains density fast: that is a failure to name, not spray to drop.
  auto loaded = sph_test::load_case("dam_break.toml", 0.05, [](hydrojump::cases::Case& c) { c.sph.max_density_variation = 0.5; });
  const auto& s = loaded.settings;
  const double rho0 = s.eos.rho0;
  for (int variant = 0; variant < 4; ++variant) {
    INFO(variant);
    ParticleSet ps = loaded.particles;
    const Eigen::Index k = fluid_indices(ps, 1).front();
    ps.rho[k] = 1.5 * rho0;
    if (variant == 0) ps.rho[k] = std::numeric_limits<double>::infinity();
    if (variant == 1) ps.u[k] = std::numeric_limits<double>::quiet_NaN();
    if (variant == 2) ps.z[k] = s.domain.z_min - 2.0 * s.domain.margin;
    if (variant == 3) ps.x[k] = s.domain.x_max + 2.0 * s.domain.margin;
    const std::int64_t id = ps.id[k];
    CHECK(remove_density_outliers(ps, s).particles == 0);
    CHECK(has_id(ps, id));
    CHECK_FALSE(diagnose(Solver(s, ps)).empty());
  }
}

TEST_CASE("an outlier removed upstream of a piston's gate section is not counted as inflow", "[sph][density_outliers][piston]") {
  GateCrossing gate(1.0);
  ParticleSet ps;
  ps.resize(3);
  ps.type.setConstant(static_cast<std::uint8_t>(ParticleType::fluid));
  ps.x << 0.5, 0.6, 1.5;
  ps.mass << 2.0, 3.0, 4.0;
  gate.start(ps);
  // The particle at 0.6 (upstream) is removed; the one at 0.5 crosses to 1.1.
  std::vector<char> remove{0, 1, 0};
  remove_particles(ps, remove);
  ps.x[0] = 1.1;
  gate.forget_removed(0.6, 3.0);
  CHECK(gate.advance(ps) == 2.0);
  // Removed downstream of the section: nothing to forget (it is not upstream water).
  gate.forget_removed(1.1, 2.0);
  remove_particles(ps, std::vector<char>{1, 0});
  CHECK(gate.advance(ps) == 0.0);
  CHECK(gate.mass_in() == 2.0);
}

TEST_CASE("a step removes a density outlier and the run goes on with it counted", "[sph][density_outliers]") {
  for (const char* integrator : {"verlet", "symplectic"}) {
    INFO(integrator);
    auto loaded = sph_test::load_case("dam_break.toml", 0.05, [&](hydrojump::cases::Case& c) {
      c.sph.time_integrator = hydrojump::cases::option_from_name<hydrojump::cases::TimeIntegrator>("test", integrator);
      c.sph.max_density_variation = 0.5;
    });
    ParticleSet ps = loaded.particles;
    const double rho0 = loaded.settings.eos.rho0;
    const Eigen::Index k = fluid_indices(ps, 1).front();
    ps.rho[k] = ps.rho_old[k] = 0.5 * rho0;  // no single step brings it back into [0.7, 1.3] rho0
    const std::int64_t id = ps.id[k];
    const double mass = ps.mass[k], water = ps.water_mass();
    Solver solver(loaded.settings, ps);
    solver.step();
    CHECK_FALSE(has_id(solver.particles(), id));
    CHECK(solver.clock().outlier_particles == 1);
    CHECK(solver.clock().outlier_mass == mass);
    CHECK(solver.particles().water_mass() == Approx(water - mass).epsilon(1e-12));
    CHECK(diagnose(solver).empty());
    solver.step();  // the neighbour list is rebuilt for the smaller set
    CHECK(diagnose(solver).empty());
    CHECK(solver.clock().outlier_particles == 1);
  }
}

TEST_CASE("a run that lost more than 1 % of its water as density outliers stops with a diagnosis",
          "[sph][density_outliers][robustness]") {
  auto loaded = sph_test::load_case("dam_break.toml", 0.05);
  const double water = loaded.particles.water_mass();
  SolverClock clock;
  clock.outlier_particles = 3;
  clock.outlier_mass = 0.009 * water;
  CHECK(diagnose(Solver(loaded.settings, loaded.particles, clock)).empty());
  clock.outlier_mass = 0.011 * water;
  CHECK_THAT(diagnose(Solver(loaded.settings, loaded.particles, clock)),
             Catch::Contains("3 fluid particles") && Catch::Contains("density left [0.7, 1.3] rho0") &&
                 Catch::Contains("more than 1 % of the water"));
}

TEST_CASE("a checkpoint keeps the count of removed density outliers and refuses an impossible one",
          "[sph][density_outliers][restart]") {
  auto loaded = sph_test::load_case("dam_break.toml", 0.05);
  Checkpoint c;
  c.fingerprint = "test";
  c.particles = loaded.particles;
  c.clock.outlier_particles = 7;
  c.clock.outlier_mass = 0.125;
  const hydrojump::testing::TempDir tmp("outlier_checkpoint");
  const auto file = tmp.path() / "checkpoint.bin";
  write_checkpoint(c, file);
  const Checkpoint back = read_checkpoint(file);
  CHECK(back.clock.outlier_particles == 7);
  CHECK(back.clock.outlier_mass == 0.125);
  c.clock.outlier_mass = -0.1;
  write_checkpoint(c, file);
  CHECK_THROWS_WITH(read_checkpoint(file), Catch::Contains("its count of removed density outliers"));
  c.clock.outlier_mass = 0.0;
  c.clock.outlier_particles = -1;
  write_checkpoint(c, file);
  CHECK_THROWS_WITH(read_checkpoint(file), Catch::Contains("is damaged"));
}
