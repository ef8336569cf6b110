#include "app/record_cli.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <iostream>
#include <memory>
#include <optional>
#include <set>

#include "app/study.hpp"
#include "util/atomic_file.hpp"
#include "util/cli_checks.hpp"
#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "compare/record.hpp"
#include "compare/validation_doc.hpp"
#include "hydrojump/version.hpp"

namespace fs = std::filesystem;

namespace hydrojump::app {

namespace {

std::string today() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[16];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d", &tm);
  return buffer;
}

struct RecordOptions {
  fs::path study_dir;
  std::vector<std::string> cases;
  fs::path records = "validation/records";
};

void record_command(const RecordOptions& o) {
  std::vector<fs::path> dirs;
  if (o.cases.empty()) {
    // Compared cases, and cases whose solver failed (a failed run is recorded too).
    for (const auto& entry : fs::directory_iterator(o.study_dir))
      if (entry.is_directory() && (fs::exists(entry.path() / "csv" / "metrics.csv") || fs::exists(entry.path() / "sph.failed") ||
                                   fs::exists(entry.path() / "vof.failed")))
        dirs.push_back(entry.path());
    std::sort(dirs.begin(), dirs.end());
    if (dirs.empty())
      throw CLI::ValidationError("STUDY_DIR", o.study_dir.string() +
                                                  " holds no compared case (no <case>/csv/metrics.csv) and no failed run (<case>/<method>.failed)");
  } else {
    for (const auto& id : o.cases) dirs.push_back(o.study_dir / id);
  }
  for (const auto& dir : dirs) {
    const fs::path resolved = fs::exists(dir / "sph" / "case.toml") ? dir / "sph" / "case.toml" : dir / "vof" / "case.toml";
    const std::string study = study_command_argument(resolved, fs::current_path());
    compare::RecordProvenance provenance{today(), ""};
    std::vector<compare::ValidationRecord> records = compare::records_from_case_dir(dir, provenance);
    for (auto& r : records) {
      r.hydrojump_version = version_string;
      r.command = "hydrojump study " + study + " --cases " + r.case_id + " --resolution " + r.resolution + " --methods " + r.method;
      compare::write_record(o.records, r);
      std::cout << "recorded " << compare::record_file(o.records, r.study, r.case_id, r.method, r.resolution).string()
                << (r.failed() ? " (a failed run: " + r.failure + ")" : std::string()) << "\n";
    }
  }
}

struct DocOptions {
  fs::path records = "validation/records";
  fs::path out = "docs/validation.md";
  std::vector<std::string> not_run;  // SPEC and one or more RESOLUTIONs
  fs::path readme;                   // a document with the headline table's markers
  bool check = false;
};

// Marks the records of `study` whose run key is not the one its case has now (other settings or other
// solver code) as stale.
void mark_stale(std::vector<compare::ValidationRecord>& records, const cases::Study& study) {
  for (auto& r : records) {
    if (r.study != study.name) continue;
    for (const auto& c : study.cases)
      if (c.id == r.case_id && c.resolutions.count(r.resolution))
        r.stale = method_run_key(study, c, r.resolution, r.method) != r.run_key;
  }
}

void validation_doc_command(const DocOptions& o) {
  auto records = compare::read_records(o.records);
  std::optional<cases::Study> study;
  if (o.not_run.size() >= 2) {
    study = o.not_run[0] == "default" ? cases::load_embedded_default_study() : cases::load_study(o.not_run[0]);
    mark_stale(records, *study);
    std::set<std::string> levels;
    for (const auto& c : study->cases)
      for (const auto& [name, level] : c.resolutions) levels.insert(name);
    for (std::size_t k = 1; k < o.not_run.size(); ++k)
      if (!levels.count(o.not_run[k])) {
        std::string known;
        for (const auto& name : levels) known += (known.empty() ? "" : ", ") + name;
        throw compare::RecordError("--not-run: \"" + o.not_run[k] + "\" is not a resolution of " + o.not_run[0] +
                                   " (it has: " + (known.empty() ? std::string("none") : known) + ")");
      }
  }
  std::string text = compare::validation_markdown(records, o.records.generic_string());
  if (study)
    for (std::size_t k = 1; k < o.not_run.size(); ++k) text += compare::not_run_markdown(*study, records, o.not_run[k]);
  std::string readme_text;
  if (!o.readme.empty()) readme_text = compare::with_headline(util::read_text_file(o.readme), compare::headline_markdown(records), o.readme.string());
  if (o.check) {
    if (!o.readme.empty() && util::read_text_file(o.readme) != readme_text) {
      std::cerr << "hydrojump validation-doc: the headline table of " << o.readme.string() << " is not what the records in "
                << o.records.string() << " give: run validation-doc with --readme " << o.readme.string() << "\n";
      throw CLI::RuntimeError(1);
    }
    if (util::read_text_file(o.out) != text) {
      std::cerr << "hydrojump validation-doc: " << o.out.string() << " is not what the records in " << o.records.string()
                << " give: run `hydrojump validation-doc --records " << o.records.string() << " --out "
                << o.out.string() << "`\n";
      throw CLI::RuntimeError(1);
    }
    std::cout << o.out.string() << " is up to date with " << o.records.string() << "\n";
    return;
  }
  if (o.out.has_parent_path()) fs::create_directories(o.out.parent_path());
  util::write_file_atomically(o.out, text);
  std::cout << "wrote " << o.out.string() << "\n";
  if (!o.readme.empty()) {
    util::write_file_atomically(o.readme, readme_text);
    std::cout << "updated the headline table of " << o.readme.string() << "\n";
  }
}

}  // namespace

