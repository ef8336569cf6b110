#include "compare/discrepancy.hpp"

#include "cases/hydraulics.hpp"
#include "compare/jump_structure.hpp"

#include <algorithm>
#include <cmath>

namespace hydrojump::compare {

SurfaceDifference surface_difference(const MethodStatistics& sph, const MethodStatistics& vof, double x_from,
                                     double x_to) {
  SurfaceDifference d;
  const std::size_t n = std::min(sph.stations.size(), vof.stations.size());
  double ss = 0.0, worst = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = sph.stations[i];
    const auto& b = vof.stations[i];
    if (std::abs(a.spec.x_m - b.spec.x_m) > 1e-9) continue;  // the stations must coincide
    if (a.spec.x_m < x_from || a.spec.x_m > x_to) continue;
    const double diff = a.surface.mean - b.surface.mean;
    if (!std::isfinite(diff)) continue;
    ss += diff * diff;
    ++d.n_stations;
    if (std::abs(diff) > worst) { worst = std::abs(diff); d.x_of_max_m = a.spec.x_m; }
  }
  if (d.n_stations > 0) {
    d.rms_m = std::sqrt(ss / d.n_stations);
    d.max_abs_m = worst;
  }
  return d;
}

static double interpolate_wet(const ColumnStatistics& s, double z) {
  if (s.z.size() < 2 || z < s.z.front() || z > s.z.back()) return not_a_number;
  const auto it = std::upper_bound(s.z.begin(), s.z.end(), z);
  std::size_t k = static_cast<std::size_t>(it - s.z.begin());
  if (k >= s.z.size()) k = s.z.size() - 1;
  if (k == 0) k = 1;
  if (s.wet_fraction[k - 1] < 0.5 || s.wet_fraction[k] < 0.5) return not_a_number;
  const double t = (z - s.z[k - 1]) / (s.z[k] - s.z[k - 1]);
  return s.u_mean[k - 1] + t * (s.u_mean[k] - s.u_mean[k - 1]);
}

std::vector<ProfileDifference> profile_differences(const MethodStatistics& sph, const MethodStatistics& vof,
                                                   double u1) {
  std::vector<ProfileDifference> out;
  for (const auto& a : sph.sections) {
    const auto it = std::find_if(vof.sections.begin(), vof.sections.end(),
                                 [&](const ColumnStatistics& b) { return b.spec.name == a.spec.name; });
    if (it == vof.sections.end()) continue;
    ProfileDifference d;
    d.section = a.spec.name;
    d.x_m = a.spec.x_m;
    double ss = 0.0;
    for (std::size_t k = 0; k < a.z.size(); ++k) {
      if (a.wet_fraction[k] < 0.5) continue;
      const double vb = interpolate_wet(*it, a.z[k]);
      const double diff = a.u_mean[k] - vb;
      if (!std::isfinite(diff)) continue;
      ss += diff * diff;
      ++d.n_points;
    }
    if (d.n_points > 0) {
      d.l2_m_s = std::sqrt(ss / d.n_points);
      d.l2_over_u1 = u1 != 0.0 ? d.l2_m_s / std::abs(u1) : not_a_number;
    }
    out.push_back(d);
  }
  return out;
}

