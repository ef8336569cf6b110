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
  // Which side of the wall p is on: > 0 the fluid side, < 0 behind the wall, 0 on the wall line. A
  // point equally far from the two opposite faces of a plate (the middle column of an odd number of
  // layers) has opposite normals that cancel: it is inside the plate, never on the fluid side.
  double side(const Eigen::Vector2d& p) const {
    if (normal_sum.squaredNorm() < 1e-12) return -1.0;
    return (p - nearest).dot(normal_sum);
  }
};

struct Seed {
  ParticleType type;
  double x, z, rho, u;
  double ghost_dx, ghost_dz;
};

}  // namespace

std::vector<BedParticle> corrugated_bed_layers(const cases::BedProfile& bed, double dx, int layers, double x_from,
                                               double x_to) {
  std::vector<BedParticle> out;
  if (!bed.corrugated() || !(dx > 0.0) || layers <= 0 || !(x_to > x_from)) return out;
  const double xa = x_from, xb = x_to;
  // Dense samples of the bed: positions and normals.
  const double fine = dx / 40.0;
  const auto n_fine = static_cast<std::size_t>(std::ceil((xb - xa) / fine));
  std::vector<Eigen::Vector2d> b(n_fine + 1), n(n_fine + 1);
  for (std::size_t k = 0; k <= n_fine; ++k) {
    const double x = xa + (xb - xa) * static_cast<double>(k) / static_cast<double>(n_fine);
    b[k] = Eigen::Vector2d(x, bed.elevation(x));
    n[k] = bed.normal(x);
  }
  // Distance from p to the bed near x (samples within 2 layers' depth plus dx either side).
  const double reach = (layers + 1.0) * dx;
  auto bed_distance = [&](const Eigen::Vector2d& p) {
    double best = 1e300;
    const double lo = p.x() - reach, hi = p.x() + reach;
    const double last = static_cast<double>(n_fine);
    const auto k0 = static_cast<std::size_t>(std::max(0.0, std::floor((lo - xa) / (xb - xa) * last)));
    const auto k1 = static_cast<std::size_t>(std::min(last, std::ceil((hi - xa) / (xb - xa) * last)));
    for (std::size_t k = k0; k <= k1; ++k) best = std::min(best, (p - b[k]).norm());
    return best;
  };
  for (int layer = 0; layer < layers; ++layer) {
    // Offset curve r(x) = b(x) - d n(x), d = (layer + 1/2) dx, and its cumulative arc length.
    const double d = (layer + 0.5) * dx;
    std::vector<double> s(n_fine + 1, 0.0);
    for (std::size_t k = 1; k <= n_fine; ++k) s[k] = s[k - 1] + ((b[k] - d * n[k]) - (b[k - 1] - d * n[k - 1])).norm();
    const auto count = static_cast<std::size_t>(std::max(1.0, std::round(s.back() / dx)));
    const double spacing = s.back() / static_cast<double>(count);
    std::size_t k = 0;
    for (std::size_t j = 0; j < count; ++j) {
      // s_j = (j + 1/2) spacing, half a spacing from the crests, like the lattice columns.
      const double target = (static_cast<double>(j) + 0.5) * spacing;
      while (k + 1 < n_fine && s[k + 1] < target) ++k;
      const double f = (target - s[k]) / std::max(s[k + 1] - s[k], 1e-300);
      const Eigen::Vector2d q = b[k] + f * (b[k + 1] - b[k]);
      const Eigen::Vector2d normal = (n[k] + f * (n[k + 1] - n[k])).normalized();
      const Eigen::Vector2d p = q - d * normal;
      // Past a crest whose radius of curvature is below d the offset curve folds over itself (a
      // swallowtail): keep only points whose nearest bed point is their own, and none closer than
      // dx/2 to a particle already placed.
      if (bed_distance(p) < d - 0.25 * dx) continue;
      bool crowded = false;
      for (auto it = out.rbegin(); it != out.rend() && !crowded; ++it)
        if (std::abs(it->position.x() - p.x()) < dx && (it->position - p).norm() < 0.5 * dx) crowded = true;
      if (crowded) continue;
      out.push_back({p, q});
    }
  }
  return out;
}

