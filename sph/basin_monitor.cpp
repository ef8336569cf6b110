#include "sph/basin_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "util/csv_table.hpp"
#include "cases/hydraulics.hpp"
#include "cases/jump_toe.hpp"
#include "cases/output_times.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {
namespace {

constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
using cases::steady_span_s;

struct MeanStd {
  double mean = nan_value, std = nan_value;
  int count = 0;
};

MeanStd mean_std(const std::vector<double>& v) {
  MeanStd r;
  double s = 0.0;
  for (const double x : v)
    if (std::isfinite(x)) {
      s += x;
      ++r.count;
    }
  if (r.count == 0) return r;
  r.mean = s / r.count;
  double ss = 0.0;
  for (const double x : v)
    if (std::isfinite(x)) ss += (x - r.mean) * (x - r.mean);
  r.std = r.count > 1 ? std::sqrt(ss / (r.count - 1)) : 0.0;
  return r;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

std::string json_stats(const MeanStd& m) {
  return "{\"mean\": " + json_number(m.mean) + ", \"std\": " + json_number(m.std) +
         ", \"samples\": " + std::to_string(m.count) + "}";
}

// Round-trip precision: the rows are also the checkpoint's copy of the samples, so a resumed run
// continues with exactly the values it had (a 10-digit copy shifted its mass balance by ~1e-10).
std::string csv_number(double v) {
  std::ostringstream o;
  o << std::setprecision(std::numeric_limits<double>::max_digits10) << v;
  return o.str();
}

}  // namespace

BasinMonitorSetup BasinMonitorSetup::from_case(const cases::Case& c, const cases::CaseGeometry& geometry, double dx,
                                               double rho0) {
  const cases::StillingBasinCase* b = c.stilling_basin();
  if (b == nullptr) throw std::invalid_argument("basin monitor: case \"" + c.id + "\" is not a stilling basin");
  if (geometry.inflows.empty() || geometry.outflows.empty())
    throw std::invalid_argument("basin monitor: case \"" + c.id + "\" has no inflow or outflow");
  BasinMonitorSetup s;
  s.case_id = c.id;
  s.dx = dx;
  s.rho0 = rho0;
  s.inflow_depth_m = b->inflow_depth_m;
  s.discharge_m2_s = cases::unit_discharge(b->inflow_depth_m, b->inflow_velocity_m_s);
  s.froude1 = cases::froude_number(b->inflow_depth_m, b->inflow_velocity_m_s, std::abs(geometry.body_force_m_s2.y()));
  s.tailwater_depth_m = b->tailwater_depth_m;
  s.tailwater_held_at = c.holds_toe()                                                ? "toe_held"
                        : c.sph.outflow_condition == cases::OutflowCondition::tailgate ? "tailgate"
                                                                                       : std::string(cases::option_name(c.sph.outflow_level_reference));
  s.belanger_y2_m = cases::belanger_sequent_depth(b->inflow_depth_m, s.froude1);
  s.floor_z_m = geometry.bed.elevation(geometry.inflows.front().x_m);
  s.x_inflow_m = geometry.inflows.front().x_m;
  s.reservoir_upstream = c.sph.inflow_condition == InflowCondition::piston;
  s.x_outflow_m = geometry.outflows.front().x_m;
  s.toe_search_from_m = s.x_inflow_m;
  for (const auto& sec : geometry.sections)
    if (sec.role == cases::SectionRole::upstream) s.toe_search_from_m = sec.x_m;
  s.drift_tolerance_m = cases::toe_drift_tolerance_m(b->bed.profile, b->bed.wavelength_m, b->inflow_depth_m);
  s.average_start_s = c.run.average_start_s;
  s.average_end_s = c.run.average_end_s > 0.0 ? c.run.average_end_s : c.run.end_time_s;
  s.output_interval_s = c.run.output_interval_s;
  s.sections = geometry.sections;
  s.bed_elevation = [bed = geometry.bed](double x) { return bed.elevation(x); };
  s.measured_sequent_depth_m = b->measured.sequent_depth_m ? *b->measured.sequent_depth_m : nan_value;
  return s;
}

BasinMonitor::BasinMonitor(BasinMonitorSetup setup) : setup_(std::move(setup)) {
  if (!(setup_.dx > 0.0) || !(setup_.x_outflow_m > setup_.x_inflow_m) || !setup_.bed_elevation)
    throw std::invalid_argument("basin monitor: needs dx > 0, an outflow downstream of the inflow and a bed");
  const int n = static_cast<int>(std::floor((setup_.x_outflow_m - setup_.x_inflow_m) / setup_.dx));
  for (int k = 0; k < n; ++k) stations_.push_back(setup_.x_inflow_m + (k + 0.5) * setup_.dx);
}

std::vector<BasinMonitor::Column> BasinMonitor::columns(const ParticleSet& particles,
                                                        const std::vector<double>& x_centres, double width) {
  std::vector<Column> out(x_centres.size());
  if (x_centres.empty()) return out;
  // Stations may be unevenly spaced (sections): test each particle against each column it can touch,
  // after sorting the columns by x.
  std::vector<std::size_t> order(x_centres.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x_centres[a] < x_centres[b]; });
  std::vector<double> sorted(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = x_centres[order[k]];
  for (Eigen::Index i = 0; i < particles.size(); ++i) {
    if (!particles.is_fluid(i)) continue;
    const double x = particles.x[i];
    auto it = std::upper_bound(sorted.begin(), sorted.end(), x - width);
    for (; it != sorted.end() && *it < x + width; ++it) {
      // hat weight Lambda((x_i - x_c)/w)/w, Lambda(s) = max(0, 1 - |s|)
      const double weight = std::max(0.0, 1.0 - std::abs(x - *it) / width) / width;
      const std::size_t k = order[static_cast<std::size_t>(it - sorted.begin())];
      const double volume = particles.mass[i] / particles.rho[i];
      out[k].depth += volume * weight;                    // h = sum V Lambda / w
      out[k].discharge += volume * particles.u[i] * weight;  // q = sum V u Lambda / w
    }
  }
  return out;
}

void BasinMonitor::record(const ParticleSet& particles, double t, double mass_in, double mass_out,
                          double outlet_target_depth, double mass_removed) {
  BasinSample s;
  s.t = t;
  s.outlet_target_depth = outlet_target_depth;
  s.mass_removed = mass_removed;
  s.mass_in = mass_in;
  s.mass_out = mass_out;
  // The water in the basin: the fluid (downstream of the inflow section only when a piston
  // reservoir's water is upstream of it) plus outflow-buffer particles (not removed yet).
  constexpr auto outflow_code = static_cast<std::uint8_t>(ParticleType::outflow);
  for (Eigen::Index i = 0; i < particles.size(); ++i)
    if ((particles.is_fluid(i) && (!setup_.reservoir_upstream || particles.x[i] >= setup_.x_inflow_m)) ||
        particles.type[i] == outflow_code)
      s.fluid_mass += particles.mass[i];
  // zeta(x) = z_b(x) + h(x) - z_floor on columns of width dx, then the toe criterion.
  const std::vector<Column> cols = columns(particles, stations_, setup_.dx);
  std::vector<double> zeta(stations_.size());
  for (std::size_t k = 0; k < stations_.size(); ++k)
    zeta[k] = setup_.bed_elevation(stations_[k]) + cols[k].depth - setup_.floor_z_m;
  const std::size_t toe =
      cases::find_jump_toe(stations_, zeta, setup_.toe_search_from_m, setup_.inflow_depth_m, cases::ToeCriterion{});
  s.toe_x = toe < stations_.size() ? stations_[toe] : nan_value;
  // Sections: columns of width 2 dx.
  std::vector<double> xs;
  for (const auto& sec : setup_.sections) xs.push_back(sec.x_m);
  const std::vector<Column> sec_cols = columns(particles, xs, 2.0 * setup_.dx);
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const double zb = setup_.bed_elevation(xs[k]);
    s.depth.push_back(sec_cols[k].depth);
    s.surface.push_back(zb + sec_cols[k].depth);
    s.discharge.push_back(sec_cols[k].discharge);
  }
  // A resumed run re-records the checkpoint's time: replace instead of duplicating (before q, so that
  // the replacement's q is over the interval from the sample before it).
  while (!samples_.empty() && samples_.back().t >= t - 1e-12) samples_.pop_back();
  // q over the interval since the previous sample: created / removed mass over rho0 and the interval.
  if (!samples_.empty()) {
    const BasinSample& p = samples_.back();
    s.q_in = (mass_in - p.mass_in) / (setup_.rho0 * (t - p.t));
    s.q_out = (mass_out - p.mass_out) / (setup_.rho0 * (t - p.t));
  } else {
    s.q_in = s.q_out = nan_value;
  }
  samples_.push_back(std::move(s));
}

