#include "compare/validation_doc.hpp"

#include "compare/jump_structure.hpp"
#include "compare/run_cost.hpp"
#include "cases/jump_toe.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <iomanip>
#include <map>
#include <set>
#include <tuple>
#include <vector>
#include <sstream>

namespace hydrojump::compare {

namespace {

constexpr const char* dash = "—";

std::string fix(double v, int decimals, bool sign = false) {
  if (!std::isfinite(v)) return dash;
  std::ostringstream s;
  if (sign) s << std::showpos;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

double value_of(const ValidationRecord& r, const std::string& quantity) {
  const RecordMetric* m = r.metric(quantity);
  return m ? m->value : std::nan("");
}

double experiment_of(const ValidationRecord& r, const std::string& quantity) {
  const RecordMetric* m = r.metric(quantity);
  return m && m->experiment ? *m->experiment : std::nan("");
}

double published_of(const ValidationRecord& r, const std::string& quantity) {
  const RecordMetric* m = r.metric(quantity);
  return m && m->published_sph ? *m->published_sph : std::nan("");
}

double theory_of(const ValidationRecord& r, const std::string& quantity) {
  const RecordMetric* m = r.metric(quantity);
  return m && m->smooth_theory ? *m->smooth_theory : std::nan("");
}

std::string status_of(const ValidationRecord& r, const std::string& quantity) {
  const RecordMetric* m = r.metric(quantity);
  return m ? m->status : dash;
}

// 100 (a / b - 1)
double percent_off(double a, double b) { return 100.0 * (a / b - 1.0); }

// "29 min", "1 h 42 min": a wall time rounded to the minute.
std::string duration_text(double seconds) {
  const long minutes = (std::lround(seconds) + 30) / 60;
  std::ostringstream o;
  if (minutes >= 60) o << minutes / 60 << " h " << std::setw(2) << std::setfill('0') << minutes % 60 << " min";
  else o << minutes << " min";
  return o.str();
}

// "2 threads" (SPH) or "1 rank" (VOF).
std::string workers_text(const std::string& method, int n) {
  return std::to_string(n) + (method == "sph" ? " thread" : " rank") + (n == 1 ? "" : "s");
}

std::string wall_text(const ValidationRecord& r) {
  if (!r.wall_time_s) return dash;
  std::string text = duration_text(*r.wall_time_s);
  if (r.threads || (r.legs && *r.legs > 1)) {
    text += " (";
    if (r.threads) text += workers_text(r.method, *r.threads);
    if (r.legs && *r.legs > 1) text += std::string(r.threads ? ", " : "") + "in " + std::to_string(*r.legs) + " legs";
    text += ")";
  }
  return text;
}

std::string row_label(const ValidationRecord& r) {
  return "| " + r.case_id + " | " + (r.method == "sph" ? std::string("SPH") : std::string("VOF")) + " | " + r.resolution +
         (r.stale ? " (stale)" : "") + " |";
}

// `text` in a Markdown table cell: '|' escaped.
std::string cell_text(const std::string& text) {
  std::string out;
  for (char ch : text) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

// The structure's name alone: "classic", "wall jet, profile off", "wall jet, profile unknown" (no
// half-velocity height, or a record made before it was measured), "surface jet"; empty where the record
// has no jet height.
std::string structure_kind(const ValidationRecord& r) {
  const double jet = value_of(r, "jet_height"), dev = value_of(r, "wall_jet_deviation");
  if (!std::isfinite(jet)) return "";
  if (jet >= classic_jet_height_limit) return "surface jet";
  if (!std::isfinite(dev)) return "wall jet, profile unknown";
  return classic_structure(jet, dev) ? "classic" : "wall jet, profile off";
}

// The structure check (jump_structure.hpp) with its numbers, the jet height fraction and the wall-jet
// profile deviation at x_2y2: "classic (0.12, 0.08)", "wall jet, profile off (0.12, 0.23)", "surface jet
// (0.85)"; a record without the deviation shows the jet height alone ("wall jet (0.12)").
std::string structure_text(const ValidationRecord& r) {
  const std::string kind = structure_kind(r);
  if (kind.empty()) return dash;
  const double jet = value_of(r, "jet_height"), dev = value_of(r, "wall_jet_deviation");
  if (!std::isfinite(dev) || kind == "surface jet")
    return (kind == "surface jet" ? kind : std::string("wall jet")) + " (" + fix(jet, 2) + ")";
  return kind + " (" + fix(jet, 2) + ", " + fix(dev, 2) + ")";
}

// The resolutions in the order of refinement: quick, default, fine, then any other by name.
int resolution_rank(const std::string& resolution) {
  if (resolution == "quick") return 0;
  if (resolution == "default") return 1;
  if (resolution == "fine") return 2;
  return 3;
}

// Per case and method, each resolution's structure and the coarsest resolution that gives a classic
// jump (issue 51: validation claims are made from there; a row whose jump is not classic is exploratory).
std::string structure_by_resolution_markdown(const std::vector<const ValidationRecord*>& finished) {
  std::vector<std::string> levels;
  for (const auto* r : finished)
    if (std::find(levels.begin(), levels.end(), r->resolution) == levels.end()) levels.push_back(r->resolution);
  std::stable_sort(levels.begin(), levels.end(), [](const std::string& a, const std::string& b) {
    return std::make_pair(resolution_rank(a), a) < std::make_pair(resolution_rank(b), b);
  });
  // (case, method) in the records' order, with each resolution's record.
  std::vector<std::pair<std::string, std::string>> keys;
  std::map<std::pair<std::string, std::string>, std::map<std::string, const ValidationRecord*>> rows;
  for (const auto* r : finished) {
    const auto key = std::make_pair(r->case_id, r->method);
    if (!rows.count(key)) keys.push_back(key);
    rows[key][r->resolution] = r;
  }
  std::ostringstream md, table;
  std::map<std::string, int> cases_of, classic_at_coarsest;  // by method
  for (const auto& key : keys) {
    const auto& by_level = rows.at(key);
    table << "| " << key.first << " | " << (key.second == "sph" ? "SPH" : "VOF") << " |";
    std::string first = "none yet";
    bool coarsest_seen = false, coarsest_classic = false;
    for (const auto& level : levels) {
      const auto it = by_level.find(level);
      if (it == by_level.end()) {
        table << " not run |";
        continue;
      }
      const std::string kind = structure_kind(*it->second);
      const std::string stale = it->second->stale ? " (stale)" : "";
      table << " " << (kind.empty() ? std::string(dash) : kind + stale) << " |";
      if (kind == "classic" && first == "none yet") first = level + stale;
      if (!coarsest_seen) coarsest_classic = kind == "classic";
      coarsest_seen = true;
    }
    table << " " << first << " |\n";
    ++cases_of[key.second];
    if (coarsest_classic) ++classic_at_coarsest[key.second];
  }
  md << "\n### Structure by resolution\n\n"
        "The jump's structure (above) at each resolution, and the coarsest resolution at which each method "
        "gives a classic jump: validation claims are made from there; a row whose jump is not classic is "
        "exploratory (its targets say so). Classic at the coarsest resolution run:";
  for (const std::string method : {"sph", "vof"})
    if (cases_of.count(method))
      md << (method == "sph" ? " SPH " : (cases_of.count("sph") ? "; VOF " : " VOF ")) << classic_at_coarsest[method]
         << " of " << cases_of[method] << " cases";
  md << ".\n\n| case | method |";
  for (const auto& level : levels) md << " " << level << " |";
  md << " first classic |\n|---|---|";
  for (std::size_t i = 0; i < levels.size(); ++i) md << "---|";
  md << "---|\n" << table.str();
  return md.str();
}

// The targets a row is held to (the predictions issue): the toe held within one wavelength (68 mm on a
// smooth bed) of the basin start with sd <= 2 y1; a smooth bed's y2 within 3 % of Belanger; a corrugated
// bed with laboratory data: y2 within 10 %, eta within 3 points, Lj within 20 %, y2/y2* within 0.05.
// Returns "met", or the misses with their numbers; "—" where nothing can be judged.
std::string targets_text(const ValidationRecord& r) {
  if (r.failed()) return "FAILED: " + cell_text(r.failure);
  std::vector<std::string> misses;
  int judged = 0;
  const auto judge = [&](bool ok, const std::string& miss) {
    ++judged;
    if (!ok) misses.push_back(miss);
  };
  const double toe = value_of(r, "toe_mean_of_frames"), sd = value_of(r, "toe_std");
  if (r.tailwater_control == "hold_toe" && std::isfinite(toe) && r.inflow_depth_m > 0.0) {
    const double allowed = r.bed_wavelength_m > 0.0 ? r.bed_wavelength_m : 0.068;
    judge(std::abs(toe - r.basin_start_m) <= allowed, "toe " + fix(toe - r.basin_start_m, 3, true) + " m");
    judge(sd <= 2.0 * r.inflow_depth_m, "toe sd " + fix(sd / r.inflow_depth_m, 1) + " y1");
  }
  const double y2 = value_of(r, "sequent_depth"), y2_lab = experiment_of(r, "sequent_depth");
  if (r.bed == "smooth" && std::isfinite(theory_of(r, "sequent_depth"))) {
    const double off = percent_off(y2, theory_of(r, "sequent_depth"));
    judge(std::abs(off) <= 3.0, "y2 " + fix(off, 1, true) + " % of y2*");
  }
  if (std::isfinite(y2_lab)) {
    judge(std::abs(percent_off(y2, y2_lab)) <= 10.0, "y2 " + fix(percent_off(y2, y2_lab), 1, true) + " %");
    const double d_eta = value_of(r, "eta") - experiment_of(r, "eta");
    if (std::isfinite(d_eta)) judge(std::abs(d_eta) <= 3.0, "η " + fix(d_eta, 2, true));
    const double lj = value_of(r, "jump_length"), lj_lab = experiment_of(r, "jump_length");
    if (std::isfinite(lj_lab)) judge(std::abs(percent_off(lj, lj_lab)) <= 20.0, "Lj " + fix(percent_off(lj, lj_lab), 1, true) + " %");
    const double d_bed = value_of(r, "bed_effect") - experiment_of(r, "bed_effect");
    if (std::isfinite(d_bed)) judge(std::abs(d_bed) <= 0.05, "y2/y2* " + fix(d_bed, 3, true));
  }
  // A run not steady over its window (its water balance or toe still moving): its numbers are those of
  // a jump still settling, whatever the targets say.
  std::string notes;  // after the targets: not steady, exploratory
  if (value_of(r, "steady") == 0.0) {
    const double imbalance = value_of(r, "water_imbalance");  // % of q
    notes = std::abs(imbalance) >= 100.0 * cases::steady_discharge_tolerance
                ? "; NOT steady (outflow − inflow " + fix(imbalance, 1, true) + " % of q)"
                : "; NOT steady (the toe drifting, lost or the window not reached)";
  }
  // A jump that is not classic (a surface jet, a wall jet off the profile): the depths may be right for
  // the wrong flow.
  const std::string kind = structure_kind(r);
  if (!kind.empty() && kind != "classic") notes += "; exploratory: " + kind;
  if (judged == 0) return dash + notes;
  if (misses.empty()) return "met (" + std::to_string(judged) + ")" + notes;
  std::string out = "missed " + std::to_string(misses.size()) + " of " + std::to_string(judged) + ": ";
  for (std::size_t i = 0; i < misses.size(); ++i) out += (i ? ", " : "") + misses[i];
  return out + notes;
}

}  // namespace

std::string validation_markdown(const std::vector<ValidationRecord>& records, const std::string& records_root) {
  std::ostringstream md;
  md << "# Validation\n\n"
        "Generated by `hydrojump validation-doc` from the records in `" << records_root << "/` (do not edit: "
        "regenerate). Every row is one record: one method on one case at one resolution, made by the command "
        "listed at the end, with the code whose fingerprint is its run key. A record marked (stale) was made "
        "with other settings or solver code than the case has now: its numbers are the model's as it was then, "
        "and the study runs that case again instead of importing it.\n\n"
        "'y2 is' says whether the sequent depth is a prediction (the outlet steered to hold the toe at the "
        "basin start, as the flume's tailgate was) or imposed (the outlet held a depth). y2* and η* are what "
        "the inputs alone give (Bélanger's sequent depth of the inflow and the energy loss with it), y2/y2* the "
        "bed effect (1 on a smooth bed). Δ: the model against the laboratory. η Bo et al. SPH: the published "
        "SPH re-simulation of the same run (Bo et al. 2019, SPHysics). A run that failed (its solver "
        "stopped before the end) is a result too: it has no numbers, and the targets table says what stopped it.\n";
  std::map<std::string, std::vector<const ValidationRecord*>> by_study;
  for (const auto& r : records) by_study[r.study].push_back(&r);
  for (const auto& [study, rows] : by_study) {
    md << "\n## Study `" << study << "`\n\n### Sequent depth and energy\n\n"
          "| case | method | resolution | y2 is | y2 (m) | y2 lab | Δy2 | y2* (inputs) | y2/y2* | y2/y2* lab | η (%) | "
          "η lab | Δη (points) | η Bo et al. SPH | η* (inputs) |\n"
          "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    std::vector<const ValidationRecord*> finished;
    std::copy_if(rows.begin(), rows.end(), std::back_inserter(finished), [](const ValidationRecord* r) { return !r->failed(); });
    for (const auto* r : finished) {
      const double y2 = value_of(*r, "sequent_depth"), y2_lab = experiment_of(*r, "sequent_depth");
      const double eta = value_of(*r, "eta"), eta_lab = experiment_of(*r, "eta");
      md << row_label(*r) << " " << status_of(*r, "sequent_depth") << " | " << fix(y2, 4) << " | " << fix(y2_lab, 3)
         << " | " << (std::isfinite(y2_lab) ? fix(percent_off(y2, y2_lab), 1, true) + " %" : dash) << " | "
         << fix(theory_of(*r, "sequent_depth"), 4) << " | " << fix(value_of(*r, "bed_effect"), 3) << " | "
         << fix(experiment_of(*r, "bed_effect"), 3) << " | " << fix(eta, 2) << " | " << fix(eta_lab, 2) << " | "
         << fix(eta - eta_lab, 2, true) << " | " << fix(published_of(*r, "eta"), 2) << " | "
         << fix(theory_of(*r, "eta"), 2) << " |\n";
    }
    md << "\n### Jump length, roller and toe\n\n"
          "Lj and Lr from the time-mean surface; the toe's mean and standard deviation over the window's frames "
          "(held at the basin start under the flume's protocol: a check of the control, not a prediction).\n\n"
          "Lr* is a classical (smooth-bed) jump's roller length at the same inflow, Lr/y1 = −12 + 160 tanh(Fr1/20) "
          "(Hager, Bremen & Kawagoshi 1990). Structure, two tailwater depths past the basin start (inside the "
          "roller): the height of the fastest forward flow as a fraction of the depth (a wall jet under a surface "
          "roller below one half, Rajaratnam 1965; a surface jet above) and the RMS deviation of the time-mean "
          "profile u/u_m from the plane wall jet's, 1.48 η^(1/7) [1 − erf(0.68 η)] with η = z/δ (Verhoff 1963), "
          "up to the half-velocity height δ. Classic: a wall jet within 0.15 u_m of that profile.\n\n"
          "| case | method | resolution | Lj (m) | Lj lab | ΔLj | Lr (m) | Lr* (m) | structure (jet, profile) | toe mean (m) | "
          "toe sd (m) | window (s) | solver wall time |\n"
          "|---|---|---|---:|---:|---:|---:|---:|---|---:|---:|---|---|\n";
    for (const auto* r : finished) {
      const double lj = value_of(*r, "jump_length"), lj_lab = experiment_of(*r, "jump_length");
      md << row_label(*r) << " " << fix(lj, 3) << " | " << fix(lj_lab, 2) << " | "
         << (std::isfinite(lj_lab) ? fix(percent_off(lj, lj_lab), 1, true) + " %" : dash) << " | "
         << fix(value_of(*r, "roller_length"), 3) << " | " << fix(theory_of(*r, "roller_length"), 3) << " | "
         << structure_text(*r) << " | "
         << fix(value_of(*r, "toe_mean_of_frames"), 3) << " | "
         << fix(value_of(*r, "toe_std"), 3) << " | " << fix(r->window_start_s, 1) << "–" << fix(r->window_end_s, 1)
         << " | " << wall_text(*r) << " |\n";
    }
    md << structure_by_resolution_markdown(finished);
    md << "\n### Targets\n\n"
          "Toe (held): mean within one bed wavelength (68 mm on a smooth bed) of the basin start, sd at most 2 y1. "
          "Smooth bed: y2 within 3 % of Bélanger. Corrugated bed with laboratory data: y2 within 10 %, η within 3 "
          "points, Lj within 20 %, y2/y2* within 0.05 of the laboratory's. Exploratory: the row's jump is not "
          "classic (above), so its depths may be right for the wrong flow. NOT steady: the run's water balance "
          "or toe was still moving over its window (|outflow − inflow| ≥ 2 % of q, or the toe drifting a bed "
          "wavelength, on a smooth bed 2 y1, a second): its numbers are those of a jump still settling.\n\n"
          "| case | method | resolution | targets |\n|---|---|---|---|\n";
    for (const auto* r : rows) md << row_label(*r) << " " << targets_text(*r) << " |\n";
    // SPH against VOF where both methods have a record of the same case and resolution.
    std::map<std::pair<std::string, std::string>, std::map<std::string, const ValidationRecord*>> pairs;
    for (const auto* r : finished) pairs[{r->case_id, r->resolution}][r->method] = r;
    std::ostringstream both;
    for (const auto& [key, methods] : pairs) {
      if (methods.size() != 2) continue;
      const double s = value_of(*methods.at("sph"), "sequent_depth"), v = value_of(*methods.at("vof"), "sequent_depth");
      both << "| " << key.first << " | " << key.second << " | " << fix(s, 4) << " | " << fix(v, 4) << " | "
           << fix(percent_off(s, v), 1, true) << " % |\n";
    }
    if (!both.str().empty())
      md << "\n### SPH against VOF\n\n| case | resolution | y2 SPH (m) | y2 VOF (m) | SPH − VOF |\n"
            "|---|---|---:|---:|---:|\n" << both.str();
    md << "\n### Records\n\n| case | method | resolution | record | recorded | run key | command |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const auto* r : rows)
      md << row_label(*r) << " `" << r->case_id << "/" << r->method << "-" << r->resolution << ".toml` | "
         << r->recorded_on << " | `" << r->run_key << "` | `" << r->command << "` |\n";
  }
  if (by_study.empty()) md << "\nNo records yet.\n";
  return md.str();
}

namespace {

// One method's cells of a headline row: its value text, with "(stale)" where its record is and `mark`
// (the y2 and targets cells carry the mark; the others of the row would only repeat it).
std::string method_cell(const ValidationRecord* r, const std::function<std::string(const ValidationRecord&)>& text,
                        bool mark = true) {
  if (!r) return "not run";
  if (r->failed()) return mark ? std::string("failed") + (r->stale ? " (stale)" : "") : std::string(dash);
  const std::string t = text(*r);
  return t + (mark && r->stale && t != dash ? " (stale)" : "");
}

// "a / b": SPH's then VOF's.
std::string pair_text(const ValidationRecord* sph, const ValidationRecord* vof,
                      const std::function<std::string(const ValidationRecord&)>& text, bool mark = false) {
  return method_cell(sph, text, mark) + " / " + method_cell(vof, text, mark);
}

}  // namespace

// One row per case and resolution, SPH and VOF side by side (the README's table stays as short as the
// list of cases; docs/validation.md has a row per record).
std::string headline_markdown(const std::vector<ValidationRecord>& records) {
  std::ostringstream md;
  md << "| case | resolution | y2, SPH / VOF | η points, SPH / VOF | Lj, SPH / VOF | y2/y2*, SPH / VOF (lab) | "
        "y2 SPH − VOF | targets SPH | targets VOF |\n"
        "|---|---|---|---|---|---|---:|---|---|\n";
  using Row = std::tuple<std::string, std::string, std::string>;  // (study, case, resolution), in the records' order
  std::vector<Row> rows;
  for (const auto& r : records)
    if (std::find(rows.begin(), rows.end(), Row{r.study, r.case_id, r.resolution}) == rows.end())
      rows.emplace_back(r.study, r.case_id, r.resolution);
  const auto y2_text = [](const ValidationRecord& r) {
    const double y2 = value_of(r, "sequent_depth"), y2_lab = experiment_of(r, "sequent_depth"),
                 y2_star = theory_of(r, "sequent_depth");
    return std::isfinite(y2_lab)    ? fix(percent_off(y2, y2_lab), 1, true) + " % of lab"
           : std::isfinite(y2_star) ? fix(percent_off(y2, y2_star), 1, true) + " % of y2*"
                                    : dash;
  };
  const auto eta_text = [](const ValidationRecord& r) { return fix(value_of(r, "eta") - experiment_of(r, "eta"), 2, true); };
  const auto lj_text = [](const ValidationRecord& r) {
    const double lj = value_of(r, "jump_length"), lj_lab = experiment_of(r, "jump_length");
    return std::isfinite(lj_lab) ? fix(percent_off(lj, lj_lab), 1, true) + " %" : dash;
  };
  const auto bed_text = [](const ValidationRecord& r) { return fix(value_of(r, "bed_effect"), 3); };
  for (const auto& [study, case_id, resolution] : rows) {
    const ValidationRecord *sph = nullptr, *vof = nullptr, *any = nullptr;
    for (const auto& r : records) {
      if (r.study != study || r.case_id != case_id || r.resolution != resolution) continue;
      (r.method == "sph" ? sph : vof) = &r;
      if (!any || !r.failed()) any = &r;  // the laboratory's values: a failed run's record has none
    }
    const double between = sph && vof ? percent_off(value_of(*sph, "sequent_depth"), value_of(*vof, "sequent_depth"))
                                      : std::nan("");
    md << "| " << case_id << " | " << resolution << " | " << pair_text(sph, vof, y2_text, true) << " | "
       << pair_text(sph, vof, eta_text) << " | " << pair_text(sph, vof, lj_text) << " | "
       << pair_text(sph, vof, bed_text) << " (" << fix(experiment_of(*any, "bed_effect"), 3) << ") | "
       << (std::isfinite(between) ? fix(between, 1, true) + " %" + (sph->stale || vof->stale ? " (stale)" : "") : dash) << " | "
       << method_cell(sph, targets_text) << " | " << method_cell(vof, targets_text) << " |\n";
  }
  if (records.empty()) md << "| no records yet | | | | | | | | |\n";
  return md.str();
}

std::string with_headline(const std::string& text, const std::string& block, const std::string& file_name) {
  const std::string start = "<!-- validation-table:start -->\n", end = "<!-- validation-table:end -->";
  const auto a = text.find(start);
  const auto b = a == std::string::npos ? std::string::npos : text.find(end, a);
  if (b == std::string::npos)
    throw RecordError(file_name + ": has no \"<!-- validation-table:start -->\" line followed by \"" + end +
                      "\": the headline table goes between them");
  return text.substr(0, a + start.size()) + block + text.substr(b);
}

std::string not_run_markdown(const cases::Study& study, const std::vector<ValidationRecord>& records,
                             const std::string& resolution) {
  // The reference of each method: the first timed record of it, of a case of this study, at this
  // resolution if there is one, else at another; the others' costs are scaled from it by run_work.
  std::map<std::string, const ValidationRecord*> reference;
  std::map<std::string, const cases::Case*> reference_case;
  for (const bool same_resolution : {true, false})
    for (const auto& r : records) {
      if (r.study != study.name || (r.resolution == resolution) != same_resolution || !r.wall_time_s ||
          r.failed() || reference.count(r.method))
        continue;
      for (const auto& c : study.cases)
        if (c.id == r.case_id && c.stilling_basin() && c.resolutions.count(r.resolution)) {
          reference[r.method] = &r;
          reference_case[r.method] = &c;
        }
    }
  std::ostringstream md;
  int missing = 0;
  std::map<std::string, double> measured, estimated;  // seconds, by method: recorded runs, estimates
  std::map<std::string, int> untimed, missing_of;      // records without a wall time; runs not recorded
  // Every stage's time (measured or estimated) and its case's work, in the study's order of stages.
  std::vector<double> stage_seconds, stage_work;
  bool all_timed = true;
  for (const auto& c : study.cases) {
    const auto* b = c.stilling_basin();
    if (!b || !c.resolutions.count(resolution)) continue;
    for (const std::string method : {"sph", "vof"}) {
      const auto recorded = std::find_if(records.begin(), records.end(), [&](const ValidationRecord& r) {
        return r.study == study.name && r.case_id == c.id && r.method == method && r.resolution == resolution && !r.stale;
      });
      stage_work.push_back(run_work(c, resolution, "sph"));  // both methods' stages by the case (app/study.cpp)
      if (recorded != records.end()) {
        if (recorded->wall_time_s) measured[method] += *recorded->wall_time_s;
        else ++untimed[method];
        all_timed = all_timed && recorded->wall_time_s.has_value();
        stage_seconds.push_back(recorded->wall_time_s.value_or(0.0));
        continue;
      }
      ++missing_of[method];
      const double size = run_size(*b, c.resolutions.at(resolution), method);
      std::ostringstream cost;
      if (reference.count(method)) {
        const ValidationRecord& ref = *reference.at(method);
        const double ratio = run_work(c, resolution, method) / run_work(*reference_case.at(method), ref.resolution, method);
        estimated[method] += *ref.wall_time_s * ratio;
        stage_seconds.push_back(*ref.wall_time_s * ratio);
        cost << "~" << duration_text(*ref.wall_time_s * ratio);
        if (ref.threads) cost << " on " << workers_text(method, *ref.threads);
      } else {
        cost << dash;
        all_timed = false;
        stage_seconds.push_back(0.0);
      }
      md << "| " << c.id << " | " << (method == "sph" ? "SPH" : "VOF") << " | ~" << fix(size / 1000.0, 0)
         << (method == "sph" ? "k particles" : "k cells") << " | " << fix(c.run.end_time_s, 1) << " s | " << cost.str() << " |\n";
      ++missing;
    }
  }
  // The same stages run by `hydrojump study` on two cores: two at a time, the largest case's first.
  const auto schedule_text = [&] {
    return " On two cores (`hydrojump study`, two stages at a time, the largest case's first, each on one thread or "
           "rank), these stage times take ~" +
           duration_text(list_schedule_seconds(stage_seconds, largest_first(stage_work), 2)) + " (list schedule";
  };
  std::ostringstream out;
  if (missing == 0) {
    // Every stage measured: the study's time from the records alone (nothing estimated).
    if (stage_seconds.empty() || !all_timed) return "";
    out << "\n## Every case run at `" << resolution << "` (study `" << study.name << "`)\n\n"
        << "Every stilling basin of the study has a current record of both methods at `" << resolution
        << "`. The whole study from the records' measured wall times (on their own threads or ranks): SPH "
        << duration_text(measured["sph"]) << ", VOF " << duration_text(measured["vof"]) << "."
        << schedule_text() << " of the measured times; the comparisons not counted).\n";
    return out.str();
  }
  out << "\n## Not run at `" << resolution << "` (study `" << study.name << "`)\n\n"
      << "Cases of the study with no current record of a method (none, or a stale one), with the size of the run (particles "
         "from the water area, cells between the bed and the surface sizes: rough counts) and its estimated wall "
         "time: the measured one of ";
  if (reference.empty()) out << "a record of the same method (none yet)";
  for (auto it = reference.begin(); it != reference.end(); ++it)
    out << (it == reference.begin() ? "" : " and ") << it->second->case_id << " (" << (it->first == "sph" ? "SPH" : "VOF")
        << (it->second->resolution == resolution ? "" : ", at `" + it->second->resolution + "`") << ")";
  out << " scaled by size × simulated time × U1 / dx (a rough guide: the solvers' time steps differ between cases).\n\n"
         "| case | method | size | simulated | estimated wall time |\n|---|---|---|---:|---|\n"
      << md.str();
  // The whole study's projected cost: what the current records took plus the estimates above.
  out << "\nThe whole study at `" << resolution << "`, projected (the recorded runs' measured wall times, on their own "
         "threads or ranks, plus the estimates above):";
  for (const std::string method : {"sph", "vof"}) {
    out << (method == "sph" ? " SPH " : "; VOF ") << duration_text(measured[method]) << " measured";
    if (untimed[method] > 0) out << " (and " << untimed[method] << " run(s) without a wall time)";
    if (missing_of[method] == 0) out << ", nothing left to run";
    else out << " + " << (reference.count(method) ? "~" + duration_text(estimated[method]) : std::string("unknown")) << " estimated";
  }
  out << ".";
  if (all_timed) out << schedule_text() << "; the comparisons not counted).";
  out << "\n";
  return out.str();
}

}  // namespace hydrojump::compare
