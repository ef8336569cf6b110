// The case a run's results were made with (cases/results_case.hpp): which lines define a run, the
// first difference between two resolved cases, and the refusal of results made with other settings.
#include <catch2/catch.hpp>

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/fingerprint.hpp"
#include "cases/results_case.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump::cases;
namespace util = hydrojump::util;

namespace {

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

const std::string resolved_case =
    "# Resolved by hydrojump from a.toml\n"
    "description = \"Study a\"\n"
    "citations = [\"Someone (2002).\"]\n"
    "[sph]\n"
    "cfl_number = 0.2\n"
    "max_density_variation = 0.3\n"
    "checkpoint_interval_wall_s = 300.0\n"
    "[case.run]\n"
    "end_time_s = 10.0\n";

}  // namespace

TEST_CASE("results_case: run-control lines and comments do not define a run, every other line does", "[cases][results_case]") {
  CHECK(is_run_control_line("max_density_variation = 0.3"));
  CHECK(is_run_control_line("  checkpoint_interval_wall_s=60"));
  CHECK_FALSE(is_run_control_line("max_density_variation_extra = 1"));
  CHECK_FALSE(is_run_control_line("cfl_number = 0.2"));
  CHECK_FALSE(is_run_control_line(""));
  CHECK(is_descriptive_line("description = \"Run C\""));
  CHECK(is_descriptive_line("  citations=[\"a\"]"));
  CHECK(is_descriptive_line("source = \"Ead & Rajaratnam (2002)\""));
  CHECK_FALSE(is_descriptive_line("descriptions = 1"));
  CHECK_FALSE(is_descriptive_line("source_depth_m = 0.1"));
  CHECK_FALSE(is_descriptive_line("sequent_depth_m = 0.1"));
  CHECK(setting_lines(resolved_case) ==
        std::vector<std::string>{"[sph]", "cfl_number = 0.2", "[case.run]", "end_time_s = 10.0"});
  // Another spec file's name, description or citation, another stability limit or checkpoint
  // interval: the same run.
  std::string relaxed = resolved_case;
  relaxed.replace(relaxed.find("a.toml"), 6, "./b.toml");
  relaxed.replace(relaxed.find("Study a"), 7, "Study a, reworded");
  relaxed.replace(relaxed.find("Someone (2002)."), 15, "Someone (2003).");
  relaxed.replace(relaxed.find("0.3"), 3, "0.45");
  relaxed.replace(relaxed.find("300.0"), 5, "60.0");
  CHECK_FALSE(first_setting_difference(resolved_case, relaxed).any());
  // Another setting: named by its lines.
  std::string changed = resolved_case;
  changed.replace(changed.find("end_time_s = 10.0"), 17, "end_time_s = 12.0");
  const auto d = first_setting_difference(resolved_case, changed);
  CHECK(d.a == "end_time_s = 10.0");
  CHECK(d.b == "end_time_s = 12.0");
  const auto shorter = first_setting_difference(resolved_case, "[sph]\ncfl_number = 0.2\n");
  CHECK(shorter.a == "[case.run]");
  CHECK(shorter.b == "(end)");
  // The laboratory values results are only compared with ([case.measured] eta_percent, ...) are not
  // settings: a corrected one is the same run (jump_length_m too: it does not shape the initial water).
  // sequent_depth_m is in the SPH run's summary: it is. The table after it counts again.
  const std::string measured = resolved_case + "[case.measured]\nsequent_depth_m = 0.104\njump_length_m = 0.41\n"
                                               "eta_percent = 48.43\nroller_length_m = 0.3\n"
                                               "[[case.sections]]\nx_m = 0.3\neta_percent = 1\n";
  std::string corrected = measured;
  corrected.replace(corrected.find("48.43"), 5, "48.50");
  corrected.replace(corrected.find("roller_length_m = 0.3"), 21, "roller_length_m = 0.35");
  corrected.replace(corrected.find("jump_length_m = 0.41"), 20, "jump_length_m = 0.45");
  CHECK_FALSE(first_setting_difference(measured, corrected).any());
  std::string edited = measured;
  edited.replace(edited.find("sequent_depth_m = 0.104"), 23, "sequent_depth_m = 0.1049");
  CHECK(first_setting_difference(measured, edited).any());
  CHECK(setting_lines(measured).back() == "eta_percent = 1");  // outside [case.measured]: a setting line
  std::string moved = measured;
  moved.replace(moved.find("x_m = 0.3"), 9, "x_m = 0.4");
  CHECK(first_setting_difference(measured, moved).b == "x_m = 0.4");
}

