#include "sph/cell_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sph/parallel.hpp"

namespace hydrojump::sph {

namespace {
void finite_range(const Eigen::VectorXd& v, double& lo, double& hi) {
  lo = 0.0;
  hi = 0.0;
  bool first = true;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) continue;
    if (first) { lo = hi = v[i]; first = false; }
    lo = std::min(lo, v[i]);
    hi = std::max(hi, v[i]);
  }
}
}  // namespace

CellGrid CellGrid::enclosing(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double support) {
  const double inf = std::numeric_limits<double>::infinity();
  return enclosing(x, z, support, Box{-inf, inf, -inf, inf});
}

CellGrid CellGrid::enclosing(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double support, const Box& limit) {
  CellGrid g;
  double xlo, xhi, zlo, zhi;
  finite_range(x, xlo, xhi);
  finite_range(z, zlo, zhi);
  xlo = std::max(xlo, limit.x_lo);
  xhi = std::max(xlo, std::min(xhi, limit.x_hi));
  zlo = std::max(zlo, limit.z_lo);
  zhi = std::max(zlo, std::min(zhi, limit.z_hi));
  g.cell_size = support;
  g.x0 = xlo;
  g.z0 = zlo;
  g.nx = static_cast<int>(std::min(1.0e6, std::floor((xhi - xlo) / support))) + 1;
  g.nz = static_cast<int>(std::min(1.0e6, std::floor((zhi - zlo) / support))) + 1;
  return g;
}

CellGrid CellGrid::periodic_x(double x_begin, double x_end, const Eigen::VectorXd& z, double support) {
  const double period = x_end - x_begin;
  const int nx = static_cast<int>(std::floor(period / support));
  if (nx < 3)
    throw std::invalid_argument("periodic length " + std::to_string(period) + " m is shorter than 3 kernel supports (" +
                                std::to_string(3 * support) + " m): make the periodic channel longer or dx smaller");
  CellGrid g;
  double zlo, zhi;
  finite_range(z, zlo, zhi);
  g.periodic = true;
  g.x0 = x_begin;
  g.nx = nx;
  g.cell_size = period / nx;
  g.z0 = zlo;
  g.nz = static_cast<int>(std::min(1.0e6, std::floor((zhi - zlo) / g.cell_size))) + 1;
  return g;
}

namespace {
// floor(f) clamped into [0, n - 1] (f finite).
inline int clamped_index(double f, int n) { return f < 1.0 ? 0 : f >= n - 1 ? n - 1 : static_cast<int>(f); }
}  // namespace

int CellList::cell_of_point(double px, double pz) const {
  const double fx = (px - grid_.x0) / grid_.cell_size;
  const double fz = (pz - grid_.z0) / grid_.cell_size;
  if (!std::isfinite(fx) || !std::isfinite(fz)) return 0;
  // Periodic: a point just outside the period (round-off at the seam) wraps to the column it is in.
  const int cx = !grid_.periodic ? clamped_index(fx, grid_.nx) : fx < 0.0 ? grid_.nx - 1 : fx >= grid_.nx ? 0 : static_cast<int>(fx);
  return clamped_index(fz, grid_.nz) * grid_.nx + cx;
}

void CellList::build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const CellGrid& grid) {
  grid_ = grid;
  const int n = static_cast<int>(x.size());
  const int cells = cell_count();
  cell_.resize(n);
  start_.assign(cells + 1, 0);
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (int i = 0; i < n; ++i) cell_[i] = cell_of_point(x[i], z[i]);
  for (int i = 0; i < n; ++i) ++start_[cell_[i] + 1];
  for (int c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  order_.resize(n);
  sorted_cell_.resize(n);
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int i = 0; i < n; ++i) {
    const int k = fill[cell_[i]]++;
    order_[k] = i;
    sorted_cell_[k] = cell_[i];
  }
}

void CellList::mark_sorted() {
  for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = static_cast<int>(k);
  cell_ = sorted_cell_;
}

}  // namespace hydrojump::sph
