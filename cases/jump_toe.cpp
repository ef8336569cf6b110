#include "cases/jump_toe.hpp"

#include "cases/output_times.hpp"

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

double toe_drift_tolerance_m(BedShape bed_profile, double wavelength_m, double inflow_depth_m) {
  return bed_profile == BedShape::smooth ? 2.0 * inflow_depth_m : wavelength_m;
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

WindowBalance window_balance(const std::vector<double>& t, const std::vector<double>& q_in,
                             const std::vector<double>& q_out, const std::vector<double>& toe_x, double t0,
                             double t1, double time_tolerance_s, double q) {
  const double nan_value = std::numeric_limits<double>::quiet_NaN();
  WindowBalance b;
  b.outflow_minus_inflow_over_q = b.toe_trend_m_per_s = b.first_output_s = b.last_output_s = nan_value;
  std::vector<double> window_t, window_toe;
  double imbalance_volume = 0.0;  // sum (q_out - q_in) dt, m^2
  const std::size_t n = std::min({t.size(), q_in.size(), q_out.size(), toe_x.size()});
  for (std::size_t k = 0; k < n; ++k) {
    if (t[k] >= t1 - time_tolerance_s) b.reaches_window_end = true;
    if (!in_output_window(t[k], t0, t1, time_tolerance_s)) continue;
    if (b.outputs > 0 && !(t[k] > b.last_output_s)) continue;  // a repeated or earlier time: not an interval
    if (b.outputs == 0) {
      b.first_output_s = t[k];
    } else {
      imbalance_volume += (q_out[k] - q_in[k]) * (t[k] - b.last_output_s);
    }
    b.last_output_s = t[k];
    ++b.outputs;
    window_t.push_back(t[k]);
    window_toe.push_back(toe_x[k]);
    if (!std::isfinite(toe_x[k])) ++b.toe_missing;
  }
  if (b.outputs >= 2 && q > 0.0)
    b.outflow_minus_inflow_over_q = imbalance_volume / (q * (b.last_output_s - b.first_output_s));
  b.toe_trend_m_per_s = least_squares_slope(window_t, window_toe);
  return b;
}

}  // namespace hydrojump::cases
