#include "compare/case_comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "cases/jump_toe.hpp"
#include "util/number_text.hpp"
#include "cases/output_times.hpp"
#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "compare/readers.hpp"
#include "compare/report.hpp"
#include "reference/discharge_samples.hpp"
#include "reference/runner.hpp"
#include "reference/tailwater_control.hpp"
#include "sph/kernel.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

cases::Study load_run_case(const fs::path& run_dir) {
  for (const fs::path& p : {run_dir / "sph" / "case.toml", run_dir / "vof" / "case.toml"}) {
    if (!fs::exists(p)) continue;
    // Both methods' results are reported under this case: each must have been made with it.
    for (const char* method : {"sph", "vof"}) cases::require_results_of(run_dir / method, p);
    return cases::load_study(p, cases::SpecPurpose::read_results);
  }
  throw std::runtime_error(run_dir.string() + ": no case.toml in " + (run_dir / "sph").string() + " or " +
                           (run_dir / "vof").string() + " (is this a directory written by `hydrojump generate`?)");
}

namespace {

// The scalar after "\"key\": " in the SPH run's summary.json (its own flat format): the raw token.
std::string summary_token(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  const auto at = json.find(needle);
  if (at == std::string::npos) return {};
  const auto begin = at + needle.size();
  const auto end = json.find_first_of(",}\n", begin);
  std::string token = json.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  if (!token.empty() && token.front() == '"') token = token.substr(1, token.size() - 2);
  return token;
}

// The number after "\"key\": " in summary.json: nullopt when the key is absent or null; a value that
// is not a number is named in `problems` (a damaged file) instead of ending the comparison.
std::optional<double> summary_number(const std::string& json, const std::string& key, std::string& problems) {
  const std::string token = summary_token(json, key);
  if (token.empty() || token == "null") return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0') {
    problems += (problems.empty() ? "" : ", ") + key + " = '" + token.substr(0, 40) + "'";
    return std::nullopt;
  }
  return value;
}

// The named columns of a run monitor's CSV table (basin.csv), each as a vector of numbers ("nan" and
// empty cells -> NaN); empty when the file is absent, unreadable or lacks a column. A row with another
// number of cells than the header is left out: the last one is a line the run is still writing, any
// other is damage, counted in `damaged_rows`; so is a row with text that is not a number in one of the
// columns, or without a finite value in the first (the time).
std::vector<std::vector<double>> csv_columns(const fs::path& file, const std::vector<std::string>& names,
                                             std::size_t& damaged_rows) {
  damaged_rows = 0;
  const util::CsvTable table = util::read_csv_table(file);
  std::vector<std::size_t> index;
  for (const auto& name : names) {
    const auto at = table.column(name);
    if (!at) return {};
    index.push_back(*at);
  }
  std::vector<std::vector<double>> columns(names.size());
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const auto& cells = table.rows[r];
    if (cells.size() != table.header.size()) {
      if (r + 1 < table.rows.size()) ++damaged_rows;
      continue;
    }
    std::vector<double> values(names.size());
    bool damaged = false;
    for (std::size_t c = 0; c < names.size(); ++c) {
      const std::string& cell = cells[index[c]];
      values[c] = util::csv_number(cell);
      if (std::isnan(values[c]) && !cell.empty() && cell != "nan") damaged = true;  // text, not a number
    }
    if (damaged || !std::isfinite(values[0])) {
      ++damaged_rows;
      continue;
    }
    for (std::size_t c = 0; c < names.size(); ++c) columns[c].push_back(values[c]);
  }
  return columns;
}

