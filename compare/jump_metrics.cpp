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

// The structure at the section "x_2y2": the height of the fastest forward flow over the depth,
//   jet_height_fraction = (z(u_max) - z_bed) / h,
// and the RMS deviation of its profile from the plane wall jet's (jump_structure.hpp).
static void wall_jet_structure(const MethodStatistics& m, JumpMetrics& r) {
  for (const auto& s : m.sections) {
    if (s.spec.name != "x_2y2" || s.n_wet == 0) continue;
    const WallJetFit fit = fit_wall_jet(s);
    if (s.depth.mean > 0.0) r.jet_height_fraction = fit.max_height_m / s.depth.mean;
    r.wall_jet_deviation = fit.deviation;
    break;
  }
}

// The depths and energies of the "upstream" and "downstream" sections:
//   upstream depth = <surface> - z_floor,   E1 = E(upstream)
//   y2             = <surface> - z_floor,   E2 = E(downstream)   (E: section_energy)
// with a note for a section that is absent or never wet.
static void section_values(const ColumnStatistics* up, const ColumnStatistics* down, const JumpInputs& in,
                           JumpMetrics& r) {
  const double g = in.gravity_m_s2;
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
}

// The laboratory's specific energy of a section, y the mean surface above the floor (crest) level and
// q the section's mean discharge:
//   E = y + q^2/(2 g y^2)
static double crest_energy(const ColumnStatistics& c, const JumpInputs& in) {
  const double g = in.gravity_m_s2;
  const double y = c.surface.mean - in.floor_z_m, q = c.discharge.mean;
  return y + q * q / (2.0 * g * y * y);
}

// The dissipation rates and the bed force between the two sections (r.e1_m and r.e2_m set):
//   eta = (E1 - E2)/E1 with alpha (eta), with alpha = 1 (eta_alpha1), with the crest depth (eta_crest_depth)
//   bed_force_fraction = (M1 - M2)/M1,   M = h^2/2 + beta q^2/(g h)
static void dissipation_and_bed_force(const ColumnStatistics& up, const ColumnStatistics& down, const JumpInputs& in,
                                      JumpMetrics& r) {
  const double g = in.gravity_m_s2;
  r.eta = dissipation_rate(r.e1_m, r.e2_m);
  r.eta_alpha1 = dissipation_rate(section_energy(up, g, true), section_energy(down, g, true));
  r.eta_crest_depth = dissipation_rate(crest_energy(up, in), crest_energy(down, in));
  r.specific_force_upstream_m2 = up.specific_force.mean;
  r.specific_force_downstream_m2 = down.specific_force.mean;
  r.bed_force_fraction = (r.specific_force_upstream_m2 - r.specific_force_downstream_m2) / r.specific_force_upstream_m2;
}

