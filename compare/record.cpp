#include "compare/record.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include <toml++/toml.h>

#include "util/atomic_file.hpp"
#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"
#include "util/number_text.hpp"
#include "cases/spec_reader.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (ch == '\n') {
      out += "\\n";
      continue;
    }
    if (static_cast<unsigned char>(ch) < 0x20) continue;
    out += ch;
  }
  return out + "\"";
}

// A TOML number that reads back to the same double ("1.0" for integral values: a float, not an integer).
std::string number(double v) {
  std::string t = util::number_text(v);
  if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
  return t;
}

std::string numbers(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + number(v[i]);
  return out + "]";
}

// The rows of a small CSV as column -> cell maps.
std::vector<std::map<std::string, std::string>> csv_rows(const fs::path& file) {
  const util::CsvTable table = util::read_csv_table(file);
  std::vector<std::map<std::string, std::string>> rows;
  for (const auto& cells : table.rows) {
    if (cells.size() != table.header.size()) continue;  // a torn line
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size(); ++i) row[table.header[i]] = cells[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

std::optional<double> finite(double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; }

double cell(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  return it == row.end() ? std::nan("") : util::csv_number(it->second);
}

// A stage file the study writes beside a case (app/stage_info.hpp: <method>.stage.toml, <method>.failed);
// none when it is absent or damaged.
std::optional<toml::table> stage_file(const fs::path& file) {
  if (!fs::exists(file)) return std::nullopt;
  try {
    return toml::parse_file(file.string());
  } catch (const toml::parse_error&) {
    return std::nullopt;  // a damaged stage file loses only what it holds
  }
}

// A stage file's timing keys: wall time (all legs), legs, threads and the machine.
void read_stage_timing(const toml::table& t, ValidationRecord& r) {
  if (auto v = t["wall_time_s"].value<double>()) r.wall_time_s = *v;
  if (auto v = t["legs"].value<int64_t>(); v && *v >= 1 && *v <= std::numeric_limits<int>::max())
    r.legs = static_cast<int>(*v);
  if (auto v = t["threads"].value<int64_t>()) r.threads = static_cast<int>(*v);
  r.machine = t["machine"].value_or(std::string());
}

[[noreturn]] void fail(const std::string& file, const std::string& key, const std::string& what) {
  throw RecordError(file + ": " + key + " " + what);
}

std::string required_string(const toml::table& t, const std::string& key, const std::string& file) {
  const auto v = t[key].value<std::string>();
  if (!v) fail(file, key, "is missing or not a string");
  return *v;
}

double required_number(const toml::table& t, const std::string& key, const std::string& file) {
  const auto v = t[key].value<double>();
  if (!v) fail(file, key, "is missing or not a number");
  return *v;
}

std::vector<double> number_array(const toml::table& t, const std::string& key, const std::string& file) {
  std::vector<double> out;
  const toml::array* a = t[key].as_array();
  if (!a) return out;
  for (const auto& n : *a) {
    const auto v = n.value<double>();
    if (!v) fail(file, key, "holds a value that is not a number");
    out.push_back(*v);
  }
  return out;
}

}  // namespace

const RecordMetric* ValidationRecord::metric(const std::string& quantity) const {
  for (const auto& m : metrics)
    if (m.quantity == quantity) return &m;
  return nullptr;
}

namespace {

// A record's description of the run from the resolved case the study ran (OUT/<case>/<method>/case.toml).
ValidationRecord record_of_resolved_case(const fs::path& resolved, const std::string& method, const std::string& key,
                                         const RecordProvenance& provenance) {
  const cases::Study study = cases::load_study(resolved);
  if (study.cases.size() != 1 || study.cases[0].resolutions.size() != 1)
    throw RecordError(resolved.string() + ": is not a resolved one-case spec");
  const cases::Case& c = study.cases[0];
  ValidationRecord r;
  r.study = study.name;
  r.case_id = c.id;
  r.description = c.description;
  r.method = method;
  r.resolution = c.resolutions.begin()->first;
  r.run_key = key;
  r.recorded_on = provenance.recorded_on;
  r.command = provenance.command;
  if (const auto* b = c.stilling_basin()) {
    r.tailwater_control = std::string(cases::option_name(b->control.mode));
    r.bed = std::string(cases::option_name(b->bed.profile));
    r.inflow_depth_m = b->inflow_depth_m;
    r.basin_start_m = b->upstream_length_m;
    r.bed_wavelength_m = b->bed.wavelength_m;
  }
  r.window_start_s = c.run.average_start_s;
  r.window_end_s = c.run.average_end_s;
  return r;
}

}  // namespace

std::vector<ValidationRecord> records_from_case_dir(const fs::path& case_dir, const RecordProvenance& provenance) {
  const fs::path metrics_file = case_dir / "csv" / "metrics.csv";
  const bool compared = fs::exists(metrics_file);
  const auto rows_of = [&](const fs::path& file) {
    return compared ? csv_rows(file) : std::vector<std::map<std::string, std::string>>{};
  };
  const auto metric_rows = rows_of(metrics_file);
  const auto profile_rows = rows_of(case_dir / "csv" / "profiles.csv");
  const auto surface_rows = rows_of(case_dir / "csv" / "longitudinal.csv");
  const std::string no_comparison = case_dir.string() + ": has no finished comparison (" + metrics_file.string() + " is missing)";
  const std::string run_compare = ": run `hydrojump compare " + case_dir.string() + "` or the study first";
  std::vector<ValidationRecord> out;
  for (const std::string method : {"sph", "vof"}) {
    const std::string key = util::read_text_file(case_dir / (method + ".stamp"));
    const fs::path resolved = case_dir / method / "case.toml";
    if (!fs::exists(resolved)) continue;  // not run by the study
    if (key.empty()) {
      // Not finished: a failed run is a result too (a miss), kept with its run key, what stopped it and
      // its timing. A failure file without both the key and the failure is no record.
      const auto failed = stage_file(case_dir / (method + ".failed"));
      const auto failed_key = failed ? (*failed)["run_key"].value<std::string>() : std::nullopt;
      const auto failure = failed ? (*failed)["failure"].value<std::string>() : std::nullopt;
      if (!failed_key || failed_key->empty() || !failure || failure->empty()) continue;
      ValidationRecord r = record_of_resolved_case(resolved, method, *failed_key, provenance);
      r.failure = *failure;
      read_stage_timing(*failed, r);
      out.push_back(std::move(r));
      continue;
    }
    if (!compared) throw RecordError(no_comparison + run_compare);
    ValidationRecord r = record_of_resolved_case(resolved, method, key, provenance);
    if (const auto info = stage_file(case_dir / (method + ".stage.toml"))) read_stage_timing(*info, r);
    // A quantity the method could not give (nan: e.g. no reverse surface flow, so no roller length) is
    // kept as value = nan where it has a laboratory, published or inputs-only value to stand beside.
    bool any_value = false;
    for (const auto& row : metric_rows) {
      const double v = cell(row, method);
      RecordMetric m{row.at("quantity"), row.count("unit") ? row.at("unit") : "",
                     row.count("status") ? row.at("status") : "predicted", v, finite(cell(row, "experiment")),
                     finite(cell(row, "published_sph")), finite(cell(row, "smooth_theory"))};
      if (!std::isfinite(v) && !m.experiment && !m.published_sph && !m.smooth_theory) continue;
      any_value = any_value || std::isfinite(v);
      r.metrics.push_back(m);
    }
    if (!any_value) continue;  // the method's results were not readable
    for (const auto& row : profile_rows) {
      if (row.at("method") != method) continue;
      const double u = cell(row, "u_mean_m_s");
      if (!std::isfinite(u)) continue;
      if (r.profiles.empty() || r.profiles.back().section != row.at("section"))
        r.profiles.push_back({row.at("section"), cell(row, "x_m"), {}, {}});
      r.profiles.back().z_m.push_back(cell(row, "z_m"));
      r.profiles.back().u_mean_m_s.push_back(u);
    }
    for (const auto& row : surface_rows) {
      const double eta = cell(row, "surface_mean_m");
      if (row.at("method") != method || !std::isfinite(eta)) continue;
      r.surface_x_m.push_back(cell(row, "x_m"));
      r.surface_mean_m.push_back(eta);
    }
    out.push_back(std::move(r));
  }
  if (out.empty() && !compared) throw RecordError(no_comparison + " and no failed run (<method>.failed)" + run_compare);
  if (out.empty())
    throw RecordError(case_dir.string() + ": no method finished here under the study (no sph.stamp or vof.stamp "
                                          "beside a resolved case.toml): records keep study results only");
  return out;
}

std::string record_text(const ValidationRecord& r) {
  std::ostringstream s;
  s << "# A validation record (compare/record.hpp): written by `hydrojump record`, read by `hydrojump study "
       "--records`\n# and `hydrojump validation-doc`. Regenerate it; do not edit it.\n";
  s << "format = " << r.format << "\n";
  s << "study = " << quoted(r.study) << "\ncase = " << quoted(r.case_id) << "\n";
  s << "description = " << quoted(r.description) << "\n";
  s << "method = " << quoted(r.method) << "\nresolution = " << quoted(r.resolution) << "\n";
  s << "run_key = " << quoted(r.run_key) << "\n";
  s << "hydrojump_version = " << quoted(r.hydrojump_version) << "\n";
  s << "recorded_on = " << quoted(r.recorded_on) << "\n";
  s << "command = " << quoted(r.command) << "\n";
  if (!r.tailwater_control.empty()) {
    s << "tailwater_control = " << quoted(r.tailwater_control) << "\nbed = " << quoted(r.bed)
      << "\ninflow_depth_m = " << number(r.inflow_depth_m) << "\nbasin_start_m = " << number(r.basin_start_m)
      << "\nbed_wavelength_m = " << number(r.bed_wavelength_m) << "\n";
  }
  if (r.wall_time_s) s << "wall_time_s = " << number(*r.wall_time_s) << "\n";
  if (r.legs) s << "legs = " << *r.legs << "\n";
  if (r.threads) s << "threads = " << *r.threads << "\n";
  if (!r.machine.empty()) s << "machine = " << quoted(r.machine) << "\n";
  if (r.failed()) s << "failure = " << quoted(r.failure) << "\n";
  s << "window_s = " << numbers({r.window_start_s, r.window_end_s}) << "\n";
  for (const auto& m : r.metrics) {
    s << "\n[[metrics]]\nquantity = " << quoted(m.quantity) << "\nunit = " << quoted(m.unit)
      << "\nstatus = " << quoted(m.status) << "\nvalue = " << number(m.value) << "\n";
    if (m.experiment) s << "experiment = " << number(*m.experiment) << "\n";
    if (m.published_sph) s << "published_sph = " << number(*m.published_sph) << "\n";
    if (m.smooth_theory) s << "smooth_theory = " << number(*m.smooth_theory) << "\n";
  }
  for (const auto& p : r.profiles) {
    s << "\n[[profiles]]\nsection = " << quoted(p.section) << "\nx_m = " << number(p.x_m)
      << "\nz_m = " << numbers(p.z_m) << "\nu_mean_m_s = " << numbers(p.u_mean_m_s) << "\n";
  }
  s << "\n[surface]\nx_m = " << numbers(r.surface_x_m) << "\nmean_m = " << numbers(r.surface_mean_m) << "\n";
  return s.str();
}

ValidationRecord parse_record(const std::string& text, const std::string& file) {
  toml::table t;
  try {
    t = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw RecordError(file + ":" + std::to_string(e.source().begin.line) + ": not a valid record (TOML: " +
                      std::string(e.description()) + ")");
  }
  ValidationRecord r;
  const auto format = t["format"].value<int64_t>();
  if (!format || *format != ValidationRecord::current_format)
    fail(file, "format", "is not " + std::to_string(ValidationRecord::current_format) +
                             " (a record of another program version: regenerate it)");
  r.study = required_string(t, "study", file);
  r.case_id = required_string(t, "case", file);
  r.description = t["description"].value_or(std::string());
  r.method = required_string(t, "method", file);
  if (r.method != "sph" && r.method != "vof") fail(file, "method", "= \"" + r.method + "\" is not \"sph\" or \"vof\"");
  r.resolution = required_string(t, "resolution", file);
  r.run_key = required_string(t, "run_key", file);
  r.hydrojump_version = t["hydrojump_version"].value_or(std::string());
  r.recorded_on = t["recorded_on"].value_or(std::string());
  r.command = t["command"].value_or(std::string());
  r.tailwater_control = t["tailwater_control"].value_or(std::string());
  r.bed = t["bed"].value_or(std::string());
  r.inflow_depth_m = t["inflow_depth_m"].value_or(0.0);
  r.basin_start_m = t["basin_start_m"].value_or(0.0);
  r.bed_wavelength_m = t["bed_wavelength_m"].value_or(0.0);
  if (auto v = t["wall_time_s"].value<double>()) r.wall_time_s = *v;
  if (auto v = t["legs"].value<int64_t>()) {
    if (*v < 1 || *v > std::numeric_limits<int>::max())
      fail(file, "legs", "= " + std::to_string(*v) + " must be at least 1 (and a count of runs)");
    r.legs = static_cast<int>(*v);
  }
  if (auto v = t["threads"].value<int64_t>()) r.threads = static_cast<int>(*v);
  r.machine = t["machine"].value_or(std::string());
  r.failure = t["failure"].value_or(std::string());
  const auto window = number_array(t, "window_s", file);
  if (window.size() != 2 || !(window[0] < window[1])) fail(file, "window_s", "is not [start, end] with start < end");
  r.window_start_s = window[0];
  r.window_end_s = window[1];
  if (const toml::array* metrics = t["metrics"].as_array()) {
    for (const auto& node : *metrics) {
      const toml::table* m = node.as_table();
      if (!m) fail(file, "metrics", "holds an entry that is not a table");
      RecordMetric row;
      row.quantity = required_string(*m, "quantity", file + ": metrics");
      row.unit = m->get("unit") ? required_string(*m, "unit", file + ": metrics") : "";
      row.status = required_string(*m, "status", file + ": metrics." + row.quantity);
      row.value = required_number(*m, "value", file + ": metrics." + row.quantity);
      if (auto v = (*m)["experiment"].value<double>()) row.experiment = *v;
      if (auto v = (*m)["published_sph"].value<double>()) row.published_sph = *v;
      if (auto v = (*m)["smooth_theory"].value<double>()) row.smooth_theory = *v;
      r.metrics.push_back(std::move(row));
    }
  }
  if (const toml::array* profiles = t["profiles"].as_array()) {
    for (const auto& node : *profiles) {
      const toml::table* p = node.as_table();
      if (!p) fail(file, "profiles", "holds an entry that is not a table");
      RecordProfile prof{required_string(*p, "section", file + ": profiles"),
                         required_number(*p, "x_m", file + ": profiles"), number_array(*p, "z_m", file),
                         number_array(*p, "u_mean_m_s", file)};
      if (prof.z_m.size() != prof.u_mean_m_s.size()) fail(file, "profiles." + prof.section, "z_m and u_mean_m_s differ in length");
      r.profiles.push_back(std::move(prof));
    }
  }
  if (const toml::table* surface = t["surface"].as_table()) {
    r.surface_x_m = number_array(*surface, "x_m", file);
    r.surface_mean_m = number_array(*surface, "mean_m", file);
    if (r.surface_x_m.size() != r.surface_mean_m.size()) fail(file, "surface", "x_m and mean_m differ in length");
  }
  return r;
}

fs::path record_file(const fs::path& root, const std::string& study, const std::string& case_id, const std::string& method,
                     const std::string& resolution) {
  return root / study / case_id / (method + "-" + resolution + ".toml");
}

void write_record(const fs::path& root, const ValidationRecord& r) {
  const fs::path file = record_file(root, r.study, r.case_id, r.method, r.resolution);
  fs::create_directories(file.parent_path());
  util::write_file_atomically(file, record_text(r));
}

std::optional<ValidationRecord> read_record_if_present(const fs::path& file) {
  if (!fs::exists(file)) return std::nullopt;
  return parse_record(util::read_text_file(file), file.string());
}

std::vector<ValidationRecord> read_records(const fs::path& root) {
  std::vector<fs::path> files;
  if (fs::is_directory(root))
    for (const auto& entry : fs::recursive_directory_iterator(root))
      if (entry.is_regular_file() && entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<ValidationRecord> out;
  for (const auto& f : files) out.push_back(parse_record(util::read_text_file(f), f.string()));
  return out;
}

void write_imported_comparison(const fs::path& case_dir, const std::vector<ValidationRecord>& records) {
  const auto of = [&](const std::string& method) -> const ValidationRecord* {
    for (const auto& r : records)
      if (r.method == method) return &r;
    return nullptr;
  };
  const ValidationRecord* sph = of("sph");
  const ValidationRecord* vof = of("vof");
  const auto text = [](std::optional<double> v) { return v ? util::number_text(*v) : std::string("nan"); };
  const auto value = [](const ValidationRecord* r, const std::string& q) -> std::optional<double> {
    const RecordMetric* m = r ? r->metric(q) : nullptr;
    return m ? std::optional<double>(m->value) : std::nullopt;
  };
  // The quantities in the order the first record lists them, then any only the other has.
  std::vector<const RecordMetric*> rows;
  for (const auto* r : {sph, vof})
    if (r)
      for (const auto& m : r->metrics)
        if (std::none_of(rows.begin(), rows.end(), [&](const RecordMetric* k) { return k->quantity == m.quantity; }))
          rows.push_back(&m);
  std::ostringstream metrics;
  metrics << "quantity,unit,sph,vof,experiment,published_sph,smooth_theory,status\n";
  for (const RecordMetric* m : rows)
    metrics << m->quantity << "," << m->unit << "," << text(value(sph, m->quantity)) << ","
            << text(value(vof, m->quantity)) << "," << text(m->experiment) << "," << text(m->published_sph) << ","
            << text(m->smooth_theory) << "," << m->status << "\n";
  const RecordMetric* eta = nullptr;
  for (const RecordMetric* m : rows)
    if (m->quantity == "eta") eta = m;
  std::ostringstream eta_csv;
  eta_csv << "case,smooth_theory_percent,experiment_percent,published_sph_percent,sph_percent,vof_percent,"
             "sph_crest_depth_percent,vof_crest_depth_percent,status\n";
  if (eta)
    eta_csv << records.front().case_id << "," << text(eta->smooth_theory) << "," << text(eta->experiment) << ","
            << text(eta->published_sph) << "," << text(value(sph, "eta")) << "," << text(value(vof, "eta")) << ","
            << text(value(sph, "eta_crest_depth")) << "," << text(value(vof, "eta_crest_depth")) << "," << eta->status
            << "\n";
  fs::create_directories(case_dir / "csv");
  util::write_file_atomically(case_dir / "csv" / "metrics.csv", metrics.str());
  util::write_file_atomically(case_dir / "csv" / "eta.csv", eta_csv.str());
}

}  // namespace hydrojump::compare
