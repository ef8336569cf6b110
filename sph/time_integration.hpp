// Time integration of the particle state (fluid: position, velocity, density; boundary: density).
//
// Symplectic position-Verlet predictor-corrector (Leimkuhler, Reich & Skeel 1996; as in DualSPHysics,
// Crespo et al. 2015):
//   predictor:  rho^{n+1/2} = rho^n + dt/2 D^n,  v^{n+1/2} = v^n + dt/2 a^n,  r^{n+1/2} = r^n + dt/2 v^n
//   corrector:  v^{n+1} = v^n + dt a^{n+1/2},    r^{n+1} = r^n + dt (v^{n+1} + v^n)/2,
//               rho^{n+1} = rho^n (2 - eps)/(2 + eps),  eps = -(D^{n+1/2} / rho^{n+1/2}) dt
// Verlet (Verlet 1967; Monaghan 1994), with an Euler step every N steps to keep the two
// interleaved solutions together:
//   v^{n+1} = v^{n-1} + 2 dt a^n,  rho^{n+1} = rho^{n-1} + 2 dt D^n,  r^{n+1} = r^n + dt v^n + dt^2/2 a^n
//   Euler:   v^{n+1} = v^n + dt a^n,  rho^{n+1} = rho^n + dt D^n
// DBC boundary particles (Crespo et al. 2007) integrate density only and never go below rho0.
//
// Variable time step (Monaghan & Kos 1999; DualSPHysics):
//   dt = CFL min(dt_f, dt_cv),  dt_f = min_i sqrt(h / |a_i|),
//   dt_cv = h / (c0 + max_ij h |v_ij.r_ij| / (r_ij^2 + eta^2))  (over approaching pairs),
// and with laminar + SPS viscosity also dt <= 0.125 h^2 / (nu0 + max_i nu_t,i) (Morris, Fox & Zhu
// 1997; nu_t the SPS eddy viscosity, which diffuses momentum as nu0 does).
//
// Usage:
//   | sph.time_integrator | interactions per step | notes                                        |
//   |---------------------|-----------------------|----------------------------------------------|
//   | "symplectic"        | 2                     | default, second order, time reversible       |
//   | "verlet"            | 1                     | sph.verlet_euler_interval: 1-1000, default 40|
//   | spec key            | range   | default | meaning                                            |
//   |---------------------|---------|---------|----------------------------------------------------|
//   | sph.cfl_number      | (0, 1)  | 0.2     | CFL in dt = CFL min(dt_f, dt_cv)                   |
// Example (spec): `[sph]  time_integrator = "verlet"   verlet_euler_interval = 40   cfl_number = 0.2`
#pragma once

#include "sph/interactions.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {

// The step size from the last interactions (the conditions above).
double variable_time_step(const InteractionSummary& summary, const SolverSettings& s);

// The symplectic scheme's half step and full step (the equations above; fluid and DBC walls).
void symplectic_predictor(ParticleSet& ps, const SolverSettings& s, double dt);
void symplectic_corrector(ParticleSet& ps, const SolverSettings& s, double dt);
// One Verlet step, or the Euler step that every verlet_euler_interval-th step takes instead.
void verlet_update(ParticleSet& ps, const SolverSettings& s, double dt, bool euler_step);
// Moves fluid particles that crossed the periodic seam back into [x_min, x_max).
void wrap_periodic(ParticleSet& ps, const SolverSettings& s);

}  // namespace hydrojump::sph
