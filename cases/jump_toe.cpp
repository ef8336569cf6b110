#include "cases/jump_toe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hydrojump::cases {

std::vector<double> running_mean(const std::vector<double>& v, int half_width) {
  std::vector<double> out(v.size(), std::numeric_limits<double>::quiet_NaN());
  const long n = static_cast<long>(v.size());
  for (long i = 0; i < n; ++i) {
    double s = 0.0;
    int c = 0;
    for (long k = std::max(0L, i - half_width); k <= std::min(n - 1, i + half_width); ++k)
      if (std::isfinite(v[static_cast<std::size_t>(k)])) {
        s += v[static_cast<std::size_t>(k)];
        ++c;
      }
    if (c > 0) out[static_cast<std::size_t>(i)] = s / c;
  }
  return out;
}

std::size_t find_jump_toe(const std::vector<double>& x, const std::vector<double>& zeta, double x_from, double y1,
                          const ToeCriterion& criterion) {
  if (x.size() < 3 || zeta.size() != x.size()) return x.size();
  const double ds = (x.back() - x.front()) / static_cast<double>(x.size() - 1);
  const int half = std::max(0, static_cast<int>(std::lround(0.5 * criterion.window_y1 * y1 / ds)));
  const std::vector<double> zm = running_mean(zeta, half);
  const auto persist = static_cast<std::size_t>(std::ceil(criterion.persistence_y1 * y1 / ds));
  const double threshold = criterion.threshold_y1 * y1;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] < x_from) continue;
    bool ok = true;
    for (std::size_t k = i; k <= std::min(x.size() - 1, i + persist); ++k)
      if (!(zm[k] > threshold)) {
        ok = false;
        break;
      }
    if (ok) return i;
  }
  return x.size();
}

double toe_drift_tolerance_m(const std::string& bed_profile, double wavelength_m, double inflow_depth_m) {
  return bed_profile == "smooth" ? 2.0 * inflow_depth_m : wavelength_m;
}

bool steady_by_means(double outflow_minus_inflow_over_q, double toe_trend_m_per_s, double toe_drift_tolerance_m) {
  return std::abs(outflow_minus_inflow_over_q) < steady_discharge_tolerance &&
         std::abs(toe_trend_m_per_s) * steady_span_s < toe_drift_tolerance_m;
}

double least_squares_slope(const std::vector<double>& t, const std::vector<double>& y) {
  const double nan_value = std::numeric_limits<double>::quiet_NaN();
  double st = 0.0, sy = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < t.size() && k < y.size(); ++k)
    if (std::isfinite(y[k])) {
      st += t[k];
      sy += y[k];
      ++n;
    }
  if (n < 3) return nan_value;
  const double tm = st / n, ym = sy / n;
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < t.size() && k < y.size(); ++k)
    if (std::isfinite(y[k])) {
      num += (t[k] - tm) * (y[k] - ym);
      den += (t[k] - tm) * (t[k] - tm);
    }
  return den > 0.0 ? num / den : nan_value;
}

}  // namespace hydrojump::cases
