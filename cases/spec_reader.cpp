#include "cases/spec_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <toml++/toml.h>

#include "cases/spec_table_reader.hpp"

#include "util/atomic_file.hpp"
#include "cases/case_rules.hpp"
#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "util/number_text.hpp"
#include "cases/output_times.hpp"

namespace hydrojump::cases {
namespace {
using namespace spec_detail;

void read_resolution(TableReader& t, Resolution& r, bool require_all) {
  const Range length = positive("m", 10.0);
  if (require_all) {
    r.particle_spacing_m = t.number("particle_spacing_m", length);
    r.vof_cell_size_bed_m = t.number("vof_cell_size_bed_m", length);
    r.vof_cell_size_bulk_m = t.number("vof_cell_size_bulk_m", length);
  } else {
    r.particle_spacing_m = t.number_or("particle_spacing_m", r.particle_spacing_m, length);
    r.vof_cell_size_bed_m = t.number_or("vof_cell_size_bed_m", r.vof_cell_size_bed_m, length);
    r.vof_cell_size_bulk_m = t.number_or("vof_cell_size_bulk_m", r.vof_cell_size_bulk_m, length);
  }
  if (r.vof_cell_size_bulk_m < r.vof_cell_size_bed_m) {
    t.fail_at(t.raw().get("vof_cell_size_bulk_m"), "vof_cell_size_bulk_m",
              "= " + util::number_text(r.vof_cell_size_bulk_m) + " is out of range: must be >= vof_cell_size_bed_m (" + util::number_text(r.vof_cell_size_bed_m) + " m)");
  }
  t.reject_unknown_keys();
}

// The study's [resolution] rule key: the inflow depth its levels are given for (resolution_rule below).
constexpr const char* resolution_rule_key = "for_inflow_depth_m";

void read_resolutions(TableReader& parent, std::map<std::string, Resolution>& out, bool require_all) {
  auto t = parent.table("resolution");
  if (!t) return;
  for (const auto& [name, node] : t->raw()) {
    const std::string key(name.str());
    if (key == resolution_rule_key) {  // the study's rule (read by the study), not a level
      if (!require_all)
        t->fail_at(&node, key, "is a rule of the study's [resolution] table: a case's own levels are given as they are");
      (void)t->number(key, positive("m", 10.0));
      continue;
    }
    if (!is_plain_name(key)) {
      t->fail_at(&node, key, std::string("is not usable as a resolution name (it names directories and TOML tables): ") + plain_name_rule);
    }
    auto level = t->table(key);
    Resolution r = out.count(key) ? out.at(key) : Resolution{};
    if (!require_all && !out.count(key)) {
      t->fail_at(&node, key, "is not a resolution defined at the study level (define [resolution." + key + "] first)");
    }
    r.name = key;
    read_resolution(*level, r, require_all);
    out[key] = r;
  }
  t->reject_unknown_keys();
}

void read_run(TableReader& t, RunSettings& run) {
  run.end_time_s = t.number("end_time_s", positive("s", max_end_time_s));
  run.output_interval_s = t.number_or("output_interval_s", run.output_interval_s, positive("s", max_end_time_s));
  if (run.output_interval_s > run.end_time_s) {
    t.fail_at(t.raw().get("output_interval_s"), "output_interval_s", "= " + util::number_text(run.output_interval_s) + " is out of range: must be <= run.end_time_s (" + util::number_text(run.end_time_s) + " s)");
  }
  // Every output is a file per method: at most max_outputs_per_run of them.
  if (run.end_time_s / run.output_interval_s > max_outputs_per_run) {
    t.fail_at(t.raw().get("output_interval_s"), "output_interval_s",
              "= " + util::number_text(run.output_interval_s) + " is out of range: must be >= run.end_time_s / " + util::number_text(max_outputs_per_run) + " (" +
                  util::number_text(run.end_time_s / max_outputs_per_run) + " s; at most " + util::number_text(max_outputs_per_run) + " outputs a run)");
  }
  run.average_start_s = t.number_or("average_start_s", 0.5 * run.end_time_s, Range{0.0, run.end_time_s, false, true, "s, within the run and before its end"});
  run.average_end_s = t.number_or("average_end_s", run.end_time_s, Range{run.average_start_s, run.end_time_s, true, false, "s, after average_start_s and within the run"});
  // A time mean (and a standard deviation, a trend) needs two outputs at least.
  if (const long n = outputs_in_window(run.average_start_s, run.average_end_s, run.output_interval_s); n < 2) {
    // Named by the key the file gives (the window's, else the output interval or the end time).
    std::string key = "end_time_s";
    for (const char* k : {"output_interval_s", "average_start_s", "average_end_s"})
      if (t.raw().get(k)) key = k;
    const double value = key == "average_end_s"       ? run.average_end_s
                          : key == "average_start_s"   ? run.average_start_s
                          : key == "output_interval_s" ? run.output_interval_s
                                                       : run.end_time_s;
    t.fail_at(t.raw().get(key), key,
              "= " + util::number_text(value) + " leaves the averaging window [" +
                  util::number_text(run.average_start_s) + ", " + util::number_text(run.average_end_s) + "] s with " +
                  util::number_text(static_cast<double>(n)) + " output time(s) (one every output_interval_s = " +
                  util::number_text(run.output_interval_s) + " s): it must hold at least 2");
  }
  t.reject_unknown_keys();
}

// The study's [run]: the run-length rule of its stilling basins (cases/case_rules.hpp).
RunRule read_run_rule(TableReader& t) {
  RunRule r;
  r.output_interval_s = t.number_or("output_interval_s", r.output_interval_s, positive("s", 100.0));
  r.start_up_sloshing_periods = t.number_or("start_up_sloshing_periods", r.start_up_sloshing_periods,
                                            Range{0.5, 100.0, false, false, "sloshing periods 2 L / sqrt(g y2*)"});
  r.window_sloshing_periods = t.number_or("window_sloshing_periods", r.window_sloshing_periods,
                                          Range{0.0, 100.0, true, false, "sloshing periods 2 L / sqrt(g y2*)"});
  r.toe_hold_sloshing_periods = t.optional_number("toe_hold_sloshing_periods",
                                                  Range{0.05, 100.0, true, true, "sloshing periods 2 L / sqrt(g y2*)"});
  t.reject_unknown_keys();
  return r;
}



// `basin_start`: a stilling basin's start (the expected toe), which the upstream section must lie
// upstream of (E1 and the toe search start there) and the downstream section downstream of (y2, E2);
// NaN for other kinds.
std::vector<Section> read_sections(TableReader& c, const toml::array& array, double x_min, double x_max,
                                   double basin_start) {
  std::vector<Section> sections;
  std::set<std::string> names;
  std::size_t index = 0;
  for (const auto& node : array) {
    auto t = c.element(node, "sections", index++);
    Section s;
    s.name = t.string("name");
    // Names become OpenFOAM set names and file names.
    if (!is_plain_name(s.name))
      t.fail_at(t.raw().get("name"), "name", "= \"" + s.name + "\" is not usable as a section name (it names OpenFOAM sets and files): " +
                                                 plain_name_rule);
    if (!names.insert(s.name).second) t.fail_at(t.raw().get("name"), "name", "= \"" + s.name + "\" is used by two sections: names must be unique");
    s.x_m = t.number("x_m", Range{x_min, x_max, false, false, "m, inside the domain"});
    s.role = t.choice("role", SectionRole::interior);
    if (std::isfinite(basin_start) && s.role == cases::SectionRole::upstream && !(s.x_m < basin_start))
      t.fail_at(t.raw().get("x_m"), "x_m", "= " + util::number_text(s.x_m) + " is out of range for the upstream section \"" + s.name +
                                               "\": must be < " + util::number_text(basin_start) +
                                               " m, the basin start (E1 and the toe search are taken upstream of the jump)");
    if (std::isfinite(basin_start) && s.role == cases::SectionRole::downstream && !(s.x_m > basin_start))
      t.fail_at(t.raw().get("x_m"), "x_m", "= " + util::number_text(s.x_m) + " is out of range for the downstream section \"" + s.name +
                                               "\": must be > " + util::number_text(basin_start) +
                                               " m, the basin start (y2 and E2 are taken behind the jump)");
    // E1 and the toe search start at the one upstream section, y2 and E2 come from the one downstream
    // section: a second one of either would be ignored, and a downstream section upstream of the
    // upstream one would turn eta and the jump length inside out.
    for (const Section& earlier : sections) {
      if ((s.role == cases::SectionRole::upstream || s.role == cases::SectionRole::downstream) && earlier.role == s.role)
        t.fail_at(t.raw().get("role"), "role", "= \"" + std::string(cases::option_name(s.role)) + "\" is also the role of section \"" + earlier.name +
                                                   "\": at most one section may have it");
      const Section* up = s.role == cases::SectionRole::upstream ? &s : (earlier.role == cases::SectionRole::upstream ? &earlier : nullptr);
      const Section* down = s.role == cases::SectionRole::downstream ? &s : (earlier.role == cases::SectionRole::downstream ? &earlier : nullptr);
      if (up && down && up != down && down->x_m <= up->x_m)
        t.fail_at(t.raw().get("x_m"), "x_m", "= " + util::number_text(s.x_m) + " puts the downstream section \"" + down->name +
                                                 "\" (x_m = " + util::number_text(down->x_m) + ") at or upstream of the upstream section \"" +
                                                 up->name + "\" (x_m = " + util::number_text(up->x_m) + "): it must lie downstream");
    }
    t.reject_unknown_keys();
    sections.push_back(s);
  }
  return sections;
}

// How far the inflow buffer's whole rows may miss the inflow depth (relative).
constexpr double kInflowRowsTolerance = 0.02;

// The most fluid particles a 2D case may start with (memory, and weeks of run time on a workstation).
constexpr double max_fluid_particles = 5.0e6;

// Resolution-dependent checks of one case at one resolution level.
void check_resolution(const Case& c, const Resolution& r, double gravity_m_s2, const std::string& file,
                      SpecPurpose purpose = SpecPurpose::run) {
  const auto fail = [&](const std::string& what) {
    throw SpecError(file + ": case \"" + c.id + "\" at resolution \"" + r.name + "\": " + what);
  };
  const double dx = r.particle_spacing_m;
  // The water a run starts with, per metre of width (m^2), for the particle-count bound below.
  double water_area_m2 = 0.0;
  if (const auto* b = c.stilling_basin()) {
    water_area_m2 = (b->upstream_length_m + b->basin_length_m + b->downstream_length_m) *
                    std::max({b->inflow_depth_m, b->tailwater_depth_m, b->bed.height_m});
    if (c.sph.inflow_condition == cases::InflowCondition::piston) {
      // The reservoir (cases/geometry.hpp, add_piston_reservoir): water at most at the energy head
      // E1 = y1 + U1^2/(2g), over reservoir_length_m or the piston's travel plus 2 H_r.
      const double head = b->inflow_depth_m + b->inflow_velocity_m_s * b->inflow_velocity_m_s / (2.0 * gravity_m_s2);
      const double length = c.sph.reservoir_length_m > 0.0
                                ? c.sph.reservoir_length_m
                                : b->inflow_depth_m * b->inflow_velocity_m_s / head * c.run.end_time_s + 2.0 * head;
      water_area_m2 += length * head;
    }
  } else if (const auto* d = c.dam_break()) {
    water_area_m2 = d->column_width_m * d->column_height_m;
  } else if (const auto* s = c.still_water()) {
    water_area_m2 = s->tank_length_m * s->water_depth_m;
  } else if (const auto* p = c.poiseuille()) {
    water_area_m2 = p->channel_length_m * p->channel_width_m;
  }
  // Fluid particles ~ area / dx^2; each takes ~0.3 kB with its neighbour lists and checkpoint copy.
  if (water_area_m2 / (dx * dx) > max_fluid_particles) {
    const double count = std::min(water_area_m2 / (dx * dx), 1e18);  // dx = 1e-200 would square to 0
    fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " gives about " + std::to_string(std::llround(count)) +
         " fluid particles: must be at most " + std::to_string(std::llround(max_fluid_particles)) + ", i.e. particle_spacing_m >= " +
         util::number_text(std::sqrt(water_area_m2 / max_fluid_particles)) + " m");
  }
  if (const auto* b = c.stilling_basin()) {
    if (b->bed.profile == cases::BedShape::sinusoidal && b->bed.wavelength_m < 4.0 * dx - 1e-12) {
      fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " resolves bed.wavelength_m = " + util::number_text(b->bed.wavelength_m) + " with " + util::number_text(b->bed.wavelength_m / dx) + " spacings: must be at least 4, i.e. particle_spacing_m <= " + util::number_text(b->bed.wavelength_m / 4.0) + " m");
    }
    if (b->inflow_depth_m < 5.0 * dx - 1e-12) {
      fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " puts " + util::number_text(b->inflow_depth_m / dx) + " particles across inflow.depth_m = " + util::number_text(b->inflow_depth_m) + ": must be at least 5, i.e. particle_spacing_m <= " + util::number_text(b->inflow_depth_m / 5.0) + " m");
    }
    // The inflow buffer (sph/open_boundaries.hpp) is N = inflow_buffer_rows(y1, dx) whole rows deep and
    // carries the spec's q, so its jet enters N dx deep at q/(N dx): Fr1 = (q^2/(g (N dx)^3))^(1/2) is off
    // by (y1/(N dx))^(3/2) - 1. The rows must match y1 within 2 % (Fr1 within 3 %; E1 within ~3 %).
    const double rows = inflow_buffer_rows(b->inflow_depth_m, dx);
    const double jet_depth = rows * dx;
    if (purpose == SpecPurpose::run && c.sph.inflow_condition == cases::InflowCondition::buffer &&
        std::abs(jet_depth / b->inflow_depth_m - 1.0) > kInflowRowsTolerance + 1e-12) {
      const double q = unit_discharge(b->inflow_depth_m, b->inflow_velocity_m_s);
      const double fr_spec = froude_number(b->inflow_depth_m, b->inflow_velocity_m_s, gravity_m_s2);
      const double fr_jet = froude_number(jet_depth, q / jet_depth, gravity_m_s2);
      fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " makes the inflow buffer " +
           util::number_text(rows) + " particle rows (" + util::number_text(jet_depth) + " m) deep for inflow.depth_m = " +
           util::number_text(b->inflow_depth_m) + ": the jet would enter with Fr1 = " + rounded_text(fr_jet, 4) + " instead of " +
           rounded_text(fr_spec, 4) + "; the rows must match the inflow depth within 2 %, i.e. particle_spacing_m = inflow.depth_m / N, e.g. " +
           rounded_text(b->inflow_depth_m / rows, 6) + " (N = " + util::number_text(rows) + ") or " +
           rounded_text(b->inflow_depth_m / (rows + 1.0), 6) + " (N = " + util::number_text(rows + 1.0) + ") m");
    }
  } else if (const auto* d = c.dam_break()) {
    if (d->column_width_m < 4.0 * dx) fail("particle_spacing_m = " + util::number_text(dx) + " puts fewer than 4 particles across column.width_m");
  } else if (const auto* s = c.still_water()) {
    if (s->water_depth_m < 4.0 * dx) fail("particle_spacing_m = " + util::number_text(dx) + " puts fewer than 4 particles across water.depth_m");
  } else if (const auto* p = c.poiseuille()) {
    if (p->channel_width_m < 8.0 * dx) fail("particle_spacing_m = " + util::number_text(dx) + " puts fewer than 8 particles across channel.width_m");
    // The periodic length must hold at least 3 kernel supports 2h, h = coef_h sqrt(2) dx.
    const double support = 2.0 * c.sph.coef_h * std::sqrt(2.0) * dx;
    if (p->channel_length_m < 3.0 * support - 1e-12) {
      fail("channel.length_m = " + util::number_text(p->channel_length_m) + " is out of range: the periodic channel must be at least 3 kernel supports long at particle_spacing_m = " + util::number_text(dx) + ", i.e. >= " + util::number_text(3.0 * support) + " m");
    }
  }
}

