#include "sph/time_integration.hpp"

#include "sph/boundary_dbc.hpp"
#include "sph/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hydrojump::sph {

namespace {
// Walls get DBC density updates; inflow/outflow buffer particles are left to their buffers.
inline bool is_wall(const ParticleSet& ps, Eigen::Index i) { return is_wall_type(ps.type[i]); }
}  // namespace

// Monaghan & Kos (1999), as in DualSPHysics:
//   dt = CFL min(dt_f, dt_cv),  dt_f = sqrt(h / max|a_i|),  dt_cv = h / (c0 + max_ij h |v_ij.r_ij| / (r_ij^2 + eta^2)),
// the max over approaching pairs (v_ij.r_ij < 0), the only ones the artificial viscosity acts on.
// With laminar + SPS viscosity also the explicit-diffusion bound of Morris, Fox & Zhu (1997), with the
// eddy viscosity of the SPS stress in it (the stress acts as a diffusion of momentum with nu0 + nu_t):
//   dt <= 0.125 h^2 / (nu0 + max nu_t).
double variable_time_step(const InteractionSummary& summary, const SolverSettings& s) {
  const double dt_f = summary.max_acceleration > 0.0 ? std::sqrt(s.h / summary.max_acceleration)
                                                     : std::numeric_limits<double>::infinity();
  const double dt_cv = s.h / (s.eos.c0 + summary.max_viscous_rate);
  double dt = s.time.cfl * std::min(dt_f, dt_cv);
  if (s.viscosity.model == Viscosity::laminar_sps) {
    const double diffusivity = s.viscosity.kinematic_viscosity + summary.max_eddy_viscosity;
    if (diffusivity > 0.0) dt = std::min(dt, 0.125 * s.h * s.h / diffusivity);
  }
  return dt;
}

// Fluid:  rho^{n+1/2} = rho^n + dt/2 D^n,  r^{n+1/2} = r^n + dt/2 v^n,  v^{n+1/2} = v^n + dt/2 a^n;
// DBC walls:  rho_b^{n+1/2} = max(rho0, rho_b^n + dt/2 D_b^n).  Saves the state at n for the corrector.
void symplectic_predictor(ParticleSet& ps, const SolverSettings& s, double dt) {
  const Eigen::Index n = ps.size();
  const bool dbc = s.boundary == BoundaryMethod::dbc;
  const double half = 0.5 * dt, rho0 = s.eos.rho0;
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    ps.x_old[i] = ps.x[i];
    ps.z_old[i] = ps.z[i];
    ps.u_old[i] = ps.u[i];
    ps.w_old[i] = ps.w[i];
    ps.rho_old[i] = ps.rho[i];
    if (ps.is_fluid(i)) {
      ps.rho[i] += half * ps.drho[i];
      ps.x[i] += half * ps.u[i];
      ps.z[i] += half * ps.w[i];
      ps.u[i] += half * ps.ax[i];
      ps.w[i] += half * ps.az[i];
    } else if (dbc && is_wall(ps, i)) {
      ps.rho[i] = dbc_wall_density(ps.rho[i] + half * ps.drho[i], rho0);
    }
  }
  wrap_periodic(ps, s);
}

// Fluid:  v^{n+1} = v^n + dt a^{n+1/2},  r^{n+1} = r^n + dt (v^{n+1} + v^n)/2,
//         rho^{n+1} = rho^n (2 - eps)/(2 + eps),  eps = -(D^{n+1/2} / rho^{n+1/2}) dt;
// DBC walls: the same density update, never below rho0.
void symplectic_corrector(ParticleSet& ps, const SolverSettings& s, double dt) {
  const Eigen::Index n = ps.size();
  const bool dbc = s.boundary == BoundaryMethod::dbc;
  const double rho0 = s.eos.rho0;
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool fluid = ps.is_fluid(i);
    if (!fluid && !(dbc && is_wall(ps, i))) continue;
    const double eps = -(ps.drho[i] / ps.rho[i]) * dt;
    double rho_new = ps.rho_old[i] * (2.0 - eps) / (2.0 + eps);
    if (!fluid) {
      ps.rho[i] = dbc_wall_density(rho_new, rho0);
      continue;
    }
    ps.rho[i] = rho_new;
    const double u_new = ps.u_old[i] + dt * ps.ax[i];
    const double w_new = ps.w_old[i] + dt * ps.az[i];
    ps.x[i] = ps.x_old[i] + dt * 0.5 * (u_new + ps.u_old[i]);
    ps.z[i] = ps.z_old[i] + dt * 0.5 * (w_new + ps.w_old[i]);
    ps.u[i] = u_new;
    ps.w[i] = w_new;
  }
  wrap_periodic(ps, s);
}

// Verlet:  v^{n+1} = v^{n-1} + 2 dt a^n,  rho^{n+1} = rho^{n-1} + 2 dt D^n,  r^{n+1} = r^n + dt v^n + dt^2/2 a^n;
// Euler step (euler_step):  v^{n+1} = v^n + dt a^n,  rho^{n+1} = rho^n + dt D^n  (same r update).
// DBC walls: density only, never below rho0.
void verlet_update(ParticleSet& ps, const SolverSettings& s, double dt, bool euler_step) {
  const Eigen::Index n = ps.size();
  const bool dbc = s.boundary == BoundaryMethod::dbc;
  const double rho0 = s.eos.rho0;
  const double dt2 = 2.0 * dt, half_dt2 = 0.5 * dt * dt;
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool fluid = ps.is_fluid(i);
    if (!fluid && !(dbc && is_wall(ps, i))) continue;
    const double rho_new = euler_step ? ps.rho[i] + dt * ps.drho[i] : ps.rho_old[i] + dt2 * ps.drho[i];
    ps.rho_old[i] = ps.rho[i];
    if (!fluid) {
      ps.rho[i] = dbc_wall_density(rho_new, rho0);
      continue;
    }
    ps.rho[i] = rho_new;
    const double u_new = euler_step ? ps.u[i] + dt * ps.ax[i] : ps.u_old[i] + dt2 * ps.ax[i];
    const double w_new = euler_step ? ps.w[i] + dt * ps.az[i] : ps.w_old[i] + dt2 * ps.az[i];
    ps.x[i] += dt * ps.u[i] + half_dt2 * ps.ax[i];
    ps.z[i] += dt * ps.w[i] + half_dt2 * ps.az[i];
    ps.u_old[i] = ps.u[i];
    ps.w_old[i] = ps.w[i];
    ps.u[i] = u_new;
    ps.w[i] = w_new;
  }
  wrap_periodic(ps, s);
}

// x -> x - P floor((x - x_min) / P),  P = x_max - x_min, for fluid that crossed the periodic seam.
void wrap_periodic(ParticleSet& ps, const SolverSettings& s) {
  if (!s.domain.periodic_x) return;
  const double period = s.domain.x_max - s.domain.x_min;
  for (Eigen::Index i = 0; i < ps.size(); ++i) {
    if (!ps.is_fluid(i) || !std::isfinite(ps.x[i])) continue;
    if (ps.x[i] >= s.domain.x_min && ps.x[i] < s.domain.x_max) continue;
    const double shift = period * std::floor((ps.x[i] - s.domain.x_min) / period);
    ps.x[i] -= shift;
    ps.x_old[i] -= shift;
    if (ps.x[i] >= s.domain.x_max) ps.x[i] = s.domain.x_min;  // round-off at the seam
  }
}

}  // namespace hydrojump::sph
