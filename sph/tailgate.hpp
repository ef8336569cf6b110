// Tailgate: a sharp-crested weir closing the downstream end of a stilling basin, the control of a
// laboratory flume (Ead & Rajaratnam 2002 set their tailwater with a tailgate). The alternative to the
// outflow buffers of open_boundaries.hpp: sph.outflow_condition = "tailgate".
//
// A vertical plate of boundary particles stands on the bed at the outflow section x_g, with its
// upstream face at x_g, its crest at z_c = z_b(x_g) + P and its downstream face at x_g + t (t = the
// open-boundary buffer length, so the domain box is the same as with an outflow buffer). Water that
// passes over the crest is removed as soon as it is beyond the downstream face: the nappe falls
// freely, with atmospheric pressure under it, so the head over the crest controls the discharge and
// the level upstream settles where the weir passes the inflow:
//
//   q = 2/3 Cd sqrt(2 g) H^(3/2),   Cd = 0.611 + 0.08 H / P        (Rehbock; Henderson 1966, sec. 6.7)
//
// With sph.tailgate_height_m = 0 the crest height P is chosen so that P + H(q, P) equals the case's
// tailwater depth (cases::tailgate_height_for_depth). Rehbock's coefficient is calibrated for H/P up
// to about 1 (usable to 2.5); the low tailgates of jumps on corrugated beds have H/P of 3-7, where the
// formula is an extrapolation: the run reports the depth it gets (summary.json, y2), and a measured
// gate height can be given instead, as in the laboratory, where the gate is set by trial.
//
// Usage
//   | key (section [sph])      | meaning                                                        |
//   |--------------------------|----------------------------------------------------------------|
//   | outflow_condition        | "tailgate" (default "hydrostatic_level", or "absorbing")       |
//   | tailgate_height_m        | crest height above the bed at the outflow section, 0-100 m;     |
//   |                          | 0 (default): from the tailwater depth by Rehbock's formula      |
// Example (cases/*.toml):
//   [case.sph]
//   outflow_condition = "tailgate"
//   tailgate_height_m = 0.03
#pragma once

#include <cstdint>

#include "cases/geometry.hpp"
#include "sph/particles.hpp"

namespace hydrojump::sph {

class Tailgate {
 public:
  // The gate at `outflow`'s section on a bed at `bed_z`, crest `crest_height` above it, `thickness`
  // thick. Throws std::invalid_argument for a non-positive height or thickness.
  Tailgate(const cases::OutflowBoundary& outflow, double bed_z, double crest_height, double thickness);

  // The plate as a wall with the fluid on its left: up the upstream face, along the crest, down the
  // downstream face.
  cases::WallPolyline plate() const;
  // Removes the fluid particles beyond the downstream face (they went over the crest). Returns the
  // mass removed (kg/m).
  double advance(ParticleSet& particles);

  double section_x() const { return x_g_; }
  double crest_z() const { return bed_z_ + height_; }
  double crest_height() const { return height_; }
  double thickness() const { return thickness_; }
  double mass_removed() const { return mass_removed_; }
  std::int64_t particles_removed() const { return particles_removed_; }

 private:
  double x_g_, bed_z_, height_, thickness_;
  double mass_removed_ = 0.0;
  std::int64_t particles_removed_ = 0;
};

}  // namespace hydrojump::sph
