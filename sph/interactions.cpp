#include "sph/interactions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <omp.h>

#include "sph/cpu_dispatch.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/pair_terms.hpp"
#include "sph/parallel.hpp"
#include "sph/viscosity.hpp"
#include "sph/wall_function.hpp"

namespace hydrojump::sph {

// The weakly compressible SPH equations (Monaghan 1994, J. Comput. Phys. 110:399-406) for each particle
// i over its neighbours j within 2h:
//   continuity (fluid):  D_i = sum_j m_j (v_i - v_j) . grad_i W_ij + diffusion_i
//   continuity (DBC wall b):  D_b = sum_j m_j (v_b - v_j) . grad_b W_bj          (boundary_dbc.hpp)
//   momentum (fluid):    a_i = -sum_j m_j (p_i + p_j)/(rho_i rho_j) grad_i W_ij + viscous_i + g
// and the time-step inputs max|a_i| and max_ij |h v_ij.r_ij / (r_ij^2 + eta^2)|. Each particle sums
// its own terms over its own neighbours (a full Verlet list, neighbour_list.hpp; pair_terms.hpp has
// the terms): a pair is evaluated from both of its particles, which costs each pair twice but writes
// to no neighbour, so the loop over a particle's fluid neighbours vectorises (SIMD lanes over j) and
// threads need no colouring. The pressure term is the symmetric form, so momentum is still conserved
// pairwise (Monaghan 1992, Annu. Rev. Astron. Astrophys. 30:543-574) to round-off. The pair loop is
// instantiated for each kernel, viscosity model and density diffusion term, so it carries no branch
// on the model.
namespace {

using detail::OwnSums;

using detail::PairArrays;

constexpr std::uint8_t kFluid = static_cast<std::uint8_t>(ParticleType::fluid);

// Per-call storage: the per-particle factors V = m/rho, 1/rho and tau/rho^2, and for laminar_sps the
// strain rates and each fluid particle's nearest wall particle.
struct Scratch {
  std::vector<double> volume, inv_rho, sxx, sxz, szz, grad, nearest_r2, nearest_dx, nearest_dz;
  std::vector<int> nearest;
};

PairArrays pair_arrays(ParticleSet& ps, const SolverSettings& s, Scratch& w) {
  const bool sps = s.viscosity.model == Viscosity::laminar_sps;
  const Eigen::Index n = ps.size();
  const auto size = static_cast<std::size_t>(n), sps_size = sps ? size : 0;
  w.volume.resize(size);
  w.inv_rho.resize(size);
  for (auto* v : {&w.sxx, &w.sxz, &w.szz}) v->resize(sps_size);
  w.grad.assign(3 * sps_size, 0.0);
  const bool nearest = sps && (s.viscosity.sps_length_near_walls || s.viscosity.wall_function_shear);
  w.nearest_r2.assign(nearest ? size : 0, std::numeric_limits<double>::infinity());
  w.nearest_dx.assign(nearest ? size : 0, 0.0);
  w.nearest_dz.assign(nearest ? size : 0, 0.0);
  w.nearest.assign(nearest ? size : 0, -1);
  // V_j = m_j / rho_j, 1/rho_j and tau_j/rho_j^2 (tau is stored divided by rho), once per particle;
  // the rates start from zero (the pair loop adds to them).
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    const double inv = 1.0 / ps.rho[i];
    w.inv_rho[i] = inv;
    w.volume[i] = ps.mass[i] * inv;
    if (sps) {
      w.sxx[i] = ps.tau_xx[i] * inv;
      w.sxz[i] = ps.tau_xz[i] * inv;
      w.szz[i] = ps.tau_zz[i] * inv;
    }
    ps.drho[i] = ps.ax[i] = ps.az[i] = 0.0;
  }
  PairArrays a;
  a.x = ps.x.data(), a.z = ps.z.data(), a.u = ps.u.data(), a.w = ps.w.data(), a.rho = ps.rho.data(), a.p = ps.p.data();
  a.m = ps.mass.data(), a.volume = w.volume.data(), a.inv_rho = w.inv_rho.data();
  a.sxx = w.sxx.data(), a.sxz = w.sxz.data(), a.szz = w.szz.data(), a.wall_u = ps.wall_u.data(), a.wall_w = ps.wall_w.data();
  a.drho = ps.drho.data(), a.ax = ps.ax.data(), a.az = ps.az.data(), a.grad = sps ? w.grad.data() : nullptr;
  a.nearest_r2 = w.nearest_r2.data(), a.nearest_dx = w.nearest_dx.data(), a.nearest_dz = w.nearest_dz.data();
  a.nearest = w.nearest.data();
  detail::PairModel& c = a.model;
  c.hydrostatic = HydrostaticDensity(s.eos.rho0, s.eos.b, s.body_force_z);
  c.support2 = s.support() * s.support();
  c.eta2 = s.eta2();
  c.h = s.h;
  c.alpha_c0_h = s.viscosity.artificial_alpha * s.eos.c0 * s.h;
  c.wall_factor = s.viscosity.artificial_wall_factor;
  c.delta_h_c0 = s.density.diffusion_delta * s.h * s.eos.c0;
  c.nu0 = s.viscosity.kinematic_viscosity;
  c.free_slip_walls = sps && s.viscosity.viscous_walls_free_slip;
  c.nearest_wall_needed = nearest;
  c.dbc = s.boundary == BoundaryMethod::dbc;
  return a;
}

// Fluid particle i's terms (into `own`) from its non-wall neighbours k in [begin, end) (fluid or
// open-boundary buffer particles: the same terms for i), a loop the compiler vectorises with gathers
// of j's values. A listed pair beyond the support has F = 0 and so adds nothing but its viscous rate,
// which is masked. always_inline, as the pair terms: pair_loop's CPU clones (cpu_dispatch.hpp) would
// otherwise call the baseline's copy.
template <class K, Viscosity V, DensityDiffusion D, bool Periodic>
[[gnu::always_inline]] inline void fluid_neighbours(const PairArrays& a, const detail::PairModel& c, const K& kernel,
                                                    const detail::PairParticle& pi, const NeighbourList& list, int begin, int end,
                                                    OwnSums& own, double& visc) {
  const int* nb = list.neighbours();
  const double* shift = list.shifts();
  double d = 0.0, ax = 0.0, az = 0.0, g0 = 0.0, g1 = 0.0, g2 = 0.0, most = 0.0;
#pragma omp simd reduction(+ : d, ax, az, g0, g1, g2) reduction(max : most)
  for (int k = begin; k < end; ++k) {
    const int j = nb[k];
    double xj = a.x[j];
    if constexpr (Periodic) xj += shift[k];
    const double dx = pi.x - xj, dz = pi.z - a.z[j];
    const double r2 = dx * dx + dz * dz;
    const detail::PairGeometry r{dx, dz, r2, kernel.gradient_factor(std::sqrt(r2))};
    OwnSums t;
    double rate = 0.0;
    detail::fluid_pair<V, D>(a, c, pi, j, r, t, rate);
    d += t.d, ax += t.ax, az += t.az;
    if constexpr (V == Viscosity::laminar_sps) g0 += t.grad[0], g1 += t.grad[1], g2 += t.grad[2];
    most = std::max(most, r2 < c.support2 ? rate : 0.0);
  }
  own.d += d, own.ax += ax, own.az += az;
  own.grad[0] += g0, own.grad[1] += g1, own.grad[2] += g2;
  visc = std::max(visc, most);
}

// Fluid particle i: its non-wall neighbours, then its wall neighbours (fewer; the nearest wall kept
// for the SPS mixing length and the wall function).
template <class K, Viscosity V, DensityDiffusion D, bool Periodic>
[[gnu::always_inline]] inline void fluid_particle(const PairArrays& a, const K& kernel, const NeighbourList& list, int i, double& visc) {
  const detail::PairModel c = a.model;
  const detail::PairParticle pi = detail::pair_particle<V>(a, i);
  OwnSums own;
  fluid_neighbours<K, V, D, Periodic>(a, c, kernel, pi, list, list.begin(i), list.wall_begin(i), own, visc);
  const int* nb = list.neighbours();
  for (int k = list.wall_begin(i), end = list.end(i); k < end; ++k) {
    const int b = nb[k];
    const double dx = pi.x - (a.x[b] + list.shift(k)), dz = pi.z - a.z[b];
    const double r2 = dx * dx + dz * dz;
    if (r2 >= c.support2) continue;
    detail::fluid_wall_pair<V>(a, i, b, dx, dz, r2, kernel.gradient_factor(std::sqrt(r2)), own, visc);
  }
  own.add_to(a, i);
}

// A DBC wall particle b's continuity from its (non-wall) neighbours j (boundary_dbc.hpp):
//   D_b = sum_j m_j (v_b - v_j) . F (r_b - r_j).
template <class K>
[[gnu::always_inline]] inline void dbc_wall_particle(const PairArrays& a, const K& kernel, const NeighbourList& list, int b) {
  const int* nb = list.neighbours();
  const double xb = a.x[b], zb = a.z[b], ub = a.u[b], wb = a.w[b], support2 = a.model.support2;
  double d = 0.0;
  for (int k = list.begin(b), end = list.wall_begin(b); k < end; ++k) {
    const int j = nb[k];
    const double dx = xb - (a.x[j] + list.shift(k)), dz = zb - a.z[j];
    const double r2 = dx * dx + dz * dz;
    if (r2 >= support2) continue;
    d += dbc_density_rate_pair(a.m[j], kernel.gradient_factor(std::sqrt(r2)), a.u[j] - ub, a.w[j] - wb, dx, dz);
  }
  a.drho[b] += d;
}

// Every particle's sums over its own list (a full list: each pair is met from both particles), the
// threads each a slice of consecutive particles with about the same work (neighbour_list.hpp); a
// particle's sum has the same order whatever the thread count. Open-boundary buffer particles, and
// mDBC walls, take nothing here. Returns the max viscous rate.
template <class K, Viscosity V, DensityDiffusion D, bool Periodic>
HYDROJUMP_HOT_LOOP double pair_loop(const PairArrays& a, const K& kernel, const ParticleSet& ps, const NeighbourList& list) {
  const std::uint8_t* type = ps.type.data();
  const bool dbc = a.model.dbc;
  double visc = 0.0;
#pragma omp parallel if (use_threads(ps.size())) reduction(max : visc)
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    for (int i = list.slice_begin(t, threads), last = list.slice_begin(t + 1, threads); i < last; ++i) {
      if (type[i] == kFluid) fluid_particle<K, V, D, Periodic>(a, kernel, list, i, visc);
      else if (dbc && is_wall_type(type[i])) dbc_wall_particle(a, kernel, list, i);
    }
  }
  return visc;
}

