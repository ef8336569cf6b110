#include "compare/report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "util/atomic_file.hpp"
#include "compare/json_writer.hpp"
#include "compare/plots.hpp"
#include "hydrojump/version.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

using json::Json;
using json::json_number;
using json::json_string;

namespace {

std::string num(double v, int precision = 6) {
  if (!std::isfinite(v)) return "nan";
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

// For human-readable tables: fixed decimals, "—" when missing.
std::string fix(double v, int decimals) {
  if (!std::isfinite(v)) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

std::string signed_fix(double v, int decimals) {
  if (!std::isfinite(v)) return "—";
  std::ostringstream s;
  s << std::showpos << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

void stats_json(Json& j, const std::string& name, const ScalarStats& s) {
  j.key(name).begin_object().field("mean", s.mean).field("std", s.std).field("count", s.count).end_object();
}

void metrics_json(Json& j, const JumpMetrics& m) {
  j.begin_object()
      .field("toe_x_m", m.toe_x_m)
      .field("toe_mean_of_frames_x_m", m.toe_mean_of_frames_x_m)
      .field("toe_std_m", m.toe_std_m)
      .field("toe_frames_found", m.toe_frames_found)
      .field("toe_frames_at_search_start", m.toe_frames_at_search_start)
      .field("toe_trend_m_per_s", m.toe_trend_m_per_s)
      .field("sequent_depth_m", m.sequent_depth_m)
      .field("sequent_depth_std_m", m.sequent_depth_std_m)
      .field("upstream_depth_m", m.upstream_depth_m)
      .field("jump_end_x_m", m.jump_end_x_m)
      .field("jump_length_m", m.jump_length_m)
      .field("roller_end_x_m", m.roller_end_x_m)
      .field("roller_length_m", m.roller_length_m)
      .field("e1_m", m.e1_m)
      .field("e2_m", m.e2_m)
      .field("eta", m.eta)
      .field("eta_alpha1", m.eta_alpha1)
      .field("eta_crest_depth", m.eta_crest_depth)
      .field("specific_force_upstream_m2", m.specific_force_upstream_m2)
      .field("specific_force_downstream_m2", m.specific_force_downstream_m2)
      .field("bed_force_fraction", m.bed_force_fraction)
      .field("velocity_settling_distance_m", m.velocity_settling_distance_m)
      .field("jet_height_fraction", m.jet_height_fraction)
      .field("wall_jet_deviation", m.wall_jet_deviation)
      .field("surface_peak_m", m.surface_peak_m)
      .field("surface_peak_x_m", m.surface_peak_x_m);
  j.key("notes").begin_array();
  for (const auto& n : m.notes) j.value(n);
  j.end_array().end_object();
}

void method_json(Json& j, const MethodOutcome& m) {
  j.begin_object().field("available", m.available).field("status", m.status).field("source", m.source);
  if (m.available) {
    j.key("times_s").begin_array();
    for (double t : m.stats.times) j.value(t);
    j.end_array();
    j.key("sections").begin_array();
    for (const auto& s : m.stats.sections) {
      j.begin_object().field("name", s.spec.name).field("role", s.spec.role).field("x_m", s.spec.x_m)
          .field("z_bed_m", s.spec.z_bed_m).field("n_times", s.n_times).field("n_wet", s.n_wet);
      stats_json(j, "surface_m", s.surface);
      stats_json(j, "surface_from_fraction_m", s.surface_from_fraction);
      stats_json(j, "depth_m", s.depth);
      stats_json(j, "discharge_m2_s", s.discharge);
      stats_json(j, "mean_velocity_m_s", s.mean_velocity);
      stats_json(j, "max_velocity_m_s", s.max_velocity);
      stats_json(j, "near_surface_velocity_m_s", s.near_surface_velocity);
      stats_json(j, "energy_coefficient", s.energy_coefficient);
      stats_json(j, "specific_energy_m", s.specific_energy);
      stats_json(j, "momentum_coefficient", s.momentum_coefficient);
      stats_json(j, "specific_force_m2", s.specific_force);
      stats_json(j, "void_fraction", s.void_fraction);
      j.end_object();
    }
    j.end_array();
    j.key("metrics");
    metrics_json(j, m.metrics);
  }
  j.end_object();
}

// Markdown and HTML written side by side from the same calls.
class Doc {
 public:
  void heading(int level, const std::string& text) {
    md_ << std::string(static_cast<std::size_t>(level), '#') << " " << text << "\n\n";
    html_ << "<h" << level << ">" << esc(text) << "</h" << level << ">\n";
  }
  void paragraph(const std::string& md, const std::string& plain) {
    md_ << md << "\n\n";
    html_ << "<p>" << esc(plain) << "</p>\n";
  }
  void para(const std::string& text) { paragraph(text, text); }
  void bullets(const std::vector<std::string>& items) {
    html_ << "<ul>\n";
    for (const auto& i : items) {
      md_ << "- " << i << "\n";
      html_ << "<li>" << esc(i) << "</li>\n";
    }
    md_ << "\n";
    html_ << "</ul>\n";
  }
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
    md_ << "|";
    for (const auto& h : header) md_ << " " << h << " |";
    md_ << "\n|";
    for (std::size_t i = 0; i < header.size(); ++i) md_ << (i == 0 ? "---|" : "---:|");
    md_ << "\n";
    html_ << "<table>\n<tr>";
    for (const auto& h : header) html_ << "<th>" << esc(h) << "</th>";
    html_ << "</tr>\n";
    for (const auto& r : rows) {
      md_ << "|";
      html_ << "<tr>";
      for (const auto& c : r) {
        md_ << " " << c << " |";
        html_ << "<td>" << esc(c) << "</td>";
      }
      md_ << "\n";
      html_ << "</tr>\n";
    }
    md_ << "\n";
    html_ << "</table>\n";
  }
  void figure(const fs::path& png, const std::string& relative, const std::string& caption) {
    md_ << "![" << caption << "](" << relative << ")\n\n*" << caption << "*\n\n";
    std::ifstream in(png, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    html_ << "<figure><img src=\"data:image/png;base64," << base64_encode(s.str()) << "\" alt=\"" << esc(caption)
          << "\"><figcaption>" << esc(caption) << "</figcaption></figure>\n";
  }
  std::string markdown() const { return md_.str(); }
  std::string html(const std::string& title) const {
    return "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + esc(title) +
           "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}"
           "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
           "td:first-child,th:first-child{text-align:left}img{max-width:100%}figcaption{font-style:italic}</style>"
           "</head><body>\n" +
           html_.str() + "</body></html>\n";
  }
  static std::string esc(const std::string& s) {
    std::string o;
    for (char ch : s) {
      if (ch == '<') o += "&lt;";
      else if (ch == '>') o += "&gt;";
      else if (ch == '&') o += "&amp;";
      else if (ch == '"') o += "&quot;";
      else o += ch;
    }
    return o;
  }

 private:
  std::ostringstream md_, html_;
};

const MethodOutcome* methods_of(const CaseComparison& c, int i) { return i == 0 ? &c.sph : &c.vof; }

// csv/case.csv: the case's inputs, the window, the laboratory y2 and Lj, and per method whether it is
// available and its toe, jump end and roller end, as key,value rows.
std::string case_csv(const CaseComparison& c) {
  std::ostringstream s;
  s << "key,value\n"
    << "case," << c.case_id << "\nresolution," << c.resolution << "\ninflow_depth_m," << num(c.inflow_depth_m)
    << "\ninflow_velocity_m_s," << num(c.inflow_velocity_m_s) << "\ntailwater_depth_m," << num(c.tailwater_depth_m)
    << "\nbelanger_y2_m," << num(c.belanger_y2_m) << "\nfloor_z_m," << num(c.floor_z_m) << "\nbasin_start_m,"
    << num(c.basin_start_m) << "\nbasin_end_m," << num(c.basin_end_m) << "\nbed_wavelength_m," << num(c.bed_wavelength_m) << "\nwindow_start_s," << num(c.window_start_s)
    << "\nwindow_end_s," << num(c.window_end_s) << "\nmeasured_y2_m,"
    << num(c.lab.sequent_depth_m.value_or(not_a_number)) << "\nmeasured_jump_length_m,"
    << num(c.lab.jump_length_m.value_or(not_a_number)) << "\n";
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    s << m->method << "_available," << (m->available ? 1 : 0) << "\n";
    s << m->method << "_toe_x_m," << num(m->available ? m->metrics.toe_x_m : not_a_number) << "\n";
    s << m->method << "_jump_end_x_m," << num(m->available ? m->metrics.jump_end_x_m : not_a_number) << "\n";
    s << m->method << "_roller_end_x_m," << num(m->available ? m->metrics.roller_end_x_m : not_a_number) << "\n";
  }
  return s.str();
}

// csv/sections.csv: per available method and section, the time means and standard deviations.
std::string sections_csv(const CaseComparison& c) {
  std::ostringstream sec;
  sec << "method,section,role,x_m,z_bed_m,n_times,n_wet,surface_mean_m,surface_std_m,surface_from_fraction_mean_m,"
         "depth_mean_m,depth_std_m,discharge_mean_m2_s,discharge_std_m2_s,mean_velocity_mean_m_s,"
         "mean_velocity_std_m_s,max_velocity_mean_m_s,max_velocity_std_m_s,energy_coefficient_mean,"
         "specific_energy_mean_m,specific_energy_std_m,momentum_coefficient_mean,specific_force_mean_m2,"
         "specific_force_std_m2,void_fraction_mean\n";
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (!m->available) continue;
    for (const auto& s : m->stats.sections)
      sec << m->method << "," << s.spec.name << "," << s.spec.role << "," << num(s.spec.x_m) << "," << num(s.spec.z_bed_m)
          << "," << s.n_times << "," << s.n_wet << "," << num(s.surface.mean) << "," << num(s.surface.std) << ","
          << num(s.surface_from_fraction.mean) << "," << num(s.depth.mean) << "," << num(s.depth.std) << ","
          << num(s.discharge.mean) << "," << num(s.discharge.std) << "," << num(s.mean_velocity.mean) << ","
          << num(s.mean_velocity.std) << "," << num(s.max_velocity.mean) << "," << num(s.max_velocity.std) << ","
          << num(s.energy_coefficient.mean) << "," << num(s.specific_energy.mean) << "," << num(s.specific_energy.std)
          << "," << num(s.momentum_coefficient.mean) << "," << num(s.specific_force.mean) << ","
          << num(s.specific_force.std) << "," << num(s.void_fraction.mean) << "\n";
  }
  return sec.str();
}

// csv/profiles.csv: per available method and section, the time-mean u(z), its sd, w(z) and the wet fraction.
std::string profiles_csv(const CaseComparison& c) {
  std::ostringstream prof;
  prof << "method,section,x_m,z_m,u_mean_m_s,u_std_m_s,w_mean_m_s,wet_fraction\n";
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (!m->available) continue;
    for (const auto& s : m->stats.sections)
      for (std::size_t k = 0; k < s.z.size(); ++k)
        prof << m->method << "," << s.spec.name << "," << num(s.spec.x_m) << "," << num(s.z[k]) << "," << num(s.u_mean[k])
             << "," << num(s.u_std[k]) << "," << num(s.w_mean[k]) << "," << num(s.wet_fraction[k]) << "\n";
  }
  return prof.str();
}

// csv/longitudinal.csv: per available method and station, the mean surface and velocities.
std::string longitudinal_csv(const CaseComparison& c) {
  std::ostringstream lon;
  lon << "method,x_m,z_bed_m,surface_mean_m,surface_std_m,near_surface_velocity_mean_m_s,mean_velocity_mean_m_s,"
         "max_velocity_mean_m_s,discharge_mean_m2_s,void_fraction_mean,n_times,n_wet\n";
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (!m->available) continue;
    for (const auto& s : m->stats.stations)
      lon << m->method << "," << num(s.spec.x_m) << "," << num(s.spec.z_bed_m) << "," << num(s.surface.mean) << ","
          << num(s.surface.std) << "," << num(s.near_surface_velocity.mean) << "," << num(s.mean_velocity.mean) << ","
          << num(s.max_velocity.mean) << "," << num(s.discharge.mean) << "," << num(s.void_fraction.mean) << ","
          << s.n_times << "," << s.n_wet << "\n";
  }
  return lon.str();
}

