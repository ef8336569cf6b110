// Validation records: one finished result of one method on one case at one resolution, kept as a small
// TOML file committed in the repository (validation/records/<study>/<case>/<method>-<resolution>.toml),
// so that a study outlives the machine it ran on.
//
// A record holds what the comparator measured (every metric with its label: predicted, imposed or
// input), the section profiles and the mean free surface needed to redraw the figures, and its key:
// the run fingerprint the study's stage stamp holds (the case's resolved settings and the solvers'
// code, sph::run_fingerprint). `hydrojump study --records DIR` imports a case whose records all match
// instead of running it again, and reports a record whose key no longer matches as stale.
//
// Usage
//   | function               | does                                                                  |
//   |------------------------|-----------------------------------------------------------------------|
//   | records_from_case_dir  | the records of a compared case directory of a study (one per method)  |
//   | record_text            | a record as TOML (numbers round-trip exactly)                         |
//   | parse_record           | a record from its TOML; RecordError names the file and key            |
//   | record_file            | ROOT/<study>/<case>/<method>-<resolution>.toml                        |
//   | write_record           | writes it (temporary file, then rename)                               |
//   | read_records           | every record under ROOT, in path order                                |
// Example:
//   for (const auto& r : records_from_case_dir("study/A", provenance)) write_record("validation/records", r);
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hydrojump::compare {

struct RecordError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One row of the comparator's metric table, for one method.
struct RecordMetric {
  std::string quantity;   // "sequent_depth", "eta", ...
  std::string unit;       // "m", "%", "" (a ratio)
  std::string status;     // "predicted" | "imposed" | "input"
  double value = 0.0;     // this method's
  std::optional<double> experiment, published_sph, smooth_theory;
};

// A velocity profile at a section: time-mean u over the window at heights z.
struct RecordProfile {
  std::string section;
  double x_m = 0.0;
  std::vector<double> z_m, u_mean_m_s;
};

struct ValidationRecord {
  static constexpr int current_format = 1;
  int format = current_format;
  std::string study, case_id, description, method, resolution;
  std::string run_key;             // the method's stage stamp (app::method_run_key: its settings + its solver's code)
  bool stale = false;              // not in the file: set where the current key is known and differs
  std::string hydrojump_version;   // of the program that compared the results
  std::string recorded_on;         // YYYY-MM-DD
  std::string command;             // what reproduces it
  std::string tailwater_control;   // stilling basins: "hold_toe" | "fixed_depth"
  std::string bed;                 // stilling basins: "smooth" | "sinusoidal"
  double inflow_depth_m = 0.0;     // y1
  double basin_start_m = 0.0;      // where the held toe is steered to
  double bed_wavelength_m = 0.0;   // S of a corrugated bed (0: smooth)
  std::optional<double> wall_time_s;  // the solver stage's over all its legs, when the study logged it
  std::optional<int> legs;         // the legs that time covers (a run stopped and resumed: several)
  std::optional<int> threads;      // SPH threads or OpenFOAM ranks of that stage
  std::string machine;             // where it ran: "<CPU model>, N cores" (empty: not logged)
  // A run that stopped before its end (the solver's diagnosis, or its log's last line): a miss kept as
  // a result. Such a record has no metrics, profiles or surface. Empty: the run finished.
  std::string failure;
  double window_start_s = 0.0, window_end_s = 0.0;
  std::vector<RecordMetric> metrics;
  std::vector<RecordProfile> profiles;
  std::vector<double> surface_x_m, surface_mean_m;  // the time-mean free surface

  const RecordMetric* metric(const std::string& quantity) const;
  bool failed() const { return !failure.empty(); }
};

// What the record writer adds to the results: today's date and the command that made them.
struct RecordProvenance {
  std::string recorded_on;
  std::string command;
};

// The records of one case directory of a study (OUT/<case>): one per method whose stage finished
// (its stamp) and whose values the comparison holds (csv/metrics.csv), and one per method whose stage
// failed (OUT/<case>/<method>.failed, written by the study: its run key, what stopped it and its wall
// time). Throws RecordError naming the missing file when the case has neither.
std::vector<ValidationRecord> records_from_case_dir(const std::filesystem::path& case_dir,
                                                    const RecordProvenance& provenance);

std::string record_text(const ValidationRecord& r);
ValidationRecord parse_record(const std::string& text, const std::string& file_name);

std::filesystem::path record_file(const std::filesystem::path& root, const std::string& study, const std::string& case_id,
                                  const std::string& method, const std::string& resolution);
void write_record(const std::filesystem::path& root, const ValidationRecord& r);
std::optional<ValidationRecord> read_record_if_present(const std::filesystem::path& file);
std::vector<ValidationRecord> read_records(const std::filesystem::path& root);

// Writes CASE_DIR/csv/metrics.csv and csv/eta.csv from the records of one case (one per method), as the
// comparator would have: what the study report reads of a case it imported instead of running.
void write_imported_comparison(const std::filesystem::path& case_dir, const std::vector<ValidationRecord>& records);

}  // namespace hydrojump::compare
