#include "sph/density_outliers.hpp"

#include <vector>

#include "sph/open_boundaries.hpp"

namespace hydrojump::sph {

DensityOutliers remove_density_outliers(ParticleSet& particles, double rho0) {
  DensityOutliers out;
  const Eigen::Index n = particles.size();
  std::vector<char> remove;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!particles.is_fluid(i) || !is_density_outlier(particles.rho[i], rho0)) continue;
    if (remove.empty()) remove.assign(static_cast<std::size_t>(n), 0);
    remove[static_cast<std::size_t>(i)] = 1;
    ++out.particles;
    out.mass += particles.mass[i];
  }
  if (out.particles > 0) remove_particles(particles, remove);
  return out;
}

}  // namespace hydrojump::sph
