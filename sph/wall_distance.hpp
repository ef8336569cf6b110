// The distance from any point of the domain to the nearest fixed wall particle, tabulated once at the
// start of a run, for Prandtl's mixing length l = min(l_m, kappa d) beyond the kernel support
// (viscosity.hpp, mixing_length_near_wall).
//
//   d(p) = min over fixed wall particles b of |p - x_b|,   capped at `reach`,
//
// tabulated at the nodes of a grid of spacing `spacing` and interpolated bilinearly in between. d is
// 1-Lipschitz, so the interpolated value lies within spacing/sqrt(2) of the exact one. Moving walls
// (a lifted gate, a piston) are not in the table: the pair loop measures them within the kernel support.
//
// Usage:
//   | sph.sps_wall_distance | where d comes from (with sph.sps_mixing_length_m > 0)                  |
//   |-----------------------|------------------------------------------------------------------------|
//   | "kernel_support"      | the nearest wall particle within the kernel support 2h; farther        |
//   |                       | particles take the full l_m (default)                                   |
//   | "whole_domain"        | within the support as above; beyond it this table, so l = kappa d holds |
//   |                       | up to d = l_m / kappa as Prandtl's wall law has it                     |
// Example (spec): `[case.sph]  sps_mixing_length_m = 0.031   sps_wall_distance = "whole_domain"`
#pragma once

#include <vector>

#include "sph/particles.hpp"

namespace hydrojump::sph {

class WallDistanceTable {
 public:
  WallDistanceTable() = default;  // empty: no table (at() returns the reach, 0 here)

  // Tabulates the distance to the fixed wall particles (ParticleType::boundary) of `particles` over
  // their bounding box grown by `reach`. periodic_x: the walls repeat with the period
  // x_max - x_min (images at +-period). Throws std::invalid_argument for reach <= 0 or spacing <= 0.
  static WallDistanceTable tabulate(const ParticleSet& particles, double reach, double spacing, bool periodic_x = false,
                                    double x_min = 0.0, double x_max = 0.0);

  // d at (x, z), capped at the reach; points outside the table are at least the reach from any wall.
  double at(double x, double z) const;

  double reach() const { return reach_; }
  bool empty() const { return values_.empty(); }

 private:
  double reach_ = 0.0, spacing_ = 1.0, x0_ = 0.0, z0_ = 0.0;
  int nx_ = 0, nz_ = 0;
  bool periodic_x_ = false;
  double period_origin_ = 0.0, period_ = 0.0;
  std::vector<double> values_;  // nx_ * nz_, x fastest
};

}  // namespace hydrojump::sph
