// The terms of one pair of particles i, j in the symmetric pair loop (interactions.cpp), added to both
// particles at once. With r = r_i - r_j (periodic image of j), g = grad_i W_ij = F(r) r = -grad_j W_ji
// and v = v_i - v_j:
//
//   continuity:  D_i += m_j v.g                        D_j += m_i v.g
//   diffusion:   D_i += -2 delta h c0 F (rho_j - rho_i - H(z_j - z_i)) V_j   (and i <-> j; Fourtakas
//                et al. 2019 with the hydrostatic part H, Molteni & Colagrossi 2009 with H = 0)
//   pressure:    a_i += -V_j (p_i + p_j)/rho_i g       a_j += V_i (p_i + p_j)/rho_j g
//   artificial:  a_i += -m_j Pi_ij g                   a_j += m_i Pi_ij g
//                Pi_ij = -2 alpha c0 h v.r / ((r^2 + eta^2)(rho_i + rho_j)) for v.r < 0 (Monaghan 1992)
//   laminar:     a_i += m_j L v                        a_j += -m_i L v,
//                L = 4 nu0 F r^2 / ((r^2 + eta^2)(rho_i + rho_j))  (Lo & Shao 2002)
//   SPS stress:  a_i += m_j (S_i + S_j) g              a_j += -m_i (S_i + S_j) g,   S = tau / rho^2
//   grad v:      G_i += -V_j v (x) g                   G_j += -V_i v (x) g
//
// and the viscous time-step rate h |v.r| / (r^2 + eta^2) of an approaching pair. A wall neighbour b
// enters a fluid particle's viscous terms with its mDBC wall velocity, the artificial viscosity with
// the wall factor, and gives the fluid particle nothing else; a DBC wall gets only the continuity.
// Open-boundary buffer particles act on fluid particles as fluid and receive nothing.
#pragma once

#include <algorithm>
#include <cstdint>

#include "sph/boundary_dbc.hpp"
#include "sph/density_diffusion.hpp"
#include "sph/settings.hpp"
#include "sph/viscosity.hpp"

