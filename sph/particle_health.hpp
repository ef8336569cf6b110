// Whether a fluid particle is in a state the run may carry on from: the run's check (diagnose() in
// sph/run.hpp) names the particles that are not and stops the run, keeping its last good checkpoint;
// the solver leaves the open boundaries alone in a step that produced one, so that an unhealthy
// particle at the outlet is diagnosed rather than drained as outflow (the outflow buffer resets the
// velocity and density of what it takes, and removes it).
//
//   | health      | condition (fluid particle i)                                          |
//   |-------------|-----------------------------------------------------------------------|
//   | non_finite  | x, z, u, w or rho NaN or infinite                                     |
//   | below_bed   | z < z_min - margin (through the bed's boundary particles)             |
//   | outside     | x outside [x_min, x_max] or z above fluid_ceiling, by more than margin |
//   | density     | |rho / rho0 - 1| > sph.max_density_variation                          |
//   | ok          | none of these                                                         |
// (margin = SolverSettings::domain_margin.) A particle whose density left [0.7, 1.3] rho0 is removed
// by the step itself (sph/density_outliers.hpp), so the density check stops a run only below that.
// Example:
//   if (fluid_health(particles, i, settings) != FluidHealth::ok) ...
#pragma once

#include <cmath>

#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {

enum class FluidHealth { ok, non_finite, below_bed, outside, density };

inline FluidHealth fluid_health(const ParticleSet& ps, Eigen::Index i, const SolverSettings& s) {
  if (!std::isfinite(ps.x[i]) || !std::isfinite(ps.z[i]) || !std::isfinite(ps.u[i]) || !std::isfinite(ps.w[i]) ||
      !std::isfinite(ps.rho[i]))
    return FluidHealth::non_finite;
  const double m = s.domain.margin;
  if (ps.z[i] < s.domain.z_min - m) return FluidHealth::below_bed;
  if (ps.x[i] < s.domain.x_min - m || ps.x[i] > s.domain.x_max + m || ps.z[i] > s.domain.fluid_ceiling + m) return FluidHealth::outside;
  if (std::abs(ps.rho[i] / s.eos.rho0 - 1.0) > s.density.max_variation) return FluidHealth::density;
  return FluidHealth::ok;
}

// Whether every fluid particle is healthy.
inline bool all_fluid_healthy(const ParticleSet& ps, const SolverSettings& s) {
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i) && fluid_health(ps, i, s) != FluidHealth::ok) return false;
  return true;
}

}  // namespace hydrojump::sph
