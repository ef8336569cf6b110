// The symmetric pair loop (sph/interactions.cpp) against a brute-force oracle: every particle summed
// over every other particle, each sum written out here from the equations (sph/pair_terms.hpp's
// header) without the loop's cells, half stencil, colour phases or pair symmetry. Fluid, fixed and
// moving wall, inflow- and outflow-buffer particles mixed, with the study's SPH model (laminar + SPS
// with the near-wall mixing length, Fourtakas diffusion, mDBC with free-slip walls), the dam-break
// benchmark's (artificial viscosity, DBC) and the other combinations of boundary, viscosity and
// diffusion; a set large enough for the loops' threads; a periodic seam; and a Verlet list (the
// solver's neighbour search) built before the particles moved up to half its skin.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include "sph/boundary_mdbc.hpp"
#include "sph/cell_list.hpp"
#include "sph/interactions.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/open_boundaries.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace sph = hydrojump::sph;

namespace {

constexpr double kDx = 0.01;

struct Layout {
  int columns = 14, rows = 12;  // the fluid block
  bool periodic = false;        // the fluid block and the walls under it only, x in [0, columns dx)
};

// A jittered block of fluid, an inflow buffer's two columns to its left and an outflow buffer's to its
// right, three wall rows under all of them (every fifth a moving wall), with random velocities,
// densities, SPS stresses and wall velocities.
sph::ParticleSet mixed_particles(unsigned seed, const Layout& l) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2 * kDx, 0.2 * kDx), vel(-0.5, 0.5), dens(995.0, 1010.0), stress(-1e-3, 1e-3);
  struct Spot {
    sph::ParticleType type;
    double x, z;
  };
  std::vector<Spot> spots;
  for (int i = 0; i < l.columns; ++i)
    for (int k = 0; k < l.rows; ++k) spots.push_back({sph::ParticleType::fluid, (i + 0.5) * kDx + jitter(rng), (k + 0.5) * kDx + jitter(rng)});
  const int buffer_columns = l.periodic ? 0 : 2;
  for (int i = 1; i <= buffer_columns; ++i)
    for (int k = 0; k < l.rows; ++k) {
      spots.push_back({sph::ParticleType::inflow, (0.5 - i) * kDx, (k + 0.5) * kDx});
      spots.push_back({sph::ParticleType::outflow, (l.columns - 0.5 + i) * kDx, (k + 0.5) * kDx});
    }
  for (int i = -buffer_columns; i < l.columns + buffer_columns; ++i)
    for (int k = 1; k <= 3; ++k)
      spots.push_back({i % 5 == 0 ? sph::ParticleType::moving_wall : sph::ParticleType::boundary, (i + 0.5) * kDx, (0.5 - k) * kDx});
  sph::ParticleSet ps;
  ps.resize(static_cast<Eigen::Index>(spots.size()));
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    const Spot& s = spots[static_cast<std::size_t>(i)];
    ps.assign(i, s.type, s.x, s.z, dens(rng), 1000.0 * kDx * kDx, i);
    ps.u[i] = vel(rng), ps.w[i] = vel(rng);
    ps.tau_xx[i] = stress(rng), ps.tau_xz[i] = stress(rng), ps.tau_zz[i] = stress(rng);
    ps.wall_u[i] = vel(rng), ps.wall_w[i] = vel(rng);
  }
  return ps;
}

sph::SolverSettings model(sph::BoundaryMethod boundary, sph::Viscosity viscosity, sph::DensityDiffusion diffusion) {
  sph::SolverSettings s;
  s.dx = kDx;
  s.h = sph::smoothing_length(1.0, kDx);
  s.eos = sph::TaitEquationOfState(1000.0, 20.0);
  s.domain = {-0.1, 1.0, -0.1, 1.0, 1.0, false, 0.0};
  s.kernel = sph::KernelType::wendland_c2;
  s.boundary = boundary;
  s.viscosity.model = viscosity;
  s.viscosity.artificial_alpha = 0.02;
  s.viscosity.artificial_wall_factor = 0.5;
  s.viscosity.sps_length = 0.003;
  s.density.diffusion = diffusion;
  s.density.diffusion_delta = diffusion == sph::DensityDiffusion::none ? 0.0 : 0.1;
  return s;
}

