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
//   strain rate: G_i += -V_j (v_x g_x, v_z g_z, v_x g_z + v_z g_x)   G_j likewise with V_i
//                (du/dx, dw/dz and du/dz + dw/dx: all the SPS stress reads of grad v)
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

// The model's constants of the pair terms.
struct PairModel {
  double support2 = 0.0, eta2 = 0.0, h = 0.0, alpha_c0_h = 0.0, wall_factor = 0.0, delta_h_c0 = 0.0, nu0 = 0.0;
  HydrostaticDensity hydrostatic{0.0, 1.0, 0.0};
  bool free_slip_walls = false, nearest_wall_needed = false, dbc = false;
};

// The particle arrays the pair terms read and write, and the model.
struct PairArrays {
  const double *x = nullptr, *z = nullptr, *u = nullptr, *w = nullptr, *rho = nullptr, *p = nullptr, *m = nullptr;
  const double *volume = nullptr, *inv_rho = nullptr, *sxx = nullptr, *sxz = nullptr, *szz = nullptr;
  const double *wall_u = nullptr, *wall_w = nullptr;
  double *drho = nullptr, *ax = nullptr, *az = nullptr;
  double* grad = nullptr;  // laminar_sps: 3 per particle (du/dx, dw/dz, du/dz + dw/dx); else none
  double *nearest_r2 = nullptr, *nearest_dx = nullptr, *nearest_dz = nullptr;
  int* nearest = nullptr;
  PairModel model;
};

// One particle's values the pair terms read. The pair loop reads particle i's once for all its pairs
// and keeps the model in a local copy: the compiler cannot tell that the terms it stores to the arrays
// leave them unchanged, and would read them again after every pair.
struct PairParticle {
  double x = 0.0, z = 0.0, u = 0.0, w = 0.0, m = 0.0, volume = 0.0, rho = 0.0, p = 0.0, inv_rho = 0.0;
  double sxx = 0.0, sxz = 0.0, szz = 0.0;  // laminar_sps only
};

template <Viscosity V>
inline PairParticle pair_particle(const PairArrays& a, int i) {
  PairParticle q{a.x[i], a.z[i], a.u[i], a.w[i], a.m[i], a.volume[i], a.rho[i], a.p[i], a.inv_rho[i]};
  if constexpr (V == Viscosity::laminar_sps) q.sxx = a.sxx[i], q.sxz = a.sxz[i], q.szz = a.szz[i];
  return q;
}

// A pair's offset (dx, dz) = r_i - r_j (periodic image of j), r2 = |r_ij|^2 < support^2 and F(|r_ij|).
struct PairGeometry {
  double dx, dz, r2, f;
  PairGeometry reversed() const { return {-dx, -dz, r2, f}; }
};

// What particle i gathers over the pairs the loop meets from it, added to its arrays once after them
// (add_to); j's terms go to the arrays at once.
struct OwnSums {
  double d = 0.0, ax = 0.0, az = 0.0, grad[3] = {0.0, 0.0, 0.0};
  void add_to(const PairArrays& a, int i) const {
    a.drho[i] += d;
    a.ax[i] += ax;
    a.az[i] += az;
    if (a.grad != nullptr)
      for (int k = 0; k < 3; ++k) a.grad[3 * static_cast<std::size_t>(i) + k] += grad[k];
  }
};