// csv/snapshot_<method>.csv: the velocity field of the last frame in the window, its wet grid points.
std::string snapshot_csv(const FieldSnapshot& f) {
  std::ostringstream snap;
  snap << "time_s,x_m,z_m,u_m_s,w_m_s\n";
  for (int iz = 0; iz < f.nz; ++iz)
    for (int ix = 0; ix < f.nx; ++ix) {
      const std::size_t k = static_cast<std::size_t>(iz) * static_cast<std::size_t>(f.nx) + static_cast<std::size_t>(ix);
      if (!std::isfinite(f.u[k])) continue;
      snap << num(f.time_s) << "," << num(f.x0 + ix * f.dx) << "," << num(f.z0 + iz * f.dz) << "," << num(f.u[k], 5)
           << "," << num(f.w[k], 5) << "\n";
    }
  return snap.str();
}

// csv/section_timeseries.csv: per available method, section and output time, the section's values.
std::string section_timeseries_csv(const CaseComparison& c) {
  std::ostringstream ts;
  ts << "method,section,time_s,surface_m,depth_m,discharge_m2_s,mean_velocity_m_s,max_velocity_m_s,"
        "specific_energy_m\n";
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (!m->available) continue;
    for (std::size_t k = 0; k < m->stats.section_series.size() && k < m->stats.sections.size(); ++k)
      for (const auto& t : m->stats.section_series[k])
        ts << m->method << "," << m->stats.sections[k].spec.name << "," << num(t.time_s) << "," << num(t.surface_m)
           << "," << num(t.depth_m) << "," << num(t.discharge_m2_s) << "," << num(t.mean_velocity_m_s) << ","
           << num(t.max_velocity_m_s) << "," << num(t.specific_energy_m) << "\n";
  }
  return ts.str();
}

