// The one geometry source of hydrojump: bed profile, domain outline, walls, initial water, inflow and
// outflow positions and comparison sections, computed once from a Case. The SPH particle generator, the
// OpenFOAM mesh writer and the comparator all take a CaseGeometry; none of them re-derives it.
//
// Coordinates: x along the channel (downstream positive), z vertical (up positive), 2D.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "cases/bed_profile.hpp"
#include "cases/spec.hpp"

namespace hydrojump::cases {

using Vec2 = Eigen::Vector2d;

// A solid wall as a polyline. The fluid lies on the LEFT of the direction of travel, so the unit
// normal pointing into the fluid of segment (p_i, p_{i+1}) is  n = (-(dz), dx) / |d|.
struct WallPolyline {
  std::string name;                     // "bed", "left_wall", "right_wall", "top_wall", ...
  std::vector<Vec2> points;
};

// A supercritical inflow through a vertical boundary at x = x_m over  z_bed(x) < z < z_bed + depth_m.
struct InflowBoundary {
  double x_m = 0.0;
  double depth_m = 0.0;
  double velocity_m_s = 0.0;
};

// An outflow boundary at x = x_m that holds the tailwater depth (above the local bed).
struct OutflowBoundary {
  double x_m = 0.0;
  double tailwater_depth_m = 0.0;
};

// Initial water: everything between the bed (or tank floor) and `surface_z_m(x)`, for x in
// [x_begin_m, x_end_m]. The surface is piecewise linear through (surface_x_m[i], surface_z_m[i]).
// The initial velocity is horizontal, u = discharge / local depth (0 where discharge is 0).
struct InitialWater {
  double x_begin_m = 0.0;
  double x_end_m = 0.0;
  std::vector<double> surface_x_m;
  std::vector<double> surface_z_m;
  double discharge_m2_s = 0.0;

  double surface_at(double x) const;   // linear interpolation, clamped at the ends
};

// A wall that translates at a constant velocity during [start_s, end_s) and rests otherwise: a
// dam-break gate lifted at a finite speed. `face` is its wetted face (fluid on the left, as for
// WallPolyline); the solvers give it their own thickness behind the face.
struct MovingWall {
  WallPolyline face;
  Vec2 velocity_m_s = Vec2::Zero();
  double start_s = 0.0;
  double end_s = 0.0;
  // A piston that holds a reservoir's level (sph/wall_motion.hpp): 0 = none, the velocity above only.
  double held_level_m = 0.0;          // H_r, above the reservoir bed at z = 0
  double reservoir_end_x_m = 0.0;     // the reservoir's downstream end (the gate's upstream face)
};

struct CaseGeometry {
  std::string kind;                     // the Case's kind
  // Axis-aligned box that contains all fluid that may ever exist (walls lie on its boundary or
  // outside it by the boundary-particle layers): [x_min, x_max] x [z_min, z_max].
  double x_min_m = 0.0, x_max_m = 0.0, z_min_m = 0.0, z_max_m = 0.0;
  bool periodic_x = false;              // poiseuille
  BedProfile bed;                       // floor / bed elevation z_b(x)
  std::vector<WallPolyline> walls;      // every solid wall, bed included
  InitialWater initial_water;
  std::vector<InflowBoundary> inflows;  // stilling basins: one at x = 0
  std::vector<OutflowBoundary> outflows;
  Vec2 body_force_m_s2 = Vec2(0.0, -9.81);  // gravity (plus the driving force for poiseuille)
  double max_water_height_m = 0.0;      // H_max used for the speed of sound
  double max_flow_speed_m_s = 0.0;      // expected largest flow speed (U1 for stilling basins,
                                        // sqrt(2 g H) for a dam break, centre-line u for poiseuille)
  std::vector<Section> sections;        // the case's sections (given or derived)
  double expected_toe_x_m = 0.0;        // stilling basins: start of the basin
  double dam_gate_x_m = 0.0;            // dam break: the gate position (= column width)
  std::vector<MovingWall> moving_walls; // dam break with gate.type = "lifted": the gate
};

// What the inflows bring: q = sum y1 U1 over geometry.inflows (m^2/s; 0 for closed cases).
double inflow_discharge(const CaseGeometry& geometry);

// The particle rows of an SPH inflow buffer of depth y1 at spacing dx: N = round(y1/dx), at least 1.
// The buffer is N dx deep and carries q, so its jet enters at Fr1 (y1/(N dx))^(3/2) (the spec check
// keeps N dx within 2 % of y1).
int inflow_buffer_rows(double depth_m, double dx);

// Computes the geometry of `c` with gravity from `fluid`. Pure function of its inputs.
CaseGeometry make_geometry(const Case& c, const FluidProperties& fluid);

// The inflow of the corrugated-bed SPH study (Bo et al. 2019, shared/reference/study-notes.md) instead
// of an inflow buffer at x = 0: a reservoir upstream of a sluice gate, pushed by a piston (push plate)
// at the speed that carries the discharge, U_p = q / H_r, so that in a steady state the gate passes q.
//
//   sluice gate: a plate of thickness t over [-t, 0], lower edge at the opening a = y1 / Cc
//                (Cc = 0.611, the contraction coefficient of a sharp-edged vertical sluice gate,
//                Henderson 1966, sec. 7.4: the jet contracts to y1 just downstream)
//   reservoir:   floor z = 0 over [x_p, 0], water at rest at H_r, the subcritical root of
//                H_r + q^2 / (2 g H_r^2) = E1 = y1 + U1^2 / (2 g)     (no loss at the gate)
//   piston:      a moving wall with its face at x_p = -t - L_r, 1.5 H_r high, moving at U_p until
//                the run's end time; L_r = U_p T_end + 2 H_r unless given, so it stops 2 H_r short
//                of the gate
// The domain box grows to x_min = x_p, z_max >= 1.5 H_r; the inflow (x = 0, y1, U1) stays in
// `inflows` as the section whose discharge is the target; the SPH solver makes no inflow buffer.
constexpr double sluice_contraction_coefficient = 0.611;

struct PistonReservoir {
  double opening_m = 0.0;         // a
  double depth_m = 0.0;           // H_r
  double length_m = 0.0;          // L_r
  double piston_speed_m_s = 0.0;  // U_p
  double piston_x_m = 0.0;        // x_p at t = 0
};

// Adds the reservoir, the sluice plate and the piston to `geometry` (a stilling basin's, from
// make_geometry). `opening_m` or `length_m` <= 0: the defaults above. Throws std::invalid_argument
// when the opening is not below the reservoir level or the reservoir is shorter than U_p T + 2 H_r.
PistonReservoir add_piston_reservoir(CaseGeometry& geometry, const StillingBasinCase& basin, double opening_m,
                                     double length_m, double end_time_s, double gate_thickness_m, double g);

// Default comparison sections of a stilling basin, derived from y1 and the tailwater depth y2:
//   "upstream"   x_toe - min(10 y1, upstream_length / 2)          (role "upstream", for E1)
//   "toe"        x_toe                                              (role "toe")
//   "x_2y2", "x_4y2", "x_6y2"  x_toe + k y2                         (role "interior")
//   "downstream" x_toe + 8 y2, kept 3 y2 clear of the outlet        (role "downstream", for E2, y2);
//                on a corrugated reach moved to the nearest crest, so y2 and E2 are read over a crest
std::vector<Section> default_stilling_basin_sections(const StillingBasinCase& basin);

}  // namespace hydrojump::cases