// T_x = c_x T_s of a stilling basin that holds its toe and sets no toe_hold_time_s of its own, from the
// study's [run] toe_hold_sloshing_periods (cases/case_rules.hpp), within the range of the key it stands
// for, (0, 1000] s.
void resolve_toe_hold_rule(TableReader& c, const Study& study, Case& result) {
  auto* b = std::get_if<StillingBasinCase>(&result.data);
  if (!b || !b->control.holds_toe() || !study.run_rule || !study.run_rule->toe_hold_sloshing_periods) return;
  if (auto tail = c.table("tailwater"); tail && tail->has("toe_hold_time_s")) return;
  const double periods = *study.run_rule->toe_hold_sloshing_periods;
  const double time = toe_hold_time_from_sloshing_periods(periods, *b, study.fluid.gravity_m_s2);
  if (!(time > 0.0 && time <= 1000.0))
    c.fail_at(nullptr, "tailwater.toe_hold_time_s",
              "= " + util::number_text(time) + " s, the study's [run] toe_hold_sloshing_periods = " + util::number_text(periods) +
                  " times this basin's sloshing period 2 L / sqrt(g y2*), is out of range: must be > 0 and <= 1000 s; "
                  "give the case its own [case.tailwater] toe_hold_time_s");
  b->control.toe_hold_time_s = time;
}