// The [sph] of cases/ead2002.toml: a mixing length limited near walls, free-slip mDBC walls.
sph::SolverSettings study_model() {
  sph::SolverSettings s = model(sph::BoundaryMethod::mdbc, sph::Viscosity::laminar_sps, sph::DensityDiffusion::fourtakas);
  s.viscosity.sps_length_near_walls = true;
  s.viscosity.viscous_walls_free_slip = true;
  return s;
}

struct Oracle {
  std::vector<double> drho, ax, az, tau_xx, tau_xz, tau_zz;
  // The loop's Fourtakas term uses the hydrostatic density's second-order expansion in
  // x = rho0 g dz / B (sph/density_diffusion.hpp): what that leaves out, bounded, per particle.
  std::vector<double> drho_expansion_bound;
  double max_viscous_rate = 0.0, max_acceleration = 0.0;
};

// What a fluid particle gathers over its neighbours.
struct FluidSums {
  double drho = 0.0, drho_bound = 0.0, ax = 0.0, az = 0.0;
  double dudx = 0.0, dwdz = 0.0, shear = 0.0;  // strain rate (laminar_sps)
  double nearest_wall_r2 = std::numeric_limits<double>::infinity();
  double max_viscous_rate = 0.0;
};

// Fluid particle I and neighbour J (fluid, buffer or wall) at r = r_I - r_J, grad_I W = f r.
void add_fluid_pair(const sph::ParticleSet& ps, const sph::SolverSettings& s, Eigen::Index I, Eigen::Index J, double rx, double rz,
                    double f, FluidSums& sum) {
  const bool wall_j = sph::is_wall_type(ps.type[J]), sps = s.viscosity.model == sph::Viscosity::laminar_sps;
  const double r2 = rx * rx + rz * rz, eta2 = 0.01 * s.h * s.h, rho0 = s.eos.rho0;
  const double gx = f * rx, gz = f * rz;
  const double du = ps.u[I] - ps.u[J], dw = ps.w[I] - ps.w[J];
  const double vj = ps.mass[J] / ps.rho[J], rho_sum = ps.rho[I] + ps.rho[J];
  if (wall_j) sum.nearest_wall_r2 = std::min(sum.nearest_wall_r2, r2);
  sum.drho += ps.mass[J] * (du * gx + dw * gz);  // continuity
  if (!wall_j && s.density.diffusion_delta > 0.0) {
    double jump = ps.rho[J] - ps.rho[I];
    const double factor = -2.0 * s.density.diffusion_delta * s.h * s.eos.c0 * f * vj;
    if (s.density.diffusion == sph::DensityDiffusion::fourtakas) {  // the hydrostatic part, exactly
      const double x = rho0 * s.body_force_z * (ps.z[J] - ps.z[I]) / s.eos.b;
      jump -= rho0 * (std::pow(1.0 + x, 1.0 / 7.0) - 1.0);
      // The expansion's first left-out term is a(a-1)(a-2)/6 x^3 = 0.038 x^3 (a = 1/7); 0.05 bounds the rest too.
      sum.drho_bound += std::abs(factor) * rho0 * 0.05 * std::abs(x * x * x);
    }
    sum.drho += factor * jump;
  }
  const double v_dot_r = du * rx + dw * rz;
  if (v_dot_r < 0.0) sum.max_viscous_rate = std::max(sum.max_viscous_rate, -s.h * v_dot_r / (r2 + eta2));
  double scale = -vj * (ps.p[I] + ps.p[J]) / ps.rho[I];  // pressure
  if (!sps && v_dot_r < 0.0) {                           // Monaghan's artificial viscosity
    const double pi_ij = -2.0 * s.viscosity.artificial_alpha * s.eos.c0 * s.h * v_dot_r / ((r2 + eta2) * rho_sum);
    scale -= (wall_j ? s.viscosity.artificial_wall_factor : 1.0) * ps.mass[J] * pi_ij;
  }
  sum.ax += scale * gx, sum.az += scale * gz;
  if (!sps) return;
  // Laminar (Lo & Shao) against a wall's mirrored velocity, SPS stress S = tau/rho^2 (tau stored over rho).
  const double uv = wall_j ? ps.u[I] - ps.wall_u[J] : du, wv = wall_j ? ps.w[I] - ps.wall_w[J] : dw;
  const double lam = 4.0 * s.viscosity.kinematic_viscosity * f * r2 / ((r2 + eta2) * rho_sum);
  const double sxx = ps.tau_xx[I] / ps.rho[I] + ps.tau_xx[J] / ps.rho[J];
  const double sxz = ps.tau_xz[I] / ps.rho[I] + ps.tau_xz[J] / ps.rho[J];
  const double szz = ps.tau_zz[I] / ps.rho[I] + ps.tau_zz[J] / ps.rho[J];
  sum.ax += ps.mass[J] * (lam * uv + sxx * gx + sxz * gz);
  sum.az += ps.mass[J] * (lam * wv + sxz * gx + szz * gz);
  // Free-slip walls: the strain rate sees the mirrored velocity; no slip: the wall particle's own.
  const double gu = wall_j && s.viscosity.viscous_walls_free_slip ? uv : du;
  const double gw = wall_j && s.viscosity.viscous_walls_free_slip ? wv : dw;
  sum.dudx -= vj * gu * gx, sum.dwdz -= vj * gw * gz, sum.shear -= vj * (gu * gz + gw * gx);
}