// csv/toe_frames.csv: the toe criterion on each frame's instantaneous surface ("nan": no toe in that
// frame), to follow a toe that moves over the window; the frames' mean, sd and trend in metrics.csv
// summarise it.
std::string toe_frames_csv(const CaseComparison& c) {
  std::ostringstream s;
  s << "method,time_s,toe_x_m\n";
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (!m->available || m->metrics.toe_frames_x_m.size() != m->stats.times.size()) continue;
    for (std::size_t k = 0; k < m->stats.times.size(); ++k)
      s << m->method << "," << num(m->stats.times[k]) << "," << num(m->metrics.toe_frames_x_m[k]) << "\n";
  }
  return s.str();
}

// csv/metrics.csv: the metric table, SPH, VOF, experiment, published SPH and theory side by side.
std::string metrics_csv(const CaseComparison& c) {
  std::ostringstream s;
  s << "quantity,unit,sph,vof,experiment,published_sph,smooth_theory,status\n";
  for (const auto& r : c.metrics)
    s << r.quantity << "," << r.unit << "," << num(r.sph) << "," << num(r.vof) << "," << num(r.experiment) << ","
      << num(r.published_sph) << "," << num(r.smooth_theory) << "," << r.status << "\n";
  return s.str();
}

// csv/profile_differences.csv: per section, the L2 of the SPH - VOF u(z) difference.
std::string profile_differences_csv(const CaseComparison& c) {
  std::ostringstream s;
  s << "section,x_m,l2_m_s,l2_over_u1,n_points\n";
  for (const auto& p : c.profiles)
    s << p.section << "," << num(p.x_m) << "," << num(p.l2_m_s) << "," << num(p.l2_over_u1) << "," << p.n_points << "\n";
  return s.str();
}

