#include "sph/wall_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hydrojump::sph {

namespace {

// A table this large (nodes) means a spacing far below the domain's scale: refused, not allocated.
constexpr double kMaxNodes = 5e7;

}  // namespace

WallDistanceTable WallDistanceTable::tabulate(const ParticleSet& particles, double reach, double spacing, bool periodic_x,
                                              double x_min, double x_max) {
  if (!(reach > 0.0) || !(spacing > 0.0) || !std::isfinite(reach) || !std::isfinite(spacing))
    throw std::invalid_argument("wall distance table: reach (" + std::to_string(reach) + " m) and spacing (" +
                                std::to_string(spacing) + " m) must be positive");
  if (periodic_x && !(x_max > x_min)) throw std::invalid_argument("wall distance table: a periodic domain needs x_max > x_min");
  WallDistanceTable t;
  t.reach_ = reach;
  t.spacing_ = spacing;
  t.periodic_x_ = periodic_x;
  t.period_origin_ = x_min;
  t.period_ = periodic_x ? x_max - x_min : 0.0;

  std::vector<double> wx, wz;
  const auto fixed_wall = static_cast<std::uint8_t>(ParticleType::boundary);
  for (Eigen::Index k = 0; k < particles.size(); ++k) {
    if (particles.type[k] != fixed_wall) continue;
    wx.push_back(particles.x[k]);
    wz.push_back(particles.z[k]);
  }
  if (wx.empty()) return t;  // no fixed wall: every point is at least the reach from one

  // The walls' box grown by the reach; a periodic table spans the whole period, where at() looks up.
  double x_lo = *std::min_element(wx.begin(), wx.end()), x_hi = *std::max_element(wx.begin(), wx.end());
  if (periodic_x) {
    x_lo = std::min(x_lo, x_min);
    x_hi = std::max(x_hi, x_max);
  }
  const auto [z_lo, z_hi] = std::minmax_element(wz.begin(), wz.end());
  t.x0_ = x_lo - reach;
  t.z0_ = *z_lo - reach;
  const double nx = std::ceil((x_hi + reach - t.x0_) / spacing) + 1.0;
  const double nz = std::ceil((*z_hi + reach - t.z0_) / spacing) + 1.0;
  if (nx * nz > kMaxNodes)
    throw std::invalid_argument("wall distance table: " + std::to_string(nx * nz) + " nodes at a spacing of " +
                                std::to_string(spacing) + " m (at most " + std::to_string(kMaxNodes) + ")");
  t.nx_ = static_cast<int>(nx);
  t.nz_ = static_cast<int>(nz);
  t.values_.assign(static_cast<std::size_t>(t.nx_) * static_cast<std::size_t>(t.nz_), reach);

  // Each wall particle (and, in a periodic domain, its images one period away) lowers the nodes
  // within the reach to their distance from it.
  const std::vector<double> shifts = periodic_x ? std::vector<double>{0.0, -t.period_, t.period_} : std::vector<double>{0.0};
  for (std::size_t b = 0; b < wx.size(); ++b) {
    for (const double shift : shifts) {
      const double bx = wx[b] + shift, bz = wz[b];
      const int i0 = std::max(0, static_cast<int>(std::floor((bx - reach - t.x0_) / spacing)));
      const int i1 = std::min(t.nx_ - 1, static_cast<int>(std::ceil((bx + reach - t.x0_) / spacing)));
      const int k0 = std::max(0, static_cast<int>(std::floor((bz - reach - t.z0_) / spacing)));
      const int k1 = std::min(t.nz_ - 1, static_cast<int>(std::ceil((bz + reach - t.z0_) / spacing)));
      for (int k = k0; k <= k1; ++k) {
        const double dz = t.z0_ + k * spacing - bz;
        double* row = t.values_.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(t.nx_);
        for (int i = i0; i <= i1; ++i) {
          const double dx = t.x0_ + i * spacing - bx;
          row[i] = std::min(row[i], std::sqrt(dx * dx + dz * dz));
        }
      }
    }
  }
  return t;
}

// Bilinear interpolation between the four nodes around (x, z):
//   d = (1-a)(1-b) d_00 + a(1-b) d_10 + (1-a) b d_01 + a b d_11,  a, b the offsets in the cell / spacing.
double WallDistanceTable::at(double x, double z) const {
  if (values_.empty()) return reach_;
  if (periodic_x_) {
    // Into [x_min, x_max), which the table spans with the walls' images around it.
    x = period_origin_ + std::fmod(std::fmod(x - period_origin_, period_) + period_, period_);
  }
  const double fx = (x - x0_) / spacing_, fz = (z - z0_) / spacing_;
  if (!(fx >= 0.0) || !(fz >= 0.0) || fx >= nx_ - 1 || fz >= nz_ - 1) return reach_;
  const int i = static_cast<int>(fx), k = static_cast<int>(fz);
  const double a = fx - i, b = fz - k;
  const double* row0 = values_.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(nx_);
  const double* row1 = row0 + nx_;
  return (1.0 - a) * (1.0 - b) * row0[i] + a * (1.0 - b) * row0[i + 1] + (1.0 - a) * b * row1[i] + a * b * row1[i + 1];
}

}  // namespace hydrojump::sph