namespace hydrojump::sph::detail {

// The particle arrays the pair terms read and write, and the model's constants.
struct PairArrays {
  const double *x = nullptr, *z = nullptr, *u = nullptr, *w = nullptr, *rho = nullptr, *p = nullptr, *m = nullptr;
  const double *volume = nullptr, *inv_rho = nullptr, *sxx = nullptr, *sxz = nullptr, *szz = nullptr;
  const double *wall_u = nullptr, *wall_w = nullptr;
  double *drho = nullptr, *ax = nullptr, *az = nullptr;
  double* grad = nullptr;  // laminar_sps: 4 per particle (du/dx, du/dz, dw/dx, dw/dz); else none
  double *nearest_r2 = nullptr, *nearest_dx = nullptr, *nearest_dz = nullptr;
  int* nearest = nullptr;
  double support2 = 0.0, eta2 = 0.0, h = 0.0, alpha_c0_h = 0.0, wall_factor = 0.0, delta_h_c0 = 0.0, nu0 = 0.0;
  HydrostaticDensity hydrostatic{0.0, 1.0, 0.0};
  bool free_slip_walls = false, nearest_wall_needed = false, dbc = false;
};

// What particle i gathers over the pairs the loop meets from it, added to its arrays once after them
// (add_to); j's terms go to the arrays at once.
struct OwnSums {
  double d = 0.0, ax = 0.0, az = 0.0, grad[4] = {0.0, 0.0, 0.0, 0.0};
  void add_to(const PairArrays& a, int i) const {
    a.drho[i] += d;
    a.ax[i] += ax;
    a.az[i] += az;
    if (a.grad != nullptr)
      for (int k = 0; k < 4; ++k) a.grad[4 * static_cast<std::size_t>(i) + k] += grad[k];
  }
};

// Fluid particle i and fluid-side particle j (fluid or, with Both = false, a buffer particle that
// receives nothing) at offset (dx, dz) = r_i - r_j, r2 < support^2, F = f.
template <Viscosity V, DensityDiffusion D, bool Both>
inline void fluid_pair(const PairArrays& a, int i, int j, double dx, double dz, double r2, double f, OwnSums& own, double& visc) {
  const double gx = f * dx, gz = f * dz;
  const double du = a.u[i] - a.u[j], dw = a.w[i] - a.w[j];
  const double v_dot_r = du * dx + dw * dz;
  const double mi = a.m[i], mj = a.m[j], vi = a.volume[i], vj = a.volume[j];
  const double rhoi = a.rho[i], rhoj = a.rho[j];
  const double dot = du * gx + dw * gz;
  double rate_i = mj * dot, rate_j = mi * dot;
  if constexpr (D != DensityDiffusion::none) {
    double jump = rhoj - rhoi, jump_back = rhoi - rhoj;
    if constexpr (D == DensityDiffusion::fourtakas) {
      jump -= a.hydrostatic.difference(-dz);
      jump_back -= a.hydrostatic.difference(dz);
    }
    rate_i += density_diffusion_pair(a.delta_h_c0, f, jump, vj);
    rate_j += density_diffusion_pair(a.delta_h_c0, f, jump_back, vi);
  }
  const double rho_sum = rhoi + rhoj;
  const double inv = 1.0 / ((r2 + a.eta2) * rho_sum);
  const double approach = v_dot_r < 0.0 ? v_dot_r * inv : 0.0;
  visc = std::max(visc, -a.h * rho_sum * approach);
  const double p_sum = a.p[i] + a.p[j];
  double si = -vj * p_sum * a.inv_rho[i], sj = vi * p_sum * a.inv_rho[j];
  if constexpr (V == Viscosity::artificial) {
    const double pi_ij = artificial_viscosity_pair(a.alpha_c0_h, approach);
    si -= mj * pi_ij;
    sj += mi * pi_ij;
  }
  double axi = si * gx, azi = si * gz, axj = sj * gx, azj = sj * gz;
  if constexpr (V == Viscosity::laminar_sps) {
    const double lam = laminar_viscosity_pair(a.nu0, f, r2, inv);
    const double sxx = a.sxx[i] + a.sxx[j], sxz = a.sxz[i] + a.sxz[j], szz = a.szz[i] + a.szz[j];
    const double tx = sxx * gx + sxz * gz, tz = sxz * gx + szz * gz;
    axi += mj * (lam * du + tx);
    azi += mj * (lam * dw + tz);
    axj -= mi * (lam * du + tx);
    azj -= mi * (lam * dw + tz);
    own.grad[0] -= vj * du * gx;
    own.grad[1] -= vj * du * gz;
    own.grad[2] -= vj * dw * gx;
    own.grad[3] -= vj * dw * gz;
    if constexpr (Both) {
      double* gj = a.grad + 4 * static_cast<std::size_t>(j);
      gj[0] -= vi * du * gx;
      gj[1] -= vi * du * gz;
      gj[2] -= vi * dw * gx;
      gj[3] -= vi * dw * gz;
    }
  }
  own.d += rate_i;
  own.ax += axi;
  own.az += azi;
  if constexpr (Both) {
    a.drho[j] += rate_j;
    a.ax[j] += axj;
    a.az[j] += azj;
  }
}

// Fluid particle i and wall particle b at offset (dx, dz) = r_i - r_b, r2 < support^2, F = f.
template <Viscosity V>
inline void fluid_wall_pair(const PairArrays& a, int i, int b, double dx, double dz, double r2, double f, OwnSums& own, double& visc) {
  if (a.nearest_wall_needed && r2 < a.nearest_r2[i]) {
    a.nearest_r2[i] = r2;
    a.nearest[i] = b;
    a.nearest_dx[i] = dx;
    a.nearest_dz[i] = dz;
  }
  const double gx = f * dx, gz = f * dz;
  const double du = a.u[i] - a.u[b], dw = a.w[i] - a.w[b];
  const double v_dot_r = du * dx + dw * dz;
  const double mb = a.m[b], rho_sum = a.rho[i] + a.rho[b];
  const double dot = du * gx + dw * gz;
  own.d += mb * dot;
  if (a.dbc) a.drho[b] += dbc_density_rate_pair(a.m[i], f, du, dw, -dx, -dz);
  const double inv = 1.0 / ((r2 + a.eta2) * rho_sum);
  const double approach = v_dot_r < 0.0 ? v_dot_r * inv : 0.0;
  visc = std::max(visc, -a.h * rho_sum * approach);
  double s = -a.volume[b] * (a.p[i] + a.p[b]) * a.inv_rho[i];
  if constexpr (V == Viscosity::artificial) s -= a.wall_factor * mb * artificial_viscosity_pair(a.alpha_c0_h, approach);
  double axi = s * gx, azi = s * gz;
  if constexpr (V == Viscosity::laminar_sps) {
    const double du_v = a.u[i] - a.wall_u[b], dw_v = a.w[i] - a.wall_w[b];
    const double lam = laminar_viscosity_pair(a.nu0, f, r2, inv);
    const double sxx = a.sxx[i] + a.sxx[b], sxz = a.sxz[i] + a.sxz[b], szz = a.szz[i] + a.szz[b];
    axi += mb * (lam * du_v + sxx * gx + sxz * gz);
    azi += mb * (lam * dw_v + sxz * gx + szz * gz);
    // Free slip: the gradient sees the slip velocity, so the wall's shear is not sensed; no slip: the
    // wall's own velocity (zero unless moving).
    const double gu = a.free_slip_walls ? du_v : du, gw = a.free_slip_walls ? dw_v : dw;
    const double vb = a.volume[b];
    own.grad[0] -= vb * gu * gx;
    own.grad[1] -= vb * gu * gz;
    own.grad[2] -= vb * gw * gx;
    own.grad[3] -= vb * gw * gz;
  }
  own.ax += axi;
  own.az += azi;
}

// DBC wall b and buffer particle j at offset (dx, dz) = r_j - r_b: the wall's continuity only.
inline void buffer_wall_pair(const PairArrays& a, int j, int b, double dx, double dz, double f) {
  if (a.dbc) a.drho[b] += dbc_density_rate_pair(a.m[j], f, a.u[j] - a.u[b], a.w[j] - a.w[b], -dx, -dz);
}

}  // namespace hydrojump::sph::detail
