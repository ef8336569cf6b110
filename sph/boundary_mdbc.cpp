#include "sph/boundary_mdbc.hpp"

#include "sph/boundary_dbc.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "sph/cpu_dispatch.hpp"
#include "sph/kernel.hpp"
#include "sph/parallel.hpp"

namespace hydrojump::sph {

namespace {


// Below this Shepard sum sum_j V_j W_gj the ghost node lies mostly outside the fluid (e.g. the wall
// above the free surface) and the boundary particle keeps rho0 (zero pressure); at or above it the
// first-order extrapolation is used unless the matrix is singular.
constexpr double kSomeSupport = 0.5;
// The matrix is dimensionless (its length and inverse-length entries pair up) and close to the
// identity inside the fluid (sum_j V_j (r_j - r_g) (x) grad_g W_gj = +I for a full support); below
// this |det| it is treated as singular.
constexpr double kMinDeterminant = 1e-3;

// The fluid side a ghost node sums over: particle arrays and the ghost list's entries.
struct GhostFluid {
  const double *x, *z, *mass, *rho, *u, *w;
  const int* neighbours;
  const double* shifts;  // periodic lists only
};

// The sums of mdbc_with over entries [begin, end) for a ghost node at (gx, gz):
//   a = sum V_j [W, (x_j - x_g) W, (z_j - z_g) W; the same with dW/dx; with dW/dz]  (rows: W, dW/dx, dW/dz),
//   rhs = sum m_j [W, dW/dx, dW/dz],  rhs_u = sum V_j u_j [...],  rhs_w = sum V_j w_j [...].
// In scalars, so that the lanes of one SIMD loop run over j; an entry beyond the support adds exactly
// 0 (its kernel value and gradient are 0 there), so the loop has no branch.
struct GhostSums {
  Eigen::Matrix3d a;
  Eigen::Vector3d rhs, rhs_u, rhs_w;
};

template <bool Periodic, class K>
[[gnu::always_inline]] inline GhostSums ghost_sums(const GhostFluid& f, const K& kernel, int begin, int end, double gx, double gz) {
  double a00 = 0, a01 = 0, a02 = 0, a10 = 0, a11 = 0, a12 = 0, a20 = 0, a21 = 0, a22 = 0;
  double m0 = 0, m1 = 0, m2 = 0, u0 = 0, u1 = 0, u2 = 0, w0 = 0, w1 = 0, w2 = 0;
#pragma omp simd reduction(+ : a00, a01, a02, a10, a11, a12, a20, a21, a22, m0, m1, m2, u0, u1, u2, w0, w1, w2)
  for (int k = begin; k < end; ++k) {
    const int j = f.neighbours[k];  // the fluid side: fluid and buffer particles
    double xj = f.x[j];
    if constexpr (Periodic) xj += f.shifts[k];
    const double rx = xj - gx, rz = f.z[j] - gz;  // r_j - r_g
    const double r = std::sqrt(rx * rx + rz * rz);
    const double wv = kernel.value(r);
    const double fr = kernel.gradient_factor(r);
    const double dwdx = -fr * rx, dwdz = -fr * rz;  // grad_g W = F (r_g - r_j)
    const double v = f.mass[j] / f.rho[j];
    const double vw = v * wv, vx = v * dwdx, vz = v * dwdz;
    a00 += vw, a01 += vw * rx, a02 += vw * rz;
    a10 += vx, a11 += vx * rx, a12 += vx * rz;
    a20 += vz, a21 += vz * rx, a22 += vz * rz;
    m0 += f.mass[j] * wv, m1 += f.mass[j] * dwdx, m2 += f.mass[j] * dwdz;
    u0 += f.u[j] * vw, u1 += f.u[j] * vx, u2 += f.u[j] * vz;
    w0 += f.w[j] * vw, w1 += f.w[j] * vx, w2 += f.w[j] * vz;
  }
  GhostSums g;
  g.a << a00, a01, a02, a10, a11, a12, a20, a21, a22;
  g.rhs = {m0, m1, m2};
  g.rhs_u = {u0, u1, u2};
  g.rhs_w = {w0, w1, w2};
  return g;
}

// For every wall particle b with ghost node g (boundary_mdbc.hpp):
//   A [rho_g, d rho/dx, d rho/dz]^T = [sum m_j W_gj, sum m_j dW_gj/dx, sum m_j dW_gj/dz]^T,
//   rho_b = max(rho0, rho_g + (r_b - r_g) . grad rho_g),
// the Shepard value sum m_j W_gj / sum V_j W_gj where A is singular, rho0 where sum V_j W_gj < 0.5;
// and the no-slip wall velocity v_b = 2 v_wall - v_g, v_g from the same system with m_j -> m_j u_j / rho_j
// (only its value, the gradient is not extrapolated).
template <class K>
HYDROJUMP_HOT_LOOP void mdbc_with(ParticleSet& ps, const GhostNeighbourList& list, const SolverSettings& s, const K& kernel) {
  const Eigen::Index n = ps.size();
  const double rho0 = s.eos.rho0;
  const GhostFluid f{ps.x.data(), ps.z.data(), ps.mass.data(), ps.rho.data(), ps.u.data(), ps.w.data(), list.neighbours(), list.shifts()};
#pragma omp parallel for schedule(dynamic, 64) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!is_wall_type(ps.type[i])) continue;  // walls only; buffers have imposed densities
    const double gx = ps.x[i] + ps.ghost_dx[i] + list.ghost_wrap(i);
    const double gz = ps.z[i] + ps.ghost_dz[i];
    const GhostSums g = list.periodic() ? ghost_sums<true>(f, kernel, list.begin(i), list.end(i), gx, gz)
                                        : ghost_sums<false>(f, kernel, list.begin(i), list.end(i), gx, gz);
    const Eigen::Matrix3d& a = g.a;
    const Eigen::Vector3d &rhs = g.rhs, &rhs_u = g.rhs_u, &rhs_w = g.rhs_w;
    double rho_b = rho0, u_g = 0.0, w_g = 0.0;
    if (a(0, 0) >= kSomeSupport) {  // the ghost node lies in the fluid (not mostly in air)
      const double det = a.determinant();
      // First order only where the ghost node is surrounded by fluid; near the free surface the
      // one-sided gradient would extrapolate spurious pressure into the wall above the water.
      if (std::abs(det) > kMinDeterminant) {
        const auto lu = a.partialPivLu();
        const Eigen::Vector3d sol = lu.solve(rhs);
        rho_b = sol(0) - (ps.ghost_dx[i] * sol(1) + ps.ghost_dz[i] * sol(2));
        u_g = lu.solve(rhs_u)(0);
        w_g = lu.solve(rhs_w)(0);
      } else {
        rho_b = rhs(0) / a(0, 0);
        u_g = rhs_u(0) / a(0, 0);
        w_g = rhs_w(0) / a(0, 0);
      }
    }
    ps.rho[i] = dbc_wall_density(rho_b, rho0);  // never below rho0, as DBC
    const double n_len = s.viscosity.viscous_walls_free_slip ? std::hypot(ps.ghost_dx[i], ps.ghost_dz[i]) : 0.0;
    if (n_len > 0.0) {
      // Free slip: the ghost velocity relative to the wall with its normal part reversed,
      //   v_b = v_wall + v_rel - 2 (v_rel . n) n,   v_rel = v_g - v_wall,  n = (g - b)/|g - b|
      const double nx = ps.ghost_dx[i] / n_len, nz = ps.ghost_dz[i] / n_len;
      const double ru = u_g - ps.u[i], rw = w_g - ps.w[i];
      const double rn = ru * nx + rw * nz;
      ps.wall_u[i] = ps.u[i] + ru - 2.0 * rn * nx;
      ps.wall_w[i] = ps.w[i] + rw - 2.0 * rn * nz;
    } else {
      // No slip (and free slip without a ghost offset): the velocity mirrored through the wall's own,
      // 2 v_wall - v_ghost (v_wall = 0 if fixed).
      ps.wall_u[i] = 2.0 * ps.u[i] - u_g;
      ps.wall_w[i] = 2.0 * ps.w[i] - w_g;
    }
  }
}

}  // namespace