namespace {

// The particle lattice: points (x0 + (i + 1/2) dx, z0 + (j + 1/2) dx). The corner is the domain box
// corner, moved (down and left, by less than dx) so that with an inflow the rows and columns line up
// with the inflow buffer's (rows at z_b(x_in) + (k + 1/2) dx, columns at x_in - (k + 1/2) dx) even
// when the corrugation troughs lie below the upstream floor.
struct Lattice {
  double x0 = 0.0, z0 = 0.0, dx = 0.0;
  double x(long i) const { return x0 + (static_cast<double>(i) + 0.5) * dx; }
  double z(long j) const { return z0 + (static_cast<double>(j) + 0.5) * dx; }
};

Lattice make_lattice(const cases::CaseGeometry& g, double dx) {
  Lattice l{g.x_min_m, g.z_min_m, dx};
  if (!g.inflows.empty()) {
    const double x_in = g.inflows.front().x_m, z_in = g.bed.elevation(x_in);
    l.x0 = x_in - std::ceil((x_in - g.x_min_m) / dx - 1e-9) * dx;
    l.z0 = z_in - std::ceil((z_in - g.z_min_m) / dx - 1e-9) * dx;
  }
  return l;
}

// The walls the particles are made for: the geometry's, plus (stilling basins) the bed continued flat
// under the inflow buffer (x < x_in) and past the outflow section (x > x_out) by the buffer length, so
// buffer particles and the fluid next to the sections have a wall below them. A tailgate
// (tailgate.hpp) closes the end of the bed instead of an outflow buffer: its plate is a wall from the
// bed's last point up to the crest and down again (no bed under it, whose "fluid above" side would
// leave the plate's lowest rows empty).
std::vector<cases::WallPolyline> particle_walls(const cases::CaseGeometry& g, const OpenBoundaries& open,
                                                double buffer_length) {
  std::vector<cases::WallPolyline> walls = g.walls;
  for (const auto& in : g.inflows) {
    if (open.inflows().empty()) break;  // a piston reservoir has its own floor
    const double zb = g.bed.elevation(in.x_m);
    walls.push_back({"inflow_bed", {cases::Vec2(in.x_m - buffer_length, zb), cases::Vec2(in.x_m, zb)}});
  }
  for (const auto& out : g.outflows) {
    if (!open.tailgates().empty()) break;
    const double zb = g.bed.elevation(out.x_m);
    walls.push_back({"outflow_bed", {cases::Vec2(out.x_m, zb), cases::Vec2(out.x_m + buffer_length, zb)}});
  }
  for (const auto& gate : open.tailgates()) walls.push_back(gate.plate());
  return walls;
}

using WallCandidates = std::map<std::pair<long, long>, Candidate>;

// Boundary candidates: lattice points within `reach` of some wall segment, with the nearest wall point
// and the normal(s) into the fluid there.
WallCandidates wall_candidates(const std::vector<cases::WallPolyline>& walls, const Lattice& l, double reach) {
  WallCandidates near_wall;
  const double dx = l.dx;
  for (const auto& wall : walls) {
    for (std::size_t k = 0; k + 1 < wall.points.size(); ++k) {
      const Eigen::Vector2d a = wall.points[k], b = wall.points[k + 1];
      const Eigen::Vector2d d = b - a;
      const double len2 = d.squaredNorm();
      if (len2 <= 0.0) continue;
      const Eigen::Vector2d normal = Eigen::Vector2d(-d.y(), d.x()) / std::sqrt(len2);  // into the fluid
      const long i0 = static_cast<long>(std::floor((std::min(a.x(), b.x()) - reach - l.x0) / dx)) - 1;
      const long i1 = static_cast<long>(std::ceil((std::max(a.x(), b.x()) + reach - l.x0) / dx)) + 1;
      const long j0 = static_cast<long>(std::floor((std::min(a.y(), b.y()) - reach - l.z0) / dx)) - 1;
      const long j1 = static_cast<long>(std::ceil((std::max(a.y(), b.y()) + reach - l.z0) / dx)) + 1;
      for (long i = i0; i <= i1; ++i)
        for (long j = j0; j <= j1; ++j) {
          const Eigen::Vector2d p(l.x(i), l.z(j));
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
  return near_wall;
}

// What the seeding steps share: the geometry, settings, open boundaries and lattice.
struct SeedContext {
  const cases::CaseGeometry& g;
  const SolverSettings& s;
  const OpenBoundaries& open;
  Lattice lattice;
  double buffer_length = 0.0;
  double gravity = 0.0;
  int n_layers = 0;

  bool in_period(double x) const { return !g.periodic_x || (x >= g.x_min_m && x < g.x_max_m); }
  // Inside an inflow buffer (above the extended bed, below the inflow depth) there is no wall: the
  // lower end of the sluice gate would otherwise put boundary particles among the buffer particles.
  bool in_inflow_buffer(double x, double z) const {
    for (std::size_t k = 0; k < g.inflows.size() && k < open.inflows().size(); ++k) {
      const auto& in = g.inflows[k];
      const double zb = g.bed.elevation(in.x_m);
      const double top = zb + std::max(in.depth_m, open.inflows()[k].rows() * lattice.dx);
      if (x < in.x_m && z > zb && z < top) return true;
    }
    return false;
  }
  // Outflow buffers start filled with tailwater: x_out < x < x_out + buffer length (a tailgate has none).
  const cases::OutflowBoundary* outflow_at(double x) const {
    if (open.outflows().empty()) return nullptr;
    for (const auto& out : g.outflows)
      if (x > out.x_m && x < out.x_m + buffer_length) return &out;
    return nullptr;
  }
  // A wall particle starts at the hydrostatic density of the water above it, else at rho0.
  double boundary_density(const Eigen::Vector2d& p) const {
    const auto& water = g.initial_water;
    double rho = s.eos.rho0;
    if (water.x_end_m > water.x_begin_m && p.x() >= water.x_begin_m - buffer_length &&
        p.x() <= water.x_end_m + buffer_length) {
      const double depth = water.surface_at(p.x()) - p.y();
      if (depth > 0.0) rho = s.eos.hydrostatic_density(gravity, depth);
    }
    return rho;
  }
};

// Fluid: the lattice points of the initial water (and the outflow buffers' tailwater) above the bed
// and off the walls, at hydrostatic density, moving with u = q / depth.
void add_fluid_seeds(const SeedContext& ctx, const WallCandidates& near_wall, std::vector<Seed>& seeds) {
  const auto& g = ctx.g;
  const auto& water = g.initial_water;
  const Lattice& l = ctx.lattice;
  const double dx = l.dx;
  if (!(water.x_end_m > water.x_begin_m)) return;
  const long i0 = static_cast<long>(std::floor((water.x_begin_m - l.x0) / dx)) - 1;
  const long i1 = static_cast<long>(std::ceil((water.x_end_m + ctx.buffer_length - l.x0) / dx)) + 1;
  for (long i = i0; i <= i1; ++i) {
    const double x = l.x(i);
    const cases::OutflowBoundary* outflow = ctx.outflow_at(x);
    if (x < water.x_begin_m || (x > water.x_end_m && outflow == nullptr) || !ctx.in_period(x)) continue;
    const ParticleType type = outflow != nullptr ? ParticleType::outflow : ParticleType::fluid;
    const double bed = outflow != nullptr ? g.bed.elevation(outflow->x_m) : g.bed.elevation(x);
    const double surface = outflow != nullptr ? bed + outflow->tailwater_depth_m : water.surface_at(x);
    const double depth = surface - bed;
    const double u = depth > 0.0 ? water.discharge_m2_s / depth : 0.0;
    const long j0 = static_cast<long>(std::floor((bed - l.z0) / dx)) - 1;
    const long j1 = static_cast<long>(std::ceil((surface - l.z0) / dx)) + 1;
    for (long j = j0; j <= j1; ++j) {
      const double z = l.z(j);
      if (z <= bed + 0.25 * dx || z >= surface) continue;
      auto it = near_wall.find({i, j});
      if (it != near_wall.end() && (it->second.distance < 0.25 * dx || it->second.side({x, z}) <= 0.0))
        continue;  // on or behind a wall
      seeds.push_back({type, x, z, ctx.s.eos.hydrostatic_density(ctx.gravity, surface - z), u, 0.0, 0.0});
    }
  }
}

// Walls: the lattice candidates behind the walls, with ghost nodes mirrored through the nearest wall
// point. A corrugated reach gets its own layers, spaced evenly along the bed (corrugated_bed_layers); the
// lattice gives the straight walls and floors. The layers span the reach widened to the lattice's
// column edges around it [layers_from, layers_to], and a lattice point whose nearest wall point lies
// in that span is left to them: the layers end half a spacing inside it and the lattice columns
// half a spacing outside, so the wall has no slit where the reach ends between two lattice columns
// (the reach itself left one up to 1.5 dx wide: 1.4 dx at the end of run C's reach, through which
// fluid seeped into the floor and out of the domain).
void add_boundary_seeds(const SeedContext& ctx, const WallCandidates& near_wall, std::vector<Seed>& seeds) {
  const auto& g = ctx.g;
  const Lattice& l = ctx.lattice;
  const double dx = l.dx;
  const bool corrugated = g.bed.corrugated();
  const double layers_from = l.x0 + std::floor((g.bed.reach_start_m() - l.x0) / dx + 1e-9) * dx;
  const double layers_to = l.x0 + std::ceil((g.bed.reach_end_m() - l.x0) / dx - 1e-9) * dx;
  const std::vector<BedParticle> bed_layers =
      corrugated ? corrugated_bed_layers(g.bed, dx, ctx.n_layers, layers_from, layers_to) : std::vector<BedParticle>{};
  auto left_to_bed_layers = [&](const Eigen::Vector2d& q) {
    return corrugated && q.x() > layers_from + 1e-9 * dx && q.x() < layers_to - 1e-9 * dx;
  };
  for (const auto& [ij, c] : near_wall) {
    const Eigen::Vector2d p(l.x(ij.first), l.z(ij.second));
    if (!ctx.in_period(p.x())) continue;
    if (c.side(p) >= 0.0 || c.distance < 0.25 * dx) continue;  // on the wall line or the fluid side
    if (ctx.in_inflow_buffer(p.x(), p.y())) continue;
    if (left_to_bed_layers(c.nearest)) continue;
    const Eigen::Vector2d ghost = 2.0 * (c.nearest - p);
    seeds.push_back({ParticleType::boundary, p.x(), p.y(), ctx.boundary_density(p), 0.0, ghost.x(), ghost.y()});
  }
  for (const BedParticle& b : bed_layers) {
    const Eigen::Vector2d ghost = 2.0 * (b.nearest - b.position);
    seeds.push_back({ParticleType::boundary, b.position.x(), b.position.y(), ctx.boundary_density(b.position), 0.0,
                     ghost.x(), ghost.y()});
  }
}

// Moving walls (a lifted dam-break gate): a plate n_layers dx thick behind the (vertical) face, on the
// lattice, ghost nodes mirrored through the face; hydrostatic with the water standing against the face
// (DBC walls start at the fluid's pressure).
void add_moving_wall_seeds(const SeedContext& ctx, std::vector<Seed>& seeds) {
  const auto& water = ctx.g.initial_water;
  const Lattice& l = ctx.lattice;
  const double dx = l.dx;
  for (const auto& moving : ctx.g.moving_walls) {
    const auto& pts = moving.face.points;
    if (pts.size() != 2 || std::abs(pts[0].x() - pts[1].x()) > 1e-12)
      throw std::invalid_argument("moving wall \"" + moving.face.name + "\": the SPH generator supports one vertical face");
    const double xf = pts[0].x(), z_lo = std::min(pts[0].y(), pts[1].y()), z_hi = std::max(pts[0].y(), pts[1].y());
    const double side = pts[1].y() > pts[0].y() ? 1.0 : -1.0;  // fluid at x < face when going up
    const long i0 = static_cast<long>(std::floor((xf - l.x0) / dx)) - ctx.n_layers - 1;
    const long i1 = static_cast<long>(std::ceil((xf - l.x0) / dx)) + ctx.n_layers + 1;
    for (long i = i0; i <= i1; ++i) {
      const double x = l.x(i);
      const double depth = side * (x - xf);  // behind the face
      if (!(depth > 0.0 && depth < ctx.n_layers * dx)) continue;
      for (long j = static_cast<long>(std::floor((z_lo - l.z0) / dx)); l.z(j) < z_hi; ++j) {
        const double z = l.z(j);
        if (z <= z_lo) continue;
        const double held = water.x_end_m > water.x_begin_m ? water.surface_at(xf) - z : 0.0;
        seeds.push_back({ParticleType::moving_wall, x, z, ctx.s.eos.hydrostatic_density(ctx.gravity, std::max(0.0, held)),
                         0.0, 2.0 * (xf - x), 0.0});
      }
    }
  }
}

// The particle set of the seeds, in their order. m = rho dx^2: every particle starts with the volume
// dx^2 of its lattice cell, so the lattice and the hydrostatic densities are consistent (with
// m = rho0 dx^2 the column would first have to contract by g H^2 / (2 c0^2), which starts an oscillation).
ParticleSet particle_set(const std::vector<Seed>& seeds, double dx) {
  ParticleSet ps;
  ps.resize(static_cast<Eigen::Index>(seeds.size()));
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const Seed& sd = seeds[k];
    const auto i = static_cast<Eigen::Index>(k);
    ps.assign(i, sd.type, sd.x, sd.z, sd.rho, sd.rho * dx * dx, static_cast<std::int64_t>(k));
    ps.u[i] = ps.u_old[i] = sd.u;
    ps.ghost_dx[i] = sd.ghost_dx;
    ps.ghost_dz[i] = sd.ghost_dz;
  }
  return ps;
}

}  // namespace

ParticleSet generate_particles(const cases::CaseGeometry& g, const SolverSettings& s, int layers) {
  const double dx = s.dx;
  if (g.periodic_x) {
    const double period = g.x_max_m - g.x_min_m;
    const double cells = period / dx;
    if (std::abs(cells - std::round(cells)) > 1e-6)
      throw std::invalid_argument("periodic length " + std::to_string(period) +
                                  " m is not a whole number of particle spacings dx = " + std::to_string(dx) + " m");
  }
  const OpenBoundaries open = OpenBoundaries::from_geometry(g, buffer_parameters(s));
  const SeedContext ctx{g, s, open, make_lattice(g, dx), open.empty() ? 0.0 : open.buffer_length(),
                        std::abs(s.body_force_z), boundary_layer_count(s.h, dx, layers)};
  const WallCandidates near_wall =
      wall_candidates(particle_walls(g, open, ctx.buffer_length), ctx.lattice, ctx.n_layers * dx);
  std::vector<Seed> seeds;
  add_fluid_seeds(ctx, near_wall, seeds);
  const std::size_t n_fluid = seeds.size();
  add_boundary_seeds(ctx, near_wall, seeds);
  add_moving_wall_seeds(ctx, seeds);
  if (n_fluid == 0) throw std::invalid_argument("the initial water region holds no fluid particle at dx = " + std::to_string(dx) + " m");
  ParticleSet ps = particle_set(seeds, dx);
  open.create(ps);  // the inflow buffers, ids after the others
  return ps;
}

}  // namespace hydrojump::sph
