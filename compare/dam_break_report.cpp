#include "compare/dam_break_report.hpp"

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "util/atomic_file.hpp"
#include "util/csv_table.hpp"
#include "util/time_directories.hpp"
#include "compare/json_writer.hpp"
#include "compare/plots.hpp"
#include "hydrojump/version.hpp"
#include "reference/line_samples.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

namespace {

// The SPH front from gauges.csv (t_s, front_x_m); rows without both numbers are left out.
void read_sph_front(const fs::path& run_dir, DamBreakMethodFront& m) {
  const fs::path file = run_dir / "sph" / "gauges.csv";
  m.source = file.string();
  const util::CsvTable table = util::read_csv_table(file);
  const auto t = table.column("t_s");
  const auto x = table.column("front_x_m");
  if (table.header.empty()) {
    m.status = "no " + file.string() + " (run `hydrojump sph " + (run_dir / "sph").string() + "`)";
    return;
  }
  if (!t || !x) {
    m.status = file.string() + " has no columns t_s and front_x_m (not a dam-break run)";
    return;
  }
  for (const auto& row : table.rows) {
    if (row.size() != table.header.size()) continue;
    const double tv = util::csv_number(row[*t]), xv = util::csv_number(row[*x]);
    if (!std::isfinite(tv) || !std::isfinite(xv)) continue;
    if (!m.trace.t_s.empty() && !(tv > m.trace.t_s.back())) continue;
    m.trace.t_s.push_back(tv);
    m.trace.x_m.push_back(xv);
  }
  m.available = m.trace.t_s.size() >= 2;
  m.status = m.available ? "ok" : file.string() + " holds fewer than 2 outputs with a front";
}

// The VOF front from the floor line of every sampled time; a time whose line is dry at its start
// (no water at the column) is left out.
void read_vof_front(const fs::path& run_dir, double cell_size_m, DamBreakMethodFront& m) {
  const fs::path dir = run_dir / "vof" / "postProcessing" / "sections";
  m.source = dir.string();
  if (!fs::is_directory(dir)) {
    m.status = "no " + dir.string() + " (run `hydrojump vof " + (run_dir / "vof").string() + "`)";
    return;
  }
  for (const auto& [t, path] : util::time_directories(dir)) {
    const fs::path line = path / "floor_alpha.water.xy";
    if (!fs::exists(line)) continue;
    try {
      const auto x = reference::surge_front(reference::read_line_sample(line), 2.0 * cell_size_m);
      if (!x) continue;
      m.trace.t_s.push_back(t);
      m.trace.x_m.push_back(*x);
    } catch (const std::exception&) {
      continue;  // a sample being written, or damaged: that time is left out
    }
  }
  m.available = m.trace.t_s.size() >= 2;
  m.status = m.available ? "ok" : dir.string() + " holds fewer than 2 times with a floor-line front";
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

void comparison_json(json::Json& j, const std::string& name, const FrontComparison& f) {
  j.key(name).begin_object();
  j.field("time_shift_s", f.time_shift_s).field("points", f.points).field("measured_points", f.measured_points);
  j.field("mean_abs_error_over_L", f.mean_abs).field("max_abs_error_over_L", f.max_abs);
  j.field("first_point_error_over_L", f.first_point_error).field("late_speed_ratio", f.late_speed_ratio);
  j.end_object();
}

std::string dam_break_json(const DamBreakComparison& c) {
  json::Json j;
  j.begin_object();
  j.field("hydrojump_version", version_string).field("kind", "dam_break").field("case", c.case_id);
  j.field("resolution", c.resolution).field("column_width_m", c.column_width_m);
  j.field("tank_length_m", c.tank_length_m).field("measured", c.measured_source);
  j.field("time_origin", "t_model = t_exp - 0.175 sqrt(L / (2 g)): the experiment's gate opening");
  j.field("time_shift_s", c.time_shift_s);
  for (const DamBreakMethodFront* m : {&c.sph, &c.vof}) {
    j.key(m->method).begin_object();
    j.field("available", m->available).field("status", m->status).field("source", m->source);
    if (m->available) {
      comparison_json(j, "shifted", m->shifted);
      comparison_json(j, "unshifted", m->unshifted);
    }
    j.end_object();
  }
  j.end_object();
  return j.str() + "\n";
}

// x/L of `m`'s comparison at the experiment time t, or NaN when that point was not compared.
double simulated_at(const FrontComparison& f, double t) {
  for (std::size_t k = 0; k < f.t_exp_s.size(); ++k)
    if (f.t_exp_s[k] == t) return f.simulated[k];
  return std::nan("");
}

std::string front_csv(const DamBreakComparison& c) {
  std::ostringstream s;
  s << std::setprecision(8);
  s << "t_exp_s,measured_x_over_L,sph_shifted_x_over_L,sph_unshifted_x_over_L,vof_shifted_x_over_L,"
       "vof_unshifted_x_over_L\n";
  const double scale = std::sqrt(c.column_width_m / measured_front_column_width_m);
  auto cell = [](double v) {
    std::ostringstream o;
    if (std::isfinite(v)) o << std::setprecision(8) << v;
    return o.str();
  };
  for (const MeasuredFrontPoint& p : c.measured) {
    const double t = p.t_s * scale;
    s << t << ',' << p.x_over_l;
    for (const DamBreakMethodFront* m : {&c.sph, &c.vof})
      s << ',' << cell(simulated_at(m->shifted, t)) << ',' << cell(simulated_at(m->unshifted, t));
    s << '\n';
  }
  return s.str();
}

std::string report_markdown(const DamBreakComparison& c, const std::string& figure) {
  std::ostringstream d;
  d << "# Case " << c.case_id << ": dam-break surge front, SPH and VOF against the experiment\n\n";
  if (!c.description.empty()) d << c.description << "\n\n";
  d << "Resolution \"" << c.resolution << "\"; column L = " << c.column_width_m << " m, tank " << c.tank_length_m
    << " m; measured front: " << c.measured_source << ". hydrojump " << version_string << ".\n\n";
  d << "Time origin: the experiment's gate took a finite time to lift, so the model time is compared at\n"
       "t_model = t_exp - 0.175 sqrt(L / (2 g)) = t_exp - "
    << fixed(c.time_shift_s, 4)
    << " s (the model's tau = t sqrt(2 g / L) moved by +0.175 onto the experiment's clock, as in published comparisons with this kind of data). "
       "The unshifted comparison is shown beside it.\n\n";
  d << "| method | time origin | points compared | mean abs(x - x_exp) / L | max | first point | late speed ratio |\n"
       "|---|---|---|---|---|---|---|\n";
  for (const DamBreakMethodFront* m : {&c.sph, &c.vof}) {
    const std::string name = m->method == "sph" ? "SPH" : "VOF";
    if (!m->available) {
      d << "| " << name << " | — | not available: " << m->status << " | | | | |\n";
      continue;
    }
    for (const FrontComparison* f : {&m->shifted, &m->unshifted})
      d << "| " << name << " | " << (f == &m->shifted ? "experiment's (shifted)" : "unshifted") << " | " << f->points
        << " of " << f->measured_points << " | " << fixed(f->mean_abs, 3) << " | " << fixed(f->max_abs, 3) << " | "
        << fixed(f->first_point_error, 3) << " | " << fixed(f->late_speed_ratio, 3) << " |\n";
  }
  d << "\nA point is compared while the measured front is inside the tank and the simulated one short of the "
       "far wall by one particle spacing or cell; the late speed is the least-squares slope after 0.4 s.\n";
  if (!figure.empty()) d << "\n![surge front](" << figure << ")\n";
  return d.str();
}

}  // namespace

DamBreakComparison compare_dam_break(const cases::Study& study, const fs::path& run_dir) {
  const cases::Case& c = study.cases.front();
  const cases::DamBreakCase* d = c.dam_break();
  if (d == nullptr) throw std::runtime_error("case \"" + c.id + "\" is not a dam break");
  if (d->measured_front_file.empty())
    throw std::runtime_error(study.source_file.string() + ": case \"" + c.id +
                             "\" has no measured front (case.measured.front_file) to compare with");
  const cases::Resolution& res = c.resolutions.begin()->second;
  DamBreakComparison r;
  r.case_id = c.id;
  r.description = c.description;
  r.resolution = res.name;
  r.column_width_m = d->column_width_m;
  r.tank_length_m = d->tank_length_m;
  r.gravity_m_s2 = study.fluid.gravity_m_s2;
  r.time_shift_s = gate_opening_time_shift_s(r.column_width_m, r.gravity_m_s2);
  r.measured_source = d->measured_front_file.string();
  r.measured = read_measured_front(d->measured_front_file);
  r.sph.method = "sph";
  r.vof.method = "vof";
  read_sph_front(run_dir, r.sph);
  read_vof_front(run_dir, res.vof_cell_size_bed_m, r.vof);
  const std::pair<DamBreakMethodFront*, double> methods[] = {{&r.sph, res.particle_spacing_m},
                                                             {&r.vof, res.vof_cell_size_bed_m}};
  for (const auto& [m, margin] : methods) {
    if (!m->available) continue;
    FrontSetup setup{r.column_width_m, r.tank_length_m, margin, r.time_shift_s};
    m->shifted = compare_front(m->trace, r.measured, setup);
    setup.time_shift_s = 0.0;
    m->unshifted = compare_front(m->trace, r.measured, setup);
  }
  return r;
}

std::string write_dam_break_report(const DamBreakComparison& c, const fs::path& out, bool plots, std::ostream& log) {
  fs::create_directories(out / "csv");
  util::write_file_atomically(out / "csv" / "front.csv", front_csv(c));
  util::write_file_atomically(out / "comparison.json", dam_break_json(c));
  std::string problem;
  if (plots) {
    fs::create_directories(out / "figures");
    problem = run_plot_script("plot_dam_break.py",
                              {(out / "csv" / "front.csv").string(), (out / "figures" / "front.png").string()},
                              out / "figures" / "plot.log");
  }
  const std::string figure = plots && problem.empty() ? "figures/front.png" : "";
  util::write_file_atomically(out / "report.md", report_markdown(c, figure));
  log << "wrote " << (out / "comparison.json").string() << ", " << (out / "csv" / "front.csv").string() << ", "
      << (out / "report.md").string() << (figure.empty() ? "" : ", " + (out / figure).string()) << "\n";
  return problem;
}

std::string dam_break_summary_text(const DamBreakComparison& c) {
  std::ostringstream s;
  for (const DamBreakMethodFront* m : {&c.sph, &c.vof}) {
    s << m->method << ": ";
    if (!m->available) {
      s << "not available (" << m->status << ")\n";
      continue;
    }
    s << "front vs the experiment, time origin shifted by " << fixed(c.time_shift_s, 4) << " s: mean "
      << fixed(m->shifted.mean_abs, 3) << " L, max " << fixed(m->shifted.max_abs, 3) << " L over " << m->shifted.points
      << " of " << m->shifted.measured_points << " points, late speed ratio " << fixed(m->shifted.late_speed_ratio, 3)
      << " (unshifted: mean " << fixed(m->unshifted.mean_abs, 3) << " L, max " << fixed(m->unshifted.max_abs, 3)
      << " L)\n";
  }
  return s.str();
}

}  // namespace hydrojump::compare
