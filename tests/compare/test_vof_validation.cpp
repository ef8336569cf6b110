// Validation of the OpenFOAM reference on the corrugated beds of Ead & Rajaratnam (2002), through the
// whole tool chain a user runs (`hydrojump generate`, `hydrojump vof`, `hydrojump compare`), with the
// study files of the repository at the quick resolution (5 mm cells near the bed and the surface).
// All [slow]: one interFoam run of 5-40 min each on one core (README.md, "Validation").
//
// What is asserted (issue 5's acceptance):
//   - corrugated runs A-E, tailwater at the measured y2: eta from the section energies within 3
//     percentage points of the experiment's, and the toe (the mean of the frames' toes over the
//     averaging window) on the corrugated reach;
//   - the bed matters (run B): with B's inflow and B's measured tailwater 0.145 m, the corrugated bed
//     holds the toe on its reach while the smooth bed lets the jump sweep past the downstream section
//     by 8-10 s.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "cases/spec_reader.hpp"
#include "compare/case_comparison.hpp"
#include "app/generate.hpp"
#include "reference/runner.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump;
using hydrojump::testing::TempDir;

namespace {

// Generates case `id` of `spec_file` at quick into `dir`, runs its OpenFOAM case serially, and
// compares it over [t0, t1] (the case's own window when t1 <= t0).
compare::CaseComparison run_vof_quick(const std::string& spec_file, const std::string& id, const fs::path& dir,
                                      double t0 = 0.0, double t1 = 0.0) {
  const cases::Study study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/" + spec_file);
  std::ostringstream log;
  app::generate_cases(study, app::select_cases(study, {id}), "quick", dir, log);
  reference::RunOptions run;
  run.progress_interval_s = 120.0;
  reference::run_vof_case(dir / id / "vof", run, log);
  compare::CompareOptions options;
  options.plots = false;
  if (t1 > t0) {
    options.window_start_s = t0;
    options.window_end_s = t1;
  }
  return compare::compare_case_directory(dir / id, options, log);
}

void check_corrugated_run(const std::string& id) {
  TempDir tmp("vof-validation-" + id);
  const compare::CaseComparison r = run_vof_quick("ead2002.toml", id, tmp.path());
  REQUIRE(r.vof.available);
  const compare::JumpMetrics& m = r.vof.metrics;
  REQUIRE(r.lab.eta_percent.has_value());
  std::ostringstream notes;
  for (const auto& n : m.notes) notes << "\n  " << n;
  WARN("run " << id << " (quick, " << r.window_start_s << "-" << r.window_end_s << " s): eta " << 100.0 * m.eta
              << " % vs " << *r.lab.eta_percent << " %, toe " << m.toe_mean_of_frames_x_m << " +- " << m.toe_std_m
              << " m (reach " << r.basin_start_m << "-" << r.basin_end_m << " m), y2 " << m.sequent_depth_m
              << " m, Lj " << m.jump_length_m << " m" << notes.str());
  CHECK(100.0 * m.eta == Approx(*r.lab.eta_percent).margin(3.0));
  CHECK(m.toe_mean_of_frames_x_m > r.basin_start_m);
  CHECK(m.toe_mean_of_frames_x_m < r.basin_end_m);
}

}  // namespace

TEST_CASE("VOF corrugated run A at quick: eta within 3 points of the experiment and the toe on the reach",
          "[compare][vof][validation][slow]") {
  check_corrugated_run("A");
}

TEST_CASE("VOF corrugated run B at quick: eta within 3 points of the experiment and the toe on the reach",
          "[compare][vof][validation][slow]") {
  check_corrugated_run("B");
}

TEST_CASE("VOF corrugated run C at quick: eta within 3 points of the experiment and the toe on the reach",
          "[compare][vof][validation][slow]") {
  check_corrugated_run("C");
}

TEST_CASE("VOF corrugated run D at quick: eta within 3 points of the experiment and the toe on the reach",
          "[compare][vof][validation][slow]") {
  check_corrugated_run("D");
}

TEST_CASE("VOF corrugated run E at quick: eta within 3 points of the experiment and the toe on the reach",
          "[compare][vof][validation][slow]") {
  check_corrugated_run("E");
}

TEST_CASE("VOF, the bed matters: at run B's tailwater the corrugated bed holds the jump and a smooth bed "
          "lets it sweep past the downstream section",
          "[compare][vof][validation][slow]") {
  TempDir tmp("vof-validation-bed-matters");
  const compare::CaseComparison corrugated = run_vof_quick("bed_matters.toml", "B", tmp.path(), 6.0, 10.0);
  const compare::CaseComparison smooth =
      run_vof_quick("bed_matters.toml", "B_smooth_low_tailwater", tmp.path(), 8.0, 10.0);
  REQUIRE(corrugated.vof.available);
  REQUIRE(smooth.vof.available);
  REQUIRE(corrugated.tailwater_depth_m == smooth.tailwater_depth_m);
  double x_downstream = 0.0;
  for (const auto& s : smooth.sections)
    if (s.role == "downstream") x_downstream = s.x_m;
  REQUIRE(x_downstream > 0.0);
  WARN("at tailwater " << corrugated.tailwater_depth_m << " m: corrugated toe "
                       << corrugated.vof.metrics.toe_mean_of_frames_x_m << " m over 6-10 s (reach "
                       << corrugated.basin_start_m << "-" << corrugated.basin_end_m << " m), smooth toe "
                       << smooth.vof.metrics.toe_mean_of_frames_x_m << " m over 8-10 s (downstream section at "
                       << x_downstream << " m)");
  CHECK(corrugated.vof.metrics.toe_mean_of_frames_x_m > corrugated.basin_start_m);
  CHECK(corrugated.vof.metrics.toe_mean_of_frames_x_m < x_downstream);
  CHECK(smooth.vof.metrics.toe_mean_of_frames_x_m > x_downstream);
}
