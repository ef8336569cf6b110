#include "sph/interactions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sph/boundary_dbc.hpp"
#include "sph/density_diffusion.hpp"
#include "sph/kernel.hpp"
#include "sph/parallel.hpp"
#include "sph/viscosity.hpp"
#include "sph/wall_function.hpp"

namespace hydrojump::sph {

namespace {

constexpr std::uint8_t kFluid = static_cast<std::uint8_t>(ParticleType::fluid);

// The weakly compressible SPH equations (Monaghan 1994, J. Comput. Phys. 110:399-406), gathered for
// each particle i over its neighbours j within 2h, with grad_i W_ij = F(r_ij) (r_i - r_j):
//   continuity (fluid):  D_i = d rho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij + diffusion_i
//                        (density_diffusion.hpp; between fluid particles only)
//   continuity (DBC wall b):  D_b = sum_j m_j (v_b - v_j) . grad_b W_bj          (boundary_dbc.hpp)
//   momentum (fluid):    a_i = -sum_j m_j (p_i + p_j)/(rho_i rho_j) grad_i W_ij + viscous_i + g
//                        (viscosity.hpp: artificial Pi_ij, or laminar + SPS stress divergence)
// and the time-step inputs max|a_i| and max_ij |h v_ij.r_ij / (r_ij^2 + eta^2)|.
// The symmetric pressure term conserves momentum pairwise (Monaghan 1992, Annu. Rev. Astron.
// Astrophys. 30:543-574).
// One function of ~215 lines on purpose: it is the pair loop, where the run spends its time, and its
// terms share the pair's kernel gradient, distance and velocity difference in registers. Split into
// per-model functions it is the compile-time specialisation of the speed issue (54), measured there.
template <class K>
InteractionSummary interactions_with(ParticleSet& ps, const CellList& cells, const SolverSettings& s, const K& kernel,
                                     const WallDistanceTable* wall_distances) {
  const int n_cells = cells.cell_count();
  const double* x = ps.x.data();
  const double* z = ps.z.data();
  const double* u = ps.u.data();
  const double* w = ps.w.data();
  const double* rho = ps.rho.data();
  const double* p = ps.p.data();
  const double* m = ps.mass.data();
  const double* txx = ps.tau_xx.data();
  const double* txz = ps.tau_xz.data();
  const double* tzz = ps.tau_zz.data();
  const double* wall_u = ps.wall_u.data();
  const double* wall_w = ps.wall_w.data();
  const std::uint8_t* type = ps.type.data();
  double* ax = ps.ax.data();
  double* az = ps.az.data();
  double* drho = ps.drho.data();

  const double support2 = s.support() * s.support();
  const double eta2 = s.eta2();
  const double h = s.h;
  const double alpha_c0_h = s.viscosity.artificial_alpha * s.eos.c0 * h;
  const double wall_factor = s.viscosity.artificial_wall_factor;
  const double delta_h_c0 = s.density.diffusion_delta * h * s.eos.c0;
  const double rho0 = s.eos.rho0, b = s.eos.b;
  const double gz = s.body_force_z;
  const bool artificial = s.viscosity.model == Viscosity::artificial;
  const bool sps = s.viscosity.model == Viscosity::laminar_sps;
  const bool diffusion = s.density.diffusion != DensityDiffusion::none && delta_h_c0 > 0.0;
  const bool fourtakas = s.density.diffusion == DensityDiffusion::fourtakas;
  const bool dbc = s.boundary == BoundaryMethod::dbc;
  const double nu0 = s.viscosity.kinematic_viscosity;
  const bool free_slip_walls = sps && s.viscosity.viscous_walls_free_slip;
  const bool wall_function = sps && s.viscosity.wall_function_shear;

  // V_j = m_j / rho_j, once per particle instead of once per pair.
  const Eigen::Index n = ps.size();
  const bool threads = use_threads(n);
  std::vector<double> volume_store(static_cast<std::size_t>(n));
  double* volume = volume_store.data();
#pragma omp parallel for schedule(static) if (threads)
  for (Eigen::Index i = 0; i < n; ++i) volume[i] = m[i] / rho[i];

  // laminar_sps: the velocity gradient of every fluid particle, accumulated in the pair loop; the SPS
  // stress made from it after the loop is used by the next interaction (one half step later), as in
  // DualSPHysics (Dominguez et al. 2022), instead of a second pair loop:
  //   grad v_i = sum_j V_j (v_j - v_i) (x) grad_i W_ij
  std::vector<double> grad_store(sps ? 4 * static_cast<std::size_t>(n) : 0, 0.0);
  double* grad = grad_store.data();
  // With a mixing length: the distance from each fluid particle to the nearest wall particle within
  // the kernel support (none: infinity, or the fixed walls' table value with "whole_domain"), for
  // Prandtl's l = min(l_m, kappa d).
  const bool wall_distance_needed = sps && s.viscosity.sps_length_near_walls;
  std::vector<double> wall_distance_store(wall_distance_needed ? static_cast<std::size_t>(n) : 0,
                                          std::numeric_limits<double>::infinity());
  double* wall_distance = wall_distance_store.data();
  // The nearest wall particle of each fluid particle: its distance for the mixing length, its ghost
  // offset for the wall function.
  const bool nearest_wall_needed = wall_distance_needed || wall_function;

  double max_acc2 = 0.0, max_visc = 0.0;
#pragma omp parallel for schedule(dynamic, 16) reduction(max : max_acc2, max_visc) if (threads)
  for (int c = 0; c < n_cells; ++c) {
    const int first = cells.cell_start(c), last = cells.cell_start(c + 1);
    if (first == last) continue;
    NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(c, ranges);
    for (int i = first; i < last; ++i) {
      const double xi = x[i], zi = z[i], ui = u[i], wi = w[i], rhoi = rho[i];
      if (type[i] != kFluid) {
        // Boundary particle (DBC, boundary_dbc.hpp): continuity with the fluid (and open-boundary
        // buffer) neighbours only; it does not move. With mDBC its density comes from the ghost node
        // instead. Buffer particles get no rates: their buffer imposes their state.
        double d = 0.0;
        if (dbc && is_wall_type(type[i])) {
          for (int k = 0; k < n_ranges; ++k) {
            const NeighbourRange rg = ranges[k];
            for (int j = rg.begin; j < rg.end; ++j) {
              if (is_wall_type(type[j])) continue;
              const double dx = xi - (x[j] + rg.shift_x), dz = zi - z[j];
              const double r2 = dx * dx + dz * dz;
              if (r2 >= support2) continue;
              // relative to the wall's own velocity (zero unless it is a moving wall)
              d += dbc_density_rate_pair(m[j], kernel.gradient_factor(std::sqrt(r2)), u[j] - ui, w[j] - wi, dx, dz);
            }
          }
        }
        drho[i] = d;
        ax[i] = 0.0;
        az[i] = 0.0;
        continue;
      }
      const double pi = p[i], inv_rhoi = 1.0 / rhoi;
      double d = 0.0, fx = 0.0, fz = 0.0, visc_rate = 0.0;
      double dudx = 0.0, dudz = 0.0, dwdx = 0.0, dwdz = 0.0;
      // The nearest wall particle within the support and the offset x_i - x_j to it.
      int nearest_wall = -1;
      double nearest_r2 = std::numeric_limits<double>::infinity(), nearest_dx = 0.0, nearest_dz = 0.0;
      for (int k = 0; k < n_ranges; ++k) {
        const NeighbourRange rg = ranges[k];
        for (int j = rg.begin; j < rg.end; ++j) {
          const double dx = xi - (x[j] + rg.shift_x), dz = zi - z[j];
          const double r2 = dx * dx + dz * dz;
          if (r2 >= support2 || j == i) continue;
          const double f = kernel.gradient_factor(std::sqrt(r2));
          const double gx = f * dx, gzw = f * dz;  // grad_i W_ij
          const double du = ui - u[j], dw = wi - w[j];
          const double v_dot_r = du * dx + dw * dz;
          const double mj = m[j], vj = volume[j];
          // Continuity: m_j v_ij . grad_i W_ij
          d += mj * (du * gx + dw * gzw);
          // Inflow/outflow buffer neighbours act like fluid (their imposed velocity and density).
          const bool fluid_j = !is_wall_type(type[j]);
          if (nearest_wall_needed && !fluid_j && r2 < nearest_r2) {
            nearest_r2 = r2;
            nearest_wall = j;
            nearest_dx = dx;
            nearest_dz = dz;
          }
          if (diffusion && fluid_j) {
            double jump = rho[j] - rhoi;
            if (fourtakas) jump -= hydrostatic_density_difference(rho0, b, gz, -dz);
            d += density_diffusion_pair(delta_h_c0, f, jump, vj);
          }
          // Pressure: -m_j (p_i + p_j)/(rho_i rho_j) grad_i W_ij
          double scalar = -vj * (pi + p[j]) * inv_rhoi;
          if (v_dot_r < 0.0) {
            // Approaching pair: the viscous time-step condition, and the artificial viscosity.
            const double dot_rr2 = v_dot_r / (r2 + eta2);
            visc_rate = std::max(visc_rate, -h * dot_rr2);
            if (artificial)
              scalar -= (fluid_j ? 1.0 : wall_factor) * mj *
                        artificial_viscosity_pair(alpha_c0_h, v_dot_r, r2, eta2, rhoi, rho[j]);
          }
          if (!artificial) {
            // Boundary neighbours enter with their mDBC wall velocity, no-slip or slip (zero with DBC).
            const double lam = mj * laminar_viscosity_pair(nu0, f, r2, eta2, rhoi, rho[j]);
            const double du_visc = fluid_j ? du : ui - wall_u[j];
            const double dw_visc = fluid_j ? dw : wi - wall_w[j];
            fx += lam * du_visc;
            fz += lam * dw_visc;
            if (sps) {
              // Free slip: wall neighbours enter the gradient with their slip velocity (mDBC), as in
              // the laminar term, so the wall's shear is not sensed; no slip: with their own (zero
              // unless moving).
              const double gu = free_slip_walls ? du_visc : du;
              const double gw = free_slip_walls ? dw_visc : dw;
              dudx -= vj * gu * gx;
              dudz -= vj * gu * gzw;
              dwdx -= vj * gw * gx;
              dwdz -= vj * gw * gzw;
              // m_j (tau_i/rho_i^2 + tau_j/rho_j^2) . grad_i W (tau stored divided by rho)
              const double inv_rhoj = vj / mj;
              const double sxx = txx[i] * inv_rhoi + txx[j] * inv_rhoj;
              const double sxz = txz[i] * inv_rhoi + txz[j] * inv_rhoj;
              const double szz = tzz[i] * inv_rhoi + tzz[j] * inv_rhoj;
              fx += mj * (sxx * gx + sxz * gzw);
              fz += mj * (sxz * gx + szz * gzw);
            }
          }
          fx += scalar * gx;
          fz += scalar * gzw;
        }
      }
      if (sps) {
        double* gi = grad + 4 * static_cast<std::size_t>(i);
        gi[0] = dudx;
        gi[1] = dudz;
        gi[2] = dwdx;
        gi[3] = dwdz;
        if (wall_distance_needed)
          wall_distance[i] = nearest_wall < 0 && wall_distances != nullptr ? wall_distances->at(xi, zi) : std::sqrt(nearest_r2);
      }
      if (wall_function && nearest_wall >= 0) {
        // The log law's wall shear on the first fluid layer (wall_function.hpp). Wall normal n along the
        // nearest wall particle's ghost offset g - b = 2 (q - b); distance to the wall surface
        // d = (x_i - x_b) . n - |g - b| / 2; velocity relative to the wall particle's own (moving walls).
        const double g_len = std::hypot(ps.ghost_dx[nearest_wall], ps.ghost_dz[nearest_wall]);
        if (g_len > 0.0) {
          const double nx = ps.ghost_dx[nearest_wall] / g_len, nz = ps.ghost_dz[nearest_wall] / g_len;
          const double d_wall = nearest_dx * nx + nearest_dz * nz - 0.5 * g_len;
          const WallShearAcceleration a = wall_shear_acceleration(ui - u[nearest_wall], wi - w[nearest_wall], nx, nz, d_wall,
                                                                  s.dx, nu0);
          fx += a.ax;
          fz += a.az;
        }
      }
      drho[i] = d;
      ax[i] = fx + s.body_force_x;
      az[i] = fz + s.body_force_z;
      max_acc2 = std::max(max_acc2, ax[i] * ax[i] + az[i] * az[i]);
      max_visc = std::max(max_visc, visc_rate);
    }
  }
  double max_nu_t = 0.0;
  if (sps) {
#pragma omp parallel for schedule(static) reduction(max : max_nu_t) if (threads)
    for (Eigen::Index i = 0; i < n; ++i) {
      if (type[i] != kFluid) {
        ps.tau_xx[i] = ps.tau_xz[i] = ps.tau_zz[i] = 0.0;
        continue;
      }
      const double* gi = grad + 4 * static_cast<std::size_t>(i);
      const double length = wall_distance_needed ? mixing_length_near_wall(s.viscosity.sps_length, wall_distance[i], s.dx) : s.viscosity.sps_length;
      const SpsStress t = sps_stress(gi[0], gi[1], gi[2], gi[3], length, s.viscosity.blin, s.dx);
      ps.tau_xx[i] = t.xx;
      ps.tau_xz[i] = t.xz;
      ps.tau_zz[i] = t.zz;
      max_nu_t = std::max(max_nu_t, t.eddy_viscosity);
    }
  }
  return InteractionSummary{std::sqrt(max_acc2), max_visc, max_nu_t};
}

}  // namespace

void compute_pressure(ParticleSet& ps, const SolverSettings& s) {
  const Eigen::Index n = ps.size();
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) ps.p[i] = s.eos.pressure(ps.rho[i]);
}

InteractionSummary compute_interactions(ParticleSet& ps, const CellList& cells, const SolverSettings& s,
                                        const WallDistanceTable* wall_distances) {
  if (s.kernel == KernelType::wendland_c2) return interactions_with(ps, cells, s, WendlandC2(s.h), wall_distances);
  return interactions_with(ps, cells, s, CubicSpline(s.h), wall_distances);
}

}  // namespace hydrojump::sph
