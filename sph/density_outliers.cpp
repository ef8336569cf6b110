#include "sph/density_outliers.hpp"

#include "sph/open_boundaries.hpp"
#include "sph/particle_health.hpp"

namespace hydrojump::sph {

DensityOutliers remove_density_outliers(ParticleSet& particles, const SolverSettings& settings) {
  DensityOutliers out;
  const double rho0 = settings.eos.rho0;
  const Eigen::Index n = particles.size();
  std::vector<char> remove;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!particles.is_fluid(i) || !is_density_outlier(particles.rho[i], rho0)) continue;
    const FluidHealth health = fluid_health(particles, i, settings);
    if (health != FluidHealth::ok && health != FluidHealth::density) continue;
    if (remove.empty()) remove.assign(static_cast<std::size_t>(n), 0);
    remove[static_cast<std::size_t>(i)] = 1;
    ++out.particles;
    out.mass += particles.mass[i];
    out.x_m.push_back(particles.x[i]);
    out.mass_kg.push_back(particles.mass[i]);
  }
  if (out.particles > 0) remove_particles(particles, remove);
  return out;
}

}  // namespace hydrojump::sph
