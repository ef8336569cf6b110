// The SPH smoothing kernel used by the comparator to interpolate particle data onto sections: a thin,
// name-checked wrapper over the SPH solver's own kernels (sph/kernel.hpp, header-only structs), so both
// sides evaluate the identical function. Support radius 2h; h = coef_h sqrt(2) dx.
//
//   Wendland C2 (Wendland 1995; "quintic" in SPHysics/DualSPHysics), q = r/h, 0 <= q <= 2:
//     W(q) = 7/(4 pi h^2) (1 - q/2)^4 (2 q + 1)
//   Cubic spline (Monaghan & Lattanzio 1985), q = r/h:
//     W(q) = 10/(7 pi h^2) (1 - 3/2 q^2 + 3/4 q^3)   0 <= q < 1
//          = 10/(7 pi h^2) (2 - q)^3 / 4              1 <= q < 2
#pragma once

#include <stdexcept>
#include <string>

#include "sph/kernel.hpp"

namespace hydrojump::compare {

class SphKernel2D {
 public:
  // `name` is "wendland_c2" or "cubic_spline"; anything else is rejected with the allowed names.
  SphKernel2D(const std::string& name, double smoothing_length_m)
      : h_(smoothing_length_m), wendland_kernel_(smoothing_length_m), cubic_kernel_(smoothing_length_m) {
    if (!(smoothing_length_m > 0.0))
      throw std::invalid_argument("SPH kernel: smoothing length must be > 0, got " +
                                  std::to_string(smoothing_length_m));
    wendland_ = sph::parse_kernel(name) == sph::KernelType::wendland_c2;
  }

  double smoothing_length() const { return h_; }
  double support_radius() const { return 2.0 * h_; }

  // W(r) for a distance r >= 0.
  double operator()(double r) const { return wendland_ ? wendland_kernel_.value(r) : cubic_kernel_.value(r); }

 private:
  double h_ = 0.0;
  sph::WendlandC2 wendland_kernel_;
  sph::CubicSpline cubic_kernel_;
  bool wendland_ = true;
};

// Wendland C2 shape with support radius R and W(0) = 1 (unnormalised), used as a distance weight.
inline double wendland_weight(double r, double support_radius) {
  const double q = r / support_radius;
  if (q >= 1.0) return 0.0;
  const double a = 1.0 - q;
  const double a2 = a * a;
  return a2 * a2 * (4.0 * q + 1.0);
}

}  // namespace hydrojump::compare
