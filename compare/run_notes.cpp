// The run notes declared in case_comparison.hpp: the SPH run monitor's verdict (sph_run_note, with the
// water balance over another window recomputed from basin.csv), water through the VOF domain's lid
// (vof_top_outflow_note), the tailgate control's log (vof_tailwater_control_note) and the VOF run's
// water balance and steadiness (vof_run_note).
#include "compare/case_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/jump_toe.hpp"
#include "reference/discharge_samples.hpp"
#include "reference/tailwater_control.hpp"
#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

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

}  // namespace hydrojump::compare
