#include "compare/time_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hydrojump::compare {

ScalarStats stats_of(const std::vector<double>& values) {
  ScalarStats s;
  double sum = 0.0;
  for (double v : values)
    if (std::isfinite(v)) { sum += v; ++s.count; }
  if (s.count == 0) return s;
  s.mean = sum / s.count;
  double ss = 0.0;
  for (double v : values)
    if (std::isfinite(v)) ss += (v - s.mean) * (v - s.mean);
  // One value says nothing about the spread: NaN (printed as "—"), not a perfectly steady 0.
  s.std = s.count > 1 ? std::sqrt(ss / (s.count - 1)) : not_a_number;
  return s;
}

MethodAccumulator::MethodAccumulator(std::string method, std::vector<ColumnSpec> sections,
                                     std::vector<ColumnSpec> stations, SnapshotGrid snapshot_grid,
                                     double gravity)
    : method_(std::move(method)), sections_(std::move(sections)), stations_(std::move(stations)),
      grid_(snapshot_grid), gravity_(gravity), section_samples_(sections_.size()),
      station_samples_(stations_.size()) {}

void MethodAccumulator::add_frame(const FrameSampler& frame, bool take_snapshot, const std::vector<double>& bed) {
  times_.push_back(frame.time_s());
  const long ns = static_cast<long>(sections_.size());
  const long nt = static_cast<long>(stations_.size());
  std::vector<ColumnSample> sec(sections_.size()), sta(stations_.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (long i = 0; i < ns + nt; ++i) {
    const ColumnSpec& c = i < ns ? sections_[static_cast<std::size_t>(i)]
                                 : stations_[static_cast<std::size_t>(i - ns)];
    ColumnSample s = frame.sample_column(c.x_m, c.z_bed_m, c.n_points, gravity_);
    if (i < ns) sec[static_cast<std::size_t>(i)] = std::move(s);
    else sta[static_cast<std::size_t>(i - ns)] = std::move(s);
  }
  for (std::size_t i = 0; i < sec.size(); ++i) section_samples_[i].push_back(std::move(sec[i]));
  for (std::size_t i = 0; i < sta.size(); ++i) {
    sta[i].z.clear(); sta[i].u.clear(); sta[i].w.clear(); sta[i].pressure.clear(); sta[i].fraction.clear();
    sta[i].water.clear();  // keep memory flat
    station_samples_[i].push_back(std::move(sta[i]));
  }
  // Snapshot of the latest frame.
  if (take_snapshot && grid_.nx > 1 && grid_.nz > 1) {
    FieldSnapshot s;
    s.time_s = frame.time_s();
    s.nx = grid_.nx; s.nz = grid_.nz;
    s.x0 = grid_.x_min; s.z0 = grid_.z_min;
    s.dx = (grid_.x_max - grid_.x_min) / (grid_.nx - 1);
    s.dz = (grid_.z_max - grid_.z_min) / (grid_.nz - 1);
    const std::size_t n = static_cast<std::size_t>(s.nx) * static_cast<std::size_t>(s.nz);
    s.u.assign(n, not_a_number); s.w.assign(n, not_a_number); s.fraction.assign(n, 0.0);
#pragma omp parallel for schedule(dynamic, 8)
    for (long k = 0; k < static_cast<long>(n); ++k) {
      const int ix = static_cast<int>(k % s.nx), iz = static_cast<int>(k / s.nx);
      const double x = s.x0 + ix * s.dx, z = s.z0 + iz * s.dz;
      if (!bed.empty() && z < bed[static_cast<std::size_t>(ix)]) continue;
      const PointSample p = frame.sample_point(x, z);
      const std::size_t kk = static_cast<std::size_t>(k);
      s.fraction[kk] = p.fraction;
      if (p.fraction >= 0.5) { s.u[kk] = p.u; s.w[kk] = p.w; }
    }
    snapshot_ = std::move(s);
  }
}

ColumnStatistics column_statistics(const ColumnSpec& spec, const std::vector<ColumnSample>& samples,
                                   int n_profile_points, bool with_profile) {
  ColumnStatistics st;
  st.spec = spec;
  st.n_times = static_cast<int>(samples.size());
  auto collect = [&](auto member) {
    std::vector<double> v;
    v.reserve(samples.size());
    for (const auto& s : samples) v.push_back(s.wet() ? s.*member : not_a_number);
    return stats_of(v);
  };
  for (const auto& s : samples) st.n_wet += s.wet() ? 1 : 0;
  st.surface = collect(&ColumnSample::surface_z_m);
  st.depth = collect(&ColumnSample::depth_m);
  st.discharge = collect(&ColumnSample::discharge_m2_s);
  st.mean_velocity = collect(&ColumnSample::mean_velocity_m_s);
  st.max_velocity = collect(&ColumnSample::max_velocity_m_s);
  st.near_surface_velocity = collect(&ColumnSample::near_surface_velocity_m_s);
  st.energy_coefficient = collect(&ColumnSample::energy_coefficient);
  st.specific_energy = collect(&ColumnSample::specific_energy_m);
  st.momentum_coefficient = collect(&ColumnSample::momentum_coefficient);
  st.specific_force = collect(&ColumnSample::specific_force_m2);
  st.void_fraction = collect(&ColumnSample::void_fraction);
  {
    std::vector<double> v;
    for (const auto& s : samples) v.push_back(s.surface_from_fraction_m);
    st.surface_from_fraction = stats_of(v);
  }
  if (!with_profile || st.n_wet == 0 || n_profile_points < 2) return st;
  double top = spec.z_bed_m;
  for (const auto& s : samples)
    if (s.wet()) top = std::max(top, s.surface_z_m);
  const std::size_t n = static_cast<std::size_t>(n_profile_points);
  st.z.resize(n); st.u_mean.assign(n, not_a_number); st.u_std.assign(n, not_a_number);
  st.w_mean.assign(n, not_a_number); st.wet_fraction.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double z = spec.z_bed_m + (top - spec.z_bed_m) * static_cast<double>(k) / static_cast<double>(n - 1);
    st.z[k] = z;
    std::vector<double> us, ws;
    for (const auto& s : samples) {
      if (!s.wet() || z > s.surface_z_m + 1e-12) continue;
      // linear interpolation in the frame's own profile (evenly spaced from z_bed to its surface)
      const double t = (z - s.z_bed_m) / (s.depth_m) * static_cast<double>(s.z.size() - 1);
      const std::size_t i = std::min(static_cast<std::size_t>(std::max(t, 0.0)), s.z.size() - 2);
      const double f = std::clamp(t - static_cast<double>(i), 0.0, 1.0);
      // a void below the frame's surface (chi = 0, sampling.hpp) has no water velocity
      if (s.water.size() == s.z.size() && s.water[i] + f * (s.water[i + 1] - s.water[i]) < 0.5) continue;
      us.push_back(s.u[i] + f * (s.u[i + 1] - s.u[i]));
      ws.push_back(s.w[i] + f * (s.w[i + 1] - s.w[i]));
    }
    st.wet_fraction[k] = static_cast<double>(us.size()) / static_cast<double>(samples.size());
    const ScalarStats su = stats_of(us), sw = stats_of(ws);
    st.u_mean[k] = su.mean; st.u_std[k] = su.std; st.w_mean[k] = sw.mean;
  }
  return st;
}

