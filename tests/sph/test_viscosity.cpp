// Artificial viscosity against the walls (sph.artificial_viscosity_wall_factor): still-water tank
// (cases/still_water.toml, dx = 0.02 m) whose fluid slides uniformly at 0.5 m/s over the DBC floor.
// With a uniform velocity the fluid-fluid artificial viscosity vanishes (v_ij = 0), so the horizontal
// acceleration of the bottom row in the middle of the tank is the wall's viscous drag alone: zero with
// the wall factor 0 (up to the pressure terms, which cancel on the symmetric lattice), a deceleration
// with the factor 1.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sph/boundary_mdbc.hpp"
#include "sph/cell_list.hpp"
#include "sph/interactions.hpp"
#include "sph/time_integration.hpp"
#include "sph/wall_function.hpp"
#include "sph_test_support.hpp"

using namespace hydrojump;

namespace {

// Sets every fluid particle sliding at `speed` (m/s) and sorts the particles into `cells`.
void slide_and_sort(sph::ParticleSet& ps, sph::CellList& cells, const sph::SolverSettings& settings,
                    double speed = 0.5) {
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i)) ps.u[i] = speed;
  cells.build(ps.x, ps.z, sph::CellGrid::enclosing(ps.x, ps.z, settings.support()));
  ps.permute(cells.order());
  cells.mark_sorted();
}

// Mean horizontal acceleration of the fluid particles of the bottom row with 0.3 < x < 0.7 m.
double bottom_row_drag(double wall_factor) {
  const double dx = 0.02;
  auto c = sph_test::load_case("still_water.toml", dx, [&](cases::Case& k) {
    k.sph.viscosity = hydrojump::cases::Viscosity::artificial;
    k.sph.artificial_viscosity_alpha = 0.1;
    k.sph.artificial_viscosity_wall_factor = wall_factor;
    k.sph.boundary = hydrojump::cases::BoundaryMethod::dbc;
  });
  sph::ParticleSet ps = c.particles;
  sph::CellList cells;
  slide_and_sort(ps, cells, c.settings);
  sph::compute_pressure(ps, c.settings);
  sph::compute_interactions(ps, cells, c.settings);
  double sum = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && ps.z[i] < c.geometry.bed.elevation(ps.x[i]) + dx && ps.x[i] > 0.3 && ps.x[i] < 0.7) {
      sum += ps.ax[i];
      ++n;
    }
  REQUIRE(n > 0);
  return sum / n;
}

}  // namespace

TEST_CASE("the artificial viscosity's wall factor scales the drag of the walls", "[sph][viscosity]") {
  const double free_slip = bottom_row_drag(0.0);
  const double no_slip = bottom_row_drag(1.0);
  INFO("bottom-row a_x: factor 0: " << free_slip << " m/s^2, factor 1: " << no_slip << " m/s^2");
  CHECK(std::abs(free_slip) < 1e-6);
  CHECK(no_slip < -0.1);
  // Linear in the factor: half the factor, half the drag.
  CHECK(bottom_row_drag(0.5) == Approx(0.5 * no_slip).epsilon(1e-9));
}

TEST_CASE("a viscosity given as nu sets alpha = 8 nu / (h c0) at each resolution", "[sph][viscosity]") {
  const double nu = 2.0e-3;
  for (const double dx : {0.02, 0.01}) {
    auto c = sph_test::load_case("still_water.toml", dx, [&](cases::Case& k) {
      k.sph.viscosity = hydrojump::cases::Viscosity::artificial;
      k.sph.artificial_viscosity_nu_m2_s = nu;
    });
    INFO("dx " << dx << ": h " << c.settings.h << " m, c0 " << c.settings.eos.c0 << " m/s");
    // nu = alpha h c0 / 8 back from the alpha the solver uses
    CHECK(c.settings.viscosity.artificial_alpha * c.settings.h * c.settings.eos.c0 / 8.0 == Approx(nu).epsilon(1e-12));
  }
  // A nu that would need alpha > 1 is refused, naming the key and the largest allowed nu.
  try {
    sph_test::load_case("still_water.toml", 0.02, [&](cases::Case& k) { k.sph.artificial_viscosity_nu_m2_s = 1.0; });
    FAIL("nu = 1 m^2/s was accepted");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Contains("sph.artificial_viscosity_nu_m2_s = 1"));
    CHECK_THAT(e.what(), Catch::Contains("nu <= h c0 / 8"));
  }
}