// csv/eta.csv: one row, this case's eta bars (theory, experiment, published SPH, this SPH and VOF, with
// and without the crest-depth convention).
std::string eta_csv(const CaseComparison& c) {
  double sph = not_a_number, vof = not_a_number, sph_crest = not_a_number, vof_crest = not_a_number;
  std::string status = "predicted";
  for (const auto& r : c.metrics) {
    if (r.quantity == "eta") { sph = r.sph; vof = r.vof; status = r.status; }
    if (r.quantity == "eta_crest_depth") { sph_crest = r.sph; vof_crest = r.vof; }
  }
  std::ostringstream s;
  s << "case,smooth_theory_percent,experiment_percent,published_sph_percent,sph_percent,vof_percent,"
       "sph_crest_depth_percent,vof_crest_depth_percent,status\n"
    << c.case_id << "," << num(c.eta_smooth_theory_percent) << ","
    << num(c.lab.eta_percent.value_or(not_a_number)) << "," << num(c.lab.published_sph_eta_percent.value_or(not_a_number))
    << "," << num(sph) << "," << num(vof) << "," << num(sph_crest) << "," << num(vof_crest) << "," << status << "\n";
  return s.str();
}

// Writes the comparison's tables into `dir` (report.hpp lists them).
void write_csvs(const CaseComparison& c, const fs::path& dir) {
  util::write_file_atomically(dir / "case.csv", case_csv(c));
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (m->available && !m->stats.snapshot.empty())
      util::write_file_atomically(dir / ("snapshot_" + m->method + ".csv"), snapshot_csv(m->stats.snapshot));
  }
  util::write_file_atomically(dir / "sections.csv", sections_csv(c));
  util::write_file_atomically(dir / "section_timeseries.csv", section_timeseries_csv(c));
  util::write_file_atomically(dir / "toe_frames.csv", toe_frames_csv(c));
  util::write_file_atomically(dir / "profiles.csv", profiles_csv(c));
  util::write_file_atomically(dir / "longitudinal.csv", longitudinal_csv(c));
  util::write_file_atomically(dir / "metrics.csv", metrics_csv(c));
  util::write_file_atomically(dir / "profile_differences.csv", profile_differences_csv(c));
  util::write_file_atomically(dir / "eta.csv", eta_csv(c));
}

