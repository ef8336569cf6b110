// Scattered 2D data (SPH particles or VOF cell centres) with a bin grid for radius queries, and the
// interpolation weights used to carry their values to arbitrary points.
//
// Two interpolation schemes (selected by name, unknown names rejected):
//   "shepard"     zeroth-order Shepard normalisation (Shepard 1968; the standard SPH interpolation):
//                   f(x) = sum_j w_j f_j / sum_j w_j
//                 exact for constant fields only (error O(h |grad f|) near a free surface or wall).
//   "mls_linear"  first-order moving least squares (Lancaster & Salkauskas 1981; for SPH the linear
//                 correction of the Shepard estimate, Bonet & Lok 1999):
//                   f(x) = sum_j phi_j f_j,  phi_j = w_j e1^T M^-1 p_j,  p_j = (1, x_j - x, z_j - z),
//                   M = sum_j w_j p_j p_j^T,
//                 exact for linear fields wherever the neighbours are not collinear; falls back to
//                 Shepard where M is ill-conditioned (fewer than 3 usable neighbours).
// The weights w_j are supplied by the caller (SPH: V_j W(|x - x_j|, h); VOF: A_j * distance weight).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace hydrojump::compare {

enum class InterpolationScheme { shepard, mls_linear };

// Parses "shepard" | "mls_linear"; throws std::invalid_argument naming the allowed values.
InterpolationScheme parse_interpolation_scheme(const std::string& name);
std::string to_string(InterpolationScheme scheme);

// Positions in the (x, z) plane with a uniform bin grid for neighbour queries.
class PointCloud2D {
 public:
  PointCloud2D() = default;
  // `bin_size_m` should be about the largest query radius.
  PointCloud2D(std::vector<double> x, std::vector<double> z, double bin_size_m);

  std::size_t size() const { return x_.size(); }
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& z() const { return z_; }

  // Calls f(j, dx, dz, r) for every point j with r = |p_j - (x, z)| < radius, dx = x_j - x.
  template <class F>
  void for_each_within(double x, double z, double radius, F&& f) const;

  // Index of the point nearest to (x, z) searching up to `max_radius`; size() if none.
  std::size_t nearest(double x, double z, double max_radius) const;

 private:
  std::vector<double> x_, z_;
  double bin_ = 1.0;
  double x0_ = 0.0, z0_ = 0.0;
  long nbx_ = 0, nbz_ = 0;
  std::vector<std::size_t> bin_start_;   // CSR: points of bin b are order_[bin_start_[b] .. [b+1])
  std::vector<std::size_t> order_;
};

// Interpolation weights phi_j of one query point.
struct Stencil {
  std::vector<std::size_t> index;
  std::vector<double> phi;
  double weight_sum = 0.0;     // sum of the raw weights w_j (SPH: the kernel sum of volumes)
  bool corrected = false;      // true when the linear MLS correction was applied

  bool empty() const { return index.empty(); }
  // sum_j phi_j values[index_j]
  double apply(const std::vector<double>& values) const {
    double s = 0.0;
    for (std::size_t k = 0; k < index.size(); ++k) s += phi[k] * values[index[k]];
    return s;
  }
};

// Builds the stencil at (x, z) from neighbours with raw weights w_j: the caller gathers (j, dx, dz, w)
// and this turns them into Shepard or MLS weights.
class StencilBuilder {
 public:
  void clear() { j_.clear(); dx_.clear(); dz_.clear(); w_.clear(); }
  void add(std::size_t j, double dx, double dz, double w) {
    if (w <= 0.0) return;
    j_.push_back(j); dx_.push_back(dx); dz_.push_back(dz); w_.push_back(w);
  }
  // `length_scale` (h or a cell size) makes the moment matrix dimensionless for the conditioning test.
  Stencil build(InterpolationScheme scheme, double length_scale) const;

 private:
  std::vector<std::size_t> j_;
  std::vector<double> dx_, dz_, w_;
};

// ---- implementation of the template ----
template <class F>
void PointCloud2D::for_each_within(double x, double z, double radius, F&& f) const {
  if (x_.empty()) return;
  const long ix0 = static_cast<long>((x - radius - x0_) / bin_);
  const long ix1 = static_cast<long>((x + radius - x0_) / bin_);
  const long iz0 = static_cast<long>((z - radius - z0_) / bin_);
  const long iz1 = static_cast<long>((z + radius - z0_) / bin_);
  const double r2max = radius * radius;
  for (long iz = iz0 < 0 ? 0 : iz0; iz <= iz1 && iz < nbz_; ++iz) {
    for (long ix = ix0 < 0 ? 0 : ix0; ix <= ix1 && ix < nbx_; ++ix) {
      const std::size_t b = static_cast<std::size_t>(iz * nbx_ + ix);
      for (std::size_t k = bin_start_[b]; k < bin_start_[b + 1]; ++k) {
        const std::size_t j = order_[k];
        const double dx = x_[j] - x;
        const double dz = z_[j] - z;
        const double r2 = dx * dx + dz * dz;
        if (r2 < r2max) f(j, dx, dz, std::sqrt(r2));
      }
    }
  }
}

}  // namespace hydrojump::compare