// The log law's wall shear on the first fluid layer (wall_function.hpp). Wall normal n along the
// nearest wall particle's ghost offset g - b = 2 (q - b); distance to the wall surface
// d = (x_i - x_b) . n - |g - b| / 2; velocity relative to the wall particle's own (moving walls).
WallShearAcceleration wall_function_term(const ParticleSet& ps, const SolverSettings& s, const Scratch& w, int i) {
  const int b = w.nearest[i];
  const double g_len = std::hypot(ps.ghost_dx[b], ps.ghost_dz[b]);
  if (!(g_len > 0.0)) return {};
  const double nx = ps.ghost_dx[b] / g_len, nz = ps.ghost_dz[b] / g_len;
  const double d_wall = w.nearest_dx[i] * nx + w.nearest_dz[i] * nz - 0.5 * g_len;
  return wall_shear_acceleration(ps.u[i] - ps.u[b], ps.w[i] - ps.w[b], nx, nz, d_wall, s.dx, s.viscosity.kinematic_viscosity);
}

// After the pair loop: a fluid particle's wall shear and body force (returns |a|^2); everything else
// keeps no acceleration, and a density rate only if it is a DBC wall.
double finish_particle(ParticleSet& ps, const SolverSettings& s, const Scratch& w, int i) {
  if (ps.type[i] != kFluid) {
    if (!(s.boundary == BoundaryMethod::dbc && is_wall_type(ps.type[i]))) ps.drho[i] = 0.0;
    ps.ax[i] = ps.az[i] = 0.0;
    return 0.0;
  }
  if (s.viscosity.model == Viscosity::laminar_sps && s.viscosity.wall_function_shear && w.nearest[i] >= 0) {
    const WallShearAcceleration shear = wall_function_term(ps, s, w, i);
    ps.ax[i] += shear.ax;
    ps.az[i] += shear.az;
  }
  ps.ax[i] += s.body_force_x;
  ps.az[i] += s.body_force_z;
  return ps.ax[i] * ps.ax[i] + ps.az[i] * ps.az[i];
}