// [case.tailwater] control = "hold_toe" against the rest of the case (merged settings; a key is named
// where the case sets it, else at [case.tailwater] control; the basin start, where the toe is held,
// lies downstream of the inflow, since domain.upstream_length_m > 0):
//   - SPH steers the outflow buffer's depth, which a tailgate weir or a level held at the downstream
//     section would steer too: those need control = "fixed_depth";
//   - VOF legs: a whole number of output intervals, at most the run; unset: 0.5 s, or the whole
//     number of output intervals that fits a shorter run;
//   - T_V and T_x at least one leg (the volume error decays by (1 - leg / T_V) per leg; T_x below one
//     leg overshoots in a single leg, and the outlet just flips between its clamps).
void check_tailwater_control(TableReader& c, Case& result, StillingBasinCase& b) {
  if (!b.control.holds_toe()) {
    // The legs are the toe control's: a case's own leg length without that control is unused.
    if (auto v = c.table("vof"); v && v->has("tailwater_control_interval_s"))
      v->fail_at(v->raw().get("tailwater_control_interval_s"), "tailwater_control_interval_s",
                 "is only used with [case.tailwater] control = \"hold_toe\" (here \"" + std::string(cases::option_name(b.control.mode)) + "\")");
    return;
  }
  auto tail = c.required_table("tailwater");
  const auto fail = [&](const char* table, const char* key, const std::string& what) {
    if (auto t = c.table(table); t && t->has(key)) t->fail_at(t->raw().get(key), key, what);
    tail.fail_at(tail.raw().get("control"), "control",
                 "= \"hold_toe\" (the default for stilling basins) cannot be used with " + std::string(table) + "." + key +
                     " " + what);
  };
  if (result.sph.outflow_condition == cases::OutflowCondition::tailgate)
    fail("sph", "outflow_condition", "= \"tailgate\": a weir sets the tailwater itself; use control = \"fixed_depth\" "
                                     "with a tailgate");
  if (result.sph.outflow_level_reference != cases::OutflowLevelReference::outlet)
    fail("sph", "outflow_level_reference", "= \"" + std::string(cases::option_name(result.sph.outflow_level_reference)) +
                                               "\": that control holds the tailwater depth, which hold_toe predicts; use "
                                               "control = \"fixed_depth\" to hold a depth");
  double& leg = result.vof.tailwater_control_interval_s;
  const double out = result.run.output_interval_s;
  if (leg == 0.0) {  // unset: 0.5 s, or as many output intervals as fit a shorter run
    leg = std::max(1.0, std::floor(std::min(0.5, result.run.end_time_s) / out + 1e-9)) * out;
  } else {
    const double ratio = leg / out;
    if (std::abs(ratio - std::round(ratio)) > 1e-6 * ratio || std::round(ratio) < 1.0)
      fail("vof", "tailwater_control_interval_s",
           "= " + util::number_text(leg) + " is out of range: must be a whole number of run.output_interval_s (" +
               util::number_text(out) + " s), since the control reads the outputs of each leg");
    if (leg > result.run.end_time_s)
      fail("vof", "tailwater_control_interval_s",
           "= " + util::number_text(leg) + " is out of range: must be <= run.end_time_s (" +
               util::number_text(result.run.end_time_s) + " s), or the control never acts during the run");
  }
  for (const auto& [key, value] : {std::pair<const char*, double>{"volume_hold_time_s", b.control.volume_hold_time_s},
                                   std::pair<const char*, double>{"toe_hold_time_s", b.control.toe_hold_time_s}}) {
    if (!(value < leg)) continue;
    const std::string what = "is out of range: " + std::string(key) + " (" + util::number_text(value) +
                             " s) must be >= the VOF legs' length [vof] tailwater_control_interval_s (" +
                             util::number_text(leg) + " s), or the control overshoots";
    if (tail.has(key)) tail.fail_at(tail.raw().get(key), key, what);
    fail("vof", "tailwater_control_interval_s", "= " + util::number_text(leg) + ": [case.tailwater] " + what);
  }
}

