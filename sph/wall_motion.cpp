#include "sph/wall_motion.hpp"

#include <algorithm>
#include <limits>

namespace hydrojump::sph {

// |[t0, t1] n [start, end)|
double WallMotion::moving_time(double t0, double t1) const {
  return std::max(0.0, std::min(t1, end_s) - std::max(t0, start_s));
}

double moving_face_x(const ParticleSet& particles) {
  constexpr auto moving = static_cast<std::uint8_t>(ParticleType::moving_wall);
  double face = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < particles.size(); ++i)
    if (particles.type[i] == moving) face = std::max(face, particles.x[i] + 0.5 * particles.ghost_dx[i]);
  return face;
}

// H = sum_{fluid i, x_i < x_end} (m_i / rho_i) / (x_end - x_face)
double reservoir_level(const ParticleSet& particles, double x_face, double x_end) {
  double volume = 0.0;
  for (Eigen::Index i = 0; i < particles.size(); ++i)
    if (particles.is_fluid(i) && particles.x[i] < x_end) volume += particles.mass[i] / particles.rho[i];
  return x_end > x_face ? volume / (x_end - x_face) : std::numeric_limits<double>::infinity();
}

// u_p = max(0, U_p0 + K (H_r - H))
WallMotion WallMotion::for_step(const ParticleSet& particles) const {
  if (!holds_level()) return *this;
  WallMotion m = *this;
  const double level = reservoir_level(particles, moving_face_x(particles), reservoir_end_x_m);
  m.u_m_s = std::max(0.0, u_m_s + level_gain_per_s * (held_level_m - level));
  m.w_m_s = 0.0;
  return m;
}

// x(t1) = x(t0) + v_wall |[t0, t1] n [start, end)|,  particle velocity (v(t1) . n) n
void move_walls(ParticleSet& particles, const WallMotion& motion, double t0, double t1) {
  if (!motion.any()) return;
  constexpr auto moving = static_cast<std::uint8_t>(ParticleType::moving_wall);
  const double tau = motion.moving_time(t0, t1);
  const bool moving_at_t1 = t1 >= motion.start_s && t1 < motion.end_s;
  const double u = moving_at_t1 ? motion.u_m_s : 0.0, w = moving_at_t1 ? motion.w_m_s : 0.0;
  for (Eigen::Index i = 0; i < particles.size(); ++i) {
    if (particles.type[i] != moving) continue;
    particles.x[i] += motion.u_m_s * tau;
    particles.z[i] += motion.w_m_s * tau;
    // The velocity the fluid sees: the wall-normal part (v . n) n, n along the ghost offset.
    const double nx = particles.ghost_dx[i], nz = particles.ghost_dz[i];
    const double n2 = nx * nx + nz * nz;
    const double vn = n2 > 0.0 ? (u * nx + w * nz) / n2 : 0.0;
    particles.u[i] = vn * nx;
    particles.w[i] = vn * nz;
    // The no-slip velocity of the viscous terms: the same (mDBC replaces it with its mirrored value).
    particles.wall_u[i] = particles.u[i];
    particles.wall_w[i] = particles.w[i];
  }
}

}  // namespace hydrojump::sph