std::string pretty_quantity(const std::string& q) {
  if (q == "upstream_depth") return "upstream depth y1 (m)";
  if (q == "toe_position") return "toe position x_t (m)";
  if (q == "toe_mean_of_frames") return "toe position, mean of the frames' toes (m)";
  if (q == "toe_std") return "toe standard deviation over the frames (m)";
  if (q == "toe_trend") return "toe trend over the window, least-squares slope of the frames' toes (m/s)";
  if (q == "water_imbalance") return "outflow − inflow over the window, from the run's discharges (% of q)";
  if (q == "steady") return "steady by the window means (1 yes, 0 no: |outflow − inflow| < 2 % of q, toe drift)";
  if (q == "sequent_depth") return "sequent depth y2 (m)";
  if (q == "bed_effect") return "bed effect y2/y2* (Bélanger's y2*)";
  if (q == "jump_length") return "jump length Lj (m)";
  if (q == "roller_length") return "roller length Lr (m)";
  if (q == "eta") return "eta = (E1-E2)/E1, with alpha (%)";
  if (q == "eta_alpha1") return "eta with alpha = 1 (%)";
  if (q == "eta_crest_depth") return "eta, lab convention y + q²/(2gy²), y above crests (%)";
  if (q == "bed_force_fraction") return "bed force (M1-M2)/M1, M = h²/2 + βq²/(gh) (%)";
  if (q == "velocity_settling_distance") return "velocity settling distance (m)";
  if (q == "jet_height") return "height of the fastest forward flow at x_2y2 / depth (wall jet < 0.5)";
  if (q == "wall_jet_deviation") return "RMS of u/u_m from Verhoff's wall-jet profile at x_2y2 (classic <= 0.15)";
  if (q == "surface_peak") return "highest mean surface, toe to downstream section (m above the floor)";
  return q;
}

}  // namespace

std::string base64_encode(const std::string& bytes) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += t[(v >> 18) & 63]; out += t[(v >> 12) & 63]; out += t[(v >> 6) & 63]; out += t[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += t[(v >> 18) & 63]; out += t[(v >> 12) & 63]; out += "==";
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += t[(v >> 18) & 63]; out += t[(v >> 12) & 63]; out += t[(v >> 6) & 63]; out += '=';
  }
  return out;
}

std::string comparison_json(const CaseComparison& c) {
  Json j;
  j.begin_object()
      .field("hydrojump_version", std::string(version_string))
      .field("case", c.case_id)
      .field("description", c.description)
      .field("resolution", c.resolution)
      .field("interpolation", c.interpolation);
  j.key("window_s").begin_array().value(c.window_start_s).value(c.window_end_s).end_array();
  j.key("inputs").begin_object()
      .field("inflow_depth_m", c.inflow_depth_m).field("inflow_velocity_m_s", c.inflow_velocity_m_s)
      .field("tailwater_depth_m", c.tailwater_depth_m).field("tailwater_control", c.tailwater_control)
      .field("gravity_m_s2", c.gravity_m_s2)
      .field("belanger_y2_m", c.belanger_y2_m).field("eta_smooth_theory_percent", c.eta_smooth_theory_percent)
      .field("particle_spacing_m", c.particle_spacing_m).field("vof_cell_size_bed_m", c.vof_cell_size_m)
      .field("basin_start_m", c.basin_start_m).field("basin_end_m", c.basin_end_m).end_object();
  j.key("sph");
  method_json(j, c.sph);
  j.key("vof");
  method_json(j, c.vof);
  j.key("sph_vs_vof").begin_object();
  j.key("surface").begin_object().field("rms_m", c.surface.rms_m).field("max_abs_m", c.surface.max_abs_m)
      .field("x_of_max_m", c.surface.x_of_max_m).field("n_stations", c.surface.n_stations).end_object();
  j.key("profiles").begin_array();
  for (const auto& p : c.profiles)
    j.begin_object().field("section", p.section).field("x_m", p.x_m).field("l2_m_s", p.l2_m_s)
        .field("l2_over_u1", p.l2_over_u1).field("n_points", p.n_points).end_object();
  j.end_array().end_object();
  j.key("metrics").begin_array();
  for (const auto& r : c.metrics)
    j.begin_object().field("quantity", r.quantity).field("unit", r.unit).field("sph", r.sph).field("vof", r.vof)
        .field("experiment", r.experiment).field("published_sph", r.published_sph)
        .field("smooth_theory", r.smooth_theory).field("status", r.status).field("sph_minus_vof", r.sph - r.vof)
        .field("sph_minus_experiment", r.sph - r.experiment).field("vof_minus_experiment", r.vof - r.experiment)
        .end_object();
  j.end_array();
  j.field("measured_source", c.measured_source);
  j.field("measured_note", c.measured_note);
  j.end_object();
  return j.str() + "\n";
}

