#include "cases/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cases/hydraulics.hpp"

namespace hydrojump::cases {

double InitialWater::surface_at(double x) const {
  if (surface_x_m.empty()) return -1e300;
  if (x <= surface_x_m.front()) return surface_z_m.front();
  if (x >= surface_x_m.back()) return surface_z_m.back();
  const auto it = std::upper_bound(surface_x_m.begin(), surface_x_m.end(), x);
  const auto i = static_cast<std::size_t>(it - surface_x_m.begin());
  const double t = (x - surface_x_m[i - 1]) / (surface_x_m[i] - surface_x_m[i - 1]);
  return surface_z_m[i - 1] + t * (surface_z_m[i] - surface_z_m[i - 1]);
}

std::vector<Section> default_stilling_basin_sections(const StillingBasinCase& basin) {
  const double y1 = basin.inflow_depth_m;
  const double y2 = basin.tailwater_depth_m;
  const double x_toe = basin.upstream_length_m;
  const double x_outlet = basin.upstream_length_m + basin.basin_length_m + basin.downstream_length_m;
  std::vector<Section> sections;
  sections.push_back({"upstream", x_toe - std::min(10.0 * y1, 0.5 * basin.upstream_length_m), SectionRole::upstream});
  sections.push_back({"toe", x_toe, SectionRole::toe});
  for (int k : {2, 4, 6}) {
    const double x = x_toe + k * y2;
    if (x < x_outlet - 3.0 * y2) {
      sections.push_back({"x_" + std::to_string(k) + "y2", x, SectionRole::interior});
    }
  }
  double x_down = std::min(x_toe + 8.0 * y2, x_outlet - 3.0 * y2);
  // On a corrugated reach, E2 and y2 are taken over a crest (depth above the crests, as measured).
  const auto& bed = basin.bed;
  if (bed.profile == cases::BedShape::sinusoidal && x_down > bed.reach_start_m && x_down < bed.reach_end_m) {
    const double crest = bed.reach_start_m + std::round((x_down - bed.reach_start_m) / bed.wavelength_m) * bed.wavelength_m;
    x_down = crest <= x_outlet - 3.0 * y2 ? crest : crest - bed.wavelength_m;
  }
  sections.push_back({"downstream", x_down, SectionRole::downstream});
  return sections;
}

namespace {

// Walls with the fluid on the left of the direction of travel.
WallPolyline segment_wall(std::string name, Vec2 from, Vec2 to) {
  return WallPolyline{std::move(name), {from, to}};
}

// The initial surface of a stilling basin: y1 up to the toe x0, then a classical jump's roller
// (Hager 1992, cases/hydraulics.hpp) up to the tailwater level y2 at x_end:
//   z(x) = y1 + (y2 - y1) min(1, tanh(1.5 X) / tanh(4.5)),   X = (x - x0) / Lr
// with Lr Hager's roller length at Fr1 (taken within [2.5, 20]), sampled every Lr / 16: the curve
// scaled by 1.0002 so that it meets the tailwater level at X = 3. Inputs only: the measured jump
// length, a result, does not shape it.
void initial_jump_surface(InitialWater& w, double x0, double x_end, double y1, double y2, double froude1) {
  const double roller = hager_roller_length(y1, std::clamp(froude1, 2.5, 20.0));
  const auto rise = [&](double x_over_lr) {
    return y1 + (y2 - y1) * std::min(1.0, roller_surface_fraction(x_over_lr) / std::tanh(4.5));
  };
  w.surface_x_m = {0.0};
  w.surface_z_m = {y1};
  constexpr int samples = 48;  // 16 per roller length, over 3
  for (int k = 0; k <= samples && x0 + k * roller / 16.0 < x_end; ++k) {
    const double x = x0 + k * roller / 16.0;
    if (x <= w.surface_x_m.back()) continue;  // a toe at x = 0
    w.surface_x_m.push_back(x);
    w.surface_z_m.push_back(rise(k / 16.0));
  }
  w.surface_x_m.push_back(x_end);
  w.surface_z_m.push_back(rise((x_end - x0) / roller));
}

CaseGeometry stilling_basin_geometry(const StillingBasinCase& b, double g) {
  CaseGeometry geo;
  const double y1 = b.inflow_depth_m, y2 = b.tailwater_depth_m;
  const double x_toe = b.upstream_length_m;
  const double x_end = b.upstream_length_m + b.basin_length_m + b.downstream_length_m;
  geo.bed = b.bed.profile == cases::BedShape::sinusoidal
                ? BedProfile::sinusoidal(b.bed.wavelength_m, b.bed.height_m, b.bed.reach_start_m,
                                         b.bed.reach_end_m)
                : BedProfile::flat(0.0);
  geo.x_min_m = 0.0;
  geo.x_max_m = x_end;
  geo.z_min_m = geo.bed.lowest_elevation();
  geo.z_max_m = std::max(y1, y2) + b.air_height_m;
  // The bed follows the profile; the resolution of the polyline is 1e-5 m (walls are re-sampled by
  // arc length by the particle generator; meshes use bed.polyline with their own tolerance).
  WallPolyline bed{"bed", geo.bed.polyline(0.0, x_end, 1e-5)};
  geo.walls.push_back(std::move(bed));
  // The sluice gate above the inflow: a vertical wall at x = 0 from the top down to y1. Its top is the
  // domain top or the energy line E1 if higher: spray of a roller that has reached the gate may fly
  // up to E1 (no higher) and must not pass over the gate into the inflow.
  const double gate_top = std::max(geo.z_max_m, specific_energy(y1, y1 * b.inflow_velocity_m_s, g));
  geo.walls.push_back(segment_wall("inlet_gate", Vec2(0.0, gate_top), Vec2(0.0, y1)));
  geo.inflows.push_back({0.0, y1, b.inflow_velocity_m_s});
  geo.outflows.push_back({x_end, y2});

  // Initial water: the supercritical layer y1 up to the expected toe (the spec's initial_toe_x_m, else
  // the basin start), then a classical jump's roller surface (initial_jump_surface), then the
  // tailwater level: the initial volume is close to a standing jump's, and the roller's water behind
  // the toe holds the start-up jet where a long ramp lets it push the toe downstream.
  auto& w = geo.initial_water;
  w.x_begin_m = 0.0;
  w.x_end_m = x_end;
  initial_jump_surface(w, b.initial_toe_x_m.value_or(x_toe), x_end, y1, y2,
                       froude_number(y1, b.inflow_velocity_m_s, g));
  w.discharge_m2_s = unit_discharge(y1, b.inflow_velocity_m_s);

  geo.body_force_m_s2 = Vec2(0.0, -g);
  geo.max_water_height_m = std::max(y1, y2) - geo.bed.lowest_elevation();
  geo.max_flow_speed_m_s = b.inflow_velocity_m_s;
  geo.expected_toe_x_m = x_toe;
  return geo;
}

// A closed-bottom tank [0, length] x [0, height] with floor and side walls, water up to `depth`
// over [0, water_end].
CaseGeometry tank_geometry(double length, double height, double water_end, double depth, double g) {
  CaseGeometry geo;
  geo.bed = BedProfile::flat(0.0);
  geo.x_min_m = 0.0;
  geo.x_max_m = length;
  geo.z_min_m = 0.0;
  geo.z_max_m = height;
  const Vec2 a(0.0, 0.0), b(length, 0.0), c(length, height), e(0.0, height);
  geo.walls.push_back(segment_wall("bed", a, b));
  geo.walls.push_back(segment_wall("right_wall", b, c));
  geo.walls.push_back(segment_wall("left_wall", e, a));
  auto& w = geo.initial_water;
  w.x_begin_m = 0.0;
  w.x_end_m = water_end;
  w.surface_x_m = {0.0, water_end};
  w.surface_z_m = {depth, depth};
  geo.body_force_m_s2 = Vec2(0.0, -g);
  geo.max_water_height_m = depth;
  return geo;
}

CaseGeometry dam_break_geometry(const DamBreakCase& d, double g) {
  CaseGeometry geo = tank_geometry(d.tank_length_m, d.tank_height_m, d.column_width_m, d.column_height_m, g);
  geo.max_flow_speed_m_s = std::sqrt(2.0 * g * d.column_height_m);
  geo.dam_gate_x_m = d.column_width_m;
  if (d.gate == cases::GateOpening::lifted) {
    // The gate: a plate on the floor at x = L holding the column, 5 % taller than it, pulled straight
    // up at the lift speed until its lower edge is 5 % above the column's top (then it rests).
    const double top = 1.05 * d.column_height_m;
    MovingWall gate;
    gate.face = segment_wall("gate", Vec2(d.column_width_m, 0.0), Vec2(d.column_width_m, top));
    gate.velocity_m_s = Vec2(0.0, d.gate_lift_speed_m_s);
    gate.start_s = 0.0;
    gate.end_s = top / d.gate_lift_speed_m_s;
    geo.moving_walls.push_back(std::move(gate));
  }
  return geo;
}

CaseGeometry still_water_geometry(const StillWaterCase& s, double g) {
  CaseGeometry geo = tank_geometry(s.tank_length_m, s.tank_height_m, s.tank_length_m, s.water_depth_m, g);
  geo.max_flow_speed_m_s = std::sqrt(g * s.water_depth_m);
  return geo;
}

// Poiseuille: gravity is not applied (a horizontal channel's hydrostatic pressure does not drive the
// flow); the body force f drives it along x. Centre-line speed u_max = f W^2 / (8 nu).
CaseGeometry poiseuille_geometry(const PoiseuilleCase& p, double nu) {
  CaseGeometry geo;
  geo.bed = BedProfile::flat(0.0);
  geo.periodic_x = true;
  geo.x_min_m = 0.0;
  geo.x_max_m = p.channel_length_m;
  geo.z_min_m = 0.0;
  geo.z_max_m = p.channel_width_m;
  geo.walls.push_back(segment_wall("bed", Vec2(0.0, 0.0), Vec2(p.channel_length_m, 0.0)));
  geo.walls.push_back(segment_wall("top_wall", Vec2(p.channel_length_m, p.channel_width_m),
                                   Vec2(0.0, p.channel_width_m)));
  auto& w = geo.initial_water;
  w.x_begin_m = 0.0;
  w.x_end_m = p.channel_length_m;
  w.surface_x_m = {0.0, p.channel_length_m};
  w.surface_z_m = {p.channel_width_m, p.channel_width_m};
  geo.body_force_m_s2 = Vec2(p.body_force_m_s2, 0.0);
  geo.max_water_height_m = p.channel_width_m;
  geo.max_flow_speed_m_s = p.body_force_m_s2 * p.channel_width_m * p.channel_width_m / (8.0 * nu);
  return geo;
}

}  // namespace

CaseGeometry make_geometry(const Case& c, const FluidProperties& fluid) {
  CaseGeometry geo;
  if (const auto* b = c.stilling_basin()) {
    geo = stilling_basin_geometry(*b, fluid.gravity_m_s2);
  } else if (const auto* d = c.dam_break()) {
    geo = dam_break_geometry(*d, fluid.gravity_m_s2);
  } else if (const auto* s = c.still_water()) {
    geo = still_water_geometry(*s, fluid.gravity_m_s2);
  } else if (const auto* p = c.poiseuille()) {
    geo = poiseuille_geometry(*p, fluid.kinematic_viscosity_m2_s);
  } else {
    throw std::logic_error("make_geometry: case '" + c.id + "' has no kind data");
  }
  geo.kind = c.kind;
  geo.sections = c.sections;
  return geo;
}

// q = sum y1 U1
double inflow_discharge(const CaseGeometry& geometry) {
  double q = 0.0;
  for (const auto& in : geometry.inflows) q += unit_discharge(in.depth_m, in.velocity_m_s);
  return q;
}

int inflow_buffer_rows(double depth_m, double dx) {
  return std::max(1, static_cast<int>(std::lround(depth_m / dx)));
}

PistonReservoir add_piston_reservoir(CaseGeometry& geo, const StillingBasinCase& b, double opening_m,
                                     double length_m, double end_time_s, double t, double g) {
  const double y1 = b.inflow_depth_m, u1 = b.inflow_velocity_m_s, q = y1 * u1;
  PistonReservoir r;
  // H_r + q^2 / (2 g H_r^2) = E1, the subcritical root: bisection on [y_c, E1], where E(H) grows.
  const double e1 = specific_energy(y1, q, g);
  r.depth_m = solve_increasing([&](double h) { return specific_energy(h, q, g); }, e1, std::cbrt(q * q / g), e1);
  r.opening_m = opening_m > 0.0 ? opening_m : y1 / sluice_contraction_coefficient;
  r.piston_speed_m_s = q / r.depth_m;
  r.length_m = length_m > 0.0 ? length_m : r.piston_speed_m_s * end_time_s + 2.0 * r.depth_m;
  if (!(r.opening_m < r.depth_m))
    throw std::invalid_argument("piston reservoir: the sluice opening " + std::to_string(r.opening_m) +
                                " m is not below the reservoir level " + std::to_string(r.depth_m) +
                                " m (sph.sluice_opening_m)");
  if (r.length_m < r.piston_speed_m_s * end_time_s + 2.0 * r.depth_m - 1e-12)
    throw std::invalid_argument("piston reservoir: sph.reservoir_length_m = " + std::to_string(r.length_m) +
                                " m is too short: the piston travels " + std::to_string(r.piston_speed_m_s * end_time_s) +
                                " m in the run and must stop 2 H_r = " + std::to_string(2.0 * r.depth_m) +
                                " m short of the gate");
  r.piston_x_m = -t - r.length_m;
  const double top = 1.5 * r.depth_m;
  geo.x_min_m = r.piston_x_m;
  geo.z_max_m = std::max(geo.z_max_m, top);
  // The sluice gate as a plate (fluid on both sides), replacing the one-sided inlet gate.
  std::erase_if(geo.walls, [](const WallPolyline& w) { return w.name == "inlet_gate"; });
  geo.walls.push_back(WallPolyline{"sluice_gate", {Vec2(0.0, geo.z_max_m), Vec2(0.0, r.opening_m),
                                                   Vec2(-t, r.opening_m), Vec2(-t, geo.z_max_m)}});
  geo.walls.push_back(segment_wall("reservoir_bed", Vec2(r.piston_x_m - t, 0.0), Vec2(0.0, 0.0)));
  MovingWall piston;
  piston.face = segment_wall("piston", Vec2(r.piston_x_m, top), Vec2(r.piston_x_m, 0.0));
  piston.velocity_m_s = Vec2(r.piston_speed_m_s, 0.0);
  piston.start_s = 0.0;
  piston.end_s = end_time_s;
  piston.held_level_m = r.depth_m;
  piston.reservoir_end_x_m = -t;
  geo.moving_walls.push_back(std::move(piston));
  // Water at rest at H_r in the reservoir, down to the jet under the gate.
  auto& w = geo.initial_water;
  w.x_begin_m = r.piston_x_m;
  w.surface_x_m.insert(w.surface_x_m.begin(), {r.piston_x_m, -t});
  w.surface_z_m.insert(w.surface_z_m.begin(), {r.depth_m, r.depth_m});
  geo.max_water_height_m = std::max(geo.max_water_height_m, r.depth_m);
  return r;
}

}  // namespace hydrojump::cases