// tau/rho of Dalrymple & Rogers from the strain rate, written out (sph/viscosity.hpp's header).
void sps_stress_by_hand(const FluidSums& sum, double length, const sph::SolverSettings& s, double& xx, double& xz, double& zz) {
  const double sxz = 0.5 * sum.shear;
  const double s2 = 2.0 * (sum.dudx * sum.dudx + sum.dwdz * sum.dwdz + 2.0 * sxz * sxz);
  const double nu_t = length * length * std::sqrt(s2);
  const double iso = -(2.0 / 3.0) * nu_t * (sum.dudx + sum.dwdz) - (2.0 / 3.0) * s.viscosity.blin * s.dx * s.dx * s2;
  xx = 2.0 * nu_t * sum.dudx + iso, xz = 2.0 * nu_t * sxz, zz = 2.0 * nu_t * sum.dwdz + iso;
}

// Every particle i over every other particle j within the support, one by one.
Oracle brute_force(const sph::ParticleSet& ps, const sph::SolverSettings& s) {
  const auto n = static_cast<std::size_t>(ps.size());
  const sph::Kernel kernel = sph::Kernel::make(s.kernel == sph::KernelType::wendland_c2 ? "wendland_c2" : "cubic_spline", s.h);
  const double period = s.domain.x_max - s.domain.x_min;
  Oracle o;
  for (auto* v : {&o.drho, &o.ax, &o.az, &o.tau_xx, &o.tau_xz, &o.tau_zz, &o.drho_expansion_bound}) v->assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto I = static_cast<Eigen::Index>(i);
    const bool fluid_i = ps.is_fluid(I), dbc_wall_i = sph::is_wall_type(ps.type[I]) && s.boundary == sph::BoundaryMethod::dbc;
    if (!fluid_i && !dbc_wall_i) continue;  // buffers and mDBC walls get nothing
    FluidSums sum;
    for (std::size_t j = 0; j < n; ++j) {
      const auto J = static_cast<Eigen::Index>(j);
      double rx = ps.x[I] - ps.x[J];
      if (s.domain.periodic_x) rx -= period * std::round(rx / period);  // the nearest periodic image
      const double rz = ps.z[I] - ps.z[J], r2 = rx * rx + rz * rz;
      if (j == i || r2 >= 4.0 * s.h * s.h) continue;
      const double f = kernel.gradient_factor(std::sqrt(r2));
      if (fluid_i) add_fluid_pair(ps, s, I, J, rx, rz, f, sum);
      else if (!sph::is_wall_type(ps.type[J]))  // DBC wall: D_b = sum m_j (v_b - v_j) . grad_b W_bj over the fluid side
        sum.drho += ps.mass[J] * ((ps.u[I] - ps.u[J]) * f * rx + (ps.w[I] - ps.w[J]) * f * rz);
    }
    o.drho[i] = sum.drho, o.drho_expansion_bound[i] = sum.drho_bound;
    if (!fluid_i) continue;
    o.ax[i] = sum.ax + s.body_force_x, o.az[i] = sum.az + s.body_force_z;
    o.max_acceleration = std::max(o.max_acceleration, std::hypot(o.ax[i], o.az[i]));
    o.max_viscous_rate = std::max(o.max_viscous_rate, sum.max_viscous_rate);
    if (s.viscosity.model == sph::Viscosity::laminar_sps) {
      // Prandtl's l = min(l_m, kappa (d - dx/2)), d to the nearest wall particle's centre within the support.
      double length = s.viscosity.sps_length;
      if (s.viscosity.sps_length_near_walls) length = std::min(length, 0.41 * std::max(0.0, std::sqrt(sum.nearest_wall_r2) - 0.5 * s.dx));
      sps_stress_by_hand(sum, length, s, o.tau_xx[i], o.tau_xz[i], o.tau_zz[i]);
    }
  }
  return o;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// The loop's rates and stresses against the oracle's, each array to 1e-9 of its largest entry (the
