// The VOF dam break against Koshizuka & Oka (1996): cases/dam_break.toml (column L = 1 m x 2 m, tank
// 4 m, laminar, the gate removed at once) run by interFoam, its surge front read from the floor line
// and compared by `hydrojump compare`'s own code (compare::compare_dam_break) in the experiment's
// time origin, t_model = t_exp - 0.175 sqrt(L / (2 g)) (compare/dam_break_front.hpp). The unshifted
// errors are printed beside (the front then leads by 0.2-0.3 L).
//
// Asserted on the shifted comparison, with 4 cm cells (default suite, about a minute) and 2 cm cells
// ([slow], a few minutes): mean |x_VOF - x_exp| / L <= 0.10, max <= 0.20 over at least 10 of the 15
// measured points, the late front speed (after t_exp = 0.4 s) within 5 % of the measured one.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "cases/spec_reader.hpp"
#include "compare/dam_break_report.hpp"
#include "reference/cli.hpp"
#include "reference/runner.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump;
using hydrojump::testing::TempDir;

namespace {

// The study's dam break with cells of `cell_m` everywhere, run serially; its comparison.
compare::DamBreakComparison run_vof_dam_break(double cell_m) {
  cases::Study study = cases::load_study(fs::path(HYDROJUMP_SOURCE_DIR) / "cases/dam_break.toml");
  REQUIRE(study.cases.size() == 1);
  cases::Case& c = study.cases.front();
  cases::Resolution res = c.resolution("quick");
  res.vof_cell_size_bed_m = cell_m;
  res.vof_cell_size_bulk_m = cell_m;
  c.resolutions = {{res.name, res}};  // the one resolution compare_dam_break reads
  const TempDir tmp("vof-dam-break");
  reference::write_vof_case(study, c, res.name, tmp.path() / "vof");
  std::ostringstream log;
  reference::RunOptions options;
  options.progress_interval_s = 60.0;
  reference::run_vof_case(tmp.path() / "vof", options, log);
  compare::DamBreakComparison r = compare::compare_dam_break(study, tmp.path());
  std::cout << "VOF dam break, " << cell_m << " m cells: " << compare::dam_break_summary_text(r);
  return r;
}

void check_front(const compare::DamBreakComparison& r) {
  REQUIRE(r.vof.available);
  const compare::FrontComparison& e = r.vof.shifted;
  CHECK(r.time_shift_s == Approx(0.0395).epsilon(0.001));
  CHECK(e.points >= 10);
  CHECK(e.mean_abs <= 0.10);
  CHECK(e.max_abs <= 0.20);
  CHECK(std::abs(e.late_speed_ratio - 1.0) <= 0.05);
}

}  // namespace

TEST_CASE("VOF dam break with 4 cm cells: the surge front in the experiment's time origin", "[reference][openfoam][dam_break]") {
  check_front(run_vof_dam_break(0.04));
}

TEST_CASE("VOF dam break with 2 cm cells: the surge front in the experiment's time origin",
          "[reference][openfoam][dam_break][slow]") {
  check_front(run_vof_dam_break(0.02));
}
