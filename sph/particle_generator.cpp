#include "sph/particle_generator.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cases/geometry.hpp"
#include "sph/open_boundaries.hpp"

namespace hydrojump::sph {

namespace {

struct Candidate {
  double distance = 1e300;
  Eigen::Vector2d nearest = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal_sum = Eigen::Vector2d::Zero();  // normals of the segments at that distance
};

struct Seed {
  ParticleType type;
  double x, z, rho, u;
  double ghost_dx, ghost_dz;
};

}  // namespace

int boundary_layer_count(const SolverSettings& settings, int layers) {
  if (layers > 0) return layers;
  return static_cast<int>(std::ceil(settings.support() / settings.dx - 1e-9));
}

ParticleSet generate_particles(const cases::CaseGeometry& g, const SolverSettings& s, int layers) {
  const double dx = s.dx;
  const int n_layers = boundary_layer_count(s, layers);
  const double x0 = g.x_min_m, z0 = g.z_min_m;
  const double gravity = std::abs(s.body_force_z);
  auto lattice_x = [&](long i) { return x0 + (static_cast<double>(i) + 0.5) * dx; };
  auto lattice_z = [&](long j) { return z0 + (static_cast<double>(j) + 0.5) * dx; };
  const double period = g.x_max_m - g.x_min_m;
  if (g.periodic_x) {
    const double cells = period / dx;
    if (std::abs(cells - std::round(cells)) > 1e-6)
      throw std::invalid_argument("periodic length " + std::to_string(period) +
                                  " m is not a whole number of particle spacings dx = " + std::to_string(dx) + " m");
  }
  auto in_period = [&](double x) { return !g.periodic_x || (x >= g.x_min_m && x < g.x_max_m); };

  // Open boundaries (stilling basins): the bed continues flat under the inflow buffer (x < x_in) and
  // past the outflow section (x > x_out) by the buffer length, so buffer particles and the fluid next
  // to the sections have a wall below them.
  const OpenBoundaries open = OpenBoundaries::from_geometry(g, buffer_parameters(s));
  const double buffer_length = open.empty() ? 0.0 : open.buffer_length();
  std::vector<cases::WallPolyline> walls = g.walls;
  for (const auto& in : g.inflows) {
    const double zb = g.bed.elevation(in.x_m);
    walls.push_back({"inflow_bed", {cases::Vec2(in.x_m - buffer_length, zb), cases::Vec2(in.x_m, zb)}});
  }
  for (const auto& out : g.outflows) {
    const double zb = g.bed.elevation(out.x_m);
    walls.push_back({"outflow_bed", {cases::Vec2(out.x_m, zb), cases::Vec2(out.x_m + buffer_length, zb)}});
  }
  // Inside an inflow buffer (above the extended bed, below the inflow depth) there is no wall: the
  // lower end of the sluice gate would otherwise put boundary particles among the buffer particles.
  auto in_inflow_buffer = [&](double x, double z) {
    for (std::size_t k = 0; k < g.inflows.size(); ++k) {
      const auto& in = g.inflows[k];
      const double zb = g.bed.elevation(in.x_m);
      const double top = zb + std::max(in.depth_m, open.inflows()[k].rows() * dx);
      if (x < in.x_m && z > zb && z < top) return true;
    }
    return false;
  };
  // Outflow buffers start filled with tailwater: x_out < x < x_out + buffer length.
  auto outflow_at = [&](double x) -> const cases::OutflowBoundary* {
    for (const auto& out : g.outflows)
      if (x > out.x_m && x < out.x_m + buffer_length) return &out;
    return nullptr;
  };

  // Boundary candidates: lattice points within n_layers dx of some wall segment.
  std::map<std::pair<long, long>, Candidate> near_wall;
  const double reach = n_layers * dx;
  for (const auto& wall : walls) {
    for (std::size_t k = 0; k + 1 < wall.points.size(); ++k) {
      const Eigen::Vector2d a = wall.points[k], b = wall.points[k + 1];
      const Eigen::Vector2d d = b - a;
      const double len2 = d.squaredNorm();
      if (len2 <= 0.0) continue;
      const Eigen::Vector2d normal = Eigen::Vector2d(-d.y(), d.x()) / std::sqrt(len2);  // into the fluid
      const long i0 = static_cast<long>(std::floor((std::min(a.x(), b.x()) - reach - x0) / dx)) - 1;
      const long i1 = static_cast<long>(std::ceil((std::max(a.x(), b.x()) + reach - x0) / dx)) + 1;
      const long j0 = static_cast<long>(std::floor((std::min(a.y(), b.y()) - reach - z0) / dx)) - 1;
      const long j1 = static_cast<long>(std::ceil((std::max(a.y(), b.y()) + reach - z0) / dx)) + 1;
      for (long i = i0; i <= i1; ++i)
        for (long j = j0; j <= j1; ++j) {
          const Eigen::Vector2d p(lattice_x(i), lattice_z(j));
          const double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
          const Eigen::Vector2d q = a + t * d;
          const double dist = (p - q).norm();
          if (dist > reach + 1e-9 * dx) continue;
          Candidate& c = near_wall[{i, j}];
          if (dist < c.distance - 1e-9 * dx) {
            c.distance = dist;
            c.nearest = q;
            c.normal_sum = normal;
          } else if (dist <= c.distance + 1e-9 * dx) {
            c.normal_sum += normal;  // tie: a vertex shared by segments
          }
        }
    }
  }

  std::vector<Seed> seeds;
  // Fluid.
  const auto& water = g.initial_water;
  if (water.x_end_m > water.x_begin_m) {
    const long i0 = static_cast<long>(std::floor((water.x_begin_m - x0) / dx)) - 1;
    const long i1 = static_cast<long>(std::ceil((water.x_end_m + buffer_length - x0) / dx)) + 1;
    for (long i = i0; i <= i1; ++i) {
      const double x = lattice_x(i);
      const cases::OutflowBoundary* outflow = outflow_at(x);
      if (x < water.x_begin_m || (x > water.x_end_m && outflow == nullptr) || !in_period(x)) continue;
      const ParticleType type = outflow != nullptr ? ParticleType::outflow : ParticleType::fluid;
      const double bed = outflow != nullptr ? g.bed.elevation(outflow->x_m) : g.bed.elevation(x);
      const double surface = outflow != nullptr ? bed + outflow->tailwater_depth_m : water.surface_at(x);
      const double depth = surface - bed;
      const double u = depth > 0.0 ? water.discharge_m2_s / depth : 0.0;
      const long j0 = static_cast<long>(std::floor((bed - z0) / dx)) - 1;
      const long j1 = static_cast<long>(std::ceil((surface - z0) / dx)) + 1;
      for (long j = j0; j <= j1; ++j) {
        const double z = lattice_z(j);
        if (z <= bed + 0.25 * dx || z >= surface) continue;
        auto it = near_wall.find({i, j});
        if (it != near_wall.end() && (it->second.distance < 0.25 * dx ||
                                      (Eigen::Vector2d(x, z) - it->second.nearest).dot(it->second.normal_sum) <= 0.0))
          continue;  // on or behind a wall
        seeds.push_back({type, x, z, s.eos.hydrostatic_density(gravity, surface - z), u, 0.0, 0.0});
      }
    }
  }
  const std::size_t n_fluid = seeds.size();
  // Boundary.
  for (const auto& [ij, c] : near_wall) {
    const Eigen::Vector2d p(lattice_x(ij.first), lattice_z(ij.second));
    if (!in_period(p.x())) continue;
    if ((p - c.nearest).dot(c.normal_sum) >= 0.0 || c.distance < 0.25 * dx) continue;  // fluid side
    if (in_inflow_buffer(p.x(), p.y())) continue;
    double rho = s.eos.rho0;
    if (water.x_end_m > water.x_begin_m && p.x() >= water.x_begin_m - buffer_length &&
        p.x() <= water.x_end_m + buffer_length) {
      const double depth = water.surface_at(p.x()) - p.y();
      if (depth > 0.0) rho = s.eos.hydrostatic_density(gravity, depth);
    }
    const Eigen::Vector2d ghost = 2.0 * (c.nearest - p);
    seeds.push_back({ParticleType::boundary, p.x(), p.y(), rho, 0.0, ghost.x(), ghost.y()});
  }
  if (n_fluid == 0) throw std::invalid_argument("the initial water region holds no fluid particle at dx = " + std::to_string(dx) + " m");

  ParticleSet ps;
  ps.resize(static_cast<Eigen::Index>(seeds.size()));
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const Seed& sd = seeds[k];
    const auto i = static_cast<Eigen::Index>(k);
    // m = rho dx^2: every particle starts with the volume dx^2 of its lattice cell, so the lattice and
    // the hydrostatic densities are consistent (with m = rho0 dx^2 the column would first have to
    // contract by g H^2 / (2 c0^2), which starts an oscillation).
    ps.assign(i, sd.type, sd.x, sd.z, sd.rho, sd.rho * dx * dx, static_cast<std::int64_t>(k));
    ps.u[i] = ps.u_old[i] = sd.u;
    ps.ghost_dx[i] = sd.ghost_dx;
    ps.ghost_dz[i] = sd.ghost_dz;
  }
  open.create(ps);  // the inflow buffers, ids after the others
  return ps;
}

}  // namespace hydrojump::sph
