// The tables of each kind of case: a stilling basin's inflow, tailwater, bed and domain; a dam break's
// column, tank and gate; still water's tank; a Poiseuille channel's width, length and body force.
#include "cases/spec_table_reader.hpp"

#include "cases/hydraulics.hpp"

namespace hydrojump::cases::spec_detail {
namespace {

MeasuredValues read_measured(TableReader& t) {
  MeasuredValues m;
  m.sequent_depth_m = t.optional_number("sequent_depth_m", positive("m", 100.0));
  m.jump_length_m = t.optional_number("jump_length_m", positive("m", 1000.0));
  m.roller_length_m = t.optional_number("roller_length_m", positive("m", 1000.0));
  m.eta_percent = t.optional_number("eta_percent", between(0.0, 100.0, "%"));
  m.eta_smooth_percent = t.optional_number("eta_smooth_percent", between(0.0, 100.0, "%"));
  m.published_sph_eta_percent = t.optional_number("published_sph_eta_percent", between(0.0, 100.0, "%"));
  m.source = t.string_or("source", "");
  m.note = t.string_or("note", "");
  t.reject_unknown_keys();
  return m;
}

// Fails if `stated` differs from `derived` by more than 2 %.
void check_stated(TableReader& t, std::string_view key, std::optional<double> stated, double derived,
                  const std::string& derivation) {
  if (stated && std::abs(*stated - derived) > 0.02 * std::abs(derived)) {
    t.fail_at(t.raw().get(key), key, "= " + util::number_text(*stated) + " disagrees with the value derived from " + derivation + ", " + util::number_text(derived) + ", by " + util::number_text(std::round(1000.0 * std::abs(*stated / derived - 1.0)) / 10.0) + " % (allowed: 2 %)");
  }
}

}  // namespace

StillingBasinCase read_stilling_basin(TableReader& c, double g) {
  StillingBasinCase b;
  auto inflow = c.required_table("inflow");
  b.inflow_depth_m = inflow.number("depth_m", positive("m", 10.0));
  b.inflow_velocity_m_s = inflow.number("velocity_m_s", positive("m/s", 100.0));
  b.stated_discharge_m2_s = inflow.optional_number("discharge_m2_s", positive("m^2/s"));
  b.stated_froude = inflow.optional_number("froude", positive(""));
  const auto hyd0 = jump_hydraulics(b.inflow_depth_m, b.inflow_velocity_m_s, b.inflow_depth_m, g);
  check_stated(inflow, "discharge_m2_s", b.stated_discharge_m2_s, hyd0.discharge_m2_s, "depth_m * velocity_m_s");
  check_stated(inflow, "froude", b.stated_froude, hyd0.froude1, "velocity_m_s / sqrt(g depth_m)");
  if (!(hyd0.froude1 > 1.0)) {
    inflow.fail_at(inflow.raw().get("velocity_m_s"), "velocity_m_s", "= " + util::number_text(b.inflow_velocity_m_s) + " gives Fr1 = " + util::number_text(hyd0.froude1) + ": a hydraulic jump needs supercritical inflow, Fr1 > 1, i.e. velocity_m_s > " + util::number_text(std::sqrt(g * b.inflow_depth_m)) + " m/s");
  }
  inflow.reject_unknown_keys();

  auto tail = c.required_table("tailwater");
  b.tailwater_rule = tail.choice("rule", TailwaterRule::given);
  if (b.tailwater_rule == cases::TailwaterRule::belanger && tail.has("depth_m")) {
    tail.fail_at(tail.raw().get("rule"), "rule", "= \"belanger\" sets the depth, and tailwater.depth_m is given too: give one of them");
  }
  if (b.tailwater_rule == cases::TailwaterRule::belanger) {
    b.tailwater_depth_m = hyd0.belanger_y2_m;
  } else {
    b.tailwater_depth_m = tail.number("depth_m", Range{b.inflow_depth_m, 100.0, true, false, "m, above the inflow depth y1"});
  }
  b.control.mode = tail.choice("control", b.control.mode);
  b.control.volume_hold_time_s = tail.number_or("volume_hold_time_s", b.control.volume_hold_time_s, positive("s", 1000.0));
  b.control.toe_hold_time_s = tail.number_or("toe_hold_time_s", b.control.toe_hold_time_s, positive("s", 1000.0));
  b.control.toe_hold_gain = tail.number_or("toe_hold_gain", b.control.toe_hold_gain, between(0.0, 10.0));
  for (const char* key : {"volume_hold_time_s", "toe_hold_time_s", "toe_hold_gain"})
    if (!b.control.holds_toe() && tail.has(key))
      tail.fail_at(tail.raw().get(key), key, "is only used with control = \"hold_toe\" (here \"" + std::string(cases::option_name(b.control.mode)) + "\")");
  tail.reject_unknown_keys();

  auto domain = c.required_table("domain");
  b.upstream_length_m = domain.number("upstream_length_m", Range{0.0, 1000.0, true, false, "m"});
  b.basin_length_m = domain.number("basin_length_m", positive("m", 1000.0));
  b.downstream_length_m = domain.number("downstream_length_m", non_negative("m", 1000.0));
  b.air_height_m = domain.number("air_height_m", positive("m", 100.0));
  b.initial_toe_x_m = domain.optional_number("initial_toe_x_m", Range{0.0, b.upstream_length_m + b.basin_length_m, true, true, "m, inside the domain upstream of the basin end"});
  domain.reject_unknown_keys();

  auto bed = c.required_table("bed");
  b.bed.profile = bed.choice("profile", BedShape::smooth, true);
  if (b.bed.profile == cases::BedShape::sinusoidal) {
    b.bed.wavelength_m = bed.number("wavelength_m", positive("m", 100.0));
    b.bed.height_m = bed.number("height_m", positive("m", 100.0));
    const double basin_start = b.upstream_length_m, basin_end = basin_start + b.basin_length_m;
    const double s = b.bed.wavelength_m;
    b.bed.reach_start_m = bed.number_or("reach_start_m", basin_start, between(0.0, basin_end, "m, within the domain upstream of the basin end"));
    const double whole = std::floor((basin_end - b.bed.reach_start_m) / s + 1e-9);
    if (whole < 1.0) {
      bed.fail_at(bed.raw().get("wavelength_m"), "wavelength_m", "= " + util::number_text(s) + " is out of range: the basin from reach_start_m to its end (" + util::number_text(basin_end - b.bed.reach_start_m) + " m) must hold at least one wavelength");
    }
    b.bed.reach_end_m = bed.number_or("reach_end_m", b.bed.reach_start_m + whole * s, Range{b.bed.reach_start_m, basin_end + 1e-9, true, false, "m, after reach_start_m and not past the basin end"});
    const double n = (b.bed.reach_end_m - b.bed.reach_start_m) / s;
    if (std::abs(n - std::round(n)) > 1e-6 * std::max(1.0, n)) {
      bed.fail_at(bed.raw().get("reach_end_m"), "reach_end_m", "= " + util::number_text(b.bed.reach_end_m) + " is out of range: the corrugated reach must be a whole number of wavelengths so it ends on a crest; nearest allowed values are " + util::number_text(b.bed.reach_start_m + std::floor(n) * s) + " and " + util::number_text(b.bed.reach_start_m + std::ceil(n) * s) + " m");
    }
  } else {
    for (const char* key : {"wavelength_m", "height_m", "reach_start_m", "reach_end_m"}) {
      if (bed.has(key)) bed.fail_at(bed.raw().get(key), key, "is only used with profile = \"sinusoidal\" (this bed is \"smooth\")");
    }
  }
  bed.reject_unknown_keys();

  if (auto m = c.table("measured")) b.measured = read_measured(*m);
  return b;
}

DamBreakCase read_dam_break(TableReader& c, const std::filesystem::path& base_dir) {
  DamBreakCase d;
  auto column = c.required_table("column");
  d.column_width_m = column.number("width_m", positive("m", 1000.0));
  d.column_height_m = column.number("height_m", positive("m", 1000.0));
  column.reject_unknown_keys();
  auto tank = c.required_table("tank");
  d.tank_length_m = tank.number("length_m", Range{d.column_width_m, 1000.0, true, false, "m, longer than the column"});
  d.tank_height_m = tank.number("height_m", Range{d.column_height_m, 1000.0, false, false, "m, at least the column height"});
  tank.reject_unknown_keys();
  if (auto gate = c.table("gate")) {
    d.gate = gate->choice("type", GateOpening::instant);
    if (d.gate == cases::GateOpening::lifted) d.gate_lift_speed_m_s = gate->number("lift_speed_m_s", positive("m/s", 1000.0));
    gate->reject_unknown_keys();
  }
  if (auto gauges = c.table("gauges")) {
    d.gauges_x_m = gauges->number_array("x_m", Range{0.0, d.tank_length_m, true, true, "m, inside the tank"});
    gauges->reject_unknown_keys();
  }
  if (auto measured = c.table("measured")) {
    if (measured->has("front_file")) {
      const std::string file = measured->string("front_file");
      std::filesystem::path p(file);
      if (p.is_relative()) p = base_dir / p;
      std::error_code ec;
      if (!std::filesystem::exists(p, ec)) {
        measured->fail_at(measured->raw().get("front_file"), "front_file", "= \"" + file + "\": no such file (looked for '" + p.string() + "')");
      } else if (std::filesystem::is_directory(p, ec)) {
        measured->fail_at(measured->raw().get("front_file"), "front_file", "= \"" + file + "\": '" + p.string() + "' is a directory, not a CSV file");
      } else if (const std::string problem = front_file_problem(p); !problem.empty()) {
        measured->fail_at(measured->raw().get("front_file"), "front_file", "= \"" + file + "\": '" + p.string() + "' " + problem);
      }
      d.measured_front_file = std::filesystem::absolute(p).lexically_normal();
    }
    measured->reject_unknown_keys();
  }
  return d;
}

StillWaterCase read_still_water(TableReader& c) {
  StillWaterCase s;
  auto tank = c.required_table("tank");
  s.tank_length_m = tank.number("length_m", positive("m", 1000.0));
  s.tank_height_m = tank.number("height_m", positive("m", 1000.0));
  tank.reject_unknown_keys();
  auto water = c.required_table("water");
  s.water_depth_m = water.number("depth_m", Range{0.0, s.tank_height_m, true, false, "m, up to the tank height"});
  water.reject_unknown_keys();
  return s;
}

PoiseuilleCase read_poiseuille(TableReader& c) {
  PoiseuilleCase p;
  auto channel = c.required_table("channel");
  p.channel_width_m = channel.number("width_m", positive("m", 100.0));
  p.channel_length_m = channel.number("length_m", positive("m", 1000.0));
  p.body_force_m_s2 = channel.number("body_force_m_s2", positive("m/s^2", 1000.0));
  channel.reject_unknown_keys();
  return p;
}

}  // namespace hydrojump::cases::spec_detail