namespace {

// Puts the directory `staged` in the place of `target` (same parent): the old one is moved aside first
// and removed after, so that csv/ and figures/ always hold one comparison's files, never a mixture
// of this one's and an earlier one's (a figure of an earlier run beside a report without it).
void replace_directory(const fs::path& staged, const fs::path& target) {
  std::string old_name = target.filename().string();  // (built step by step: GCC 12 warns falsely on "." + string&&)
  old_name.insert(0, 1, '.');
  old_name += ".old";
  const fs::path old = target.parent_path() / old_name;
  // A replacement cut short (killed between the two renames) left the previous directory aside:
  // it is put back first, so that it is replaced, not lost.
  if (fs::exists(old) && !fs::exists(target)) fs::rename(old, target);
  fs::remove_all(old);
  if (fs::exists(target)) fs::rename(target, old);
  fs::create_directories(staged);
  fs::rename(staged, target);
  fs::remove_all(old);
}

// Writes csv/ and (when `plots` and a method has results) figures/: this comparison's tables and
// figures are made beside the previous ones and then take their place. Returns why the figures could
// not be made (logged too), with the staged directories named by the places they took.
std::string write_tables_and_figures(const CaseComparison& c, const fs::path& out, bool plots, std::ostream& log) {
  const fs::path csv = out / "csv";
  const fs::path figs = out / "figures";
  const fs::path staged_csv = out / ".csv.new", staged_figs = out / ".figures.new";
  fs::remove_all(staged_csv);
  fs::remove_all(staged_figs);
  fs::create_directories(staged_csv);
  write_csvs(c, staged_csv);
  std::string plot_problem;
  if (plots && (c.sph.available || c.vof.available)) plot_problem = plot_case_figures(staged_csv, staged_figs);
  replace_directory(staged_csv, csv);
  replace_directory(staged_figs, figs);
  // The message names the log and the tables where they now are (the staged directories took the places
  // of figures/ and csv/).
  for (const auto& [staged, final_dir] : {std::pair{staged_figs, figs}, std::pair{staged_csv, csv}}) {
    for (auto at = plot_problem.find(staged.string()); at != std::string::npos;
         at = plot_problem.find(staged.string(), at + final_dir.string().size()))
      plot_problem.replace(at, staged.string().size(), final_dir.string());
  }
  if (!plot_problem.empty()) log << "plots: " << plot_problem << std::endl;
  return plot_problem;
}

// The report's title, the case's description, its inputs (resolution, window, inflow, tailwater,
// Bélanger's y2*) and each method's status.
void report_header(Doc& d, const CaseComparison& c) {
  d.heading(1, "Case " + c.case_id + ": SPH vs VOF vs experiment");
  if (!c.description.empty()) d.para(c.description);
  std::ostringstream info;
  info << "Resolution \"" << c.resolution << "\" (SPH dx = " << c.particle_spacing_m << " m, VOF bed cells "
       << c.vof_cell_size_m << " m); averaging window " << c.window_start_s << "–" << c.window_end_s
       << " s; inflow y1 = " << c.inflow_depth_m << " m, U1 = " << c.inflow_velocity_m_s << " m/s (q = "
       << c.inflow_depth_m * c.inflow_velocity_m_s << " m²/s); tailwater " << c.tailwater_depth_m
       << (c.tailwater_control == "hold_toe" ? " m (the initial level: the outlet is steered to hold the toe)"
                                              : " m (held at the outlet)")
       << "; Bélanger y2* = " << fix(c.belanger_y2_m, 4) << " m. Interpolation: " << c.interpolation
       << ". hydrojump " << version_string << ".";
  d.para(info.str());
  std::vector<std::string> status;
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    status.push_back(std::string(i == 0 ? "SPH" : "VOF") + ": " +
                     (m->available ? m->status + ", " + std::to_string(m->stats.times.size()) + " frames from " + m->source
                                   : m->status));
  }
  d.bullets(status);
}