BasinMonitor::BalanceSeries BasinMonitor::balance_series() const {
  BalanceSeries s;
  for (const auto& sample : samples_) {
    s.t.push_back(sample.t);
    s.q_in.push_back(sample.q_in);
    s.q_out.push_back(sample.q_out);
    s.toe_x.push_back(sample.toe_x);
  }
  return s;
}

// The window rule (cases::window_balance, as for the averaging window) over the second before output k.
bool BasinMonitor::steady_at(const BalanceSeries& series, std::size_t k) const {
  const double t = series.t[k];
  const double tol = cases::output_time_tolerance_s(setup_.output_interval_s);
  if (t < series.t.front() + steady_span_s - tol) return false;  // not a full second of history yet
  const cases::WindowBalance b = cases::window_balance(series.t, series.q_in, series.q_out, series.toe_x,
                                                       t - steady_span_s, t, tol, setup_.discharge_m2_s);
  // A jump not found in some frames counts as unsteady.
  return b.toe_missing == 0 &&
         cases::steady_by_means(b.outflow_minus_inflow_over_q, b.toe_trend_m_per_s, setup_.drift_tolerance_m);
}

double BasinMonitor::steady_from() const { return steady_from(balance_series()); }

// Backwards from the latest output to the first that is not steady: one window per output of the
// steady tail (one in all while the run is unsteady) instead of one per output of the whole run.
double BasinMonitor::steady_from(const BalanceSeries& series) const {
  double from = nan_value;
  for (std::size_t k = samples_.size(); k-- > 0;) {
    if (!steady_at(series, k)) break;
    from = samples_[k].t;
  }
  return from;
}

