#include "compare/study_summary.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "util/csv_table.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

namespace {

// Rows of a small CSV as maps column -> text.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file) {
  const util::CsvTable table = util::read_csv_table(file);
  std::vector<std::map<std::string, std::string>> rows;
  for (const auto& cells : table.rows) {
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < table.header.size() && i < cells.size(); ++i) row[table.header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

double value(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  return it == row.end() ? std::nan("") : util::csv_number(it->second);
}

std::string fix(double v, int decimals, bool sign = false) {
  if (!std::isfinite(v)) return "—";
  std::ostringstream s;
  if (sign) s << std::showpos;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

}  // namespace

StudySummary summarize_study(const std::vector<std::pair<std::string, fs::path>>& cases) {
  StudySummary out;
  std::ostringstream eta, len, pos, csv;
  csv << "case,smooth_theory_percent,experiment_percent,published_sph_percent,sph_percent,vof_percent,"
         "sph_crest_depth_percent,vof_crest_depth_percent\n";
  eta << "| case | smooth bed (theory) | experiment | published SPH | this SPH | this VOF | SPH − exp. | VOF − exp. | "
         "SPH − published SPH | SPH − VOF | SPH, lab convention | VOF, lab convention |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  len << "| case | y2 is | y2* (inputs) | y2 exp. (m) | y2 SPH | y2 VOF | y2/y2* exp. | y2/y2* SPH | y2/y2* VOF | "
         "Lj exp. (m) | Lj SPH | Lj VOF | Lr SPH (m) | Lr VOF |\n"
         "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  pos << "| case | toe SPH (m) | toe VOF (m) | toe sd SPH (m) | toe sd VOF (m) | bed force exp. (%) | bed force SPH (%) | "
         "bed force VOF (%) |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& [id, dir] : cases) {
    const fs::path eta_file = dir / "csv" / "eta.csv";
    const auto eta_rows = read_csv(eta_file);
    if (eta_rows.empty()) {
      eta << "| " << id << " | missing: no comparison | | | | | | | | | | |\n";
      len << "| " << id << " | missing | | | | | | | | | | | | |\n";
      pos << "| " << id << " | missing | | | | | | |\n";
      continue;
    }
    out.eta_files.push_back(eta_file);
    const auto& r = eta_rows.front();
    const double th = value(r, "smooth_theory_percent"), ex = value(r, "experiment_percent"),
                 pub = value(r, "published_sph_percent"), sph = value(r, "sph_percent"), vof = value(r, "vof_percent"),
                 sph_c = value(r, "sph_crest_depth_percent"), vof_c = value(r, "vof_crest_depth_percent");
    csv << id << "," << fix(th, 4) << "," << fix(ex, 4) << "," << fix(pub, 4) << "," << fix(sph, 4) << "," << fix(vof, 4)
        << "," << fix(sph_c, 4) << "," << fix(vof_c, 4) << "\n";
    eta << "| " << id << " | " << fix(th, 2) << " | " << fix(ex, 2) << " | " << fix(pub, 2) << " | " << fix(sph, 2)
        << " | " << fix(vof, 2) << " | " << fix(sph - ex, 2, true) << " | " << fix(vof - ex, 2, true) << " | "
        << fix(sph - pub, 2, true) << " | " << fix(sph - vof, 2, true) << " | " << fix(sph_c, 2) << " | " << fix(vof_c, 2)
        << " |\n";
    std::map<std::string, std::map<std::string, std::string>> metrics;
    for (const auto& m : read_csv(dir / "csv" / "metrics.csv")) metrics[m.at("quantity")] = m;
    auto get = [&](const std::string& q, const std::string& col) {
      const auto it = metrics.find(q);
      return it == metrics.end() ? std::nan("") : value(it->second, col);
    };
    const auto status = metrics.find("sequent_depth");
    const std::string y2_is = status == metrics.end() || !status->second.count("status") ? "—" : status->second.at("status");
    len << "| " << id << " | " << y2_is << " | " << fix(get("sequent_depth", "smooth_theory"), 3) << " | "
        << fix(get("sequent_depth", "experiment"), 3) << " | " << fix(get("sequent_depth", "sph"), 3)
        << " | " << fix(get("sequent_depth", "vof"), 3) << " | " << fix(get("bed_effect", "experiment"), 3) << " | "
        << fix(get("bed_effect", "sph"), 3) << " | " << fix(get("bed_effect", "vof"), 3) << " | "
        << fix(get("jump_length", "experiment"), 3) << " | "
        << fix(get("jump_length", "sph"), 3) << " | " << fix(get("jump_length", "vof"), 3) << " | "
        << fix(get("roller_length", "sph"), 3) << " | " << fix(get("roller_length", "vof"), 3) << " |\n";
    pos << "| " << id << " | " << fix(get("toe_position", "sph"), 3) << " | " << fix(get("toe_position", "vof"), 3) << " | "
        << fix(get("toe_std", "sph"), 3) << " | " << fix(get("toe_std", "vof"), 3) << " | "
        << fix(get("bed_force_fraction", "experiment"), 1) << " | " << fix(get("bed_force_fraction", "sph"), 1) << " | " << fix(get("bed_force_fraction", "vof"), 1) << " |\n";
  }
  out.markdown = "### Energy dissipation rate η (%)\n\nη = (E1 − E2)/E1 with E = z_b + h + αU²/(2g) at the upstream and "
                 "downstream sections; 'lab convention': E = y + q²/(2gy²) with y above the corrugation crests.\n\n" +
                 eta.str() + "\n### Sequent depth, jump and roller length\n\n"
                 "'y2 is': predicted (the outlet steered to hold the toe at the basin start, as the flume's tailgate "
                 "was) or imposed (the outlet held a depth); y2* is Bélanger's sequent depth from the inflow alone, "
                 "and y2/y2* the bed effect (1 on a smooth bed).\n\n" +
                 len.str() +
                 "\n### Jump position and momentum balance\n\nToe: time-mean surface criterion and its standard "
                 "deviation over the frames. Bed force (M1 − M2)/M1 with the specific force M = h²/2 + βq²/(gh) at the "
                 "upstream and downstream sections: 0 for Bélanger's frictionless smooth bed, positive when the bed "
                 "holds part of the jump's force (corrugations), negative when more force leaves than enters (a jump "
                 "pushed upstream). The experiment's value uses uniform sections at y1 and the measured y2.\n\n" +
                 pos.str() + "\n";
  // "—" is for people; the CSV keeps "nan" for missing values.
  std::string c = csv.str();
  for (std::size_t p = c.find("—"); p != std::string::npos; p = c.find("—")) c.replace(p, std::string("—").size(), "nan");
  out.eta_csv = c;
  return out;
}

}  // namespace hydrojump::compare