// two add the same terms in other orders), the density rates also to what the loop's expansion of
// the Fourtakas hydrostatic part leaves out.
// skin > 0: the loop reads a Verlet list (sph/neighbour_list.hpp) built on cells of support + skin,
// after which every particle moves by up to skin/2 in a random direction (the oracle sees where they
// went; on a periodic domain they stay inside it).
// The particles sorted into cells of `reach` (periodic in x if the domain is), as the solver's search.
sph::CellList sorted_cells(sph::ParticleSet& ps, const sph::SolverSettings& s, double reach) {
  sph::CellList cells;
  cells.build(ps.x, ps.z,
              s.domain.periodic_x ? sph::CellGrid::periodic_x(s.domain.x_min, s.domain.x_max, ps.z, reach)
                                  : sph::CellGrid::enclosing(ps.x, ps.z, reach));
  ps.permute(cells.order());
  cells.mark_sorted();
  return cells;
}

// Every particle moved a random distance up to `most` in a random direction (kept inside a periodic
// domain): what a Verlet list built before must still cover when `most` is half its skin.
void move_particles(sph::ParticleSet& ps, const sph::SolverSettings& s, double most, unsigned seed) {
  if (!(most > 0.0)) return;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::acos(-1.0)), length(0.0, most);
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    const double a = angle(rng), l = length(rng);
    ps.x[i] += l * std::cos(a), ps.z[i] += l * std::sin(a);
    if (s.domain.periodic_x) ps.x[i] = std::clamp(ps.x[i], s.domain.x_min, std::nextafter(s.domain.x_max, 0.0));
  }
}

