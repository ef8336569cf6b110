// Initial particles of a case from its CaseGeometry (the one geometry source, cases/geometry.hpp).
//
// Fluid: a square lattice of spacing dx, offset dx/2 from the domain box corner (x_min, z_min), filling
// the initial water region  bed(x) < z < surface(x),  x_begin <= x <= x_end, at rest or with the
// initial horizontal velocity q / depth, with hydrostatic density  rho = rho0 (1 + rho0 g d / B)^(1/7).
// Boundary: the same lattice (except under a corrugated reach: corrugated_bed_layers below), every
// point on the solid side of a wall (the right of the polyline's
// direction of travel) closer to it than `layers` dx, so the walls lie halfway between the outer
// fluid row and the first boundary row. Each boundary particle gets its mDBC ghost offset 2 (q - r),
// q the nearest wall point (corners mirror through the corner point).
// Particle mass is the initial density times dx^2 (per metre of width), so each particle starts with
// the volume of its lattice cell.
// Open boundaries (stilling basins, sph/open_boundaries.hpp): the bed continues flat by the buffer
// length under the inflow buffer (x < x_in) and past the outflow section (x > x_out); the inflow
// buffer's particles are appended last (ids after the others, no wall particles among them); the
// outflow buffer starts filled with tailwater (type outflow, hydrostatic, u = q / y_t).
//
// Usage: `ParticleSet ps = generate_particles(geometry, settings, case_.sph.boundary_layers);`
//   | argument | meaning                                                           |
//   |----------|-------------------------------------------------------------------|
//   | layers   | boundary layers; 0 = enough for the kernel support, ceil(2h/dx)   |
#pragma once

#include "sph/particles.hpp"
#include "sph/settings.hpp"

#include <vector>

#include <Eigen/Core>

#include "cases/bed_profile.hpp"

namespace hydrojump::cases {
struct CaseGeometry;
}

namespace hydrojump::sph {

// Boundary particles under a corrugated reach, in `layers` layers at depths (k + 1/2) dx below the
// bed along its normal, spaced evenly (about dx) along the arc length of each layer's offset curve,
// starting half a spacing from the reach's first crest. Where a crest is sharper than a layer's depth
// the offset curve folds; points closer to another part of the bed than their own depth (by dx/4) and
// points within dx/2 of one already placed are dropped. `nearest` is the bed point each was offset
// from (its mDBC ghost node lies at 2 nearest - position).
// The layers cover [x_from, x_to]: the reach, which the generator widens to the floor lattice's
// column edges around it, so that the layers end where the lattice begins (no slit in the wall
// wherever the reach ends fall between lattice columns).
struct BedParticle {
  Eigen::Vector2d position;
  Eigen::Vector2d nearest;
};
std::vector<BedParticle> corrugated_bed_layers(const cases::BedProfile& bed, double dx, int layers, double x_from,
                                               double x_to);

ParticleSet generate_particles(const cases::CaseGeometry& geometry, const SolverSettings& settings, int layers = 0);

}  // namespace hydrojump::sph