// [case.run], or the study's [run] rule for a stilling basin without one.
void read_case_run(TableReader& c, const Study& study, Case& result) {
  if (auto run = c.table("run")) {
    read_run(*run, result.run);
  } else if (!study.run_rule) {
    c.required_table("run");  // names the missing table
  } else if (const auto* b = result.stilling_basin()) {
    result.run = run_from_sloshing_periods(*study.run_rule, *b, study.fluid.gravity_m_s2);
  } else {
    c.fail_at(nullptr, "run", "is missing: the study's [run] rule sets the run of stilling basins only (it needs a "
                              "sloshing period); give this " + result.kind + " case its [case.run] with end_time_s");
  }
}

// l = c_l y2* of a stilling basin (cases/case_rules.hpp) into sps_mixing_length_m.
void resolve_mixing_length_rule(TableReader& c, const Study& study, Case& result) {
  const double coefficient = result.sph.sps_mixing_length_per_sequent_depth;
  if (coefficient == 0.0) return;
  const auto* b = result.stilling_basin();
  if (!b)
    c.fail_at(nullptr, "sph", "inherits sps_mixing_length_per_sequent_depth = " + util::number_text(coefficient) +
                                  ", a rule for stilling basins (l = c_l y2*): give this " + result.kind +
                                  " case sps_mixing_length_m in [case.sph]");
  result.sph.sps_mixing_length_m = mixing_length_from_sequent_depth(coefficient, *b, study.fluid.gravity_m_s2);
}