// The SPS stress of a simple shear u = gamma z: S_xz = gamma/2, |S| = gamma, nu_t = l^2 gamma,
// tau_xz/rho = 2 nu_t S_xz = l^2 gamma^2, tau_xx/rho = tau_zz/rho = -2/3 C_I dx^2 gamma^2 (S_kk = 0).
TEST_CASE("SPS stress of a simple shear: Smagorinsky's length C_s dx or a mixing length", "[sph][viscosity]") {
  const double gamma = 12.0, dx = 0.005, blin = 0.0066;
  for (const double length : {0.12 * dx, 0.015}) {
    const auto t = hydrojump::sph::sps_stress(0.0, 0.0, gamma, length, blin, dx);
    CHECK(t.xz == Approx(length * length * gamma * gamma).epsilon(1e-12));
    CHECK(t.xx == Approx(-2.0 / 3.0 * blin * dx * dx * gamma * gamma).epsilon(1e-12));
    CHECK(t.zz == Approx(t.xx).epsilon(1e-12));
    CHECK(t.eddy_viscosity == Approx(length * length * gamma).epsilon(1e-12));
  }
}

// The SPS stress diffuses momentum with nu0 + nu_t, so the explicit step must keep
// dt <= 0.125 h^2 / (nu0 + max nu_t) (Morris, Fox & Zhu 1997), not only 0.125 h^2 / nu0.
TEST_CASE("with SPS the time step is bounded by 0.125 h^2 / (nu0 + max nu_t)", "[sph][viscosity]") {
  auto c = sph_test::load_case("still_water.toml", 0.02, [](cases::Case& k) {
    k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
    k.sph.sps_mixing_length_m = 0.05;
    k.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
  });
  const sph::SolverSettings& s = c.settings;
  const double acoustic = s.time.cfl * s.h / s.eos.c0;  // no acceleration, no approaching pair
  // nu_t = 0: the molecular bound 0.125 h^2 / 1e-6 is far above the acoustic step.
  CHECK(sph::variable_time_step({0.0, 0.0, 0.0}, s) == Approx(acoustic).epsilon(1e-12));
  // A large eddy viscosity binds: 0.125 h^2 / (nu0 + nu_t).
  const double nu_t = 1.0;
  const double diffusive = 0.125 * s.h * s.h / (s.viscosity.kinematic_viscosity + nu_t);
  REQUIRE(diffusive < acoustic);
  CHECK(sph::variable_time_step({0.0, 0.0, nu_t}, s) == Approx(diffusive).epsilon(1e-12));
  // Not with the artificial viscosity, which has no eddy viscosity.
  auto a = sph_test::load_case("still_water.toml", 0.02, [](cases::Case& k) { k.sph.viscosity = hydrojump::cases::Viscosity::artificial; });
  CHECK(sph::variable_time_step({0.0, 0.0, 0.0}, a.settings) ==
        Approx(a.settings.time.cfl * a.settings.h / a.settings.eos.c0).epsilon(1e-12));
}

