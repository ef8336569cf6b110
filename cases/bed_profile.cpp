#include "cases/bed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace hydrojump::cases {
namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

// Adaptive Simpson quadrature of f over [a, b].
template <class F>
double adaptive_simpson(const F& f, double a, double b, double fa, double fm, double fb, double whole,
                        double tolerance, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  if (depth <= 0 || std::abs(left + right - whole) <= 15.0 * tolerance) {
    return left + right + (left + right - whole) / 15.0;
  }
  return adaptive_simpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         adaptive_simpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

}  // namespace

BedProfile BedProfile::flat(double floor_z_m) {
  BedProfile b;
  b.floor_z_m_ = floor_z_m;
  return b;
}

BedProfile BedProfile::sinusoidal(double wavelength_m, double height_m, double reach_start_m,
                                  double reach_end_m) {
  if (!(wavelength_m > 0.0) || !(height_m >= 0.0) || !(reach_end_m >= reach_start_m)) {
    throw std::invalid_argument("BedProfile::sinusoidal: need S > 0, T >= 0 and end >= start");
  }
  BedProfile b;
  b.wavelength_m_ = wavelength_m;
  b.height_m_ = height_m;
  b.reach_start_m_ = reach_start_m;
  b.reach_end_m_ = reach_end_m;
  return b;
}

// z_b(x) = floor - T/2 (1 - cos(2 pi (x - x0) / S))  on the reach, the floor elsewhere
double BedProfile::elevation(double x) const {
  if (height_m_ <= 0.0 || x <= reach_start_m_ || x >= reach_end_m_) return floor_z_m_;
  return floor_z_m_ - 0.5 * height_m_ * (1.0 - std::cos(two_pi * (x - reach_start_m_) / wavelength_m_));
}

// dz_b/dx = -T/2 (2 pi / S) sin(2 pi (x - x0) / S)
double BedProfile::slope(double x) const {
  if (height_m_ <= 0.0 || x <= reach_start_m_ || x >= reach_end_m_) return 0.0;
  const double k = two_pi / wavelength_m_;
  return -0.5 * height_m_ * k * std::sin(k * (x - reach_start_m_));
}

// n = (-z_b', 1) / sqrt(1 + z_b'^2)
Eigen::Vector2d BedProfile::normal(double x) const {
  const double s = slope(x);
  return Eigen::Vector2d(-s, 1.0) / std::sqrt(1.0 + s * s);
}

double BedProfile::lowest_elevation() const { return floor_z_m_ - height_m_; }

// L = int_a^b sqrt(1 + z_b'(x)^2) dx
double BedProfile::arc_length(double x_a, double x_b) const {
  if (x_b <= x_a) return 0.0;
  const auto integrand = [this](double x) {
    const double s = slope(x);
    return std::sqrt(1.0 + s * s);
  };
  if (!corrugated()) return x_b - x_a;
  // Integrate piecewise over quarter wavelengths so the quadrature never straddles a kink.
  double total = 0.0;
  const double step = 0.25 * wavelength_m_;
  double a = x_a;
  while (a < x_b) {
    const double b = std::min(x_b, a + step);
    const double fa = integrand(a), fb = integrand(b), fm = integrand(0.5 * (a + b));
    const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    total += adaptive_simpson(integrand, a, b, fa, fm, fb, whole, 1e-12, 40);
    a = b;
  }
  return total;
}

std::vector<Eigen::Vector2d> BedProfile::points_by_arc_length(double x_a, double x_b,
                                                              double spacing_m) const {
  if (!(spacing_m > 0.0)) throw std::invalid_argument("points_by_arc_length: spacing must be > 0");
  std::vector<Eigen::Vector2d> points;
  if (x_b < x_a) return points;
  const double total = arc_length(x_a, x_b);
  const auto n_gaps = std::max<long>(1, std::lround(total / spacing_m));
  const double ds = total / static_cast<double>(n_gaps);
  points.reserve(static_cast<std::size_t>(n_gaps + 1));
  points.emplace_back(x_a, elevation(x_a));
  // March in x with small steps, accumulating arc length, and emit a point every ds (linear
  // interpolation inside the marching step; the step is small enough that the error is ~1e-9 m).
  const double dx = std::min(spacing_m, corrugated() ? wavelength_m_ : spacing_m) / 64.0;
  double x = x_a, s = 0.0, next = ds;
  long emitted = 0;
  while (emitted < n_gaps - 1 && x < x_b) {
    const double x_next = std::min(x_b, x + dx);
    const double ds_step = arc_length(x, x_next);
    while (emitted < n_gaps - 1 && s + ds_step >= next) {
      const double xi = x + (x_next - x) * (next - s) / ds_step;
      points.emplace_back(xi, elevation(xi));
      ++emitted;
      next += ds;
    }
    s += ds_step;
    x = x_next;
  }
  points.emplace_back(x_b, elevation(x_b));
  return points;
}

std::vector<Eigen::Vector2d> BedProfile::polyline(double x_a, double x_b, double max_deviation_m) const {
  std::vector<Eigen::Vector2d> points;
  if (!corrugated() || x_b <= reach_start_m_ || x_a >= reach_end_m_) {
    points.emplace_back(x_a, elevation(x_a));
    points.emplace_back(x_b, elevation(x_b));
    return points;
  }
  // Chord deviation of a curve with curvature |z''| <= T/2 (2 pi/S)^2 over a chord of length c is
  // about |z''| c^2 / 8, so c = sqrt(8 d / |z''|max).
  const double k = two_pi / wavelength_m_;
  const double curvature = 0.5 * height_m_ * k * k;
  const double chord = std::sqrt(8.0 * std::max(max_deviation_m, 1e-9) / curvature);
  const auto add_uniform = [&](double a, double b) {
    const auto n = std::max<long>(1, static_cast<long>(std::ceil((b - a) / chord)));
    for (long i = 1; i <= n; ++i) {
      const double x = a + (b - a) * static_cast<double>(i) / static_cast<double>(n);
      points.emplace_back(x, elevation(x));
    }
  };
  points.emplace_back(x_a, elevation(x_a));
  const double r0 = std::max(x_a, reach_start_m_), r1 = std::min(x_b, reach_end_m_);
  if (r0 > x_a) points.emplace_back(r0, elevation(r0));
  add_uniform(r0, r1);
  if (x_b > r1) points.emplace_back(x_b, elevation(x_b));
  return points;
}

}  // namespace hydrojump::cases
