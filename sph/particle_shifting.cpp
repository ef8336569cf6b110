#include "sph/particle_shifting.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sph/kernel.hpp"
#include "sph/parallel.hpp"
#include "sph/settings.hpp"
#include "sph/time_integration.hpp"

namespace hydrojump::sph {

ParticleShifting parse_particle_shifting(const std::string& name) {
  if (name == "none") return ParticleShifting::none;
  if (name == "fickian") return ParticleShifting::fickian;
  throw std::invalid_argument("sph.particle_shifting = \"" + name + "\" is not allowed: use \"none\" or \"fickian\"");
}

ShiftingCorrection parse_shifting_correction(const std::string& name) {
  if (name == "none") return ShiftingCorrection::none;
  if (name == "taylor") return ShiftingCorrection::taylor;
  if (name == "taylor_volume") return ShiftingCorrection::taylor_volume;
  throw std::invalid_argument("sph.particle_shifting_correction = \"" + name +
                              "\" is not allowed: use \"none\", \"taylor\" or \"taylor_volume\"");
}

namespace {

constexpr std::uint8_t kFluid = static_cast<std::uint8_t>(ParticleType::fluid);

// grad C_i = sum_j V_j grad_i W_ij,  div r_i = -sum_j V_j (r_i - r_j) . grad_i W_ij,
// with grad_i W_ij = F(r_ij) (r_i - r_j), gathered by particle i over all its neighbours; with
// `taylor`, also grad phi_i = sum_j V_j (phi_j - phi_i) grad_i W_ij for phi = u, w, rho over the
// fluid and buffer neighbours (not the walls).
template <class K, bool taylor>
void gradients_with(const ParticleSet& ps, const CellList& cells, const SolverSettings& s, const K& kernel,
                    ConcentrationGradients& out) {
  const Eigen::Index n = ps.size();
  const auto size = static_cast<std::size_t>(n);
  out.grad_x.assign(size, 0.0);
  out.grad_z.assign(size, 0.0);
  out.div_r.assign(size, 0.0);
  for (auto* v : {&out.du_dx, &out.du_dz, &out.dw_dx, &out.dw_dz, &out.drho_dx, &out.drho_dz}) {
    if (taylor) v->assign(size, 0.0);
    else v->clear();
  }
  const double support2 = s.support() * s.support();
  const double* x = ps.x.data();
  const double* z = ps.z.data();
  const double* m = ps.mass.data();
  const double* rho = ps.rho.data();
  const double* u = ps.u.data();
  const double* w = ps.w.data();
  const std::uint8_t* type = ps.type.data();
  double* gx_out = out.grad_x.data();
  double* gz_out = out.grad_z.data();
  double* div_out = out.div_r.data();
  const int n_cells = cells.cell_count();
#pragma omp parallel for schedule(dynamic, 16) if (use_threads(n))
  for (int c = 0; c < n_cells; ++c) {
    const int first = cells.cell_start(c), last = cells.cell_start(c + 1);
    if (first == last) continue;
    NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(c, ranges);
    for (int i = first; i < last; ++i) {
      if (type[i] != kFluid) continue;
      double gx = 0.0, gz = 0.0, div = 0.0;
      double uxx = 0.0, uzz = 0.0, wxx = 0.0, wzz = 0.0, rx = 0.0, rz = 0.0;  // taylor: grad u, w, rho
      for (int k = 0; k < n_ranges; ++k) {
        const NeighbourRange rg = ranges[k];
        for (int j = rg.begin; j < rg.end; ++j) {
          if (j == i) continue;
          const double dx = x[i] - (x[j] + rg.shift_x), dz = z[i] - z[j];
          const double r2 = dx * dx + dz * dz;
          if (r2 >= support2) continue;
          const double vf = m[j] / rho[j] * kernel.gradient_factor(std::sqrt(r2));
          gx += vf * dx;
          gz += vf * dz;
          div -= vf * r2;
          if (taylor && !is_wall_type(type[j])) {
            const double du = u[j] - u[i], dw = w[j] - w[i], drho = rho[j] - rho[i];
            uxx += vf * du * dx;
            uzz += vf * du * dz;
            wxx += vf * dw * dx;
            wzz += vf * dw * dz;
            rx += vf * drho * dx;
            rz += vf * drho * dz;
          }
        }
      }
      gx_out[i] = gx;
      gz_out[i] = gz;
      div_out[i] = div;
      if (taylor) {
        const auto k = static_cast<std::size_t>(i);
        out.du_dx[k] = uxx;
        out.du_dz[k] = uzz;
        out.dw_dx[k] = wxx;
        out.dw_dz[k] = wzz;
        out.drho_dx[k] = rx;
        out.drho_dz[k] = rz;
      }
    }
  }
}

}  // namespace

void concentration_gradients(const ParticleSet& ps, const CellList& cells, const SolverSettings& s,
                             ConcentrationGradients& out) {
  const bool taylor = s.shifting_correction != ShiftingCorrection::none;
  if (s.kernel == KernelType::wendland_c2) {
    if (taylor) gradients_with<WendlandC2, true>(ps, cells, s, WendlandC2(s.h), out);
    else gradients_with<WendlandC2, false>(ps, cells, s, WendlandC2(s.h), out);
  } else {
    if (taylor) gradients_with<CubicSpline, true>(ps, cells, s, CubicSpline(s.h), out);
    else gradients_with<CubicSpline, false>(ps, cells, s, CubicSpline(s.h), out);
  }
}

namespace {

// div(delta r)_i = sum_j V_j (delta r_j - delta r_i) . grad_i W_ij over all neighbours (walls and buffer
// particles do not shift: delta r_j = 0), for the fluid particles.
template <class K>
void shift_divergence_with(const ParticleSet& ps, const CellList& cells, const SolverSettings& s, const K& kernel,
                           const std::vector<double>& sx, const std::vector<double>& sz, std::vector<double>& div) {
  const Eigen::Index n = ps.size();
  div.assign(static_cast<std::size_t>(n), 0.0);
  const double support2 = s.support() * s.support();
  const int n_cells = cells.cell_count();
#pragma omp parallel for schedule(dynamic, 16) if (use_threads(n))
  for (int c = 0; c < n_cells; ++c) {
    const int first = cells.cell_start(c), last = cells.cell_start(c + 1);
    if (first == last) continue;
    NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(c, ranges);
    for (int i = first; i < last; ++i) {
      if (ps.type[i] != kFluid) continue;
      const auto ki = static_cast<std::size_t>(i);
      double sum = 0.0;
      for (int r = 0; r < n_ranges; ++r) {
        const NeighbourRange rg = ranges[r];
        for (int j = rg.begin; j < rg.end; ++j) {
          if (j == i) continue;
          const double dx = ps.x[i] - (ps.x[j] + rg.shift_x), dz = ps.z[i] - ps.z[j];
          const double r2 = dx * dx + dz * dz;
          if (r2 >= support2) continue;
          const auto kj = static_cast<std::size_t>(j);
          const double vf = ps.mass[j] / ps.rho[j] * kernel.gradient_factor(std::sqrt(r2));
          sum += vf * ((sx[kj] - sx[ki]) * dx + (sz[kj] - sz[ki]) * dz);
        }
      }
      div[ki] = sum;
    }
  }
}

}  // namespace

// delta r_i = -A h |v_i| dt f_i grad C_i,  f_i = (div r_i - TFS) / (2 - TFS)  where div r_i >= TFS
// (not at the free surface), |delta r_i| capped at 0.1 dx;  "taylor" and
// "taylor_volume": phi_i += delta r_i . grad phi_i;  "taylor_volume": also rho_i -= rho_i div(delta r)_i.
ShiftSummary shift_particles(ParticleSet& ps, const ConcentrationGradients& g, const SolverSettings& s, double dt,
                             const CellList* cells) {
  const Eigen::Index n = ps.size();
  if (static_cast<Eigen::Index>(g.grad_x.size()) != n)
    throw std::logic_error("shift_particles: the concentration gradients are of another particle set");
  const bool volume = s.shifting_correction == ShiftingCorrection::taylor_volume;
  const bool taylor = s.shifting_correction == ShiftingCorrection::taylor || volume;
  if (taylor && static_cast<Eigen::Index>(g.du_dx.size()) != n)
    throw std::logic_error("shift_particles: correction \"taylor\" needs the velocity and density gradients");
  if (volume && cells == nullptr)
    throw std::logic_error("shift_particles: correction \"taylor_volume\" needs the cell list");
  const double a_h_dt = s.shifting_coefficient * s.h * dt;
  const double tfs = s.shifting_surface_threshold;
  const double ramp_width = 2.0 - tfs;  // > 0: SolverSettings::validate keeps TFS <= 1.9
  const double max_shift = 0.1 * s.dx;
  std::vector<double> shift_x(static_cast<std::size_t>(n), 0.0), shift_z(static_cast<std::size_t>(n), 0.0);
  Eigen::Index shifted = 0, at_surface = 0, capped = 0;
  double max_d2 = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : shifted, at_surface, capped) reduction(max : max_d2) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!ps.is_fluid(i)) continue;
    const auto k = static_cast<std::size_t>(i);
    if (g.div_r[k] < tfs) {
      ++at_surface;
      continue;
    }
    const double d = a_h_dt * std::hypot(ps.u[i], ps.w[i]) * (g.div_r[k] - tfs) / ramp_width;
    double sx = -d * g.grad_x[k], sz = -d * g.grad_z[k];
    const double length = std::hypot(sx, sz);
    if (length > max_shift) {
      sx *= max_shift / length;
      sz *= max_shift / length;
      ++capped;
    }
    shift_x[k] = sx;
    shift_z[k] = sz;
    max_d2 = std::max(max_d2, sx * sx + sz * sz);
    ++shifted;
  }
  std::vector<double> divergence;
  if (volume) {
    if (s.kernel == KernelType::wendland_c2) shift_divergence_with(ps, *cells, s, WendlandC2(s.h), shift_x, shift_z, divergence);
    else shift_divergence_with(ps, *cells, s, CubicSpline(s.h), shift_x, shift_z, divergence);
  }
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!ps.is_fluid(i)) continue;
    const auto k = static_cast<std::size_t>(i);
    const double sx = shift_x[k], sz = shift_z[k];
    ps.x[i] += sx;
    ps.z[i] += sz;
    if (taylor) {
      ps.u[i] += sx * g.du_dx[k] + sz * g.du_dz[k];
      ps.w[i] += sx * g.dw_dx[k] + sz * g.dw_dz[k];
      ps.rho[i] += sx * g.drho_dx[k] + sz * g.drho_dz[k];
    }
    if (volume) ps.rho[i] -= ps.rho[i] * divergence[k];
  }
  wrap_periodic(ps, s);
  return ShiftSummary{shifted, at_surface, capped, std::sqrt(max_d2)};
}

}  // namespace hydrojump::sph
