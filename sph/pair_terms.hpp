// The terms particle i takes from a neighbour j in the pair loop (interactions.cpp), which sums them
// over each particle's own list. With r = r_i - r_j (periodic image of j), g = grad_i W_ij = F(r) r
// and v = v_i - v_j:
//
//   continuity:  D_i += m_j v.g
//   diffusion:   D_i += -2 delta h c0 F (rho_j - rho_i - H(z_j - z_i)) V_j   (Fourtakas et al. 2019
//                with the hydrostatic part H, Molteni & Colagrossi 2009 with H = 0)
//   pressure:    a_i += -V_j (p_i + p_j)/rho_i g
//   artificial:  a_i += -m_j Pi_ij g,
//                Pi_ij = -2 alpha c0 h v.r / ((r^2 + eta^2)(rho_i + rho_j)) for v.r < 0 (Monaghan 1992)
//   laminar:     a_i += m_j L v,  L = 4 nu0 F r^2 / ((r^2 + eta^2)(rho_i + rho_j))  (Lo & Shao 2002)
//   SPS stress:  a_i += m_j (S_i + S_j) g,   S = tau / rho^2
//   strain rate: G_i += -V_j (v_x g_x, v_z g_z, v_x g_z + v_z g_x)
//                (du/dx, dw/dz and du/dz + dw/dx: all the SPS stress reads of grad v)
//
// and the viscous time-step rate h |v.r| / (r^2 + eta^2) of an approaching pair. Each term is the
// pair's symmetric form (j takes the same with i and j swapped from its own list), so momentum is
// conserved pairwise. A wall neighbour b enters a fluid particle's viscous terms with its mDBC wall
// velocity, the artificial viscosity with the wall factor, and gives the fluid particle nothing else;
// a DBC wall takes only the continuity (boundary_dbc.hpp). Open-boundary buffer particles act on
// fluid particles as fluid and take nothing.
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

// What particle i gathers over its neighbours, added to its arrays once after them (add_to).
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

// Fluid particle i (values pi) and fluid-side particle j (fluid or buffer): i's terms.
template <Viscosity V, DensityDiffusion D>
[[gnu::always_inline]] inline void fluid_pair(const PairArrays& a, const PairModel& c, const PairParticle& pi, int j, const PairGeometry& r,
                                              OwnSums& own, double& visc) {
  const double dx = r.dx, dz = r.dz, r2 = r.r2, f = r.f;
  const double gx = f * dx, gz = f * dz;
  const double du = pi.u - a.u[j], dw = pi.w - a.w[j];
  const double v_dot_r = du * dx + dw * dz;
  const double mj = a.m[j], vj = a.volume[j];
  const double rhoj = a.rho[j];
  double rate = mj * (du * gx + dw * gz);
  if constexpr (D != DensityDiffusion::none) {
    double jump = rhoj - pi.rho;
    if constexpr (D == DensityDiffusion::fourtakas) jump -= c.hydrostatic.difference(-dz);
    rate += density_diffusion_pair(c.delta_h_c0, f, jump, vj);
  }
  const double rho_sum = pi.rho + rhoj;
  const double inv = 1.0 / ((r2 + c.eta2) * rho_sum);
  const double approach = std::min(v_dot_r, 0.0) * inv;  // 0 unless approaching; no branch (SIMD lanes)
  visc = std::max(visc, -c.h * rho_sum * approach);
  double si = -vj * (pi.p + a.p[j]) * pi.inv_rho;
  if constexpr (V == Viscosity::artificial) si -= mj * artificial_viscosity_pair(c.alpha_c0_h, approach);
  double axi = si * gx, azi = si * gz;
  if constexpr (V == Viscosity::laminar_sps) {
    const double lam = laminar_viscosity_pair(c.nu0, f, r2, inv);
    const double sxx = pi.sxx + a.sxx[j], sxz = pi.sxz + a.sxz[j], szz = pi.szz + a.szz[j];
    axi += mj * (lam * du + sxx * gx + sxz * gz);
    azi += mj * (lam * dw + sxz * gx + szz * gz);
    own.grad[0] -= vj * du * gx;
    own.grad[1] -= vj * dw * gz;
    own.grad[2] -= vj * (du * gz + dw * gx);
  }
  own.d += rate;
  own.ax += axi;
  own.az += azi;
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

}  // namespace hydrojump::sph::detail