void check_against_oracle(const sph::SolverSettings& s, unsigned seed, const Layout& layout = {}, double skin = 0.0) {
  sph::ParticleSet ps = mixed_particles(seed, layout);
  const double reach = s.support() + skin;
  const sph::CellList cells = sorted_cells(ps, s, reach);
  sph::NeighbourList list;
  list.build(ps.x, ps.z, ps.type, cells, reach);
  move_particles(ps, s, 0.5 * skin, seed + 100u);
  sph::compute_pressure(ps, s);
  const sph::ParticleSet before = ps;
  const sph::InteractionSummary summary = sph::compute_interactions(ps, list, s);
  const Oracle o = brute_force(before, s);
  const std::vector<double> none(o.drho.size(), 0.0);
  const auto check = [&](const char* name, const Eigen::VectorXd& got, const std::vector<double>& want, const std::vector<double>& bound) {
    const double tol = 1e-9 * std::max(max_abs(want), 1e-30);
    double worst = 0.0;  // the largest difference beyond the particle's bound, over the tolerance
    Eigen::Index at = 0;
    for (Eigen::Index i = 0; i < got.size(); ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double d = std::abs(got[i] - want[k]) / (tol + bound[k]);
      if (d > worst) worst = d, at = i;
    }
    const auto k = static_cast<std::size_t>(at);
    INFO(name << ": particle " << at << " (type " << int(ps.type[at]) << ") " << got[at] << " against " << want[k] << ", allowed "
              << tol << " + " << bound[k]);
    CHECK(worst <= 1.0);
  };
  check("drho", ps.drho, o.drho, o.drho_expansion_bound);
  check("ax", ps.ax, o.ax, none);
  check("az", ps.az, o.az, none);
  if (s.viscosity.model == sph::Viscosity::laminar_sps) {
    check("tau_xx", ps.tau_xx, o.tau_xx, none);
    check("tau_xz", ps.tau_xz, o.tau_xz, none);
    check("tau_zz", ps.tau_zz, o.tau_zz, none);
    CHECK(max_abs(o.tau_xx) > 0.0);
  }
  CHECK(summary.max_viscous_rate == Approx(o.max_viscous_rate).epsilon(1e-12));
  CHECK(summary.max_acceleration == Approx(o.max_acceleration).epsilon(1e-9));
  CHECK(o.max_viscous_rate > 0.0);  // the set has approaching pairs: the check above is not 0 == 0
}

}  // namespace

TEST_CASE("the pair loop equals a brute-force sum over all particles: the study's SPH model", "[sph][interactions]") {
  for (unsigned seed : {1u, 2u, 3u}) check_against_oracle(study_model(), seed);
}

TEST_CASE("the pair loop equals a brute-force sum over all particles: every boundary, viscosity and diffusion",
          "[sph][interactions]") {
  using B = sph::BoundaryMethod;
  using V = sph::Viscosity;
  using D = sph::DensityDiffusion;
  for (B b : {B::dbc, B::mdbc})
    for (V v : {V::artificial, V::laminar_sps})
      for (D d : {D::none, D::molteni, D::fourtakas}) {
        INFO("boundary " << int(b) << ", viscosity " << int(v) << ", diffusion " << int(d));
        sph::SolverSettings s = model(b, v, d);
        s.kernel = d == D::molteni ? sph::KernelType::cubic_spline : sph::KernelType::wendland_c2;
        check_against_oracle(s, 4u);
      }
}

TEST_CASE("the pair loop equals a brute-force sum over all particles: a set large enough for threads", "[sph][interactions]") {
  const Layout large{70, 60, false};
  REQUIRE(sph::use_threads(mixed_particles(5u, large).size()));
  check_against_oracle(study_model(), 5u, large);
}

TEST_CASE("the pair loop equals a brute-force sum over all particles: periodic in x", "[sph][interactions]") {
  // Pairs across the seam: the oracle takes each pair's nearest periodic image.
  sph::SolverSettings s = study_model();
  const Layout layout{14, 12, true};
  s.domain.periodic_x = true;
  s.domain.x_min = 0.0;
  s.domain.x_max = layout.columns * kDx;
  for (unsigned seed : {6u, 7u}) check_against_oracle(s, seed, layout);
}