// The interactions report the largest eddy viscosity of the stress they computed: in a simple shear
// u = gamma (z - z_bed) away from the walls and the free surface, nu_t = l_m^2 gamma.
TEST_CASE("the interactions report the SPS stress's largest eddy viscosity, l_m^2 gamma in a simple shear",
          "[sph][viscosity]") {
  const double gamma = 2.0, lm = 0.03;
  auto c = sph_test::load_case("still_water.toml", 0.02, [&](cases::Case& k) {
    k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
    k.sph.sps_mixing_length_m = lm;
    k.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
  });
  sph::ParticleSet ps = c.particles;
  sph::CellList cells;
  slide_and_sort(ps, cells, c.settings, 0.0);
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i)) ps.u[i] = gamma * (ps.z[i] - c.geometry.bed.elevation(ps.x[i]));
  sph::mdbc_boundary_density(ps, cells, c.settings);
  sph::compute_pressure(ps, c.settings);
  const sph::InteractionSummary summary = sph::compute_interactions(ps, cells, c.settings);
  INFO("max nu_t " << summary.max_eddy_viscosity << " m^2/s, l_m^2 gamma " << lm * lm * gamma);
  // Interior particles see the shear exactly on the lattice; rows near the surface or a wall see less
  // (a truncated kernel, a shorter mixing length): the maximum is the interior's.
  CHECK(summary.max_eddy_viscosity == Approx(lm * lm * gamma).epsilon(0.05));
}

TEST_CASE("the SPS length is C_s dx, or the mixing length at every resolution", "[sph][viscosity]") {
  for (const double dx : {0.02, 0.01}) {
    const auto smagorinsky = sph_test::load_case("still_water.toml", dx, [](cases::Case& k) {
      k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
      k.sph.sps_smagorinsky_constant = 0.12;
    });
    CHECK(smagorinsky.settings.viscosity.sps_length == Approx(0.12 * dx).epsilon(1e-12));
    const auto mixing = sph_test::load_case("still_water.toml", dx, [](cases::Case& k) {
      k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
      k.sph.sps_mixing_length_m = 0.015;
    });
    CHECK(mixing.settings.viscosity.sps_length == Approx(0.015).epsilon(1e-12));
  }
}

// Prandtl near a wall: l = min(l_m, 0.41 d), d measured from the wall line dx/2 in front of the
// nearest wall particle's centre; no wall in reach: l_m.
TEST_CASE("the mixing length vanishes at a wall as kappa d and is l_m away from it", "[sph][viscosity]") {
  using hydrojump::sph::mixing_length_near_wall;
  const double dx = 0.005, lm = 0.015;
  CHECK(mixing_length_near_wall(lm, 0.5 * dx, dx) == 0.0);                             // on the wall line
  CHECK(mixing_length_near_wall(lm, 0.2 * dx, dx) == 0.0);                             // never negative
  CHECK(mixing_length_near_wall(lm, 0.5 * dx + 0.01, dx) == Approx(0.41 * 0.01).epsilon(1e-12));
  CHECK(mixing_length_near_wall(lm, 0.5 * dx + 0.05, dx) == lm);                       // 0.41 * 0.05 > l_m
  CHECK(mixing_length_near_wall(lm, std::numeric_limits<double>::infinity(), dx) == lm);
}

namespace {

// laminar_sps with a mixing length over an mDBC floor, the fluid sliding uniformly at 0.5 m/s: the
// mean horizontal acceleration of the four bottom rows (0.3 < x < 0.7 m) after two interactions (the
// first makes the SPS stress the second uses), with the given wall condition.
double bottom_row_sps_drag(const std::string& wall_condition) {
  const double dx = 0.02;
  auto c = sph_test::load_case("still_water.toml", dx, [&](cases::Case& k) {
    k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
    k.sph.sps_mixing_length_m = 0.05;
    k.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
    k.sph.viscous_wall_condition = hydrojump::cases::option_from_name<hydrojump::cases::ViscousWallCondition>("test", wall_condition);
  });
  REQUIRE(c.settings.viscosity.viscous_walls_free_slip == (wall_condition == "free_slip"));
  sph::ParticleSet ps = c.particles;
  sph::CellList cells;
  slide_and_sort(ps, cells, c.settings);
  for (int pass = 0; pass < 2; ++pass) {
    sph::mdbc_boundary_density(ps, cells, c.settings);
    sph::compute_pressure(ps, c.settings);
    sph::compute_interactions(ps, cells, c.settings);
  }
  // The stress of the first row is passed on to the second by the pair sums, so the wall's drag shows
  // in the sum over the bottom rows, not in the first row alone.
  double sum = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && ps.z[i] < c.geometry.bed.elevation(ps.x[i]) + 4.0 * dx && ps.x[i] > 0.3 && ps.x[i] < 0.7) {
      sum += ps.ax[i];
      ++n;
    }
  REQUIRE(n > 0);
  return sum / n;
}

}  // namespace

