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

// Computes the geometry of `c` with gravity from `fluid`. Pure function of its inputs.
CaseGeometry make_geometry(const Case& c, const FluidProperties& fluid);

// Default comparison sections of a stilling basin, derived from y1 and the tailwater depth y2:
//   "upstream"   x_toe - min(10 y1, upstream_length / 2)          (role "upstream", for E1)
//   "toe"        x_toe                                              (role "toe")
//   "x_2y2", "x_4y2", "x_6y2"  x_toe + k y2                         (role "interior")
//   "downstream" x_toe + 8 y2, kept 3 y2 clear of the outlet        (role "downstream", for E2, y2);
//                on a corrugated reach moved to the nearest crest, so y2 and E2 are read over a crest
std::vector<Section> default_stilling_basin_sections(const StillingBasinCase& basin);

}  // namespace hydrojump::cases
