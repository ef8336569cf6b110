// The case a solver directory's results were made with. `generate` writes the resolved case.toml
// into DIR/sph and DIR/vof; each solver copies it to results_case.toml when a run starts afresh, so
// later readers (`compare`, `generate` over a finished run) can tell whether the results still
// belong to the case.toml beside them.
//
// Two resolved cases are the same run when their setting lines agree: comments (which name the spec
// file however it was spelt), the descriptive texts (`description`, `citations`, `source`: readers
// take them from the case.toml beside the results, never from the record), the laboratory values the
// results are only compared with ([case.measured] eta_percent, eta_smooth_percent,
// published_sph_eta_percent, roller_length_m, jump_length_m, front_file: a corrected one re-runs the
// comparison only; sequent_depth_m is in the SPH run's summary, so it stays a setting) and the
// run-control settings a resumed run may change (sph.max_density_variation,
// sph.checkpoint_interval_wall_s) are left out.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hydrojump::cases {

// The file beside case.toml that records the case a run started with.
inline constexpr const char* results_case_file_name = "results_case.toml";

// Whether `line` (of a resolved case.toml) is a run-control setting: it never changes the trajectory
// (the stability limit checked after each step, the checkpoint interval), so a run may be resumed
// with another value.
bool is_run_control_line(std::string_view line);

// Whether `line` holds one of the descriptive texts (study or case `description`, the study's
// `citations`, the measurements' `source` and `note`): words about the run, not settings of it.
bool is_descriptive_line(std::string_view line);

// Whether `line` assigns one of the laboratory values a run is only compared with (within
// [case.measured]: eta_percent, eta_smooth_percent, published_sph_eta_percent, roller_length_m,
// jump_length_m, front_file).
bool is_laboratory_comparison_line(std::string_view line);

// The lines of a resolved case text that define its run: every line but comments, descriptive texts,
// the laboratory comparison values of [case.measured] and run-control settings.
std::vector<std::string> setting_lines(std::string_view case_text);

// The setting lines one method's results depend on ("sph" or "vof"): setting_lines less the other
// method's model table ([vof] for "sph", [sph] for "vof"). Throws std::invalid_argument for another
// method.
std::vector<std::string> method_setting_lines(std::string_view case_text, std::string_view method);

// The first setting line where two case texts differ, as {line of a, line of b} ("(end)" past the
// last line); both empty when their settings agree.
struct SettingDifference {
  std::string a, b;
  bool any() const { return !a.empty() || !b.empty(); }
};
SettingDifference first_setting_difference(std::string_view case_text_a, std::string_view case_text_b);

// Whether a solver directory holds results of a run (SPH outputs or checkpoint, an OpenFOAM log or a
// time directory after 0, also under processor0/).
bool holds_results(const std::filesystem::path& solver_dir);

// The file holding the case `solver_dir`'s results were made with: its results_case.toml, or its own
// case.toml for runs of earlier versions that did not record one.
std::filesystem::path recorded_case_file(const std::filesystem::path& solver_dir);

// Records `solver_dir`/case.toml as the case of the run starting there (results_case.toml, written
// atomically).
void record_results_case(const std::filesystem::path& solver_dir);

// Throws std::runtime_error when `solver_dir` holds results that were made with settings other than
// those of `case_toml` (its results_case.toml, or its own case.toml for runs of earlier versions that
// did not record one), naming the first differing setting and what to do. Nothing to check (returns)
// when it holds no results.
void require_results_of(const std::filesystem::path& solver_dir, const std::filesystem::path& case_toml);

}  // namespace hydrojump::cases
