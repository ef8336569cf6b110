// The tailgate step of `[case.tailwater] control = "hold_toe"` after each leg of interFoam: the toe over
// the leg's outputs (the freeSurface iso-surface) and the water volume at its end (water_volume) give
// the law's step (tailwater_control.hpp),
//   I += (y2* - y1)/T_x (x_toe - x_basin) dt;   V* = I + k_p (y2* - y1) (x_toe - x_basin);
//   Umean = (q + (V - V*)/T_V) / y2*
// which is logged in tailwater_control.csv and written as the outlet's Umean into the latest U (every
// processor's when decomposed).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

#include "reference/discharge_samples.hpp"
#include "reference/runner_parts.hpp"
#include "util/time_directories.hpp"

namespace hydrojump::reference::detail {

namespace fs = std::filesystem;

namespace {

// The last logged step at or before the leg's start: the integral part of its volume target (nothing:
// none yet) and its time.
struct PreviousStep {
  std::optional<double> volume_integral_m2;
  double time_s = 0.0;
};

// The step integrates from the previous step (the log's last row at or before the leg's start), not
// from the leg's start: a run resumed between two control times, or after a step that was never
// logged (the runner killed between the leg's end and its log row), still moves the volume target by
// the toe over the whole time since that step.
PreviousStep previous_step(const fs::path& dir, const TailwaterControlLaw& law, double leg_start_s, double tol) {
  PreviousStep previous;
  for (const TailwaterControlStep& s : read_tailwater_control_log(dir)) {
    if (s.time_s <= leg_start_s + tol) {
      // I = V* - P(x_toe): the row's toe is the one its proportional part used
      previous.volume_integral_m2 = s.volume_target_m2 - cases::toe_hold_proportional(law.gains, s.toe_x_m);
      previous.time_s = s.time_s;
    }
  }
  return previous;
}

// The toe on the free surface at each output in (previous step, leg end]; throws when there is none.
std::vector<double> toes_since(const fs::path& dir, const TailwaterControlLaw& law, double previous_step_s,
                               double leg_start_s, double leg_end_s, double tol) {
  std::vector<double> toes;
  int samples = 0;
  const fs::path surfaces = dir / "postProcessing" / free_surface_function;
  std::vector<double> x, z;
  for (const auto& [t, time_dir] : util::time_directories(surfaces)) {
    if (t <= previous_step_s + tol || t > leg_end_s + tol) continue;
    // Before a resume, a stop wrote its time off the output grid (4.41491 s): an uninterrupted run has
    // no sample there, so the step does not count it either.
    const double k = t / law.output_interval_s;
    if (t <= leg_start_s + tol && std::abs(k - std::round(k)) > 1e-6 * std::max(1.0, k)) continue;
    const fs::path file = time_dir / free_surface_file;
    if (!fs::exists(file)) continue;
    ++samples;
    try {
      read_surface_points(file, x, z);
    } catch (const std::exception& e) {
      throw OpenFoamError(std::string("tailwater control: ") + e.what());
    }
    toes.push_back(toe_on_surface(x, z, law.toe_search_from_m, law.gains.outlet_x_m, law.gains.inflow_depth_m));
  }
  if (samples == 0) {
    throw OpenFoamError("tailwater control: no free surface (" + std::string(free_surface_file) + ") in " +
                        surfaces.string() + " for (" + format_seconds(previous_step_s) + ", " + format_seconds(leg_end_s) +
                        "] s (the case's controlDict lacks the freeSurface function object: regenerate the case)");
  }
  return toes;
}

// The water volume (m^3) at the leg's end: the last row up to it, written during this leg (after its
// start), not one left by an earlier run; throws when there is none.
double water_volume_at(const fs::path& dir, double leg_start_s, double leg_end_s, double tol) {
  const fs::path volume_dir = dir / "postProcessing" / water_volume_function;
  std::optional<std::pair<double, double>> volume_m3;
  for (const auto& row : read_surface_field_value(volume_dir, "volFieldValue.dat")) {
    if (row.first <= leg_end_s + tol) volume_m3 = row;
  }
  if (!volume_m3 || volume_m3->first <= leg_start_s + tol) {
    throw OpenFoamError("tailwater control: no water volume at t = " + format_seconds(leg_end_s) + " s in " +
                        volume_dir.string() + "/*/volFieldValue.dat" +
                        (volume_m3 ? " (its last row before is at t = " + format_seconds(volume_m3->first) + " s)"
                                   : std::string(" (the case's controlDict lacks the water_volume function object: "
                                                 "regenerate the case)")));
  }
  return volume_m3->second;
}

// The U files of the latest time directory (each processor's when decomposed), plain text; throws when
// there is none or one is compressed.
std::vector<fs::path> latest_u_files(const fs::path& dir, bool parallel) {
  std::vector<fs::path> u_files;
  if (parallel) {
    for (const fs::path& rank : processor_directories(dir)) {
      const auto times = util::time_directories(rank, 0.0);
      if (!times.empty()) u_files.push_back(times.back().path / "U");
    }
  } else {
    const auto times = util::time_directories(dir, 0.0);
    if (!times.empty()) u_files.push_back(times.back().path / "U");
  }
  if (u_files.empty()) throw OpenFoamError("tailwater control: no time directory in " + dir.string());
  for (const fs::path& f : u_files) {
    if (!fs::exists(f) && fs::exists(f.string() + ".gz")) {
      throw OpenFoamError("tailwater control: " + f.string() + ".gz is compressed, but the control rewrites the "
                          "outlet's Umean in plain field files (a case with tailwater.control = \"hold_toe\" is "
                          "written with writeCompression off: regenerate it with `hydrojump generate`)");
    }
  }
  return u_files;
}

}  // namespace

void tailwater_control_after_leg(const fs::path& dir, const TailwaterControlLaw& law, double thickness_m,
                                 bool parallel, double leg_start_s, double leg_end_s, std::ostream& out) {
  const double tol = 1e-6 * std::max(law.interval_s, 1e-3);
  const PreviousStep previous = previous_step(dir, law, leg_start_s, tol);
  const std::vector<double> toes = toes_since(dir, law, previous.time_s, leg_start_s, leg_end_s, tol);
  const double volume_m3 = water_volume_at(dir, leg_start_s, leg_end_s, tol);
  const TailwaterControlStep step = tailwater_control_step(law, previous.volume_integral_m2, leg_end_s,
                                                          leg_end_s - previous.time_s, toes, volume_m3 / thickness_m);
  const std::vector<fs::path> u_files = latest_u_files(dir, parallel);
  const double previous_umean = read_outlet_mean_velocity(u_files.front());
  for (const fs::path& f : u_files) write_outlet_mean_velocity(f, step.outlet_mean_velocity_m_s);
  append_tailwater_control_log(dir, step);
  std::ostringstream line;
  line << std::setprecision(4) << "  tailwater control at t = " << format_seconds(leg_end_s) << " s: toe ";
  if (step.toe_outputs > 0) {
    line << step.toe_x_m << " m (" << step.toe_outputs << " outputs)";
  } else {
    line << "none (counted at the outlet)";
  }
  line << ", target " << law.gains.target_toe_x_m << " m; water " << step.water_volume_m2 << " m2, target "
       << step.volume_target_m2 << " m2; outlet Umean " << previous_umean << " -> " << step.outlet_mean_velocity_m_s
       << " m/s\n";
  out << line.str() << std::flush;
}

}  // namespace hydrojump::reference::detail