// The study's levels scaled to a basin's inflow depth stay within the range a level is read with,
// (0, 10] m (read_resolution), so that the resolved case.toml the solvers read back holds them.
void check_scaled_resolutions(TableReader& c, const Study& study, const Case& result) {
  const auto* b = result.stilling_basin();
  if (!b || !study.resolution_for_inflow_depth_m) return;
  for (const auto& [name, r] : result.resolutions)
    for (const auto& [key, value] : {std::pair{"particle_spacing_m", r.particle_spacing_m},
                                     std::pair{"vof_cell_size_bed_m", r.vof_cell_size_bed_m},
                                     std::pair{"vof_cell_size_bulk_m", r.vof_cell_size_bulk_m}})
      if (!(value > 0.0 && value <= 10.0))
        c.fail_at(nullptr, "resolution." + name + "." + key,
                  "= " + util::number_text(value) + " m, the study's level scaled to this basin's inflow depth (" +
                      util::number_text(b->inflow_depth_m) + " m / [resolution] " + resolution_rule_key + " = " +
                      util::number_text(*study.resolution_for_inflow_depth_m) +
                      " m), is out of range: must be > 0 and <= 10 m; give the case its own [case.resolution." + name + "]");
}

Case read_case(TableReader& c, const Study& study, const SphSettings& sph,
               const VofSettings& vof, const std::map<std::string, Resolution>& resolutions,
               const std::filesystem::path& base_dir) {
  Case result;
  result.id = c.string("id");
  if (!is_plain_name(result.id)) {
    c.fail_at(c.raw().get("id"), "id", "= \"" + result.id + "\" is not usable as a directory name: " + std::string(plain_name_rule));
  }
  // "all" is what `--case all` selects every case with; a case of that name would make it ambiguous.
  if (result.id == "all")
    c.fail_at(c.raw().get("id"), "id", "= \"all\" is reserved: `--case all` selects every case; choose another id");
  result.kind = c.choice("kind", "", {"stilling_basin", "dam_break", "still_water", "poiseuille"}, true);
  result.description = c.string_or("description", "");
  result.sph = sph;
  result.vof = vof;
  if (auto t = c.table("sph")) read_sph(*t, result.sph);
  if (auto t = c.table("vof")) read_vof(*t, result.vof);
  const double g = study.fluid.gravity_m_s2;
  if (result.kind == "stilling_basin") {
    result.data = read_stilling_basin(c, g);
  } else if (result.kind == "dam_break") {
    result.data = read_dam_break(c, base_dir);
  } else if (result.kind == "still_water") {
    result.data = read_still_water(c);
  } else {
    result.data = read_poiseuille(c);
  }
  // The study's levels, scaled to this basin's inflow depth by the study's rule; then the case's own.
  result.resolutions = resolutions;
  if (const auto* b = std::get_if<StillingBasinCase>(&result.data); b && study.resolution_for_inflow_depth_m)
    for (auto& [name, r] : result.resolutions) {
      const double scale = b->inflow_depth_m / *study.resolution_for_inflow_depth_m;
      r.particle_spacing_m *= scale;
      r.vof_cell_size_bed_m *= scale;
      r.vof_cell_size_bulk_m *= scale;
    }
  read_resolutions(c, result.resolutions, false);
  check_scaled_resolutions(c, study, result);
  read_case_run(c, study, result);
  resolve_mixing_length_rule(c, study, result);
  resolve_toe_hold_rule(c, study, result);
  // Sections need the domain, which make_geometry derives; use it (sections are not read yet).
  const CaseGeometry geo = make_geometry(result, study.fluid);
  if (const toml::array* array = c.array_of_tables("sections")) {
    const double basin_start = result.stilling_basin() ? geo.expected_toe_x_m : std::nan("");
    result.sections = read_sections(c, *array, geo.x_min_m, geo.x_max_m, basin_start);
    result.sections_given = true;
  } else if (const auto* b = result.stilling_basin()) {
    result.sections = default_stilling_basin_sections(*b);
    // The downstream section (y2, E2) must lie past the toe, and 3 y2 clear of the outlet.
    const double needed = 3.0 * b->tailwater_depth_m + (b->bed.profile == cases::BedShape::sinusoidal ? b->bed.wavelength_m : 0.0);
    if (result.sections.back().x_m <= b->upstream_length_m + b->tailwater_depth_m) {
      auto domain = c.required_table("domain");
      domain.fail_at(domain.raw().get("basin_length_m"), "basin_length_m",
                     "= " + util::number_text(b->basin_length_m) + " is too short for the default sections: basin_length_m + downstream_length_m must exceed " + util::number_text(needed + b->tailwater_depth_m) + " m (4 tailwater depths" + (b->bed.profile == cases::BedShape::sinusoidal ? std::string(" plus a wavelength") : std::string()) + "), or list [[case.sections]] explicitly");
    }
  } else if (const auto* d = result.dam_break()) {
    for (std::size_t i = 0; i < d->gauges_x_m.size(); ++i) {
      result.sections.push_back({"H" + std::to_string(i + 1), d->gauges_x_m[i], SectionRole::gauge});
    }
  }
  if (auto* b = std::get_if<StillingBasinCase>(&result.data)) check_tailwater_control(c, result, *b);
  c.reject_unknown_keys();
  return result;
}

}  // namespace