// sph.viscous_wall_condition: with no slip the floor brakes a uniform flow through the laminar and
// SPS terms; with free slip (mDBC's slip velocity) it does not (the pressure terms cancel on the
// symmetric lattice, as in the artificial-viscosity test above).
TEST_CASE("free-slip walls take no viscous drag from a uniform flow, no-slip walls do (laminar_sps, mDBC)",
          "[sph][viscosity]") {
  const double no_slip = bottom_row_sps_drag("no_slip");
  const double free_slip = bottom_row_sps_drag("free_slip");
  INFO("bottom-row a_x: no slip " << no_slip << " m/s^2, free slip " << free_slip << " m/s^2");
  // No slip at dx 0.02 m: the first row's wall gradient (~9 1/s) and l = 0.41 dx/2 give a wall stress of
  // ~1e-3 m^2/s^2, ~0.02 m/s^2 over four rows; free slip: none (round-off).
  CHECK(no_slip < -0.005);
  CHECK(std::abs(free_slip) < 1e-6 * std::abs(no_slip));
}

// The log law's friction velocity: in the log layer u_t / u_tau = ln(E y+) / kappa, in the viscous
// sublayer u_t / u_tau = y+; the two meet at y+ = 11.53 (the law is continuous there).
TEST_CASE("the wall function's friction velocity solves the log law, or the sublayer's law near the wall",
          "[sph][viscosity][wall_function]") {
  using hydrojump::sph::friction_velocity;
  const double nu = 1e-6;
  int log_layer = 0, sublayer = 0;
  for (const double u_t : {0.001, 0.05, 0.5, 3.0}) {
    for (const double d : {0.001, 0.0025, 0.01}) {
      const double u_tau = friction_velocity(u_t, d, nu);
      const double y_plus = d * u_tau / nu;
      INFO("u_t " << u_t << " m/s, d " << d << " m: u_tau " << u_tau << " m/s, y+ " << y_plus);
      if (y_plus >= 11.53)
        CHECK(u_t / u_tau == Approx(std::log(9.8 * y_plus) / 0.41).epsilon(1e-10));
      else
        CHECK(u_t / u_tau == Approx(y_plus).epsilon(1e-12));
      ++(y_plus >= 11.53 ? log_layer : sublayer);
    }
  }
  CHECK(log_layer >= 6);  // both laws were exercised
  CHECK(sublayer >= 2);
  // Continuity at the sublayer's edge: just below and just above y+ = 11.53 give nearly the same u_tau.
  // In the sublayer u_t/u_tau = y+ = d u_tau/nu, so y+ = sqrt(u_t d/nu): the edge at u_t = 0.2 m/s
  // lies at d = 11.53^2 nu/u_t (6.6e-4 m for water).
  const double d_edge = 11.53 * 11.53 * nu / 0.2;
  const double below = friction_velocity(0.2, d_edge * (1.0 - 1e-6), nu);
  const double above = friction_velocity(0.2, d_edge * (1.0 + 1e-6), nu);
  // The two points lie on either side of the edge: the sublayer's law below, the log law above.
  const double y_plus_below = d_edge * (1.0 - 1e-6) * below / nu;
  const double y_plus_above = d_edge * (1.0 + 1e-6) * above / nu;
  CHECK(0.2 / below == Approx(y_plus_below).epsilon(1e-12));
  CHECK(0.2 / above == Approx(std::log(9.8 * y_plus_above) / 0.41).epsilon(1e-10));
  CHECK(0.2 / above != Approx(y_plus_above).epsilon(1e-7));  // not the sublayer's law (the two differ by 1e-5 here)
  CHECK(above == Approx(below).epsilon(1e-4));
  CHECK(friction_velocity(0.0, 0.01, nu) == 0.0);
}