// The comparison window's balance from the run's basin.csv (cases::window_balance), as a clause of the
// note: "; over this comparison's window (...) outflow - inflow = ..." or why it cannot be given.
std::string sph_window_balance_clause(const fs::path& basin_csv, double t0, double t1, double time_tolerance_s, double q,
                                      double toe_drift_tolerance_m, RunBalance& balance) {
  const std::string name = basin_csv.filename().string();
  if (!fs::exists(basin_csv)) return "; no " + name + " beside it to recompute them";
  std::size_t damaged_rows = 0;
  const auto c = csv_columns(basin_csv, {"t_s", "inflow_discharge_m2_s", "outflow_discharge_m2_s", "toe_x_m"}, damaged_rows);
  if (c.empty())
    return "; " + name + " is unreadable or lacks a column of t_s, inflow_discharge_m2_s, outflow_discharge_m2_s, toe_x_m";
  const cases::WindowBalance b = cases::window_balance(c[0], c[1], c[2], c[3], t0, t1, time_tolerance_s, q);
  if (b.outputs < 2)
    return "; " + name + " has " + std::to_string(b.outputs) +
           " output(s) in this comparison's window, too few for its water balance";
  if (!std::isfinite(b.outflow_minus_inflow_over_q))
    return "; " + name + " lacks a discharge (NaN) in this comparison's window";
  // The trend to 1e-6 m/s: a toe standing still prints 0, not the rounding of its least-squares sums.
  const double trend = std::round(b.toe_trend_m_per_s * 1e6) / 1e6 + 0.0;
  std::ostringstream o;
  o << std::setprecision(3) << "; over this comparison's window (" << name << ", outputs " << b.first_output_s << "-"
    << b.last_output_s << " s) outflow - inflow = " << 100.0 * b.outflow_minus_inflow_over_q << " % of q, toe trend ";
  if (std::isfinite(trend))
    o << trend << " m/s";
  else
    o << "unknown";
  if (b.toe_missing > 0) o << ", no toe in " << b.toe_missing << " of " << b.outputs << " outputs";
  if (!b.reaches_window_end) o << "; the run has not reached " << t1 << " s";
  if (damaged_rows > 0)
    o << "; " << damaged_rows << " damaged row(s) of " << name
      << " (not as many cells as its header, text that is not a number, or no time) left out";
  const bool steady = damaged_rows == 0 && b.toe_missing == 0 && b.reaches_window_end &&
                      cases::steady_by_means(b.outflow_minus_inflow_over_q, b.toe_trend_m_per_s, toe_drift_tolerance_m);
  o << (steady ? " (steady by the window means)" : " (NOT steady by the window means)");
  balance.imbalance = b.outflow_minus_inflow_over_q;
  balance.steady = steady;
  return o.str();
}

}  // namespace

std::string sph_run_note(const fs::path& summary_file, double window_start_s, double window_end_s,
                         double time_tolerance_s, RunBalance* balance) {
  RunBalance ignored;
  RunBalance& out = balance ? *balance : ignored;
  if (!fs::exists(summary_file)) return {};
  const std::string name = summary_file.filename().string();
  std::string json;
  try {
    json = util::read_text_file(summary_file);
  } catch (const std::exception& e) {
    return "run monitor (" + name + "): unreadable (" + e.what() + "), so its verdict is not shown";
  }
  const std::string state = summary_token(json, "jump_state");
  if (state.empty())
    return "run monitor (" + name + "): no jump_state in it (damaged, or not written by `hydrojump sph`), so its "
           "verdict is not shown";
  std::string problems;  // values that are not numbers
  const std::string window = summary_token(json, "steady_over_window");
  const auto from = summary_number(json, "steady_from_s", problems);
  const auto q_error = summary_number(json, "inflow_discharge_relative_error", problems);
  // The monitor's own averaging window: its verdicts are for that window, which `compare --window` may
  // have moved.
  std::string run_window;
  bool other_window = false;
  {
    const std::string key = "\"averaging_window_s\": [";
    const auto at = json.find(key);
    double a = 0.0, b = 0.0;
    char comma = 0;
    std::istringstream in(at == std::string::npos ? std::string() : json.substr(at + key.size(), 64));
    if (in >> a >> comma >> b && comma == ',') {
      std::ostringstream w;
      w << ", its averaging window " << a << "-" << b << " s";
      run_window = w.str();
      other_window = window_end_s > window_start_s &&
                     (std::abs(a - window_start_s) > 1e-6 || std::abs(b - window_end_s) > 1e-6);
    }
  }
  std::ostringstream o;
  o << "run monitor (" << name << run_window << "): jump " << state
    << (window == "true" ? ", steady over the averaging window" : ", NOT steady over the averaging window");
  if (from) o << " (steady from t = " << *from << " s)";
  if (q_error) o << "; inflow discharge error " << *q_error * 100.0 << " %";
  const auto imbalance = summary_number(json, "window_outflow_minus_inflow_over_q", problems);
  const auto trend = summary_number(json, "window_toe_trend_m_per_s", problems);
  const std::string by_means = summary_token(json, "steady_by_window_means");
  if (imbalance) {
    o << "; over the window outflow - inflow = " << *imbalance * 100.0 << " % of q";
    if (trend) o << ", toe trend " << *trend << " m/s";
    o << (by_means == "true" ? " (steady by the window means)" : " (NOT steady by the window means)");
    if (!other_window && !run_window.empty()) {  // the numbers are for the comparison's window
      out.imbalance = *imbalance;
      if (!by_means.empty()) out.steady = by_means == "true";
    }
  }
  if (other_window) {
    o << "; these verdicts are for the run's window, not for this comparison's " << window_start_s << "-"
      << window_end_s << " s";
    const auto q = summary_number(json, "discharge_m2_s", problems);
    const auto tolerance = summary_number(json, "toe_drift_tolerance_m", problems);
    if (q && tolerance)
      o << sph_window_balance_clause(summary_file.parent_path() / "basin.csv", window_start_s, window_end_s,
                                     time_tolerance_s, *q, *tolerance, out);
    else
      o << "; " << name << " lacks the prescribed discharge or the toe drift tolerance to recompute them";
  }
  if (!problems.empty()) o << "; " << name << " holds values that are not numbers (" << problems << "), left out";
  return o.str();
}