std::string study_command_argument(const fs::path& resolved_case, const fs::path& working_dir) {
  const std::string text = util::read_text_file(resolved_case);
  const std::string lead = "# Resolved by hydrojump from ";
  if (text.rfind(lead, 0) != 0) return "SPEC";
  const auto end = text.find(": case \"", lead.size());
  const std::string file = text.substr(lead.size(), end == std::string::npos ? std::string::npos : end - lead.size());
  if (file.find("<embedded") == 0) return "default";
  const fs::path given(file);
  if (!given.is_absolute() || !working_dir.is_absolute()) return file;
  const fs::path below = given.lexically_normal().lexically_relative(working_dir.lexically_normal());
  if (below.empty() || *below.begin() == "..") return file;
  return below.generic_string();
}

void register_record_commands(CLI::App& app) {
  auto r = std::make_shared<RecordOptions>();
  auto* record = app.add_subcommand(
      "record",
      "Keep the finished comparisons of a study directory, and its failed runs (with what stopped them), as "
      "validation records: one small TOML file per case, "
      "method and resolution, RECORDS/<study>/<case>/<method>-<resolution>.toml, holding every metric with its "
      "label (predicted, imposed, input), the laboratory and inputs-only values, the section profiles and mean "
      "surface, the window, the solver's wall time, and its key (the case's resolved settings and the solvers' "
      "code). Commit them: `hydrojump study --records RECORDS` then imports a case instead of running it, and "
      "`hydrojump validation-doc` writes docs/validation.md from them.");
  record->add_option("STUDY_DIR", r->study_dir, "a study's output directory (`hydrojump study --out`)")
      ->required()
      ->check(CLI::ExistingDirectory);
  record->add_option("--cases", r->cases, "case ids, comma-separated (default: every compared case)")->delimiter(',');
  record->add_option("--records", r->records, "records folder")->capture_default_str()->check(util::non_empty_path());
  record->callback([r] {
    try {
      record_command(*r);
    } catch (const compare::RecordError& e) {
      std::cerr << "hydrojump record: " << e.what() << "\n";
      throw CLI::RuntimeError(1);
    }
  });

  auto d = std::make_shared<DocOptions>();
  auto* doc = app.add_subcommand(
      "validation-doc",
      "Write docs/validation.md from the validation records: per case, method and resolution the predicted "
      "sequent depth, energy dissipation, jump and roller length and toe against the laboratory and the "
      "inputs-only values, SPH against VOF, and the record and command behind each row. --check compares "
      "instead of writing (exit 1 when the file is out of date).");
  doc->add_option("--records", d->records, "records folder")->capture_default_str()->check(util::non_empty_path());
  doc->add_option("--out,-o", d->out, "the document")->capture_default_str()->check(util::non_empty_path());
  doc->add_option("--not-run", d->not_run,
                  "SPEC RESOLUTION [RESOLUTION...]: also list the stilling basins of SPEC (a file, or \"default\") with "
                  "no record of a method at each RESOLUTION, with the size and estimated wall time of each missing run")
      ->expected(2, 1 + 8);
  doc->add_option("--readme", d->readme,
                  "also set the headline table of this document (e.g. README.md) between its lines "
                  "<!-- validation-table:start --> and <!-- validation-table:end -->")
      ->check(CLI::ExistingFile);
  doc->add_flag("--check", d->check, "compare the document with what the records give; write nothing");
  doc->callback([d] {
    try {
      validation_doc_command(*d);
    } catch (const compare::RecordError& e) {
      std::cerr << "hydrojump validation-doc: " << e.what() << "\n";
      throw CLI::RuntimeError(1);
    }
  });
}

}  // namespace hydrojump::app