TEST_CASE("the pair loop on a Verlet list equals the brute-force sum after the particles moved half the skin",
          "[sph][interactions][neighbours]") {
  // A skin of 0.1 support and 0.5 support (the list is used while no particle has moved skin/2).
  sph::SolverSettings s = study_model();
  for (const double skin : {0.1 * s.support(), 0.5 * s.support()}) {
    INFO("skin " << skin << " m");
    for (unsigned seed : {11u, 12u}) check_against_oracle(s, seed, {}, skin);
    check_against_oracle(model(sph::BoundaryMethod::dbc, sph::Viscosity::artificial, sph::DensityDiffusion::fourtakas), 13u, {}, skin);
    sph::SolverSettings p = s;
    const Layout layout{20, 12, true};
    p.domain.periodic_x = true;
    p.domain.x_min = 0.0;
    p.domain.x_max = layout.columns * kDx;
    check_against_oracle(p, 14u, layout, skin);
  }
}

// mDBC's ghost-node neighbours come from a Verlet list built with the pair list: after every particle
// moved up to half the skin, the wall densities and velocities equal those of a search made afresh at
// the new positions (the same sums over the same neighbours, in another order: round-off only).
TEST_CASE("mDBC on a ghost list equals a fresh search after the particles moved half the skin", "[sph][mdbc][neighbours]") {
  const sph::SolverSettings study = study_model();
  for (const bool periodic : {false, true}) {
    sph::SolverSettings s = study;
    const Layout layout{periodic ? 20 : 14, 12, periodic};
    if (periodic) s.domain.periodic_x = true, s.domain.x_min = 0.0, s.domain.x_max = layout.columns * kDx;
    for (const double skin : {0.1 * s.support(), 0.5 * s.support()}) {
      INFO("periodic " << periodic << ", skin " << skin << " m");
      sph::ParticleSet ps = mixed_particles(21u, layout);
      for (Eigen::Index i = 0; i < ps.size(); ++i)
        if (sph::is_wall_type(ps.type[i])) ps.ghost_dz[i] = -2.0 * ps.z[i];  // mirrored through the bed z = 0
      const double reach = s.support() + skin;
      const sph::CellList cells = sorted_cells(ps, s, reach);
      sph::GhostNeighbourList list;
      list.build(ps.x, ps.z, ps, cells, s, reach);
      move_particles(ps, s, 0.5 * skin, 121u);
      sph::ParticleSet fresh = ps;
      sph::mdbc_boundary_density(ps, list, s);
      const sph::CellList fresh_cells = sorted_cells(fresh, s, s.support());
      sph::mdbc_boundary_density(fresh, fresh_cells, s);
      std::vector<Eigen::Index> at(static_cast<std::size_t>(ps.size()));
      for (Eigen::Index k = 0; k < fresh.size(); ++k) at[static_cast<std::size_t>(fresh.id[k])] = k;
      int walls_above_rho0 = 0;
      for (Eigen::Index i = 0; i < ps.size(); ++i) {
        if (!sph::is_wall_type(ps.type[i])) continue;
        const Eigen::Index k = at[static_cast<std::size_t>(ps.id[i])];
        INFO("wall particle " << ps.id[i]);
        CHECK(ps.rho[i] == Approx(fresh.rho[k]).epsilon(1e-12));
        CHECK(ps.wall_u[i] == Approx(fresh.wall_u[k]).epsilon(1e-9).margin(1e-12));
        CHECK(ps.wall_w[i] == Approx(fresh.wall_w[k]).epsilon(1e-9).margin(1e-12));
        walls_above_rho0 += ps.rho[i] > s.eos.rho0 ? 1 : 0;
      }
      CHECK(walls_above_rho0 > 10);  // the ghost nodes found fluid, not just the floor rho0
    }
  }
}