std::string BasinMonitor::csv() const {
  std::ostringstream o;
  o << "t_s,toe_x_m,inflow_discharge_m2_s,outflow_discharge_m2_s,inflow_mass_kg_per_m,outflow_mass_kg_per_m,"
       "fluid_mass_kg_per_m,outlet_target_depth_m,outlier_mass_kg_per_m";
  for (const auto& sec : setup_.sections)
    o << ",depth_" << sec.name << "_m,surface_z_" << sec.name << "_m,discharge_" << sec.name << "_m2_s";
  o << "\n";
  for (const auto& r : csv_rows()) o << r << "\n";
  return o.str();
}

std::vector<std::string> BasinMonitor::csv_rows() const {
  std::vector<std::string> rows;
  for (const auto& s : samples_) {
    std::string r = csv_number(s.t) + ',' + csv_number(s.toe_x) + ',' + csv_number(s.q_in) + ',' +
                    csv_number(s.q_out) + ',' + csv_number(s.mass_in) + ',' + csv_number(s.mass_out) + ',' +
                    csv_number(s.fluid_mass) + ',' + csv_number(s.outlet_target_depth) + ',' + csv_number(s.mass_removed);
    for (std::size_t k = 0; k < s.depth.size(); ++k)
      r += ',' + csv_number(s.depth[k]) + ',' + csv_number(s.surface[k]) + ',' + csv_number(s.discharge[k]);
    rows.push_back(std::move(r));
  }
  return rows;
}