// laminar_sps: the SPS stress of every fluid particle from its velocity gradient of this call, for the
// next interaction (one half step later, as in DualSPHysics, Dominguez et al. 2022, instead of a
// second pair loop); with a mixing length near walls Prandtl's l = min(l_m, kappa d), d the distance
// to the nearest wall particle within the support (none: infinity, or the fixed walls' table value
// with "whole_domain"). Returns max nu_t.
double update_sps_stress(ParticleSet& ps, const SolverSettings& s, const Scratch& w, const WallDistanceTable* wall_distances) {
  const Eigen::Index n = ps.size();
  const bool near_walls = s.viscosity.sps_length_near_walls;
  double max_nu_t = 0.0;
#pragma omp parallel for schedule(static) reduction(max : max_nu_t) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    if (ps.type[i] != kFluid) {
      ps.tau_xx[i] = ps.tau_xz[i] = ps.tau_zz[i] = 0.0;
      continue;
    }
    double length = s.viscosity.sps_length;
    if (near_walls) {
      const double d = w.nearest[i] < 0 && wall_distances != nullptr ? wall_distances->at(ps.x[i], ps.z[i]) : std::sqrt(w.nearest_r2[i]);
      length = mixing_length_near_wall(s.viscosity.sps_length, d, s.dx);
    }
    const double* gi = w.grad.data() + 3 * static_cast<std::size_t>(i);
    const SpsStress t = sps_stress(gi[0], gi[1], gi[2], length, s.viscosity.blin, s.dx);
    ps.tau_xx[i] = t.xx;
    ps.tau_xz[i] = t.xz;
    ps.tau_zz[i] = t.zz;
    max_nu_t = std::max(max_nu_t, t.eddy_viscosity);
  }
  return max_nu_t;
}

