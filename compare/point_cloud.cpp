#include "compare/point_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

namespace hydrojump::compare {

InterpolationScheme parse_interpolation_scheme(const std::string& name) {
  if (name == "shepard") return InterpolationScheme::shepard;
  if (name == "mls_linear") return InterpolationScheme::mls_linear;
  throw std::invalid_argument("interpolation scheme \"" + name +
                              "\" is unknown: allowed \"mls_linear\", \"shepard\"");
}

std::string to_string(InterpolationScheme scheme) {
  return scheme == InterpolationScheme::shepard ? "shepard" : "mls_linear";
}

PointCloud2D::PointCloud2D(std::vector<double> x, std::vector<double> z, double bin_size_m)
    : x_(std::move(x)), z_(std::move(z)), bin_(bin_size_m) {
  if (x_.size() != z_.size()) throw std::invalid_argument("PointCloud2D: x and z differ in length");
  if (!(bin_ > 0.0)) throw std::invalid_argument("PointCloud2D: bin size must be > 0");
  if (x_.empty()) return;
  const auto [xmin, xmax] = std::minmax_element(x_.begin(), x_.end());
  const auto [zmin, zmax] = std::minmax_element(z_.begin(), z_.end());
  x0_ = *xmin;
  z0_ = *zmin;
  // Keep the grid bounded even for a wild outlier: at most ~4 million bins.
  const double span = std::max(*xmax - *xmin, *zmax - *zmin);
  if (span / bin_ > 2048.0) bin_ = span / 2048.0;
  nbx_ = static_cast<long>((*xmax - x0_) / bin_) + 1;
  nbz_ = static_cast<long>((*zmax - z0_) / bin_) + 1;
  const std::size_t nb = static_cast<std::size_t>(nbx_ * nbz_);
  std::vector<std::size_t> bin_of(x_.size());
  bin_start_.assign(nb + 1, 0);
  for (std::size_t j = 0; j < x_.size(); ++j) {
    const long ix = std::min(nbx_ - 1, static_cast<long>((x_[j] - x0_) / bin_));
    const long iz = std::min(nbz_ - 1, static_cast<long>((z_[j] - z0_) / bin_));
    bin_of[j] = static_cast<std::size_t>(iz * nbx_ + ix);
    ++bin_start_[bin_of[j] + 1];
  }
  for (std::size_t b = 0; b < nb; ++b) bin_start_[b + 1] += bin_start_[b];
  order_.resize(x_.size());
  std::vector<std::size_t> fill(bin_start_.begin(), bin_start_.end() - 1);
  for (std::size_t j = 0; j < x_.size(); ++j) order_[fill[bin_of[j]]++] = j;
}

std::size_t PointCloud2D::nearest(double x, double z, double max_radius) const {
  std::size_t best = size();
  if (x_.empty()) return best;
  double best_r = std::numeric_limits<double>::infinity();
  for (double radius = bin_; ; radius *= 2.0) {
    const double r_search = std::min(radius, max_radius);
    for_each_within(x, z, r_search, [&](std::size_t j, double, double, double r) {
      if (r < best_r) { best_r = r; best = j; }
    });
    if (best != size() || r_search >= max_radius) break;
  }
  return best;
}

Stencil StencilBuilder::build(InterpolationScheme scheme, double length_scale) const {
  Stencil s;
  const std::size_t n = j_.size();
  if (n == 0) return s;
  s.index = j_;
  s.phi.resize(n);
  double wsum = 0.0;
  for (double w : w_) wsum += w;
  s.weight_sum = wsum;
  if (scheme == InterpolationScheme::mls_linear && n >= 3) {
    // Moment matrix in units scaled by `length_scale`:  M = sum w p p^T,  p = (1, dx/L, dz/L).
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    const double inv_l = 1.0 / length_scale;
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d p(1.0, dx_[k] * inv_l, dz_[k] * inv_l);
      m.noalias() += (w_[k] / wsum) * p * p.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m, Eigen::EigenvaluesOnly);
    const double lmin = eig.eigenvalues()(0);
    const double lmax = eig.eigenvalues()(2);
    if (lmin > 1.0e-6 * lmax) {
      const Eigen::Vector3d c = m.ldlt().solve(Eigen::Vector3d::UnitX());  // M^-1 e1 (M symmetric)
      for (std::size_t k = 0; k < n; ++k) {
        s.phi[k] = (w_[k] / wsum) * (c(0) + c(1) * dx_[k] * inv_l + c(2) * dz_[k] * inv_l);
      }
      s.corrected = true;
      return s;
    }
  }
  for (std::size_t k = 0; k < n; ++k) s.phi[k] = w_[k] / wsum;
  return s;
}

}  // namespace hydrojump::compare