// "Jump metrics": the protocol (what the tailwater control imposes) and the metric table, each metric
// beside the experiment and the inputs-only values, with the differences SPH − VOF, SPH − exp., VOF − exp.
void metric_table_section(Doc& d, const CaseComparison& c) {
  d.heading(2, "Jump metrics");
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : c.metrics) {
    const int dec = r.unit == "%" ? 2 : 4;
    rows.push_back({pretty_quantity(r.quantity), r.status, fix(r.sph, dec), fix(r.vof, dec), fix(r.experiment, dec),
                    fix(r.smooth_theory, dec), fix(r.published_sph, dec), signed_fix(r.sph - r.vof, dec),
                    signed_fix(r.sph - r.experiment, dec), signed_fix(r.vof - r.experiment, dec)});
  }
  d.para(c.tailwater_control == "hold_toe"
             ? "Protocol: the flume's (the outlet steered to hold the toe at the basin start): the toe is imposed; "
               "y2, η, Lj, Lr and the bed force are predictions."
             : "Protocol: the outlet holds the tailwater depth (control = \"fixed_depth\"): y2 and what follows from "
               "it (η, the bed force) are imposed, not results; the toe and the lengths are predictions.");
  d.table({"quantity", "predicted / imposed", "this SPH", "this VOF", "experiment", "inputs only (smooth bed: Bélanger, USBR, Hager)",
           "published SPH", "SPH − VOF", "SPH − exp.", "VOF − exp."},
          rows);
}

// The energy dissipation rate's table, eta = (E1 − E2)/E1 in %: smooth-bed theory, experiment,
// published SPH, this SPH and VOF, and their differences.
void eta_table(Doc& d, const CaseComparison& c) {
  double sph = not_a_number, vof = not_a_number;
  for (const auto& r : c.metrics)
    if (r.quantity == "eta") { sph = r.sph; vof = r.vof; }
  const double exp = c.lab.eta_percent.value_or(not_a_number);
  const double pub = c.lab.published_sph_eta_percent.value_or(not_a_number);
  d.heading(3, std::string("Energy dissipation rate η (%), ") +
                   (c.tailwater_control == "hold_toe" ? "predicted" : "imposed with y2"));
  d.table({"smooth bed (theory)", "experiment", "published SPH", "this SPH", "this VOF", "SPH − exp.", "VOF − exp.",
           "SPH − published SPH"},
          {{fix(c.eta_smooth_theory_percent, 2), fix(exp, 2), fix(pub, 2), fix(sph, 2), fix(vof, 2),
            signed_fix(sph - exp, 2), signed_fix(vof - exp, 2), signed_fix(sph - pub, 2)}});
}

// The available methods' notes (why a metric is missing, water balance, steadiness), as bullets.
void method_notes(Doc& d, const CaseComparison& c) {
  std::vector<std::string> notes;
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (m->available)
      for (const auto& n : m->metrics.notes) notes.push_back(std::string(i == 0 ? "SPH" : "VOF") + ": " + n);
  }
  if (!notes.empty()) d.bullets(notes);
}

// "SPH vs VOF": the time-mean surfaces' RMS and maximum difference over the basin, and per section the
// L2 of the u(z) difference, absolute and over U1.
void sph_vs_vof_section(Doc& d, const CaseComparison& c) {
  d.heading(2, "SPH vs VOF");
  if (!(c.sph.available && c.vof.available)) {
    d.para("Not available: it needs both results (see the status above).");
    return;
  }
  std::ostringstream s;
  s << "Time-mean free surface over the basin (" << c.basin_start_m << "–" << c.basin_end_m << " m, "
    << c.surface.n_stations << " stations): RMS difference " << fix(c.surface.rms_m * 1000, 2)
    << " mm, maximum " << fix(c.surface.max_abs_m * 1000, 2) << " mm at x = " << fix(c.surface.x_of_max_m, 3) << " m.";
  d.para(s.str());
  std::vector<std::vector<std::string>> pr;
  for (const auto& p : c.profiles)
    pr.push_back({p.section, fix(p.x_m, 3), fix(p.l2_m_s, 4), fix(100 * p.l2_over_u1, 2), std::to_string(p.n_points)});
  d.table({"section", "x (m)", "L2 of u(z) difference (m/s)", "L2 / U1 (%)", "points"}, pr);
}

// "Sections": per available method a table of each section's time means (surface ± sd, U, u_max, q,
// α, E, β, M), then the discharge check against the inflow q = y1 U1.
void sections_section(Doc& d, const CaseComparison& c) {
  d.heading(2, "Sections (time means ± standard deviation)");
  for (int i = 0; i < 2; ++i) {
    const MethodOutcome* m = methods_of(c, i);
    if (!m->available) continue;
    std::vector<std::vector<std::string>> sr;
    for (const auto& s : m->stats.sections) {
      sr.push_back({s.spec.name + " (" + s.spec.role + ")", fix(s.spec.x_m, 3),
                    fix(s.surface.mean, 4) + " ± " + fix(s.surface.std, 4), fix(s.surface_from_fraction.mean, 4),
                    fix(s.mean_velocity.mean, 3), fix(s.max_velocity.mean, 3), fix(s.discharge.mean, 4),
                    fix(s.energy_coefficient.mean, 3), fix(s.specific_energy.mean, 4),
                    fix(s.momentum_coefficient.mean, 3), fix(s.specific_force.mean, 5)});
    }
    d.heading(3, i == 0 ? "SPH" : "VOF");
    d.table({"section", "x (m)", "surface η (m)", "η from ∫fraction (m)", "U (m/s)", "u_max (m/s)", "q (m²/s)", "α",
             "E (m)", "β", "M (m²)"},
            sr);
  }
  std::ostringstream qcheck;
  qcheck << "Discharge check: every section's q should equal the inflow q = " << fix(c.inflow_depth_m * c.inflow_velocity_m_s, 4)
         << " m²/s once the jump is steady.";
  d.para(qcheck.str());
}