void BasinMonitor::restore(const std::vector<std::string>& csv_rows) {
  samples_.clear();
  for (const auto& row : csv_rows) {
    std::vector<double> v;
    for (const auto& cell : util::split_csv_line(row)) v.push_back(util::csv_number(cell));  // "nan" -> NaN
    const std::size_t n_sec = setup_.sections.size();
    if (v.size() != 9 + 3 * n_sec) throw std::runtime_error("basin monitor: a checkpoint row does not match the case");
    BasinSample s;
    s.t = v[0];
    s.toe_x = v[1];
    s.q_in = v[2];
    s.q_out = v[3];
    s.mass_in = v[4];
    s.mass_out = v[5];
    s.fluid_mass = v[6];
    s.outlet_target_depth = v[7];
    s.mass_removed = v[8];
    for (std::size_t k = 0; k < n_sec; ++k) {
      s.depth.push_back(v[9 + 3 * k]);
      s.surface.push_back(v[10 + 3 * k]);
      s.discharge.push_back(v[11 + 3 * k]);
    }
    samples_.push_back(std::move(s));
  }
}

std::string BasinMonitor::jump_state() const {
  if (samples_.empty()) return "none";
  const double toe = samples_.back().toe_x;
  if (!std::isfinite(toe)) return "swept_downstream";
  // Past the "downstream" section (where y2 and E2 are read) the jump has left the basin's measuring
  // reach, as the comparator reports it.
  for (const auto& sec : setup_.sections)
    if (sec.role == cases::SectionRole::downstream && toe > sec.x_m) return "swept_downstream";
  if (toe <= setup_.toe_search_from_m + setup_.dx) return "at_inflow";
  return "in_basin";
}

std::string BasinMonitor::status_line() const {
  if (samples_.empty()) return {};
  const BasinSample& s = samples_.back();
  std::ostringstream o;
  o << std::fixed << std::setprecision(3) << "toe ";
  const std::string state = jump_state();
  if (state == "swept_downstream")
  {
    if (std::isfinite(s.toe_x)) o << s.toe_x << " m, past the downstream section";
    else o << "none";
    o << " (jump swept downstream: tailwater too low?)";
  }
  else if (state == "at_inflow") o << s.toe_x << " m (jump drowned at the inflow: tailwater too high?)";
  else if (std::isfinite(s.toe_x)) o << s.toe_x << " m";
  else o << "not found";
  // q is the mass passed between two outputs: the first output has none yet.
  if (std::isfinite(s.q_in) && std::isfinite(s.q_out))
    o << std::setprecision(4) << "  q_in " << s.q_in << "  q_out " << s.q_out << " m^2/s";
  else
    o << "  q_in, q_out from the second output on";
  // A control's output: the depth the outlet holds so that the downstream section holds y2, or the toe
  // stands at the basin start.
  if (setup_.tailwater_held_at != "outlet" && setup_.tailwater_held_at != "tailgate" &&
      std::isfinite(s.outlet_target_depth))
    o << std::setprecision(4) << "  outlet y_t " << s.outlet_target_depth << " m";
  const double from = steady_from();
  if (std::isfinite(from)) o << "  steady since t = " << std::setprecision(1) << from << " s";
  return o.str();
}