TEST_CASE("results_case: results are refused under a case.toml other than the one they were made with", "[cases][results_case]") {
  const hydrojump::testing::TempDir tmp("results_case");
  const fs::path& dir = tmp.path();
  fs::create_directories(dir / "sph");
  const fs::path sph = dir / "sph";
  write(sph / "case.toml", resolved_case);
  // No results: nothing to check, whatever the case.
  write(dir / "other.toml", "[case.run]\nend_time_s = 1.0\n");
  CHECK_NOTHROW(require_results_of(sph, dir / "other.toml"));
  // A run starts: its case is recorded; then the case.toml beside it is edited by hand.
  record_results_case(sph);
  CHECK(util::read_text_file(sph / results_case_file_name) == resolved_case);
  write(sph / "summary.json", "{}\n");
  CHECK_NOTHROW(require_results_of(sph, sph / "case.toml"));
  std::string edited = resolved_case;
  edited.replace(edited.find("cfl_number = 0.2"), 16, "cfl_number = 0.1");
  write(sph / "case.toml", edited);
  CHECK_THROWS_WITH(require_results_of(sph, sph / "case.toml"),
                    Catch::Contains(sph.string() + " holds results made with other settings") &&
                        Catch::Contains("results_case.toml has 'cfl_number = 0.2' where") &&
                        Catch::Contains("has 'cfl_number = 0.1'"));
  // A case.toml damaged into binary: its line is quoted with \xNN escapes, not as raw bytes; an emptied
  // one says so (it read as "has '[sph]' where ... has '(end)'").
  write(sph / "case.toml", std::string("\x01\xff\x1b[31mgarbage\n", 14));
  CHECK_THROWS_WITH(require_results_of(sph, sph / "case.toml"),
                    Catch::Contains("has '\\x01\\xff\\x1b[31mgarbage'"));
  write(sph / "case.toml", "");
  CHECK_THROWS_WITH(require_results_of(sph, sph / "case.toml"),
                    Catch::Contains("case.toml is empty or not a readable file, so the results in"));
  // A relaxed stability limit is not another case.
  std::string relaxed = resolved_case;
  relaxed.replace(relaxed.find("0.3"), 3, "0.45");
  write(sph / "case.toml", relaxed);
  CHECK_NOTHROW(require_results_of(sph, sph / "case.toml"));
  // An emptied record says so (it used to read as "has '(end)' where ... has '[sph]'").
  write(sph / results_case_file_name, "");
  CHECK_THROWS_WITH(require_results_of(sph, sph / "case.toml"),
                    Catch::Contains(results_case_file_name) && Catch::Contains("is empty or not a readable file"));
  // Results of an earlier version (no record): their own case.toml is what made them.
  fs::remove(sph / results_case_file_name);
  CHECK_NOTHROW(require_results_of(sph, sph / "case.toml"));
  CHECK_THROWS_WITH(require_results_of(sph, dir / "other.toml"), Catch::Contains("case.toml has '[sph]'"));
  // Results without any case.toml cannot be told apart.
  fs::remove(sph / "case.toml");
  CHECK_THROWS_WITH(require_results_of(sph, dir / "other.toml"), Catch::Contains("no case.toml"));
}

TEST_CASE("results_case: an OpenFOAM run without its log is known by its time directories", "[cases][results_case]") {
  const hydrojump::testing::TempDir tmp("results_case_vof");
  const fs::path vof = tmp.path() / "vof";
  // A generated case: 0.orig/, 0/, constant/, system/ are not results.
  for (const char* d : {"0.orig", "0", "constant", "system", "processor0/0", "processor0/constant"})
    fs::create_directories(vof / d);
  CHECK_FALSE(holds_results(vof));
  // interFoam run by hand wrote 0.5/ (serial) or processor0/0.25/ (decomposed), and no log.interFoam.
  fs::create_directories(vof / "processor0" / "0.25");
  CHECK(holds_results(vof));
  fs::remove_all(vof / "processor0");
  CHECK_FALSE(holds_results(vof));
  fs::create_directories(vof / "0.5");
  CHECK(holds_results(vof));
  // ... so its results are checked against the case.toml beside them (they have no record).
  write(vof / "case.toml", resolved_case);
  write(tmp.path() / "other.toml", "[case.run]\nend_time_s = 1.0\n");
  CHECK_THROWS_WITH(require_results_of(vof, tmp.path() / "other.toml"), Catch::Contains("holds results made with other settings"));
  // A file named like a time is not a time directory; neither are names that only begin with a number.
  fs::remove_all(vof / "0.5");
  write(vof / "1", "not a directory\n");
  fs::create_directories(vof / "2e");
  fs::create_directories(vof / "-1");
  CHECK_FALSE(holds_results(vof));
}

TEST_CASE("results_case: one method's setting lines leave out the other method's model table only", "[cases][results_case]") {
  const std::string text = "# comment\n[sph]\ncfl_number = 0.2\n[vof]\nmax_courant = 0.8\n[resolution.quick]\n"
                           "particle_spacing_m = 0.005\n[[case]]\nid = \"A\"\n[[case.sections]]\nx_m = 0.3\n";
  const std::vector<std::string> sph = {"[sph]", "cfl_number = 0.2", "[resolution.quick]", "particle_spacing_m = 0.005",
                                        "[[case]]", "id = \"A\"", "[[case.sections]]", "x_m = 0.3"};
  const std::vector<std::string> vof = {"[vof]", "max_courant = 0.8", "[resolution.quick]", "particle_spacing_m = 0.005",
                                        "[[case]]", "id = \"A\"", "[[case.sections]]", "x_m = 0.3"};
  CHECK(method_setting_lines(text, "sph") == sph);
  CHECK(method_setting_lines(text, "vof") == vof);
  CHECK_THROWS_AS(method_setting_lines(text, "lbm"), std::invalid_argument);
}