// Water leaving through an outflow buffer is retired (type retired, mass 0, at rest) and stays on the
// neighbour lists until the next search drops it (sph/particles.hpp). Every pair term carries m_j or
// V_j, so the fluid's rates, SPS stresses and mDBC's wall densities and velocities with retired
// particles on the lists equal those of a search made without them (round-off only).
TEST_CASE("retired particles on the lists act on nothing: the same rates as without them", "[sph][interactions][mdbc]") {
  const sph::SolverSettings s = study_model();
  sph::ParticleSet ps = mixed_particles(31u, {});
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (sph::is_wall_type(ps.type[i])) ps.ghost_dz[i] = -2.0 * ps.z[i];  // mirrored through the bed z = 0
  const double reach = 1.1 * s.support();
  const sph::CellList cells = sorted_cells(ps, s, reach);
  sph::NeighbourList list;
  list.build(ps.x, ps.z, ps.type, cells, reach);
  sph::GhostNeighbourList ghosts;
  ghosts.build(ps.x, ps.z, ps, cells, s, reach);
  // Every fourth non-wall particle retired: fluid inside the block and buffer particles alike.
  int retired = 0;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (!sph::is_wall_type(ps.type[i]) && ps.id[i] % 4 == 0) ps.retire(i), ++retired;
  sph::ParticleSet without = ps;
  CHECK(sph::remove_retired(without) == retired);
  REQUIRE(without.size() == ps.size() - retired);
  sph::mdbc_boundary_density(ps, ghosts, s);
  sph::compute_pressure(ps, s);
  sph::compute_interactions(ps, list, s);
  const sph::CellList fresh_cells = sorted_cells(without, s, s.support());
  sph::mdbc_boundary_density(without, fresh_cells, s);
  sph::compute_pressure(without, s);
  sph::compute_interactions(without, fresh_cells, s);
  std::vector<Eigen::Index> at(static_cast<std::size_t>(ps.size()), -1);
  for (Eigen::Index k = 0; k < without.size(); ++k) at[static_cast<std::size_t>(without.id[k])] = k;
  const auto largest = [](const Eigen::VectorXd& v) { return std::max(v.cwiseAbs().maxCoeff(), 1e-30); };
  int compared = 0;
  for (const auto& [name, got, want] : {std::tuple{"drho", &ps.drho, &without.drho}, std::tuple{"ax", &ps.ax, &without.ax},
                                        std::tuple{"az", &ps.az, &without.az}, std::tuple{"tau_xx", &ps.tau_xx, &without.tau_xx},
                                        std::tuple{"tau_xz", &ps.tau_xz, &without.tau_xz}, std::tuple{"tau_zz", &ps.tau_zz, &without.tau_zz},
                                        std::tuple{"rho", &ps.rho, &without.rho}, std::tuple{"wall_u", &ps.wall_u, &without.wall_u},
                                        std::tuple{"wall_w", &ps.wall_w, &without.wall_w}}) {
    const double tol = 1e-9 * largest(*want);
    for (Eigen::Index i = 0; i < ps.size(); ++i) {
      const Eigen::Index k = at[static_cast<std::size_t>(ps.id[i])];
      if (k < 0) continue;  // retired
      INFO(name << " of particle " << ps.id[i] << " (type " << int(ps.type[i]) << ")");
      CHECK(std::abs((*got)[i] - (*want)[k]) <= tol);
      ++compared;
    }
  }
  CHECK(compared > 1000);
  // Not vacuous: the retired particles sat within the support of fluid particles and of wall ghost nodes.
  int near_fluid = 0, near_ghost = 0;
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    const bool wall = sph::is_wall_type(ps.type[i]);
    if (!wall && !ps.is_fluid(i)) continue;
    const double xi = ps.x[i] + (wall ? ps.ghost_dx[i] : 0.0), zi = ps.z[i] + (wall ? ps.ghost_dz[i] : 0.0);
    for (Eigen::Index j = 0; j < ps.size(); ++j)
      if (ps.type[j] == static_cast<std::uint8_t>(sph::ParticleType::retired) && std::hypot(xi - ps.x[j], zi - ps.z[j]) < s.support())
        ++(wall ? near_ghost : near_fluid);
  }
  CHECK(near_fluid > 100);
  CHECK(near_ghost > 10);
}