std::string vof_top_outflow_note(const fs::path& vof_dir, double t0, double t1, double inflow_q_m2_s,
                                 double thickness_m) {
  const fs::path function_dir = vof_dir / "postProcessing" / "discharge_atmosphere";
  const auto top = reference::surface_field_value_mean(function_dir, t0, t1);
  if (!top || !(inflow_q_m2_s > 0.0) || !(thickness_m > 0.0)) return {};
  const double q_top = *top / thickness_m;  // > 0: water leaving
  if (q_top <= top_outflow_note_fraction * inflow_q_m2_s) return {};
  std::ostringstream o;
  o << std::setprecision(3) << "water leaves through the top of the domain (patch atmosphere, "
    << function_dir.string() << "): " << q_top << " m^2/s over the window, " << 100.0 * q_top / inflow_q_m2_s
    << " % of the inflow q (splashes or the jump's surface jet reach the lid): the basin loses that water, "
       "so its sections' discharge and depths are not those of the flume; raise [case.domain] air_height_m";
  return o.str();
}

std::string vof_tailwater_control_note(const fs::path& vof_dir, double t0, double t1) {
  double u_min = 0.0, u_max = 0.0, u_sum = 0.0, toe_sum = 0.0;
  int steps = 0, toe_steps = 0;
  for (const reference::TailwaterControlStep& s : reference::read_tailwater_control_log(vof_dir)) {
    if (s.time_s < t0 - 1e-9 || s.time_s > t1 + 1e-9) continue;
    u_min = steps == 0 ? s.outlet_mean_velocity_m_s : std::min(u_min, s.outlet_mean_velocity_m_s);
    u_max = steps == 0 ? s.outlet_mean_velocity_m_s : std::max(u_max, s.outlet_mean_velocity_m_s);
    u_sum += s.outlet_mean_velocity_m_s;
    ++steps;
    if (std::isfinite(s.toe_x_m)) {
      toe_sum += s.toe_x_m;
      ++toe_steps;
    }
  }
  if (steps == 0) return {};
  std::ostringstream o;
  o << std::setprecision(4) << "tailwater set by the tailgate control (" << (vof_dir / reference::tailwater_control_log).string()
    << ", " << steps << " steps in the window): outlet Umean " << u_min << "-" << u_max << " m/s (mean "
    << u_sum / steps << "), legs' mean toe " << (toe_steps > 0 ? toe_sum / toe_steps : std::nan(""))
    << " m; y2 is the depth the held jump needed, not a prescribed tailwater";
  return o.str();
}

