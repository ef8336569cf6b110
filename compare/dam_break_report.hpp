// `hydrojump compare RUN_DIR` for a dam-break case: the surge front of both methods against the
// measured one (compare/dam_break_front.hpp), in the experiment's time origin and unshifted.
//
// Read (either may be missing; the report then shows the other):
//   SPH   RUN_DIR/sph/gauges.csv, columns t_s and front_x_m (written by `hydrojump sph` at each output)
//   VOF   RUN_DIR/vof/postProcessing/sections/<time>/floor_alpha.water.xy (the floor line, half a cell
//         above the floor), the front by reference::surge_front with dry gaps up to 2 cells
// and the measured table the case names (case.measured.front_file, copied beside case.toml).
//
// Written into the output directory (RUN_DIR unless --out):
//   | file               | content                                                                 |
//   |--------------------|-------------------------------------------------------------------------|
//   | comparison.json    | the set-up, the time shift, per method the shifted and unshifted        |
//   |                    | comparison (points, mean, max, first point, late speed ratio)           |
//   | csv/front.csv      | per measured time: measured x/L, each method's x/L shifted and unshifted |
//   | figures/front.png  | the fronts against the data (compare/plot/plot_dam_break.py)            |
//   | report.md          | the same as a table, with the time shift and its source                 |
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "cases/spec.hpp"
#include "compare/dam_break_front.hpp"

namespace hydrojump::compare {

struct DamBreakMethodFront {
  std::string method;               // "sph" | "vof"
  bool available = false;
  std::string status;               // "ok", or why the result is missing
  std::string source;               // the file or directory read
  FrontTrace trace;
  FrontComparison shifted, unshifted;
};

struct DamBreakComparison {
  std::string case_id, description, resolution;
  double column_width_m = 0.0, tank_length_m = 0.0, gravity_m_s2 = 9.81;
  double time_shift_s = 0.0;        // gate_opening_time_shift_s(L, g)
  std::string measured_source;
  std::vector<MeasuredFrontPoint> measured;
  DamBreakMethodFront sph, vof;
  std::string figures_problem;      // why the figure was not made ("" when it was, or without plots)
};

// Reads both results of a resolved dam-break case and compares them. Throws std::runtime_error when
// the case has no measured front.
DamBreakComparison compare_dam_break(const cases::Study& study, const std::filesystem::path& run_dir);

// Writes comparison.json, csv/front.csv, report.md and (with `plots`) figures/front.png into `out`;
// returns why the figure was not made, or "".
std::string write_dam_break_report(const DamBreakComparison& c, const std::filesystem::path& out, bool plots,
                                   std::ostream& log);

// Per method: "sph: front vs Koshizuka & Oka, shifted by 0.0395 s: mean 0.041 L, max 0.083 L over 14 of 15
// points, late speed ratio 1.01 (unshifted: mean 0.183 L, max 0.243 L)".
std::string dam_break_summary_text(const DamBreakComparison& c);

}  // namespace hydrojump::compare