// Continuity check: in a steady window both sections carry the inflow's q = y1 U1. A mean q off by
// more than 5 %,
//   |<q> / (y1 U1) - 1| > 0.05,
// means the basin was still filling or draining (or the section is in spray), so E2, eta and M2 there
// are not those of a stationary jump: a note per such section.
static void continuity_notes(const ColumnStatistics& up, const ColumnStatistics& down, const JumpInputs& in,
                             JumpMetrics& r) {
  const double q_in = in.inflow_depth_m * in.inflow_velocity_m_s;
  for (const ColumnStatistics* c : {&up, &down}) {
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

// The time-mean surface along the stations and where the jump lies on it.
struct SurfaceLine {
  std::vector<double> x;         // the stations' positions
  std::vector<double> zeta;      // time-mean surface above the floor
  std::vector<double> smoothed;  // zeta's running mean over toe_window_y1 * y1
  double x_up = 0.0, x_down = 0.0;   // the "upstream" and "downstream" sections (else the line's ends)
  bool has_upstream = false, has_downstream = false;
  std::size_t toe = 0;           // the toe station (x.size(): none)
  std::size_t search_start = 0;  // the first station the toe search looks at (x >= x_up)
};

// The surface line of the stations (at least 3): zeta_i = <surface>_i - z_floor, its running mean over
// half = round(0.5 toe_window_y1 y1 / ds) stations each side, ds = (x_last - x_first)/(n - 1), and the
// toe by find_toe from the upstream section on.
static SurfaceLine surface_line(const MethodStatistics& m, const ColumnStatistics* up, const ColumnStatistics* down,
                                const JumpInputs& in) {
  const auto& st = m.stations;
  SurfaceLine l;
  l.x.resize(st.size());
  l.zeta.resize(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) {
    l.x[i] = st[i].spec.x_m;
    l.zeta[i] = st[i].surface.mean - in.floor_z_m;
  }
  const double ds = (l.x.back() - l.x.front()) / static_cast<double>(l.x.size() - 1);
  const int half = std::max(0, static_cast<int>(std::lround(0.5 * in.options.toe_window_y1 * in.inflow_depth_m / ds)));
  l.smoothed = cases::running_mean(l.zeta, half);
  l.x_down = down ? down->spec.x_m : st.back().spec.x_m;
  l.x_up = up ? up->spec.x_m : st.front().spec.x_m;
  l.has_upstream = up != nullptr;
  l.has_downstream = down != nullptr;
  l.toe = find_toe(l.x, l.zeta, l.x_up, in);
  // A toe at the first station the search looks at means the surface already stands above the
  // threshold at the search start, so the jump reaches the upstream section (or lies upstream of it).
  while (l.search_start < l.x.size() && l.x[l.search_start] < l.x_up) ++l.search_start;
  return l;
}

// The same toe criterion on each frame's instantaneous surface: how much the toe moves. Each frame's
// toe (NaN without one), their mean, standard deviation and count, the trend
//   toe_trend = least-squares slope of the frames' toes against time,
// and a note when frames have their toe at the search start.
static void frame_toes(const MethodStatistics& m, const SurfaceLine& line, const JumpInputs& in, JumpMetrics& r) {
  const std::vector<double>& xs = line.x;
  std::vector<double> toes;  // one per frame (NaN without a toe), aligned with m.times
  for (const auto& frame : m.station_surface_series) {
    if (frame.size() != xs.size()) {
      toes.push_back(not_a_number);
      continue;
    }
    std::vector<double> z(frame.size());
    for (std::size_t i = 0; i < frame.size(); ++i) z[i] = frame[i] - in.floor_z_m;
    const std::size_t k = find_toe(xs, z, line.x_up, in);
    toes.push_back(k < xs.size() ? xs[k] : not_a_number);
    if (line.has_upstream && k == line.search_start) ++r.toe_frames_at_search_start;
  }
  const ScalarStats ts = stats_of(toes);
  r.toe_mean_of_frames_x_m = ts.mean;
  r.toe_std_m = ts.std;
  r.toe_frames_found = ts.count;
  if (m.times.size() == toes.size()) r.toe_trend_m_per_s = cases::least_squares_slope(m.times, toes);
  if (r.toe_frames_at_search_start > 0) {
    std::ostringstream s;
    s << "in " << r.toe_frames_at_search_start << " of " << toes.size() << " frames the toe is at the search start (x = "
      << xs[std::min(line.search_start, xs.size() - 1)]
      << " m, the \"upstream\" section): the roller reaches that section or lies upstream of it, so those frames' toes"
         " are downstream bounds and the frames' toe mean and standard deviation are biased";
    r.notes.push_back(s.str());
  }
  r.toe_frames_x_m = std::move(toes);
}

// The toe x_t of the time-mean surface, and whether the jump lies between the sections: false (with a
// note, and the values the misplaced jump spoils dropped) when there is no toe, when the toe lies at or
// past the "downstream" section, or when it lies at the search start (the jump reaches the "upstream"
// section); the lengths are then not measured.
static bool jump_between_sections(const std::vector<ColumnStatistics>& st, const SurfaceLine& line,
                                  const JumpInputs& in, JumpMetrics& r) {
  const double y1 = in.inflow_depth_m;
  if (line.toe == st.size()) {
    // No jump in the reach (swept out downstream, or never formed): the downstream section samples
    // the incoming stream, not a sequent depth, so its values would be silently wrong.
    std::ostringstream s;
    s << "no jump toe: the mean surface never stays above " << in.options.toe_threshold_y1 << " y1 = "
      << in.options.toe_threshold_y1 * y1 << " m above the floor, so y2, E2, eta, the bed force, Lr and Lj are unavailable";
    r.notes.push_back(s.str());
    drop_downstream_values(r);
    return false;
  }
  r.toe_x_m = st[line.toe].spec.x_m;
  // A jump swept past the downstream section: that section samples the incoming stream (or the
  // jump itself), not the sequent depth, so y2, E2 and eta would be silently wrong; the roller and
  // the settling lie beyond the sections.
  if (line.has_downstream && r.toe_x_m >= line.x_down) {
    std::ostringstream s;
    s << "the toe (x = " << r.toe_x_m << " m) lies downstream of the \"downstream\" section (x = " << line.x_down
      << " m): the jump was swept past it, so y2, E2, eta, the bed force, Lr and Lj are unavailable";
    r.notes.push_back(s.str());
    drop_downstream_values(r);
    return false;
  }
  // A mean toe at the search start: the mean surface already stands above the threshold at the
  // upstream section, so E1 there is sampled in the roller (not the incoming stream) and the true toe
  // lies at or upstream of it; Lr and Lj measured from it would be too short.
  if (line.has_upstream && line.toe == line.search_start) {
    std::ostringstream s;
    s << "the mean surface already stands above " << in.options.toe_threshold_y1 << " y1 at the \"upstream\" section (x = "
      << r.toe_x_m << " m, where the toe search starts): the jump reaches it, so the toe lies at or upstream of it,"
         " and E1, eta, the bed force, Lr and Lj are unavailable";
    r.notes.push_back(s.str());
    drop_upstream_values(r);
    return false;
  }
  return true;
}

// The last station from the toe on that lies at or upstream of the downstream section.
static std::size_t last_station_to_downstream(const std::vector<ColumnStatistics>& st, const SurfaceLine& line) {
  std::size_t last = line.toe;
  while (last + 1 < st.size() && st[last + 1].spec.x_m <= line.x_down + 1e-12) ++last;
  return last;
}

// Surface peak: the highest smoothed mean surface from the toe to station `last`, and where. A classic
// roller jump's mean surface rises to about y2 and stays there; a crest well above y2,
//   peak > (1 + surface_peak_tolerance) y2,
// is a standing wave over the jump (the inflow jet deflected up to the surface, the recirculation below
// it), whatever the four numbers say: a note.
static void surface_peak(const std::vector<ColumnStatistics>& st, const SurfaceLine& line, std::size_t last,
                         const JumpInputs& in, JumpMetrics& r) {
  const std::vector<double>& zm = line.smoothed;
  for (std::size_t i = line.toe; i <= last && i < st.size(); ++i) {
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
}

// Roller: the last station in (toe, last] with reverse near-surface flow (u(eta - 0.1 h) < 0),
//   Lr = x_roller - x_t;
// returns its index, where the jump-end search starts (the toe without a roller, with a note).
static std::size_t roller_end(const std::vector<ColumnStatistics>& st, std::size_t toe, std::size_t last,
                              JumpMetrics& r) {
  std::size_t end = toe;
  for (std::size_t i = last + 1; i-- > toe + 1;) {
    if (st[i].near_surface_velocity.mean < 0.0) {
      end = i;
      r.roller_end_x_m = st[i].spec.x_m;
      r.roller_length_m = r.roller_end_x_m - r.toe_x_m;
      break;
    }
  }
  if (!std::isfinite(r.roller_length_m))
    r.notes.push_back("no reverse near-surface flow downstream of the toe: roller length unavailable");
  return end;
}

// Jump end (section 3-3): the first station from the roller end on from which the smoothed mean surface
// stays within the band up to station `last`,
//   |zeta - y2| <= settle_tolerance |y2 - y1|,   Lj = x_end - x_t.
// The laboratory sections lie in the order toe (1-1), roller end (2-2), settled surface (3-3), so the
// search starts at the roller end: a flat roller whose mean surface is already inside the band would
// otherwise end the jump inside its own roller (Lj < Lr).
static void jump_end(const std::vector<ColumnStatistics>& st, const SurfaceLine& line, std::size_t roller,
                     std::size_t last, const JumpInputs& in, JumpMetrics& r) {
  if (!std::isfinite(r.sequent_depth_m)) return;
  const std::vector<double>& zm = line.smoothed;
  const double band = in.options.settle_tolerance * std::abs(r.sequent_depth_m - in.inflow_depth_m);
  const auto settled = [&](std::size_t i) { return std::isfinite(zm[i]) && std::abs(zm[i] - r.sequent_depth_m) <= band; };
  const std::size_t end = start_of_settled_tail(roller, last, settled);
  if (end <= last) {
    r.jump_end_x_m = st[end].spec.x_m;
    r.jump_length_m = r.jump_end_x_m - r.toe_x_m;
    if (end == roller && roller > line.toe && settled(roller - 1)) {
      std::ostringstream s;
      s << "the mean surface is within the settling band already inside the roller; the jump ends at the roller end"
           " (x = " << r.jump_end_x_m << " m)";
      r.notes.push_back(s.str());
    }
  } else {
    r.notes.push_back("the surface has not settled within the tolerance at the downstream section");
  }
}

// Velocity decay: the settling distance, the first x - x_t from which the mean maximum velocity stays
// within the tolerance of its value at station `last`,
//   |u_max(x) - u_max(x_last)| <= velocity_settle_tolerance |u_max(x_last)|.
static void velocity_settling(const std::vector<ColumnStatistics>& st, std::size_t toe, std::size_t last,
                              const JumpInputs& in, JumpMetrics& r) {
  const double u_ref = st[last].max_velocity.mean;
  if (!std::isfinite(u_ref)) return;
  const double tol = in.options.velocity_settle_tolerance * std::abs(u_ref);
  const std::size_t k =
      start_of_settled_tail(toe, last, [&](std::size_t i) { return std::abs(st[i].max_velocity.mean - u_ref) <= tol; });
  if (k <= last) r.velocity_settling_distance_m = st[k].spec.x_m - r.toe_x_m;
}

JumpMetrics compute_jump_metrics(const MethodStatistics& m, const JumpInputs& in) {
  JumpMetrics r;
  wall_jet_structure(m, r);
  const ColumnStatistics* up = find_role(m, "upstream");
  const ColumnStatistics* down = find_role(m, "downstream");
  section_values(up, down, in, r);
  if (std::isfinite(r.e1_m) && std::isfinite(r.e2_m)) {  // both sections wet
    dissipation_and_bed_force(*up, *down, in, r);
    continuity_notes(*up, *down, in, r);
  }

  // Longitudinal analysis on the stations.
  const auto& st = m.stations;
  if (st.size() < 3) {
    r.notes.push_back("fewer than 3 stations along the channel: toe, Lj and Lr unavailable");
    return r;
  }
  const SurfaceLine line = surface_line(m, up, down, in);
  if (!m.station_surface_series.empty()) frame_toes(m, line, in, r);
  if (!jump_between_sections(st, line, in, r)) return r;
  const std::size_t last = last_station_to_downstream(st, line);
  surface_peak(st, line, last, in, r);
  const std::size_t roller = roller_end(st, line.toe, last, r);
  jump_end(st, line, roller, last, in, r);
  velocity_settling(st, line.toe, last, in, r);
  return r;
}

}  // namespace hydrojump::compare
