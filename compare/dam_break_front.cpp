#include "compare/dam_break_front.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "util/csv_table.hpp"

namespace hydrojump::compare {

namespace {

// Least-squares slope of x over t; NaN for fewer than two points or equal times.
double slope(const std::vector<double>& t, const std::vector<double>& x) {
  const double n = static_cast<double>(t.size());
  double st = 0.0, sx = 0.0, stt = 0.0, stx = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    st += t[k];
    sx += x[k];
    stt += t[k] * t[k];
    stx += t[k] * x[k];
  }
  const double d = n * stt - st * st;
  if (t.size() < 2 || !(d > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return (n * stx - st * sx) / d;
}

// x(t) by linear interpolation in the trace; NaN outside it.
double front_at(const FrontTrace& trace, double t) {
  const auto& ts = trace.t_s;
  if (ts.empty() || t < ts.front() || t > ts.back()) return std::numeric_limits<double>::quiet_NaN();
  const auto hi = std::lower_bound(ts.begin(), ts.end(), t);
  const std::size_t j = static_cast<std::size_t>(hi - ts.begin());
  if (j == 0 || ts[j] == t) return trace.x_m[j];
  const double w = (t - ts[j - 1]) / (ts[j] - ts[j - 1]);
  return trace.x_m[j - 1] + w * (trace.x_m[j] - trace.x_m[j - 1]);
}

}  // namespace

// dt_gate = 0.175 sqrt(L / (2 g))
double gate_opening_time_shift_s(double column_width_m, double gravity_m_s2) {
  if (!(column_width_m > 0.0) || !(gravity_m_s2 > 0.0))
    throw std::invalid_argument("gate_opening_time_shift_s: L and g must be positive");
  return gate_opening_time_shift_tau * std::sqrt(column_width_m / (2.0 * gravity_m_s2));
}

std::vector<MeasuredFrontPoint> read_measured_front(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read (the measured surge front)");
  std::vector<std::string> header;
  std::optional<std::size_t> t, x;
  std::vector<MeasuredFrontPoint> points;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string> cells = util::split_csv_line(line);
    if (header.empty()) {
      header = cells;
      const util::CsvTable named{header, {}};
      t = named.column("t_s");
      x = named.column("x_front_over_L");
      if (!t || !x) throw std::runtime_error(file.string() + ": no header with the columns t_s and x_front_over_L");
      continue;
    }
    const double tv = cells.size() == header.size() ? util::csv_number(cells[*t]) : std::nan("");
    const double xv = cells.size() == header.size() ? util::csv_number(cells[*x]) : std::nan("");
    if (!std::isfinite(tv) || !std::isfinite(xv))
      throw std::runtime_error(file.string() + ": a row without numbers for t_s and x_front_over_L: " + line);
    points.push_back({tv, xv});
  }
  if (points.size() < 2) throw std::runtime_error(file.string() + ": fewer than 2 rows of the measured front");
  return points;
}

FrontComparison compare_front(const FrontTrace& trace, const std::vector<MeasuredFrontPoint>& measured,
                              const FrontSetup& setup) {
  const double l = setup.column_width_m;
  const double time_scale = std::sqrt(l / measured_front_column_width_m);  // Froude similarity
  FrontComparison c;
  c.time_shift_s = setup.time_shift_s;
  c.measured_points = static_cast<int>(measured.size());
  std::vector<double> late_t, late_sim, late_exp;
  for (const MeasuredFrontPoint& p : measured) {
    const double t_exp = p.t_s * time_scale;
    const double x_sim = front_at(trace, t_exp - setup.time_shift_s);  // t_model = t_exp - dt_gate
    if (!std::isfinite(x_sim)) continue;
    if (!(p.x_over_l * l < setup.tank_length_m) || !(x_sim < setup.tank_length_m - setup.wall_margin_m)) continue;
    const double d = std::abs(x_sim / l - p.x_over_l);
    if (c.points == 0) c.first_point_error = d;
    c.mean_abs += d;
    c.max_abs = std::max(c.max_abs, d);
    ++c.points;
    c.t_exp_s.push_back(t_exp);
    c.measured.push_back(p.x_over_l);
    c.simulated.push_back(x_sim / l);
    if (p.t_s > late_front_from_s) {
      late_t.push_back(t_exp);
      late_sim.push_back(x_sim / l);
      late_exp.push_back(p.x_over_l);
    }
  }
  if (c.points > 0) c.mean_abs /= c.points;
  c.late_speed_ratio = slope(late_t, late_sim) / slope(late_t, late_exp);
  return c;
}

}  // namespace hydrojump::compare