std::string vof_run_note(const VofRunNoteInputs& in, RunBalance* balance) {
  const auto q = reference::patch_discharges(in.vof_dir, in.window_start_s, in.window_end_s, in.thickness_m);
  if (!q || !(in.inflow_q_m2_s > 0.0)) return {};
  const double imbalance = (q->outflow_m2_s + q->top_outflow_m2_s - q->inflow_m2_s) / in.inflow_q_m2_s;
  const bool trend_known = std::isfinite(in.toe_trend_m_per_s);
  const bool steady = in.frames_without_toe == 0 && in.reaches_window_end &&
                      cases::steady_by_means(imbalance, in.toe_trend_m_per_s, in.toe_drift_tolerance_m);
  if (balance) *balance = {imbalance, steady};
  std::ostringstream o;
  o << std::setprecision(4) << "water balance over the window (postProcessing/discharge_inlet, _outlet"
    << (q->top_sampled ? ", _atmosphere" : "") << "): in " << q->inflow_m2_s << ", out " << q->outflow_m2_s;
  if (q->top_sampled) o << " + top " << q->top_outflow_m2_s;
  o << " m^2/s; outflow - inflow = " << std::setprecision(3) << 100.0 * imbalance << " % of q"
    << (imbalance > 0.0 ? " (draining)" : " (filling)") << "; toe trend ";
  if (trend_known)
    o << in.toe_trend_m_per_s << " m/s";
  else
    o << "unknown (fewer than 3 frames with a toe)";
  if (in.frames_without_toe > 0) o << ", no toe in " << in.frames_without_toe << " of " << in.frames << " frames";
  if (!in.reaches_window_end) o << "; the run has not reached " << in.window_end_s << " s";
  o << (steady ? " (steady by the window means: " : " (NOT steady by the window means: ") << "|outflow - inflow| < "
    << 100.0 * cases::steady_discharge_tolerance << " % of q and |toe trend| x " << cases::steady_span_s << " s < "
    << in.toe_drift_tolerance_m << " m)";
  return o.str();
}

namespace {

void set_run_balance(JumpMetrics& m, const RunBalance& b) {
  m.window_imbalance = b.imbalance;
  m.steady_by_means = b.steady ? (*b.steady ? 1.0 : 0.0) : not_a_number;
}

// Progress lines "sph: frame 3/40 at t = 5.15 s (elapsed 12 s, ETA 2 min)".
class Progress {
 public:
  Progress(std::ostream& log, std::string what, std::size_t total)
      : log_(log), what_(std::move(what)), total_(total), t0_(std::chrono::steady_clock::now()) {}
  void step(std::size_t done, double time_s) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    if (done < total_ && el - last_ < 5.0 && done != 1) return;
    last_ = el;
    const double eta = done > 0 ? el / static_cast<double>(done) * static_cast<double>(total_ - done) : 0.0;
    log_ << what_ << ": frame " << done << "/" << total_ << " at t = " << std::setprecision(4) << time_s
         << " s (elapsed " << std::lround(el) << " s, ETA " << std::lround(eta) << " s)" << std::endl;
  }

 private:
  std::ostream& log_;
  std::string what_;
  std::size_t total_;
  std::chrono::steady_clock::time_point t0_;
  double last_ = -1e9;
};

std::string window_text(double t0, double t1) {
  std::ostringstream s;
  s << "[" << t0 << ", " << t1 << "] s";
  return s.str();
}

// "ok", or "ok; N unreadable frame(s) skipped, the first: ..."
std::string skipped_status(const std::vector<std::string>& skipped) {
  if (skipped.empty()) return "ok";
  return "ok; " + std::to_string(skipped.size()) + " unreadable frame(s) skipped, the first: " + skipped.front();
}

// When the results end before the window does (a run stopped early, or still running): the clause
// saying that the averages cover only part of the window; empty otherwise. `last_output_s` is the
// last output of the whole series (a window may end between two outputs).
std::string window_coverage_clause(double last_output_s, double first_in_window_s, double last_in_window_s, double t1,
                                   double tolerance_s) {
  if (last_output_s >= t1 - tolerance_s) return {};
  return "; PART OF THE WINDOW ONLY: the results end at t = " + util::number_text(last_output_s) +
         " s, before the window's end " + util::number_text(t1) + " s, so the averages are over the outputs of " +
         window_text(first_in_window_s, last_in_window_s) + " (run on, or give --window)";
}

}  // namespace

