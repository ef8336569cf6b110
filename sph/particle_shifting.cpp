#include "sph/particle_shifting.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sph/kernel.hpp"
#include "sph/parallel.hpp"
#include "sph/settings.hpp"
#include "sph/time_integration.hpp"

namespace hydrojump::sph {

namespace {

constexpr std::uint8_t kFluid = static_cast<std::uint8_t>(ParticleType::fluid);

// The neighbour sum both passes share: for every fluid particle i (in the order of `cells`),
//   Sum acc{};  add_pair(acc, i, j, dx, dz, r2, V_j F(r_ij))  for each neighbour j within the support,
//   store(i, acc),
// with (dx, dz) = r_i - r_j (periodic image included) and grad_i W_ij = F(r_ij) (dx, dz).
template <class Sum, class K, class AddPair, class Store>
void sum_over_neighbours(const ParticleSet& ps, const CellList& cells, const SolverSettings& s, const K& kernel,
                         AddPair add_pair, Store store) {
  const double support2 = s.support() * s.support();
  const double* x = ps.x.data();
  const double* z = ps.z.data();
  const double* m = ps.mass.data();
  const double* rho = ps.rho.data();
  const std::uint8_t* type = ps.type.data();
  const int n_cells = cells.cell_count();
#pragma omp parallel for schedule(dynamic, 16) if (use_threads(ps.size()))
  for (int c = 0; c < n_cells; ++c) {
    const int first = cells.cell_start(c), last = cells.cell_start(c + 1);
    if (first == last) continue;
    NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(c, ranges);
    for (int i = first; i < last; ++i) {
      if (type[i] != kFluid) continue;
      Sum acc{};
      for (int k = 0; k < n_ranges; ++k) {
        const NeighbourRange rg = ranges[k];
        for (int j = rg.begin; j < rg.end; ++j) {
          if (j == i) continue;
          const double dx = x[i] - (x[j] + rg.shift_x), dz = z[i] - z[j];
          const double r2 = dx * dx + dz * dz;
          if (r2 >= support2) continue;
          add_pair(acc, i, j, dx, dz, r2, m[j] / rho[j] * kernel.gradient_factor(std::sqrt(r2)));
        }
      }
      store(i, acc);
    }
  }
}

// Per-particle sums of the first pass.
struct GradientSums {
  double gx = 0.0, gz = 0.0, div = 0.0;                                    // grad C, div r
  double uxx = 0.0, uzz = 0.0, wxx = 0.0, wzz = 0.0, rx = 0.0, rz = 0.0;  // taylor: grad u, w, rho
};

// grad C_i = sum_j V_j grad_i W_ij,  div r_i = -sum_j V_j (r_i - r_j) . grad_i W_ij,
// gathered by particle i over all its neighbours; with `taylor`, also
// grad phi_i = sum_j V_j (phi_j - phi_i) grad_i W_ij for phi = u, w, rho over the fluid and buffer
// neighbours (not the walls).
template <class K, bool taylor>
void gradients_with(const ParticleSet& ps, const CellList& cells, const SolverSettings& s, const K& kernel,
                    ConcentrationGradients& out) {
  const auto size = static_cast<std::size_t>(ps.size());
  out.grad_x.assign(size, 0.0);
  out.grad_z.assign(size, 0.0);
  out.div_r.assign(size, 0.0);
  for (auto* v : {&out.du_dx, &out.du_dz, &out.dw_dx, &out.dw_dz, &out.drho_dx, &out.drho_dz}) {
    if (taylor) v->assign(size, 0.0);
    else v->clear();
  }
  const double* rho = ps.rho.data();
  const double* u = ps.u.data();
  const double* w = ps.w.data();
  const std::uint8_t* type = ps.type.data();
  const auto add_pair = [=](GradientSums& a, int i, int j, double dx, double dz, double r2, double vf) {
    a.gx += vf * dx;
    a.gz += vf * dz;
    a.div -= vf * r2;
    if (taylor && !is_wall_type(type[j])) {
      const double du = u[j] - u[i], dw = w[j] - w[i], drho = rho[j] - rho[i];
      a.uxx += vf * du * dx;
      a.uzz += vf * du * dz;
      a.wxx += vf * dw * dx;
      a.wzz += vf * dw * dz;
      a.rx += vf * drho * dx;
      a.rz += vf * drho * dz;
    }
  };
  const auto store = [&out](int i, const GradientSums& a) {
    const auto k = static_cast<std::size_t>(i);
    out.grad_x[k] = a.gx;
    out.grad_z[k] = a.gz;
    out.div_r[k] = a.div;
    if (taylor) {
      out.du_dx[k] = a.uxx;
      out.du_dz[k] = a.uzz;
      out.dw_dx[k] = a.wxx;
      out.dw_dz[k] = a.wzz;
      out.drho_dx[k] = a.rx;
      out.drho_dz[k] = a.rz;
    }
  };
  sum_over_neighbours<GradientSums>(ps, cells, s, kernel, add_pair, store);
}

// div(delta r)_i = sum_j V_j (delta r_j - delta r_i) . grad_i W_ij over all neighbours (walls and buffer
// particles do not shift: delta r_j = 0), for the fluid particles.
template <class K>
void shift_divergence_with(const ParticleSet& ps, const CellList& cells, const SolverSettings& s, const K& kernel,
                           ConcentrationGradients& g) {
  g.shift_div.assign(static_cast<std::size_t>(ps.size()), 0.0);
  const double* sx = g.shift_x.data();
  const double* sz = g.shift_z.data();
  double* div = g.shift_div.data();
  const auto add_pair = [=](double& sum, int i, int j, double dx, double dz, double, double vf) {
    sum += vf * ((sx[j] - sx[i]) * dx + (sz[j] - sz[i]) * dz);
  };
  sum_over_neighbours<double>(ps, cells, s, kernel, add_pair, [=](int i, double sum) { div[i] = sum; });
}

}  // namespace

void concentration_gradients(const ParticleSet& ps, const CellList& cells, const SolverSettings& s,
                             ConcentrationGradients& out) {
  const bool taylor = s.shifting.correction != ShiftingCorrection::none;
  if (s.kernel == KernelType::wendland_c2) {
    if (taylor) gradients_with<WendlandC2, true>(ps, cells, s, WendlandC2(s.h), out);
    else gradients_with<WendlandC2, false>(ps, cells, s, WendlandC2(s.h), out);
  } else {
    if (taylor) gradients_with<CubicSpline, true>(ps, cells, s, CubicSpline(s.h), out);
    else gradients_with<CubicSpline, false>(ps, cells, s, CubicSpline(s.h), out);
  }
}

// delta r_i = -A h |v_i| dt f_i grad C_i,  f_i = (div r_i - TFS) / (2 - TFS)  where div r_i >= TFS
// (not at the free surface), |delta r_i| capped at 0.1 dx;  "taylor" and
// "taylor_volume": phi_i += delta r_i . grad phi_i;  "taylor_volume": also rho_i -= rho_i div(delta r)_i.
ShiftSummary shift_particles(ParticleSet& ps, ConcentrationGradients& g, const SolverSettings& s, double dt,
                             const CellList* cells) {
  const Eigen::Index n = ps.size();
  if (static_cast<Eigen::Index>(g.grad_x.size()) != n)
    throw std::logic_error("shift_particles: the concentration gradients are of another particle set");
  const bool volume = s.shifting.correction == ShiftingCorrection::taylor_volume;
  const bool taylor = s.shifting.correction == ShiftingCorrection::taylor || volume;
  if (taylor && static_cast<Eigen::Index>(g.du_dx.size()) != n)
    throw std::logic_error("shift_particles: correction \"taylor\" needs the velocity and density gradients");
  if (volume && cells == nullptr)
    throw std::logic_error("shift_particles: correction \"taylor_volume\" needs the cell list");
  const double a_h_dt = s.shifting.coefficient * s.h * dt;
  const double tfs = s.shifting.surface_threshold;
  const double ramp_width = 2.0 - tfs;  // > 0: SolverSettings::validate keeps TFS <= 1.9
  const double max_shift = 0.1 * s.dx;
  Eigen::Index shifted = 0, at_surface = 0, capped = 0;
  double max_d2 = 0.0;
  // Particle i's shift (0 for the others). The caller counts it in the summary (the counters are
  // OpenMP reduction variables, private to each thread inside the loop, so not captured here).
  enum class Shift { not_fluid, surface, moved, moved_capped };
  const auto shift_of = [&](Eigen::Index i, double& sx, double& sz) {
    sx = sz = 0.0;
    if (!ps.is_fluid(i)) return Shift::not_fluid;
    const auto k = static_cast<std::size_t>(i);
    if (g.div_r[k] < tfs) return Shift::surface;
    const double d = a_h_dt * std::hypot(ps.u[i], ps.w[i]) * (g.div_r[k] - tfs) / ramp_width;
    sx = -d * g.grad_x[k];
    sz = -d * g.grad_z[k];
    const double length = std::hypot(sx, sz);
    if (length <= max_shift) return Shift::moved;
    sx *= max_shift / length;
    sz *= max_shift / length;
    return Shift::moved_capped;
  };
  // Moves particle i by (sx, sz) and corrects what it carries.
  const auto apply = [&](Eigen::Index i, double sx, double sz) {
    const auto k = static_cast<std::size_t>(i);
    ps.x[i] += sx;
    ps.z[i] += sz;
    if (taylor) {
      ps.u[i] += sx * g.du_dx[k] + sz * g.du_dz[k];
      ps.w[i] += sx * g.dw_dx[k] + sz * g.dw_dz[k];
      ps.rho[i] += sx * g.drho_dx[k] + sz * g.drho_dz[k];
    }
    if (volume) ps.rho[i] -= ps.rho[i] * g.shift_div[k];
  };
  // Without "taylor_volume" each particle moves as soon as its shift is known (one pass); with it,
  // div(delta r) needs every neighbour's shift first, so the shifts are kept and applied after it.
  if (volume) {
    g.shift_x.resize(static_cast<std::size_t>(n));
    g.shift_z.resize(static_cast<std::size_t>(n));
  }
#pragma omp parallel for schedule(static) reduction(+ : shifted, at_surface, capped) reduction(max : max_d2) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    double sx, sz;
    const Shift what = shift_of(i, sx, sz);
    at_surface += what == Shift::surface;
    shifted += what == Shift::moved || what == Shift::moved_capped;
    capped += what == Shift::moved_capped;
    max_d2 = std::max(max_d2, sx * sx + sz * sz);
    if (volume) {
      const auto k = static_cast<std::size_t>(i);
      g.shift_x[k] = sx;
      g.shift_z[k] = sz;
    } else if (ps.is_fluid(i)) {
      apply(i, sx, sz);
    }
  }
  if (volume) {
    if (s.kernel == KernelType::wendland_c2) shift_divergence_with(ps, *cells, s, WendlandC2(s.h), g);
    else shift_divergence_with(ps, *cells, s, CubicSpline(s.h), g);
#pragma omp parallel for schedule(static) if (use_threads(n))
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (ps.is_fluid(i)) apply(i, g.shift_x[k], g.shift_z[k]);
    }
  }
  wrap_periodic(ps, s);
  return ShiftSummary{shifted, at_surface, capped, std::sqrt(max_d2)};
}

}  // namespace hydrojump::sph