template <class K, Viscosity V, DensityDiffusion D>
InteractionSummary interactions_with(ParticleSet& ps, const NeighbourList& list, const SolverSettings& s, const K& kernel,
                                     const WallDistanceTable* wall_distances) {
  Scratch w;
  const PairArrays a = pair_arrays(ps, s, w);
  const double max_visc = list.periodic() ? pair_loop<K, V, D, true>(a, kernel, ps, list) : pair_loop<K, V, D, false>(a, kernel, ps, list);
  const Eigen::Index n = ps.size();
  double max_acc2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : max_acc2) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) max_acc2 = std::max(max_acc2, finish_particle(ps, s, w, static_cast<int>(i)));
  const double max_nu_t = V == Viscosity::laminar_sps ? update_sps_stress(ps, s, w, wall_distances) : 0.0;
  return InteractionSummary{std::sqrt(max_acc2), max_visc, max_nu_t};
}

template <class K, Viscosity V>
InteractionSummary with_diffusion(ParticleSet& ps, const NeighbourList& list, const SolverSettings& s, const K& kernel,
                                  const WallDistanceTable* wall_distances) {
  const DensityDiffusion d = s.density.diffusion_delta > 0.0 ? s.density.diffusion : DensityDiffusion::none;
  if (d == DensityDiffusion::molteni) return interactions_with<K, V, DensityDiffusion::molteni>(ps, list, s, kernel, wall_distances);
  if (d == DensityDiffusion::fourtakas) return interactions_with<K, V, DensityDiffusion::fourtakas>(ps, list, s, kernel, wall_distances);
  return interactions_with<K, V, DensityDiffusion::none>(ps, list, s, kernel, wall_distances);
}

template <class K>
InteractionSummary with_model(ParticleSet& ps, const NeighbourList& list, const SolverSettings& s, const K& kernel,
                              const WallDistanceTable* wall_distances) {
  if (s.viscosity.model == Viscosity::artificial) return with_diffusion<K, Viscosity::artificial>(ps, list, s, kernel, wall_distances);
  return with_diffusion<K, Viscosity::laminar_sps>(ps, list, s, kernel, wall_distances);
}

}  // namespace

void compute_pressure(ParticleSet& ps, const SolverSettings& s) {
  const Eigen::Index n = ps.size();
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) ps.p[i] = s.eos.pressure(ps.rho[i]);
}

InteractionSummary compute_interactions(ParticleSet& ps, const NeighbourList& list, const SolverSettings& s,
                                        const WallDistanceTable* wall_distances) {
  if (s.kernel == KernelType::wendland_c2) return with_model(ps, list, s, WendlandC2(s.h), wall_distances);
  return with_model(ps, list, s, CubicSpline(s.h), wall_distances);
}

InteractionSummary compute_interactions(ParticleSet& ps, const CellList& cells, const SolverSettings& s,
                                        const WallDistanceTable* wall_distances) {
  NeighbourList list;
  list.build(ps.x, ps.z, ps.type, cells, s.support(), s.boundary == BoundaryMethod::dbc);
  return compute_interactions(ps, list, s, wall_distances);
}

}  // namespace hydrojump::sph