namespace {

// laminar_sps with the wall function over an mDBC floor, the fluid sliding uniformly at `speed`: the
// horizontal acceleration of each fluid particle with 0.3 < x < 0.7 m, by row above the floor.
std::vector<double> row_accelerations_with_wall_function(double speed, double dx, int rows) {
  auto c = sph_test::load_case("still_water.toml", dx, [&](cases::Case& k) {
    k.sph.viscosity = hydrojump::cases::Viscosity::laminar_sps;
    k.sph.sps_mixing_length_m = 0.05;
    k.sph.boundary = hydrojump::cases::BoundaryMethod::mdbc;
    k.sph.viscous_wall_condition = hydrojump::cases::ViscousWallCondition::wall_function;
  });
  REQUIRE(c.settings.viscosity.viscous_walls_free_slip);
  REQUIRE(c.settings.viscosity.wall_function_shear);
  sph::ParticleSet ps = c.particles;
  sph::CellList cells;
  slide_and_sort(ps, cells, c.settings, speed);
  sph::mdbc_boundary_density(ps, cells, c.settings);
  sph::compute_pressure(ps, c.settings);
  sph::compute_interactions(ps, cells, c.settings);
  std::vector<double> sum(static_cast<std::size_t>(rows), 0.0);
  std::vector<int> count(static_cast<std::size_t>(rows), 0);
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    if (!ps.is_fluid(i) || ps.x[i] < 0.3 || ps.x[i] > 0.7) continue;
    const int row = static_cast<int>(std::floor((ps.z[i] - c.geometry.bed.elevation(ps.x[i])) / dx));
    if (row < 0 || row >= rows) continue;
    sum[static_cast<std::size_t>(row)] += ps.ax[i];
    ++count[static_cast<std::size_t>(row)];
  }
  for (int r = 0; r < rows; ++r) {
    REQUIRE(count[static_cast<std::size_t>(r)] > 0);
    sum[static_cast<std::size_t>(r)] /= count[static_cast<std::size_t>(r)];
  }
  return sum;
}

}  // namespace

// A uniform flow over a flat floor: the first row (at d = dx/2 above the wall surface) takes the log
// law's stress, a = -u_tau^2 / dx against the flow; the rows above take none (free slip in the
// viscous terms, pressure terms cancel on the symmetric lattice).
TEST_CASE("the wall function brakes the first fluid row by the log law's wall shear, and no other row",
          "[sph][viscosity][wall_function]") {
  const double dx = 0.02, nu = 1e-6;
  for (const double speed : {0.5, -1.5}) {
    const std::vector<double> a = row_accelerations_with_wall_function(speed, dx, 4);
    const double u_tau = hydrojump::sph::friction_velocity(std::abs(speed), 0.5 * dx, nu);
    INFO("speed " << speed << " m/s: rows a_x " << a[0] << ", " << a[1] << ", " << a[2] << ", " << a[3]
                  << " m/s^2; log law -sign(u) u_tau^2/dx = " << -std::copysign(u_tau * u_tau / dx, speed));
    CHECK(a[0] == Approx(-std::copysign(u_tau * u_tau / dx, speed)).epsilon(1e-6));
    for (int r = 1; r < 4; ++r) CHECK(std::abs(a[static_cast<std::size_t>(r)]) < 1e-6 * std::abs(a[0]));
  }
}
