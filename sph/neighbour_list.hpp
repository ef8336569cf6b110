// A Verlet neighbour list for the gather pair loop (Verlet 1967, Phys. Rev. 159:98-103; the "skin"
// of molecular dynamics codes, e.g. LAMMPS' full neighbor lists): every particle lists each other
// particle closer than reach = support + skin, and the list serves every interaction until some
// particle has moved more than skin/2 from where the list saw it, since two particles that come
// within the support by then were within the reach when listed:
//   |r_i - r_j| < support  and  |d_i|, |d_j| <= skin/2   =>   |r_i0 - r_j0| < support + skin.
// The pair terms still test r < support with the current positions.
//
// A full list: a pair is listed from both of its particles, so each particle sums its own terms over
// its own list (no writes to a neighbour, no colouring of cells, and a particle's sum has the same
// order whatever the number of threads). Each particle's list holds first its non-wall neighbours
// (fluid and open-boundary buffer particles, kinds that change into each other), then its wall
// neighbours; a wall particle lists no walls (walls stay walls), and with `walls_pair_fluid` false
// (mDBC: a wall takes nothing from the pair loop) lists nothing. Neighbours follow in sorted order.
// A non-wall particle's non-wall part is padded with the particle itself to a multiple of
// kSimdPadding entries, so the pair loop's SIMD lanes need no scalar remainder: a pair at r = 0 adds
// exactly nothing to any term (every term is a multiple of r, v_i - v_j or rho_i - rho_j).
//
// Usage:
//   NeighbourList list;
//   list.build(x0, z0, type, cells, reach, walls_pair_fluid);   // cells built from x0, z0, cell size >= reach
//   for (int k = list.begin(i); k < list.wall_begin(i); ++k) pair(i, list.neighbours()[k], list.shift(k));
//   for (int k = list.wall_begin(i); k < list.end(i); ++k) wall_pair(i, list.neighbours()[k], list.shift(k));
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sph/cell_list.hpp"

namespace hydrojump::sph {

class NeighbourList {
 public:
  // The non-wall part of a non-wall particle's list has a multiple of this many entries (AVX2's
  // four doubles; AVX-512's eight then take one half-width step at most).
  static constexpr int kSimdPadding = 8;

  // Lists the pairs closer than `reach` at positions (x, z) (the positions `cells` was built from,
  // particles in cell order, cell size >= reach). Cells run in parallel (OpenMP); the list does not
  // depend on the thread count.
  void build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>& type,
             const CellList& cells, double reach, bool walls_pair_fluid = true);

  // Particle i's neighbours: entries [begin(i), wall_begin(i)) are not walls (or i itself, padding),
  // [wall_begin(i), end(i)) are walls; neighbour k is seen at x_j + shift(k) (nonzero only across a
  // periodic seam).
  int begin(int i) const { return start_[static_cast<std::size_t>(i)]; }
  int wall_begin(int i) const { return wall_start_[static_cast<std::size_t>(i)]; }
  int end(int i) const { return start_[static_cast<std::size_t>(i) + 1]; }
  const int* neighbours() const { return j_.data(); }
  bool periodic() const { return !shift_.empty(); }
  double shift(int k) const { return shift_.empty() ? 0.0 : shift_[static_cast<std::size_t>(k)]; }
  const double* shifts() const { return shift_.data(); }  // periodic lists only
  // Particles the list was built for.
  Eigen::Index particles() const { return static_cast<Eigen::Index>(start_.size()) - 1; }
  // The first particle of slice k (0 <= k <= slices) when the particles are cut into `slices`
  // ranges of consecutive particles with about the same number of list entries plus particles each
  // (the pair loop's work): the threads' shares of the pair loop.
  int slice_begin(int k, int slices) const;

 private:
  std::vector<int> start_{0};    // size particles + 1
  std::vector<int> wall_start_;  // size particles
  std::vector<int> j_;
  std::vector<double> shift_;    // size entries; periodic grids only
  // The build's candidate slots (each particle's 3x3 block of cells), filled and then compacted.
  std::vector<int> slot_j_, slot_start_, slot_fill_, slot_wall_;
  std::vector<double> slot_shift_;
};

}  // namespace hydrojump::sph
