// Synthetic SPH particle sets and VOF cell sets with known fields, for the comparator tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>

#include "compare/sampling.hpp"

namespace hydrojump::compare::testing {

using Field = std::function<double(double x, double z)>;

// Fluid particles on a square lattice of spacing dx filling [0, length] x [0, depth] (centres at
// (i + 1/2) dx), with `boundary_layers` layers of boundary particles below z = 0 (type 1), density
// rho0 everywhere, velocity (u(x, z), w(x, z)).
inline ParticleFrame lattice_particles(double length, double depth, double dx, int boundary_layers,
                                       const Field& u, const Field& w, double rho0 = 1000.0) {
  ParticleFrame f;
  const int nx = static_cast<int>(std::lround(length / dx));
  const int nz = static_cast<int>(std::lround(depth / dx));
  for (int k = -boundary_layers; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) * dx, z = (k + 0.5) * dx;
      f.x.push_back(x);
      f.z.push_back(z);
      f.type.push_back(k < 0 ? 1 : 0);
      f.u.push_back(k < 0 ? 0.0 : u(x, z));
      f.w.push_back(k < 0 ? 0.0 : w(x, z));
      f.density.push_back(rho0);
      f.pressure.push_back(rho0 * 9.81 * (depth - z));
    }
  }
  return f;
}

// A Cartesian mesh of nx x nz cells over [0, length] x [z0, z0 + height] with alpha = the fraction of
// each cell below `surface_z` and cell-centre velocities u(xc, zc), w(xc, zc).
inline CellFrame cartesian_cells(double length, double z0, double height, int nx, int nz,
                                 double surface_z, const Field& u, const Field& w) {
  CellFrame f;
  const double dx = length / nx, dz = height / nz;
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const double xl = i * dx, zl = z0 + k * dz;
      f.x_lo.push_back(xl); f.x_hi.push_back(xl + dx);
      f.z_lo.push_back(zl); f.z_hi.push_back(zl + dz);
      f.xc.push_back(xl + 0.5 * dx); f.zc.push_back(zl + 0.5 * dz);
      f.alpha.push_back(std::clamp((surface_z - zl) / dz, 0.0, 1.0));
      f.u.push_back(u(xl + 0.5 * dx, zl + 0.5 * dz));
      f.w.push_back(w(xl + 0.5 * dx, zl + 0.5 * dz));
      f.pressure.push_back(0.0);
    }
  }
  return f;
}

}  // namespace hydrojump::compare::testing
