// SPH smoothing kernels in 2D, with support radius 2h and h = coef_h * sqrt(2) * dx.
//
// Wendland C2 ("quintic" in DualSPHysics; Wendland 1995, Adv. Comput. Math. 4:389-396):
//   W(q) = 7/(4 pi h^2) (1 - q/2)^4 (2q + 1),            0 <= q = r/h <= 2
// Cubic spline (Monaghan & Lattanzio 1985, Astron. Astrophys. 149:135-143):
//   W(q) = 10/(7 pi h^2) (1 - 3/2 q^2 + 3/4 q^3),         0 <= q < 1
//        = 10/(7 pi h^2) 1/4 (2 - q)^3,                   1 <= q < 2
//
// Gradients are returned as a factor F(r) with  grad_i W(r_ij) = F(r) (r_i - r_j),  F = W'(r)/r,
// which is what the interaction loop needs (no division by r, finite at r = 0).
//
// Usage:
//   | spec key    | value / range    | default         | notes                              |
//   |-------------|------------------|-----------------|------------------------------------|
//   | sph.kernel  | "wendland_c2"    | "wendland_c2"   | Wendland C2; no pairing instability|
//   |             | "cubic_spline"   |                 | classic B-spline                   |
//   | sph.coef_h  | 0.5-3            | 1.0             | h = coef_h sqrt(2) dx              |
// Example (spec): `[sph]  kernel = "wendland_c2"   coef_h = 1.0`
// Example (code): `Kernel k = Kernel::make("wendland_c2", 1.4142 * 0.01);  double w = k.value(0.005);`
#pragma once

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <string>

#include "cases/options.hpp"

namespace hydrojump::sph {

struct WendlandC2 {
  double h = 0.0, inv_h = 0.0, alpha = 0.0;
  explicit WendlandC2(double h_m) : h(h_m), inv_h(1.0 / h_m), alpha(7.0 / (4.0 * std::numbers::pi * h_m * h_m)) {}
  // W(r) = alpha (1 - q/2)^4 (2q + 1)
  // (0 for q >= 2, without a branch: max instead.)
  double value(double r) const {
    const double q = r * inv_h;
    const double a = std::max(0.0, 1.0 - 0.5 * q);
    const double a2 = a * a;
    return alpha * a2 * a2 * (2.0 * q + 1.0);
  }
  // W'(r)/r = -5 alpha / h^2 (1 - q/2)^3, 0 for q >= 2. Without a branch (max instead), so the pair
  // loop's SIMD lanes need none.
  double gradient_factor(double r) const {
    const double a = std::max(0.0, 1.0 - 0.5 * (r * inv_h));
    return -5.0 * alpha * inv_h * inv_h * a * a * a;
  }
};

struct CubicSpline {
  double h = 0.0, inv_h = 0.0, alpha = 0.0;
  explicit CubicSpline(double h_m) : h(h_m), inv_h(1.0 / h_m), alpha(10.0 / (7.0 * std::numbers::pi * h_m * h_m)) {}
  // W(q) = alpha (1 - 3/2 q^2 + 3/4 q^3) for q < 1, alpha/4 (2 - q)^3 for 1 <= q < 2
  double value(double r) const {
    const double q = r * inv_h;
    if (q >= 2.0) return 0.0;
    if (q < 1.0) return alpha * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    const double a = 2.0 - q;
    return alpha * 0.25 * a * a * a;
  }
  // W'(r)/r = alpha/h^2 (-3 + 9/4 q) for q < 1,  -3/4 alpha (2 - q)^2 / (q h^2) for 1 <= q < 2, 0
  // beyond. Both pieces computed and one selected (no branch for the pair loop's SIMD lanes).
  double gradient_factor(double r) const {
    const double q = r * inv_h;
    const double inner = alpha * inv_h * inv_h * (-3.0 + 2.25 * q);
    const double a = std::max(0.0, 2.0 - q);
    const double outer = -0.75 * alpha * a * a * inv_h * inv_h / std::max(q, 1.0);
    return q < 1.0 ? inner : outer;
  }
};

// A kernel chosen by name at run time (tests, diagnostics, interpolation). The interaction loop is
// instantiated on the concrete kernel types above instead.
// The kernel names of the spec (sph.kernel, cases/options.hpp), for a name given outside a spec (the
// comparator's kernel, tests). Throws std::invalid_argument naming the allowed values.
using cases::KernelType;
inline KernelType parse_kernel(const std::string& name) { return cases::option_from_name<KernelType>("sph.kernel", name); }

class Kernel {
 public:
  // Throws std::invalid_argument naming the allowed values for an unknown name or h <= 0.
  static Kernel make(const std::string& name, double h_m);
  const std::string& name() const { return name_; }
  double h() const { return h_; }
  double support_radius() const { return 2.0 * h_; }
  double value(double r) const { return wendland_ ? WendlandC2(h_).value(r) : CubicSpline(h_).value(r); }
  double gradient_factor(double r) const {
    return wendland_ ? WendlandC2(h_).gradient_factor(r) : CubicSpline(h_).gradient_factor(r);
  }

 private:
  std::string name_;
  double h_ = 0.0;
  bool wendland_ = true;
};

// h = coef_h * sqrt(2) * dx  (DualSPHysics convention in 2D)
inline double smoothing_length(double coef_h, double dx) { return coef_h * std::numbers::sqrt2 * dx; }

}  // namespace hydrojump::sph