std::vector<MetricRow> metric_table(const JumpMetrics* sph, const JumpMetrics* vof, const MeasuredReference& lab,
                                    double inflow_depth_m, double inflow_velocity_m_s, double gravity_m_s2,
                                    bool toe_held) {
  auto v = [](const JumpMetrics* m, double JumpMetrics::*f, double scale = 1.0) {
    return m ? m->*f * scale : not_a_number;
  };
  auto o = [](const std::optional<double>& x) { return x ? *x : not_a_number; };
  // The smooth-bed column: eta of a classical jump at this inflow (Belanger's y2*), as the report's
  // "smooth bed (theory)" (the study's listed smooth-bed value, rounded from it, is lab.eta_smooth_percent).
  const double smooth_theory = inflow_depth_m > 0.0 && inflow_velocity_m_s > 0.0 && gravity_m_s2 > 0.0
                                   ? 100.0 * cases::jump_hydraulics(inflow_depth_m, inflow_velocity_m_s, inflow_depth_m,
                                                                    gravity_m_s2).eta_smooth
                                   : not_a_number;
  std::vector<MetricRow> rows;
  rows.push_back({"upstream_depth", "m", v(sph, &JumpMetrics::upstream_depth_m), v(vof, &JumpMetrics::upstream_depth_m),
                  inflow_depth_m, not_a_number, not_a_number});
  rows.push_back({"toe_position", "m", v(sph, &JumpMetrics::toe_x_m), v(vof, &JumpMetrics::toe_x_m), not_a_number,
                  not_a_number, not_a_number});
  rows.push_back({"toe_mean_of_frames", "m", v(sph, &JumpMetrics::toe_mean_of_frames_x_m),
                  v(vof, &JumpMetrics::toe_mean_of_frames_x_m), not_a_number, not_a_number, not_a_number});
  rows.push_back({"toe_std", "m", v(sph, &JumpMetrics::toe_std_m), v(vof, &JumpMetrics::toe_std_m), not_a_number,
                  not_a_number, not_a_number});
  rows.push_back({"toe_trend", "m/s", v(sph, &JumpMetrics::toe_trend_m_per_s), v(vof, &JumpMetrics::toe_trend_m_per_s),
                  not_a_number, not_a_number, not_a_number});
  // The run's water balance and steadiness over the window: checks of the run, not predictions.
  rows.push_back({"water_imbalance", "%", v(sph, &JumpMetrics::window_imbalance, 100.0),
                  v(vof, &JumpMetrics::window_imbalance, 100.0), not_a_number, not_a_number, not_a_number, "check"});
  rows.push_back({"steady", "", v(sph, &JumpMetrics::steady_by_means), v(vof, &JumpMetrics::steady_by_means),
                  not_a_number, not_a_number, not_a_number, "check"});
  const double belanger_y2 = inflow_depth_m > 0.0 && inflow_velocity_m_s > 0.0 && gravity_m_s2 > 0.0
                                 ? cases::belanger_sequent_depth(inflow_depth_m,
                                                                 cases::froude_number(inflow_depth_m, inflow_velocity_m_s,
                                                                                      gravity_m_s2))
                                 : not_a_number;
  rows.push_back({"sequent_depth", "m", v(sph, &JumpMetrics::sequent_depth_m), v(vof, &JumpMetrics::sequent_depth_m),
                  o(lab.sequent_depth_m), not_a_number, belanger_y2});
  // The bed effect y2 / y2*: what the bed does to the sequent depth (1 on a smooth bed).
  rows.push_back({"bed_effect", "", v(sph, &JumpMetrics::sequent_depth_m, 1.0 / belanger_y2),
                  v(vof, &JumpMetrics::sequent_depth_m, 1.0 / belanger_y2), o(lab.sequent_depth_m) / belanger_y2,
                  not_a_number, 1.0});
  // The classical jump's lengths at this inflow (jump_structure.hpp): USBR's 6 y2*, Hager et al.'s Lr.
  const double fr1 = inflow_depth_m > 0.0 && gravity_m_s2 > 0.0
                         ? cases::froude_number(inflow_depth_m, inflow_velocity_m_s, gravity_m_s2)
                         : not_a_number;
  rows.push_back({"jump_length", "m", v(sph, &JumpMetrics::jump_length_m), v(vof, &JumpMetrics::jump_length_m),
                  o(lab.jump_length_m), not_a_number, usbr_jump_length(belanger_y2, fr1)});
  rows.push_back({"roller_length", "m", v(sph, &JumpMetrics::roller_length_m), v(vof, &JumpMetrics::roller_length_m),
                  o(lab.roller_length_m), not_a_number, hager_roller_length(inflow_depth_m, fr1)});
  rows.push_back({"eta", "%", v(sph, &JumpMetrics::eta, 100.0), v(vof, &JumpMetrics::eta, 100.0), o(lab.eta_percent),
                  o(lab.published_sph_eta_percent), smooth_theory});
  rows.push_back({"eta_alpha1", "%", v(sph, &JumpMetrics::eta_alpha1, 100.0), v(vof, &JumpMetrics::eta_alpha1, 100.0),
                  o(lab.eta_percent), o(lab.published_sph_eta_percent), smooth_theory});
  rows.push_back({"eta_crest_depth", "%", v(sph, &JumpMetrics::eta_crest_depth, 100.0),
                  v(vof, &JumpMetrics::eta_crest_depth, 100.0), o(lab.eta_percent), o(lab.published_sph_eta_percent),
                  smooth_theory});
  // M = h^2/2 + q^2/(g h) of uniform sections at y1 and at the measured y2
  double lab_bed_force = not_a_number;
  if (lab.sequent_depth_m && inflow_depth_m > 0.0 && gravity_m_s2 > 0.0) {
    const double q = inflow_depth_m * inflow_velocity_m_s;
    const double m1 = specific_force(inflow_depth_m, q, gravity_m_s2);
    lab_bed_force = 100.0 * (m1 - specific_force(*lab.sequent_depth_m, q, gravity_m_s2)) / m1;
  }
  rows.push_back({"bed_force_fraction", "%", v(sph, &JumpMetrics::bed_force_fraction, 100.0),
                  v(vof, &JumpMetrics::bed_force_fraction, 100.0), lab_bed_force, not_a_number, 0.0});
  rows.push_back({"velocity_settling_distance", "m", v(sph, &JumpMetrics::velocity_settling_distance_m),
                  v(vof, &JumpMetrics::velocity_settling_distance_m), not_a_number, not_a_number, not_a_number});
  rows.push_back({"jet_height", "", v(sph, &JumpMetrics::jet_height_fraction), v(vof, &JumpMetrics::jet_height_fraction),
                  not_a_number, not_a_number, not_a_number});
  rows.push_back({"wall_jet_deviation", "", v(sph, &JumpMetrics::wall_jet_deviation),
                  v(vof, &JumpMetrics::wall_jet_deviation), not_a_number, not_a_number, not_a_number});
  rows.push_back({"surface_peak", "m", v(sph, &JumpMetrics::surface_peak_m), v(vof, &JumpMetrics::surface_peak_m),
                  not_a_number, not_a_number, not_a_number});
  // What the set-up holds: the inflow always; the toe's mean under the toe-holding control; else the
  // tailwater, and with it y2 and what the inputs give from it (eta, the bed force and effect).
  for (MetricRow& r : rows) {
    const bool from_y2 = r.quantity == "sequent_depth" || r.quantity == "bed_effect" || r.quantity.rfind("eta", 0) == 0 ||
                         r.quantity == "bed_force_fraction";
    const bool toe = r.quantity == "toe_position" || r.quantity == "toe_mean_of_frames";
    if (r.quantity == "upstream_depth") r.status = "input";
    else if (toe_held ? toe : from_y2) r.status = "imposed";
  }
  return rows;
}

}  // namespace hydrojump::compare