CaseComparison compare_case(const cases::Study& study, const fs::path& run_dir, const CompareOptions& options,
                            std::ostream& log) {
  if (study.cases.size() != 1)
    throw std::runtime_error(study.source_file.string() + ": expected exactly one [[case]] (a resolved case), found " +
                             std::to_string(study.cases.size()));
  const cases::Case& c = study.cases.front();
  const cases::StillingBasinCase* basin = c.stilling_basin();
  if (!basin)
    throw std::runtime_error("case \"" + c.id + "\" is of kind \"" + c.kind +
                             "\": `hydrojump compare` handles kind \"stilling_basin\" only");
  if (c.resolutions.size() != 1)
    throw std::runtime_error(study.source_file.string() + ": a resolved case has exactly one [resolution.*] table, found " +
                             std::to_string(c.resolutions.size()));
  const cases::Resolution& res = c.resolutions.begin()->second;
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const double g = study.fluid.gravity_m_s2;

  CaseComparison r;
  r.case_id = c.id;
  r.description = c.description;
  r.tailwater_control = basin->control.mode;
  r.resolution = res.name;
  r.inflow_depth_m = basin->inflow_depth_m;
  r.inflow_velocity_m_s = basin->inflow_velocity_m_s;
  r.tailwater_depth_m = basin->tailwater_depth_m;
  r.gravity_m_s2 = g;
  r.floor_z_m = geo.bed.elevation(geo.inflows.empty() ? geo.x_min_m : geo.inflows.front().x_m);
  r.basin_start_m = basin->upstream_length_m;
  r.basin_end_m = basin->upstream_length_m + basin->basin_length_m;
  r.bed_wavelength_m = geo.bed.corrugated() ? geo.bed.wavelength_m() : 0.0;
  r.window_start_s = options.window_start_s.value_or(c.run.average_start_s);
  r.window_end_s = options.window_end_s.value_or(c.run.average_end_s > 0.0 ? c.run.average_end_s : c.run.end_time_s);
  if (!(r.window_end_s >= r.window_start_s))
    throw std::runtime_error("case \"" + c.id + "\": averaging window " + window_text(r.window_start_s, r.window_end_s) +
                             " is empty (end before start)");
  // No run of the case reaches beyond its latest end time (sph and vof --end-time are bounded by it).
  if (r.window_end_s > c.run.latest_end_time_s())
    throw std::runtime_error("case \"" + c.id + "\": the averaging window " + window_text(r.window_start_s, r.window_end_s) +
                             " ends after " + util::number_text(c.run.latest_end_time_s()) +
                             " s, the latest time a run of this case can reach (at most " +
                             util::number_text(cases::max_outputs_per_run) + " outputs, one every " +
                             util::number_text(c.run.output_interval_s) + " s): give --window within it");
  // A time mean, its standard deviation and trend need two outputs at least.
  if (const long n = cases::outputs_in_window(r.window_start_s, r.window_end_s, c.run.output_interval_s); n < 2)
    throw std::runtime_error("case \"" + c.id + "\": the averaging window " + window_text(r.window_start_s, r.window_end_s) +
                             " holds " + std::to_string(n) + " output time(s) (one every " +
                             util::number_text(c.run.output_interval_s) + " s): give a window with at least 2");
  const cases::JumpHydraulics jh = cases::jump_hydraulics(r.inflow_depth_m, r.inflow_velocity_m_s, r.tailwater_depth_m, g);
  r.belanger_y2_m = jh.belanger_y2_m;
  r.eta_smooth_theory_percent = 100.0 * jh.eta_smooth;
  r.particle_spacing_m = res.particle_spacing_m;
  r.vof_cell_size_m = res.vof_cell_size_bed_m;
  r.interpolation = to_string(options.scheme);
  r.measured_source = basin->measured.source;
  r.measured_note = basin->measured.note;
  r.lab.sequent_depth_m = basin->measured.sequent_depth_m;
  r.lab.jump_length_m = basin->measured.jump_length_m;
  r.lab.roller_length_m = basin->measured.roller_length_m;
  r.lab.eta_percent = basin->measured.eta_percent;
  r.lab.eta_smooth_percent = basin->measured.eta_smooth_percent;
  r.lab.published_sph_eta_percent = basin->measured.published_sph_eta_percent;

  // Columns: the case's sections, and stations along the whole channel.
  for (const auto& s : geo.sections)
    r.sections.push_back({s.name, s.role, s.x_m, geo.bed.elevation(s.x_m), options.section_points});
  const double length = geo.x_max_m - geo.x_min_m;
  double ds = options.station_spacing_m;
  // The toe, the lengths and the surface are found on the stations: they must be finer than y1.
  if (ds > r.inflow_depth_m)
    throw std::runtime_error("--station-spacing " + util::number_text(ds) + " m is coarser than the inflow depth y1 = " +
                             util::number_text(r.inflow_depth_m) + " m of case \"" + c.id +
                             "\": the toe and the jump's lengths need stations finer than y1 (default: the finer of the "
                             "SPH particle spacing and the VOF bed cell)");
  if (!(ds > 0.0)) {
    ds = std::min(res.particle_spacing_m > 0 ? res.particle_spacing_m : 1e9,
                  res.vof_cell_size_bed_m > 0 ? res.vof_cell_size_bed_m : 1e9);
    if (ds > 1e8) ds = length / 500.0;
  }
  // At most 3,000 stations (a finer spacing costs time and adds nothing at the kernel's or the cells'
  // scale); a finer --station-spacing is said, not silently coarsened.
  if (options.station_spacing_m > 0.0 && ds < length / 3000.0)
    log << "compare: --station-spacing " << util::number_text(ds) << " m is finer than the limit of 3000 stations over "
        << util::number_text(length) << " m: using " << std::setprecision(4) << length / 3000.0 << std::setprecision(6)
        << " m" << std::endl;
  ds = std::max(ds, length / 3000.0);
  const int n_stations = std::max(3, static_cast<int>(std::floor(length / ds)));
  std::vector<ColumnSpec> stations;
  for (int i = 0; i < n_stations; ++i) {
    const double x = geo.x_min_m + (i + 0.5) * length / n_stations;
    stations.push_back({"", "station", x, geo.bed.elevation(x), options.station_points});
  }
  SnapshotGrid grid;
  grid.x_min = geo.x_min_m; grid.x_max = geo.x_max_m;
  grid.z_min = geo.z_min_m; grid.z_max = geo.z_max_m;
  grid.nx = std::min(800, std::max(50, static_cast<int>(length / ds)));
  grid.nz = std::clamp(static_cast<int>(std::lround(grid.nx * (geo.z_max_m - geo.z_min_m) / length)), 10, 400);
  std::vector<double> grid_bed(static_cast<std::size_t>(grid.nx));
  for (int i = 0; i < grid.nx; ++i)
    grid_bed[static_cast<std::size_t>(i)] = geo.bed.elevation(grid.x_min + i * length / (grid.nx - 1));

  const double t0 = r.window_start_s, t1 = r.window_end_s;
  // Outputs come up to a time step after their nominal time (cases/output_times.hpp).
  const double time_tolerance_s = cases::output_time_tolerance_s(c.run.output_interval_s);
  // ---- SPH
  r.sph.method = "sph";
  try {
    const fs::path pvd = options.sph_pvd.empty() ? find_pvd(run_dir / "sph") : options.sph_pvd;
    r.sph.source = pvd.string();
    // A series from another directory (--sph-pvd): when a case record lies beside it, it must be this
    // case's, as the one in RUN_DIR/sph is (load_run_case). Results of other programs have none.
    if (const fs::path other = pvd.parent_path(); !options.sph_pvd.empty() && fs::exists(cases::recorded_case_file(other))) {
      const fs::path recorded = cases::recorded_case_file(other);
      const auto d = cases::first_setting_difference(util::read_text_file(recorded), util::read_text_file(study.source_file));
      if (d.any()) {
        throw std::runtime_error(pvd.string() + " was made with other settings than " + study.source_file.string() + ": " +
                                 recorded.string() + " has '" + d.a + "' where it has '" + d.b + "'");
      }
    }
    const auto all = read_pvd(pvd);
    const auto entries = entries_in_window(all, t0, t1, time_tolerance_s);
    if (entries.empty()) {
      r.sph.status = "missing: no output time of " + pvd.string() + " lies in the averaging window " +
                     window_text(t0, t1) + " (the series covers " + window_text(all.front().time_s, all.back().time_s) + ")";
    } else {
      SphSamplingSettings s;
      s.kernel = c.sph.kernel;
      s.particle_spacing_m = res.particle_spacing_m;
      s.smoothing_length_m = sph::smoothing_length(c.sph.coef_h, res.particle_spacing_m);
      s.reference_density_kg_m3 = study.fluid.density_kg_m3;
      s.scheme = options.scheme;
      s.z_ceiling_m = geo.z_max_m + 2.0 * s.smoothing_length_m;  // a particle thrown above the domain is no surface
      MethodAccumulator acc("sph", r.sections, stations, grid, g);
      Progress progress(log, "sph", entries.size());
      std::vector<std::string> skipped;
      for (std::size_t i = 0; i < entries.size(); ++i) {
        try {
          const ParticleFrame f = read_vtp_particles(entries[i].file, entries[i].time_s);
          acc.add_frame(*make_sph_sampler(f, s), i + 1 == entries.size(), grid_bed);
        } catch (const std::exception& e) {  // one unreadable frame does not lose the others
          skipped.push_back(e.what());
          log << "sph: frame at t = " << entries[i].time_s << " s skipped: " << e.what() << std::endl;
        }
        progress.step(i + 1, entries[i].time_s);
      }
      if (acc.frame_count() == 0) throw std::runtime_error("no readable frame: " + skipped.front());
      r.sph.stats = acc.finish(options.section_points);
      r.sph.available = true;
      r.sph.status = skipped_status(skipped) + window_coverage_clause(all.back().time_s, entries.front().time_s,
                                                                      entries.back().time_s, t1, time_tolerance_s);
    }
  } catch (const std::exception& e) {
    r.sph.status = std::string("missing: ") + e.what();
  }
  // ---- VOF
  r.vof.method = "vof";
  const fs::path vof_dir = run_dir / "vof";
  r.vof.source = vof_dir.string();
  try {
    if (const std::string lack = missing_openfoam_results(vof_dir); !lack.empty()) {
      r.vof.status = "missing: " + vof_dir.string() + " has no OpenFOAM results (" + lack + ")";
      if (fs::exists(vof_dir / "processor0"))
        r.vof.status += "; it holds a decomposed run: reconstruct it first (reconstructPar)";
    } else {
      OpenFoamResults foam(vof_dir);
      const auto times = foam.times_in_window(t0, t1, time_tolerance_s);
      if (times.empty()) {
        r.vof.status = "missing: no written time of " + vof_dir.string() + " lies in the averaging window " +
                       window_text(t0, t1) + " (times " + window_text(foam.times().front(), foam.times().back()) + ")";
      } else {
        MethodAccumulator acc("vof", r.sections, stations, grid, g);
        Progress progress(log, "vof", times.size());
        std::vector<std::string> skipped;
        for (std::size_t i = 0; i < times.size(); ++i) {
          try {
            const CellFrame f = foam.read(times[i]);
            acc.add_frame(*make_vof_sampler(f, options.scheme), i + 1 == times.size(), grid_bed);
          } catch (const std::exception& e) {
            skipped.push_back(e.what());
            log << "vof: time " << times[i] << " s skipped: " << e.what() << std::endl;
          }
          progress.step(i + 1, times[i]);
        }
        if (acc.frame_count() == 0) throw std::runtime_error("no readable time: " + skipped.front());
        r.vof.stats = acc.finish(options.section_points);
        r.vof.available = true;
        r.vof.status = skipped_status(skipped) + window_coverage_clause(foam.times().back(), times.front(), times.back(), t1,
                                                                        time_tolerance_s);
      }
    }
  } catch (const std::exception& e) {
    r.vof.status = std::string("missing: ") + e.what();
  }
  for (MethodOutcome* m : {&r.sph, &r.vof}) {
    log << m->method << ": " << m->status << std::endl;
    if (!m->available) continue;
    m->metrics = compute_jump_metrics(m->stats, {r.inflow_depth_m, r.inflow_velocity_m_s, r.floor_z_m, g, options.metrics});
  }
  // The VOF run's water balance from its discharge samples; a damaged sample file costs these notes
  // (the note says which file), not the comparison.
  if (r.vof.available) {
    try {
      const std::string note = vof_top_outflow_note(run_dir / "vof", r.window_start_s, r.window_end_s,
                                                    r.inflow_depth_m * r.inflow_velocity_m_s, r.vof_cell_size_m);
      if (!note.empty()) r.vof.metrics.notes.push_back(note);
      VofRunNoteInputs balance_inputs{run_dir / "vof", r.window_start_s, r.window_end_s, r.inflow_depth_m * r.inflow_velocity_m_s,
                                      r.vof_cell_size_m, r.vof.metrics.toe_trend_m_per_s,
                                      cases::toe_drift_tolerance_m(basin->bed.profile, basin->bed.wavelength_m, r.inflow_depth_m)};
      const std::vector<double>& frame_toes = r.vof.metrics.toe_frames_x_m;
      balance_inputs.frames = static_cast<int>(frame_toes.size());
      balance_inputs.frames_without_toe =
          static_cast<int>(std::count_if(frame_toes.begin(), frame_toes.end(), [](double x) { return !std::isfinite(x); }));
      // As the SPH rule: some output at or after the window's end (the window itself may end off the grid).
      const std::optional<double> latest = reference::latest_time(run_dir / "vof");
      balance_inputs.reaches_window_end = latest && *latest >= r.window_end_s - time_tolerance_s;
      RunBalance numbers;
      const std::string balance = vof_run_note(balance_inputs, &numbers);
      if (!balance.empty()) r.vof.metrics.notes.push_back(balance);
      set_run_balance(r.vof.metrics, numbers);
    } catch (const std::exception& e) {
      r.vof.metrics.notes.push_back(std::string("water balance unavailable: ") + e.what());
    }
    // The tailgate's log, read only for a case run with the control (a file left from another run is
    // not this run's).
    if (c.holds_toe()) {
      try {
        const std::string control = vof_tailwater_control_note(run_dir / "vof", r.window_start_s, r.window_end_s);
        if (!control.empty()) r.vof.metrics.notes.push_back(control);
      } catch (const std::exception& e) {
        r.vof.metrics.notes.push_back(std::string("tailgate control log unreadable: ") + e.what());
      }
    }
  }
  // The SPH run's own verdict (summary.json of sph/basin_monitor.hpp), when it wrote one.
  if (r.sph.available) {
    RunBalance numbers;
    const std::string note =
        sph_run_note(run_dir / "sph" / "summary.json", r.window_start_s, r.window_end_s, time_tolerance_s, &numbers);
    if (!note.empty()) r.sph.metrics.notes.push_back(note);
    set_run_balance(r.sph.metrics, numbers);
  }
  if (r.sph.available && r.vof.available) {
    r.surface = surface_difference(r.sph.stats, r.vof.stats, r.basin_start_m, r.basin_end_m);
    r.profiles = profile_differences(r.sph.stats, r.vof.stats, r.inflow_velocity_m_s);
  }
  r.metrics = metric_table(r.sph.available ? &r.sph.metrics : nullptr, r.vof.available ? &r.vof.metrics : nullptr,
                           r.lab, r.inflow_depth_m, r.inflow_velocity_m_s, r.gravity_m_s2, c.holds_toe());
  return r;
}