MethodStatistics MethodAccumulator::finish(int n_profile_points) const {
  MethodStatistics m;
  m.method = method_;
  m.times = times_;
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    m.sections.push_back(column_statistics(sections_[i], section_samples_[i], n_profile_points, true));
    std::vector<SectionTimeSample> series;
    for (std::size_t t = 0; t < section_samples_[i].size(); ++t) {
      const ColumnSample& c = section_samples_[i][t];
      series.push_back({times_[t], c.surface_z_m, c.depth_m, c.discharge_m2_s, c.mean_velocity_m_s,
                        c.max_velocity_m_s, c.specific_energy_m});
    }
    m.section_series.push_back(std::move(series));
  }
  for (std::size_t i = 0; i < stations_.size(); ++i)
    m.stations.push_back(column_statistics(stations_[i], station_samples_[i], 0, false));
  m.station_surface_series.assign(times_.size(), std::vector<double>(stations_.size(), not_a_number));
  for (std::size_t i = 0; i < stations_.size(); ++i)
    for (std::size_t t = 0; t < times_.size() && t < station_samples_[i].size(); ++t)
      if (station_samples_[i][t].wet()) m.station_surface_series[t][i] = station_samples_[i][t].surface_z_m;
  m.snapshot = snapshot_;
  return m;
}

}  // namespace hydrojump::compare