std::string BasinMonitor::summary_json() const {
  const double a = setup_.average_start_s, b = setup_.average_end_s;
  // Outputs come up to a time step after their nominal time (cases/output_times.hpp).
  const double tol = cases::output_time_tolerance_s(setup_.output_interval_s);
  auto in_window = [&](const BasinSample& s) { return cases::in_output_window(s.t, a, b, tol); };
  std::vector<double> qin, qout, toe, outlet_depth;
  const std::size_t n_sec = setup_.sections.size();
  std::vector<std::vector<double>> depth(n_sec), surface(n_sec), discharge(n_sec);
  for (const auto& s : samples_) {
    if (!in_window(s)) continue;
    // q_in/q_out cover the interval before the sample: count it if that interval lies in the window.
    if (s.t > a + tol) {
      qin.push_back(s.q_in);
      qout.push_back(s.q_out);
    }
    toe.push_back(s.toe_x);
    if (std::isfinite(s.outlet_target_depth)) outlet_depth.push_back(s.outlet_target_depth);
    for (std::size_t k = 0; k < n_sec; ++k) {
      depth[k].push_back(s.depth[k]);
      surface[k].push_back(s.surface[k]);
      discharge[k].push_back(s.discharge[k]);
    }
  }
  const MeanStd q_in = mean_std(qin), q_out = mean_std(qout), toe_stats = mean_std(toe);
  int toe_missing = 0;
  for (const double x : toe)
    if (!std::isfinite(x)) ++toe_missing;

  double y2 = nan_value, y2_std = nan_value;
  for (std::size_t k = 0; k < n_sec; ++k)
    if (setup_.sections[k].role == cases::SectionRole::downstream) {
      const MeanStd d = mean_std(depth[k]);
      y2 = d.mean;
      y2_std = d.std;
    }
  const double y1 = setup_.inflow_depth_m;
  const double belanger_ratio = setup_.belanger_y2_m / y1;

  const BasinSample* last = samples_.empty() ? nullptr : &samples_.back();
  const BasinSample* first = samples_.empty() ? nullptr : &samples_.front();
  double mass_change = nan_value, net_in = nan_value, mass_error = nan_value;
  if (last && first) {
    mass_change = last->fluid_mass - first->fluid_mass;
    net_in = (last->mass_in - first->mass_in) - (last->mass_out - first->mass_out) -
             (last->mass_removed - first->mass_removed);
    const double injected = last->mass_in - first->mass_in;
    mass_error = injected > 0.0 ? (mass_change - net_in) / injected : nan_value;
  }
  // The same two conditions on the whole window (cases::window_balance): the interval discharges
  // weighted by their intervals, i.e. (mass out - mass in) / (rho0 q (t_last - t_first)) between the
  // window's first and last outputs, and the toe's least-squares trend. Waves leaving the basin make 1 s
  // means of q_out swing by more than 2 % in runs whose window balances; a basin still filling or
  // draining shows here.
  const BalanceSeries series = balance_series();
  const cases::WindowBalance balance = cases::window_balance(series.t, series.q_in, series.q_out, series.toe_x,
                                                             a, b, tol, setup_.discharge_m2_s);
  const double window_imbalance = balance.outflow_minus_inflow_over_q;
  const double toe_trend = balance.toe_trend_m_per_s;
  const bool steady_means = jump_state() == "in_basin" &&
                            cases::steady_by_means(window_imbalance, toe_trend, setup_.drift_tolerance_m) &&
                            toe_missing == 0;
  const double from = steady_from(series);
  const bool window_complete = balance.reaches_window_end;  // an output at or after the window's end
  const bool steady_window = std::isfinite(from) && from <= a + tol && window_complete;

  std::ostringstream o;
  o << "{\n";
  o << "  \"case\": " << json_string(setup_.case_id) << ",\n";
  o << "  \"time_s\": " << json_number(last ? last->t : nan_value) << ",\n";
  o << "  \"averaging_window_s\": [" << json_number(a) << ", " << json_number(b) << "],\n";
  o << "  \"window_complete\": " << (window_complete ? "true" : "false") << ",\n";
  o << "  \"definitions\": "
    << json_string("depth h = sum V_i / w over fluid particles in a column of width w (dx for the toe profile, 2 dx "
                   "at sections); toe = cases/jump_toe.hpp criterion (running mean over 0.8 y1 of the surface "
                   "above the floor exceeds 1.5 y1 for 2 y1); q_in, q_out = mass entering the basin (inflow buffer, or "
                   "under a piston reservoir's gate) / leaving it (outflow buffer, or over a tailgate) per rho0 and time; steady = |q_in - q_out| < 2 % of q and toe drift over 1 s below the tolerance, at every output from "
                   "steady_from_s on; steady_by_window_means = the jump in the basin, |mass out - mass in| over the "
                   "window < 2 % of rho0 q times its length (window_outflow_minus_inflow_over_q, > 0: draining) and "
                   "the toe's least-squares trend over the window (window_toe_trend_m_per_s) times 1 s below the tolerance")
    << ",\n";
  o << "  \"prescribed\": {\"inflow_depth_m\": " << json_number(y1)
    << ", \"discharge_m2_s\": " << json_number(setup_.discharge_m2_s) << ", \"froude1\": " << json_number(setup_.froude1)
    << ", \"tailwater_depth_m\": " << json_number(setup_.tailwater_depth_m)
    << ", \"tailwater_held_at\": " << json_string(setup_.tailwater_held_at)
    << ", \"belanger_sequent_depth_m\": " << json_number(setup_.belanger_y2_m)
    << ", \"measured_sequent_depth_m\": " << json_number(setup_.measured_sequent_depth_m) << "},\n";
  o << "  \"inflow_discharge_m2_s\": " << json_stats(q_in) << ",\n";
  o << "  \"inflow_discharge_relative_error\": "
    << json_number((q_in.mean - setup_.discharge_m2_s) / setup_.discharge_m2_s) << ",\n";
  o << "  \"outflow_discharge_m2_s\": " << json_stats(q_out) << ",\n";
  // The outlet's target depth: constant y2 when held at the outlet; moved by the level control when
  // held at the downstream section (its window mean is the tailwater the outlet had to hold).
  o << "  \"outlet_target_depth_m\": " << json_stats(mean_std(outlet_depth)) << ",\n";
  o << "  \"mass_balance\": {\"fluid_mass_change_kg_per_m\": " << json_number(mass_change)
    << ", \"inflow_minus_outflow_kg_per_m\": " << json_number(net_in)
    << ", \"density_outliers_kg_per_m\": " << json_number(last && first ? last->mass_removed - first->mass_removed : nan_value)
    << ", \"relative_to_injected\": " << json_number(mass_error) << "},\n";
  o << "  \"jump_state\": " << json_string(jump_state()) << ",\n";
  o << "  \"toe_x_m\": " << json_stats(toe_stats) << ",\n";
  o << "  \"toe_missing_samples\": " << toe_missing << ",\n";
  o << "  \"toe_std_over_y1\": " << json_number(toe_stats.std / y1) << ",\n";
  o << "  \"sequent_depth_m\": {\"mean\": " << json_number(y2) << ", \"std\": " << json_number(y2_std) << "},\n";
  o << "  \"y2_over_y1\": " << json_number(y2 / y1) << ",\n";
  o << "  \"belanger_ratio\": " << json_number(belanger_ratio) << ",\n";
  o << "  \"y2_over_y1_relative_to_belanger\": " << json_number((y2 / y1 - belanger_ratio) / belanger_ratio) << ",\n";
  o << "  \"steady\": {\"steady_from_s\": " << json_number(from) << ", \"steady_over_window\": "
    << (steady_window ? "true" : "false") << ", \"toe_drift_tolerance_m\": " << json_number(setup_.drift_tolerance_m)
    << ", \"window_outflow_minus_inflow_over_q\": " << json_number(window_imbalance)
    << ", \"window_toe_trend_m_per_s\": " << json_number(toe_trend)
    << ", \"steady_by_window_means\": " << (steady_means && window_complete ? "true" : "false") << "},\n";
  o << "  \"sections\": [";
  for (std::size_t k = 0; k < n_sec; ++k) {
    const auto& sec = setup_.sections[k];
    o << (k ? ",\n" : "\n") << "    {\"name\": " << json_string(sec.name) << ", \"role\": " << json_string(std::string(cases::option_name(sec.role)))
      << ", \"x_m\": " << json_number(sec.x_m) << ", \"depth_m\": " << json_stats(mean_std(depth[k]))
      << ", \"surface_z_m\": " << json_stats(mean_std(surface[k]))
      << ", \"discharge_m2_s\": " << json_stats(mean_std(discharge[k])) << "}";
  }
  o << "\n  ]\n}\n";
  return o.str();
}

}  // namespace hydrojump::sph
