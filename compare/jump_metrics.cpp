#include "compare/jump_metrics.hpp"

#include "cases/jump_toe.hpp"
#include "compare/jump_structure.hpp"

#include <algorithm>
#include <iomanip>
#include <cmath>
#include <sstream>
#include <utility>

namespace hydrojump::compare {

double section_energy(const ColumnStatistics& s, double gravity, bool alpha_one) {
  const double h = s.depth.mean, u = s.mean_velocity.mean;
  if (!std::isfinite(h) || !std::isfinite(u)) return not_a_number;
  if (alpha_one) return s.spec.z_bed_m + h + u * u / (2.0 * gravity);
  // Time mean of E(t) = z_b + h + alpha U^2/(2g) per frame.
  return s.specific_energy.mean;
}

double dissipation_rate(double e1, double e2) { return (e1 - e2) / e1; }

// M = h^2/2 + q^2/(g h)
double specific_force(double depth_m, double discharge_m2_s, double gravity_m_s2) {
  return 0.5 * depth_m * depth_m + discharge_m2_s * discharge_m2_s / (gravity_m_s2 * depth_m);
}

std::size_t find_toe(const std::vector<double>& x, const std::vector<double>& zeta, double x_from,
                     const JumpInputs& in) {
  const cases::ToeCriterion criterion{in.options.toe_threshold_y1, in.options.toe_window_y1,
                                      in.options.toe_persistence_y1};
  return cases::find_jump_toe(x, zeta, x_from, in.inflow_depth_m, criterion);
}

// The first index k in [from, last] from which settled(i) holds for every i in [k, last]; last + 1 when
// settled(last) fails. (The jump end and the velocity settling point are both "from here on it stays".)
template <class Predicate>
static std::size_t start_of_settled_tail(std::size_t from, std::size_t last, Predicate settled) {
  std::size_t k = last + 1;
  for (std::size_t i = last + 1; i-- > from;) {
    if (settled(i)) k = i; else break;
  }
  return k;
}

// What the downstream section gives (y2, E2, eta, M2, the bed force) when it does not lie behind a
// jump: not available.
static void drop_downstream_values(JumpMetrics& r) {
  r.sequent_depth_m = r.sequent_depth_std_m = r.e2_m = not_a_number;
  r.eta = r.eta_alpha1 = r.eta_crest_depth = not_a_number;
  r.specific_force_downstream_m2 = r.bed_force_fraction = not_a_number;
}

// What the upstream section gives (E1, eta, M1, the bed force) when the jump reaches it: not available.
static void drop_upstream_values(JumpMetrics& r) {
  r.e1_m = not_a_number;
  r.eta = r.eta_alpha1 = r.eta_crest_depth = not_a_number;
  r.specific_force_upstream_m2 = r.bed_force_fraction = not_a_number;
}

static const ColumnStatistics* find_role(const MethodStatistics& m, const std::string& role) {
  for (const auto& s : m.sections)
    if (s.spec.role == role) return &s;
  return nullptr;
}

JumpMetrics compute_jump_metrics(const MethodStatistics& m, const JumpInputs& in) {
  JumpMetrics r;
  // The structure at x_2y2: (z(u_max) - z_bed) / h, and the profile against the wall jet's.
  for (const auto& s : m.sections) {
    if (s.spec.name != "x_2y2" || s.n_wet == 0) continue;
    const WallJetFit fit = fit_wall_jet(s);
    if (s.depth.mean > 0.0) r.jet_height_fraction = fit.max_height_m / s.depth.mean;
    r.wall_jet_deviation = fit.deviation;
    break;
  }
  const double g = in.gravity_m_s2;
  const double y1 = in.inflow_depth_m;
  const ColumnStatistics* up = find_role(m, "upstream");
  const ColumnStatistics* down = find_role(m, "downstream");
  if (up && up->n_wet > 0) {
    r.upstream_depth_m = up->surface.mean - in.floor_z_m;
    r.e1_m = section_energy(*up, g, false);
  } else {
    r.notes.push_back("no wet \"upstream\" section: E1 and eta unavailable");
  }
  if (down && down->n_wet > 0) {
    r.sequent_depth_m = down->surface.mean - in.floor_z_m;
    r.sequent_depth_std_m = down->surface.std;
    r.e2_m = section_energy(*down, g, false);
  } else {
    r.notes.push_back("no wet \"downstream\" section: y2, E2, eta and Lj unavailable");
  }
  if (std::isfinite(r.e1_m) && std::isfinite(r.e2_m)) {
    r.eta = dissipation_rate(r.e1_m, r.e2_m);
    r.eta_alpha1 = dissipation_rate(section_energy(*up, g, true), section_energy(*down, g, true));
    // E = y + q^2/(2 g y^2) with y above the floor (crest) level
    auto crest_energy = [&](const ColumnStatistics& c) {
      const double y = c.surface.mean - in.floor_z_m, q = c.discharge.mean;
      return y + q * q / (2.0 * g * y * y);
    };
    r.eta_crest_depth = dissipation_rate(crest_energy(*up), crest_energy(*down));
    // (M1 - M2)/M1 with M = h^2/2 + beta q^2/(g h)
    r.specific_force_upstream_m2 = up->specific_force.mean;
    r.specific_force_downstream_m2 = down->specific_force.mean;
    r.bed_force_fraction = (r.specific_force_upstream_m2 - r.specific_force_downstream_m2) / r.specific_force_upstream_m2;
    // Continuity check: in a steady window both sections carry the inflow's q = y1 U1. A mean q off
    // by more than 5 % means the basin was still filling or draining (or the section is in spray),
    // so E2, eta and M2 there are not those of a stationary jump.
    const double q_in = in.inflow_depth_m * in.inflow_velocity_m_s;
    for (const ColumnStatistics* c : {up, down}) {
      const double ratio = c->discharge.mean / q_in - 1.0;
      if (q_in > 0.0 && std::abs(ratio) > 0.05) {
        std::ostringstream s;
        s << "the \"" << c->spec.role << "\" section's mean discharge " << c->discharge.mean << " m^2/s is "
          << std::fixed << std::setprecision(1) << 100.0 * ratio << " % off the inflow q = " << std::defaultfloat << std::setprecision(4)
          << q_in << " m^2/s: the averaging window is not steady there (storage still changing), so its "
          << "energy and force are not those of a stationary jump";
        r.notes.push_back(s.str());
      }
    }
  }

  // Longitudinal analysis on the stations.
  const auto& st = m.stations;
  if (st.size() < 3) {
    r.notes.push_back("fewer than 3 stations along the channel: toe, Lj and Lr unavailable");
    return r;
  }
  std::vector<double> xs(st.size()), zeta(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) {
    xs[i] = st[i].spec.x_m;
    zeta[i] = st[i].surface.mean - in.floor_z_m;
  }
  const double ds = (xs.back() - xs.front()) / static_cast<double>(xs.size() - 1);
  const int half = std::max(0, static_cast<int>(std::lround(0.5 * in.options.toe_window_y1 * y1 / ds)));
  const std::vector<double> zm = cases::running_mean(zeta, half);
  const double x_down = down ? down->spec.x_m : st.back().spec.x_m;
  const double x_up = up ? up->spec.x_m : st.front().spec.x_m;
  const std::size_t toe = find_toe(xs, zeta, x_up, in);
  // The first station the search looks at: a toe there means the surface already stands above the
  // threshold at the search start, so the jump reaches the upstream section (or lies upstream of it).
  std::size_t search_start = 0;
  while (search_start < xs.size() && xs[search_start] < x_up) ++search_start;
  // The same criterion on each frame's instantaneous surface: how much the toe moves.
  if (!m.station_surface_series.empty()) {
    std::vector<double> toes;  // one per frame (NaN without a toe), aligned with m.times
    for (const auto& frame : m.station_surface_series) {
      if (frame.size() != xs.size()) {
        toes.push_back(not_a_number);
        continue;
      }
      std::vector<double> z(frame.size());
      for (std::size_t i = 0; i < frame.size(); ++i) z[i] = frame[i] - in.floor_z_m;
      const std::size_t k = find_toe(xs, z, x_up, in);
      toes.push_back(k < xs.size() ? xs[k] : not_a_number);
      if (up && k == search_start) ++r.toe_frames_at_search_start;
    }
    const ScalarStats ts = stats_of(toes);
    r.toe_mean_of_frames_x_m = ts.mean;
    r.toe_std_m = ts.std;
    r.toe_frames_found = ts.count;
    if (m.times.size() == toes.size()) r.toe_trend_m_per_s = cases::least_squares_slope(m.times, toes);
    if (r.toe_frames_at_search_start > 0) {
      std::ostringstream s;
      s << "in " << r.toe_frames_at_search_start << " of " << toes.size() << " frames the toe is at the search start (x = "
        << xs[std::min(search_start, xs.size() - 1)]
        << " m, the \"upstream\" section): the roller reaches that section or lies upstream of it, so those frames' toes"
           " are downstream bounds and the frames' toe mean and standard deviation are biased";
      r.notes.push_back(s.str());
    }
    r.toe_frames_x_m = std::move(toes);
  }
  if (toe == st.size()) {
    // No jump in the reach (swept out downstream, or never formed): the downstream section samples
    // the incoming stream, not a sequent depth, so its values would be silently wrong.
    std::ostringstream s;
    s << "no jump toe: the mean surface never stays above " << in.options.toe_threshold_y1 << " y1 = "
      << in.options.toe_threshold_y1 * y1 << " m above the floor, so y2, E2, eta, the bed force, Lr and Lj are unavailable";
    r.notes.push_back(s.str());
    drop_downstream_values(r);
    return r;
  }
  r.toe_x_m = st[toe].spec.x_m;
  // A jump swept past the downstream section: that section samples the incoming stream (or the
  // jump itself), not the sequent depth, so y2, E2 and eta would be silently wrong; the roller and
  // the settling lie beyond the sections.
  if (down && r.toe_x_m >= x_down) {
    std::ostringstream s;
    s << "the toe (x = " << r.toe_x_m << " m) lies downstream of the \"downstream\" section (x = " << x_down
      << " m): the jump was swept past it, so y2, E2, eta, the bed force, Lr and Lj are unavailable";
    r.notes.push_back(s.str());
    drop_downstream_values(r);
    return r;
  }
  // A mean toe at the search start: the mean surface already stands above the threshold at the
  // upstream section, so E1 there is sampled in the roller (not the incoming stream) and the true toe
  // lies at or upstream of it; Lr and Lj measured from it would be too short.
  if (up && toe == search_start) {
    std::ostringstream s;
    s << "the mean surface already stands above " << in.options.toe_threshold_y1 << " y1 at the \"upstream\" section (x = "
      << r.toe_x_m << " m, where the toe search starts): the jump reaches it, so the toe lies at or upstream of it,"
         " and E1, eta, the bed force, Lr and Lj are unavailable";
    r.notes.push_back(s.str());
    drop_upstream_values(r);
    return r;
  }
  std::size_t last = toe;  // last station up to the downstream section
  while (last + 1 < st.size() && st[last + 1].spec.x_m <= x_down + 1e-12) ++last;

  // Surface peak: a classic roller jump's mean surface rises to about y2 and stays there; a crest well
  // above y2 between the toe and the downstream section is a standing wave over the jump (the inflow jet
  // deflected up to the surface, the recirculation below it), whatever the four numbers say.
  for (std::size_t i = toe; i <= last && i < st.size(); ++i) {
    // !(a <= b) rather than a > b: true for the first finite value while the peak is still NaN.
    if (std::isfinite(zm[i]) && !(zm[i] <= r.surface_peak_m)) {
      r.surface_peak_m = zm[i];
      r.surface_peak_x_m = st[i].spec.x_m;
    }
  }
  if (std::isfinite(r.sequent_depth_m) && r.surface_peak_m > (1.0 + in.options.surface_peak_tolerance) * r.sequent_depth_m) {
    std::ostringstream s;
    s << "the mean surface peaks at " << r.surface_peak_m / r.sequent_depth_m << " y2 (" << r.surface_peak_m
      << " m above the floor at x = " << r.surface_peak_x_m
      << " m) between the toe and the downstream section: a standing wave over the jump, not the monotonic rise"
         " of a roller jump";
    r.notes.push_back(s.str());
  }
  // Roller: last station with reverse near-surface flow (its index: where the jump-end search starts).
  std::size_t roller_end = toe;
  for (std::size_t i = last + 1; i-- > toe + 1;) {
    if (st[i].near_surface_velocity.mean < 0.0) {
      roller_end = i;
      r.roller_end_x_m = st[i].spec.x_m;
      r.roller_length_m = r.roller_end_x_m - r.toe_x_m;
      break;
    }
  }
  if (!std::isfinite(r.roller_length_m))
    r.notes.push_back("no reverse near-surface flow downstream of the toe: roller length unavailable");
  // Jump end (section 3-3). The laboratory sections lie in the order toe (1-1), roller end (2-2),
  // settled surface (3-3), so the search starts at the roller end: a flat roller whose mean surface
  // is already inside the band would otherwise end the jump inside its own roller (Lj < Lr).
  if (std::isfinite(r.sequent_depth_m)) {
    const double band = in.options.settle_tolerance * std::abs(r.sequent_depth_m - y1);
    const auto settled = [&](std::size_t i) { return std::isfinite(zm[i]) && std::abs(zm[i] - r.sequent_depth_m) <= band; };
    const std::size_t end = start_of_settled_tail(roller_end, last, settled);
    if (end <= last) {
      r.jump_end_x_m = st[end].spec.x_m;
      r.jump_length_m = r.jump_end_x_m - r.toe_x_m;
      if (end == roller_end && roller_end > toe && settled(roller_end - 1)) {
        std::ostringstream s;
        s << "the mean surface is within the settling band already inside the roller; the jump ends at the roller end"
             " (x = " << r.jump_end_x_m << " m)";
        r.notes.push_back(s.str());
      }
    } else {
      r.notes.push_back("the surface has not settled within the tolerance at the downstream section");
    }
  }
  // Velocity decay.
  const double u_ref = st[last].max_velocity.mean;
  if (std::isfinite(u_ref)) {
    const double tol = in.options.velocity_settle_tolerance * std::abs(u_ref);
    const std::size_t k =
        start_of_settled_tail(toe, last, [&](std::size_t i) { return std::abs(st[i].max_velocity.mean - u_ref) <= tol; });
    if (k <= last) r.velocity_settling_distance_m = st[k].spec.x_m - r.toe_x_m;
  }
  return r;
}

}  // namespace hydrojump::compare
