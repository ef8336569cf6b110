#include "sph/tailgate.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "sph/open_boundaries.hpp"

namespace hydrojump::sph {

Tailgate::Tailgate(const cases::OutflowBoundary& outflow, double bed_z, double crest_height, double thickness)
    : x_g_(outflow.x_m), bed_z_(bed_z), height_(crest_height), thickness_(thickness) {
  if (!(crest_height > 0.0))
    throw std::invalid_argument("tailgate: the crest height must be positive (got " + std::to_string(crest_height) +
                                " m; sph.tailgate_height_m)");
  if (!(thickness > 0.0)) throw std::invalid_argument("tailgate: the plate thickness must be positive");
}

cases::WallPolyline Tailgate::plate() const {
  const double zc = crest_z();
  return {"tailgate",
          {cases::Vec2(x_g_, bed_z_), cases::Vec2(x_g_, zc), cases::Vec2(x_g_ + thickness_, zc),
           cases::Vec2(x_g_ + thickness_, bed_z_)}};
}

double Tailgate::advance(ParticleSet& particles) {
  constexpr auto fluid_code = static_cast<std::uint8_t>(ParticleType::fluid);
  const double x_end = x_g_ + thickness_;
  const Eigen::Index n = particles.size();
  std::vector<char> remove;
  double mass = 0.0;
  std::int64_t count = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (particles.type[i] != fluid_code || !(particles.x[i] > x_end)) continue;
    if (remove.empty()) remove.assign(static_cast<std::size_t>(n), 0);
    remove[static_cast<std::size_t>(i)] = 1;
    mass += particles.mass[i];
    ++count;
  }
  if (count > 0) remove_particles(particles, remove);
  mass_removed_ += mass;
  particles_removed_ += count;
  return mass;
}

}  // namespace hydrojump::sph