// "Figures": the figures in `figs` that exist, with their captions, or why they could not be made.
void figures_section(Doc& d, const fs::path& figs, const std::string& plot_problem) {
  d.heading(2, "Figures");
  if (!plot_problem.empty()) d.para("Figures unavailable: " + plot_problem);
  const std::vector<std::pair<std::string, std::string>> figures = {
      {"surface.png", "Time-mean free surface (band: ± one standard deviation), bed, experiment y1 and y2"},
      {"profiles.png", "Time-mean velocity profiles u(z) at the sections"},
      {"velocity_decay.png", "Decay of the maximum and mean velocity along the basin (normalised by U1)"},
      {"eta.png", "Energy dissipation rate: smooth-bed theory, experiment, published SPH, this SPH, this VOF"},
      {"toe_frames.png", "The toe of each frame over the window, the time-mean surface's toe and the basin start"},
      {"snapshot_sph.png", "SPH velocity field, last frame of the window"},
      {"snapshot_vof.png", "VOF velocity field, last frame of the window"}};
  for (const auto& [file, caption] : figures)
    if (fs::exists(figs / file)) d.figure(figs / file, "figures/" + file, caption);
}

// "Definitions": how the surface, E and η, the toe, y2 and the lengths are measured, then where the
// laboratory values come from.
void definitions_section(Doc& d, const CaseComparison& c) {
  d.heading(2, "Definitions");
  d.bullets({"Free surface: SPH, the 0.5 level of the kernel-interpolated fluid fraction sum_j V_j W; VOF, the "
             "alpha = 0.5 crossing along the cells of the vertical line (the column integral of the fraction is "
             "the check shown in the section tables).",
             "E = z_b + h + αU²/(2g) with α = ∫u³dz/(U³h); η = (E1 − E2)/E1 between the upstream and downstream "
             "sections; 'η with α = 1' drops the velocity-profile correction; 'lab convention' uses "
             "E = y + q²/(2gy²) with y the depth above the corrugation crests, as the experiments' values were "
             "computed (it differs from η when a section lies over a trough).",
             "Toe: first x where the running mean (0.8 y1) of the time-mean surface stays above 1.5 y1 over 2 y1 "
             "(x_t); the same criterion on each frame's surface gives the frames' toes, their mean and standard "
             "deviation (a toe that oscillates puts x_t upstream of that mean). y2: time-mean surface at the "
             "downstream section above the upstream floor (corrugation crests).",
             "Roller end: last x with a negative time-mean velocity at 0.1 h below the surface; Lr = end − toe. "
             "Jump end: first x from the roller end on (from the toe without a roller) from which the mean surface "
             "stays within 5 % of (y2 − y1) of y2 up to the downstream section; Lj = end − toe (so Lj ≥ Lr, as "
             "the laboratory sections 1–1, 2–2, 3–3 lie in that order)."});
  if (!c.measured_source.empty()) d.para("Laboratory values: " + c.measured_source);
  if (!c.measured_note.empty()) d.para("Note on the laboratory values: " + c.measured_note);
}

}  // namespace

std::string write_report(const CaseComparison& c, const fs::path& out, bool plots, std::ostream& log) {
  const std::string plot_problem = write_tables_and_figures(c, out, plots, log);
  util::write_file_atomically(out / "comparison.json", comparison_json(c));

  Doc d;
  report_header(d, c);
  metric_table_section(d, c);
  eta_table(d, c);
  method_notes(d, c);
  sph_vs_vof_section(d, c);
  sections_section(d, c);
  figures_section(d, out / "figures", plot_problem);
  definitions_section(d, c);

  util::write_file_atomically(out / "report.md", d.markdown());
  util::write_file_atomically(out / "report.html", d.html("hydrojump comparison, case " + c.case_id));
  log << "report: " << (out / "report.md").string() << ", " << (out / "report.html").string() << ", "
      << (out / "comparison.json").string() << std::endl;
  return plot_problem;
}

}  // namespace hydrojump::compare