// Fluid particle i (values pi) and fluid-side particle j (fluid or, with Both = false, a buffer
// particle that receives nothing).
template <Viscosity V, DensityDiffusion D, bool Both>
[[gnu::always_inline]] inline void fluid_pair(const PairArrays& a, const PairModel& c, const PairParticle& pi, int j, const PairGeometry& r,
                                              OwnSums& own, double& visc) {
  const double dx = r.dx, dz = r.dz, r2 = r.r2, f = r.f;
  const double gx = f * dx, gz = f * dz;
  const double du = pi.u - a.u[j], dw = pi.w - a.w[j];
  const double v_dot_r = du * dx + dw * dz;
  const double mi = pi.m, mj = a.m[j], vi = pi.volume, vj = a.volume[j];
  const double rhoi = pi.rho, rhoj = a.rho[j];
  const double dot = du * gx + dw * gz;
  double rate_i = mj * dot, rate_j = mi * dot;
  if constexpr (D != DensityDiffusion::none) {
    double jump = rhoj - rhoi, jump_back = rhoi - rhoj;
    if constexpr (D == DensityDiffusion::fourtakas) {
      jump -= c.hydrostatic.difference(-dz);
      jump_back -= c.hydrostatic.difference(dz);
    }
    rate_i += density_diffusion_pair(c.delta_h_c0, f, jump, vj);
    rate_j += density_diffusion_pair(c.delta_h_c0, f, jump_back, vi);
  }
  const double rho_sum = rhoi + rhoj;
  const double inv = 1.0 / ((r2 + c.eta2) * rho_sum);
  const double approach = v_dot_r < 0.0 ? v_dot_r * inv : 0.0;
  visc = std::max(visc, -c.h * rho_sum * approach);
  const double p_sum = pi.p + a.p[j];
  double si = -vj * p_sum * pi.inv_rho, sj = vi * p_sum * a.inv_rho[j];
  if constexpr (V == Viscosity::artificial) {
    const double pi_ij = artificial_viscosity_pair(c.alpha_c0_h, approach);
    si -= mj * pi_ij;
    sj += mi * pi_ij;
  }
  double axi = si * gx, azi = si * gz, axj = sj * gx, azj = sj * gz;
  if constexpr (V == Viscosity::laminar_sps) {
    const double lam = laminar_viscosity_pair(c.nu0, f, r2, inv);
    const double sxx = pi.sxx + a.sxx[j], sxz = pi.sxz + a.sxz[j], szz = pi.szz + a.szz[j];
    const double tx = sxx * gx + sxz * gz, tz = sxz * gx + szz * gz;
    axi += mj * (lam * du + tx);
    azi += mj * (lam * dw + tz);
    axj -= mi * (lam * du + tx);
    azj -= mi * (lam * dw + tz);
    const double sx = du * gx, sz = dw * gz, shear = du * gz + dw * gx;
    own.grad[0] -= vj * sx;
    own.grad[1] -= vj * sz;
    own.grad[2] -= vj * shear;
    if constexpr (Both) {
      double* gj = a.grad + 3 * static_cast<std::size_t>(j);
      gj[0] -= vi * sx;
      gj[1] -= vi * sz;
      gj[2] -= vi * shear;
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
  if (a.model.nearest_wall_needed && r2 < a.nearest_r2[i]) {
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
  if (a.model.dbc) a.drho[b] += dbc_density_rate_pair(a.m[i], f, du, dw, -dx, -dz);
  const double inv = 1.0 / ((r2 + a.model.eta2) * rho_sum);
  const double approach = v_dot_r < 0.0 ? v_dot_r * inv : 0.0;
  visc = std::max(visc, -a.model.h * rho_sum * approach);
  double s = -a.volume[b] * (a.p[i] + a.p[b]) * a.inv_rho[i];
  if constexpr (V == Viscosity::artificial) s -= a.model.wall_factor * mb * artificial_viscosity_pair(a.model.alpha_c0_h, approach);
  double axi = s * gx, azi = s * gz;
  if constexpr (V == Viscosity::laminar_sps) {
    const double du_v = a.u[i] - a.wall_u[b], dw_v = a.w[i] - a.wall_w[b];
    const double lam = laminar_viscosity_pair(a.model.nu0, f, r2, inv);
    const double sxx = a.sxx[i] + a.sxx[b], sxz = a.sxz[i] + a.sxz[b], szz = a.szz[i] + a.szz[b];
    axi += mb * (lam * du_v + sxx * gx + sxz * gz);
    azi += mb * (lam * dw_v + sxz * gx + szz * gz);
    // Free slip: the gradient sees the slip velocity, so the wall's shear is not sensed; no slip: the
    // wall's own velocity (zero unless moving).
    const double gu = a.model.free_slip_walls ? du_v : du, gw = a.model.free_slip_walls ? dw_v : dw;
    const double vb = a.volume[b];
    own.grad[0] -= vb * gu * gx;
    own.grad[1] -= vb * gw * gz;
    own.grad[2] -= vb * (gu * gz + gw * gx);
  }
  own.ax += axi;
  own.az += azi;
}

// DBC wall b and buffer particle j at offset (dx, dz) = r_j - r_b: the wall's continuity only.
inline void buffer_wall_pair(const PairArrays& a, int j, int b, double dx, double dz, double f) {
  if (a.model.dbc) a.drho[b] += dbc_density_rate_pair(a.m[j], f, a.u[j] - a.u[b], a.w[j] - a.w[b], -dx, -dz);
}

}  // namespace hydrojump::sph::detail