const Resolution& Case::resolution(const std::string& name) const {
  const auto it = resolutions.find(name);
  if (it == resolutions.end()) {
    std::string known;
    for (const auto& [k, v] : resolutions) known += (known.empty() ? "\"" : ", \"") + k + "\"";
    throw SpecError("case \"" + id + "\": no resolution called \"" + name + "\" (defined: " +
                    (known.empty() ? std::string("none") : known) + ")");
  }
  return it->second;
}

const Case* Study::find_case(const std::string& id) const {
  for (const auto& c : cases) {
    if (c.id == id) return &c;
  }
  return nullptr;
}

Study parse_study(std::string_view toml_text, const std::string& source_name,
                  const std::filesystem::path& base_dir, SpecPurpose purpose) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw SpecError(source_name + ":" + std::to_string(e.source().begin.line) + ": not valid TOML: " + std::string(e.description()));
  }
  Study study;
  study.source_file = source_name;
  TableReader top(root, source_name, "", "");

  auto head = top.required_table("study");
  study.name = head.string("name");
  // The name goes into the comments of the generated OpenFOAM dictionaries and into reports: one line.
  if (study.name.empty() || study.name.size() > 200 ||
      std::any_of(study.name.begin(), study.name.end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
    head.fail_at(head.raw().get("name"), "name",
                 "is not usable: a study name is 1 to 200 characters on one line, with no control characters "
                 "(newlines, tabs), since it is written into the comments of the generated OpenFOAM files (here " +
                 std::to_string(study.name.size()) + " characters)");
  study.description = head.string_or("description", "");
  study.citations = head.string_array("citations");
  head.reject_unknown_keys();

  if (auto fluid = top.table("fluid")) {
    study.fluid.density_kg_m3 = fluid->number_or("density_kg_m3", study.fluid.density_kg_m3, positive("kg/m^3", 1e5));
    study.fluid.kinematic_viscosity_m2_s = fluid->number_or("kinematic_viscosity_m2_s", study.fluid.kinematic_viscosity_m2_s, positive("m^2/s", 1.0));
    study.fluid.gravity_m_s2 = fluid->number_or("gravity_m_s2", study.fluid.gravity_m_s2, positive("m/s^2", 100.0));
    fluid->reject_unknown_keys();
  }
  if (auto run = top.table("run")) study.run_rule = read_run_rule(*run);
  SphSettings sph;
  if (auto t = top.table("sph")) read_sph(*t, sph);
  VofSettings vof;
  if (auto t = top.table("vof")) read_vof(*t, vof);
  std::map<std::string, Resolution> resolutions;
  if (auto levels = top.table("resolution"); levels && levels->has(resolution_rule_key))
    study.resolution_for_inflow_depth_m = levels->number(resolution_rule_key, positive("m", 10.0));
  read_resolutions(top, resolutions, true);
  if (resolutions.empty()) {
    top.fail_at(nullptr, "resolution", "is missing: define at least one level, e.g. [resolution.quick] with particle_spacing_m, vof_cell_size_bed_m and vof_cell_size_bulk_m");
  }

  const toml::array* cases = top.array_of_tables("case");
  if (!cases || cases->empty()) top.fail_at(nullptr, "case", "is missing: a study needs at least one [[case]]");
  std::set<std::string> ids;
  std::size_t index = 0;
  for (const auto& node : *cases) {
    TableReader c = top.element(node, "case", index);
    // Name the case in every message about it once its id is known.
    std::string id;
    if (const auto* id_node = node.as_table()->get("id"); id_node && id_node->is_string()) id = *id_node->value<std::string>();
    TableReader named(*node.as_table(), source_name, id.empty() ? "" : "case \"" + id + "\": ", "");
    Case parsed = read_case(id.empty() ? c : named, study, sph, vof, resolutions, base_dir);
    if (!ids.insert(parsed.id).second) {
      named.fail_at(node.as_table()->get("id"), "id", "= \"" + parsed.id + "\" is used by two cases: ids must be unique");
    }
    for (const auto& [name, r] : parsed.resolutions) check_resolution(parsed, r, study.fluid.gravity_m_s2, source_name, purpose);
    study.cases.push_back(std::move(parsed));
    ++index;
  }
  top.reject_unknown_keys();
  return study;
}

Study load_study(const std::filesystem::path& file, SpecPurpose purpose) {
  // A directory opens as an empty stream on Linux and would be reported as a spec without [study].
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw SpecError(file.string() + ": is a directory, not a study file (a .toml spec or a generated case.toml)");
  // A pipe or a device would block the open or be read for ever.
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw SpecError(file.string() + ": is not a regular file (a pipe or a device?), not a study file (a .toml spec "
                    "or a generated case.toml)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SpecError(file.string() + ": cannot open the study file");
  // At most max_input_file_bytes.
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_input_file_bytes)
      throw SpecError(file.string() + ": is larger than 16 MiB, not a study file (a .toml spec or a generated case.toml)");
  }
  const auto base = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  Study study = parse_study(text, file.string(), base, purpose);
  study.source_file = file;
  return study;
}

Study load_embedded_default_study() {
  // Relative data paths of the embedded study resolve against the source tree's cases/ folder.
  return parse_study(embedded_default_study_text(), "<embedded cases/ead2002.toml>", std::filesystem::path("cases"));
}

void validate_for_resolution(const Study& study, const Case& c, const std::string& resolution) {
  if (c.resolutions.count(resolution) == 0) {
    try {
      (void)c.resolution(resolution);  // its message lists the resolutions the case has
    } catch (const SpecError& e) {
      throw SpecError(study.source_file.string() + ": " + e.what());
    }
  }
  check_resolution(c, c.resolution(resolution), study.fluid.gravity_m_s2, study.source_file.string());
}

}  // namespace hydrojump::cases