void GhostNeighbourList::build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const ParticleSet& ps, const CellList& cells,
                               const SolverSettings& s, double reach) {
  const Eigen::Index n = ps.size();
  const auto size = static_cast<std::size_t>(n);
  const bool periodic = cells.grid().periodic;
  const double period = s.domain.x_max - s.domain.x_min;
  const double reach2 = reach * reach;
  // Each wall particle's ghost node (brought into the periodic domain) and its cell.
  std::vector<double> gx(size), gz(size);
  std::vector<int> cell(size, -1);
  wrap_.assign(periodic ? size : 0, 0.0);
  start_.assign(size, 0);
  end_.assign(size, 0);
  std::int64_t total = 0;
  for (Eigen::Index b = 0; b < n; ++b) {
    const auto k = static_cast<std::size_t>(b);
    start_[k] = static_cast<int>(total);
    end_[k] = start_[k];
    if (!is_wall_type(ps.type[b])) continue;
    gx[k] = x[b] + ps.ghost_dx[b];
    gz[k] = z[b] + ps.ghost_dz[b];
    if (periodic) {
      const double wrapped = s.domain.x_min + std::fmod(std::fmod(gx[k] - s.domain.x_min, period) + period, period);
      wrap_[k] = wrapped - gx[k];
      gx[k] = wrapped;
    }
    cell[k] = cells.cell_of_point(gx[k], gz[k]);
    cells.for_each_neighbour_range(cell[k], [&](int begin, int end, double) { total += end - begin; });
    // Only particles piled into a few cells (a run blowing up) get here; its checks then stop it.
    if (total > std::numeric_limits<int>::max()) throw std::runtime_error("mDBC ghost list: over 2^31 candidates (particles piled up)");
  }
  j_.resize(static_cast<std::size_t>(total));
  shift_.assign(periodic ? j_.size() : 0, 0.0);
#pragma omp parallel for schedule(dynamic, 64) if (use_threads(n))
  for (Eigen::Index b = 0; b < n; ++b) {
    const auto k = static_cast<std::size_t>(b);
    if (cell[k] < 0) continue;
    int fill = start_[k];
    cells.for_each_neighbour_range(cell[k], [&](int begin, int end, double shift) {
      for (int j = begin; j < end; ++j) {
        if (is_wall_type(ps.type[j])) continue;  // the fluid side: fluid and buffer particles
        const double rx = x[j] + shift - gx[k], rz = z[j] - gz[k];
        if (rx * rx + rz * rz >= reach2) continue;
        j_[static_cast<std::size_t>(fill)] = j;
        if (periodic) shift_[static_cast<std::size_t>(fill)] = shift;
        ++fill;
      }
    });
    end_[k] = fill;
  }
}

void mdbc_boundary_density(ParticleSet& ps, const GhostNeighbourList& list, const SolverSettings& s) {
  if (list.particles() != ps.size()) throw std::logic_error("mdbc_boundary_density: the ghost list was built for another particle set");
  if (s.kernel == KernelType::wendland_c2) mdbc_with(ps, list, s, WendlandC2(s.h));
  else mdbc_with(ps, list, s, CubicSpline(s.h));
}

void mdbc_boundary_density(ParticleSet& ps, const CellList& cells, const SolverSettings& s) {
  GhostNeighbourList list;
  list.build(ps.x, ps.z, ps, cells, s, s.support());
  mdbc_boundary_density(ps, list, s);
}

}  // namespace hydrojump::sph