std::string summary_text(const CaseComparison& c) {
  std::ostringstream o;
  auto lab = [&o](const std::optional<double>& v) {
    if (v) o << " [" << *v << "]";
  };
  // What the set-up held is marked as such (the toe under the toe-holding control, else y2 and eta).
  const bool held = c.tailwater_control == "hold_toe";
  const char* toe_label = held ? " (imposed)" : " (predicted)";
  const char* y2_label = held ? " (predicted)" : " (imposed)";
  for (const MethodOutcome* m : {&c.sph, &c.vof}) {
    if (!m->available) continue;
    const JumpMetrics& r = m->metrics;
    o << std::setprecision(4) << m->method << ": toe " << r.toe_mean_of_frames_x_m << " +- " << r.toe_std_m << " m"
      << toe_label;
    if (std::isfinite(r.toe_trend_m_per_s)) o << " (trend " << std::showpos << r.toe_trend_m_per_s << std::noshowpos << " m/s)";
    o << ", y2 " << r.sequent_depth_m << " m" << y2_label;
    lab(c.lab.sequent_depth_m);
    if (c.belanger_y2_m > 0.0) o << " {y2* " << c.belanger_y2_m << ", y2/y2* " << r.sequent_depth_m / c.belanger_y2_m << "}";
    o << ", eta " << 100.0 * r.eta << " %" << y2_label;
    lab(c.lab.eta_percent);
    o << ", Lj " << r.jump_length_m << " m (predicted)";
    lab(c.lab.jump_length_m);
    o << "\n";
    for (const auto& n : r.notes) o << m->method << ": " << n << "\n";
  }
  return o.str();
}

CaseComparison compare_case_directory(const fs::path& run_dir, const CompareOptions& options, std::ostream& log) {
  if (!fs::is_directory(run_dir)) throw std::runtime_error(run_dir.string() + ": run directory does not exist");
  const cases::Study study = load_run_case(run_dir);
  CaseComparison r = compare_case(study, run_dir, options, log);
  const fs::path out = options.out_dir.empty() ? run_dir : options.out_dir;
  r.figures_problem = write_report(r, out, options.plots, log);
  log << "summary over " << window_text(r.window_start_s, r.window_end_s) << " (experiment in brackets):\n"
      << summary_text(r) << std::flush;
  return r;
}

}  // namespace hydrojump::compare
