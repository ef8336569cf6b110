#include "sph/piston_inflow.hpp"

namespace hydrojump::sph {

// M_up = sum_i m_i over the fluid with x_i < x_in
double GateCrossing::upstream_mass(const ParticleSet& particles) const {
  double m = 0.0;
  for (Eigen::Index i = 0; i < particles.size(); ++i)
    if (particles.is_fluid(i) && particles.x[i] < x_in_) m += particles.mass[i];
  return m;
}

void GateCrossing::start(const ParticleSet& particles) { upstream_ = upstream_mass(particles); }

// m_in += M_up(before) - M_up(now)
double GateCrossing::advance(const ParticleSet& particles) {
  const double now = upstream_mass(particles);
  const double crossed = upstream_ - now;
  upstream_ = now;
  mass_in_ += crossed;
  return crossed;
}

}  // namespace hydrojump::sph
