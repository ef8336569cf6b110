// A Verlet neighbour list for the symmetric pair loop (Verlet 1967, Phys. Rev. 159:98-103; the
// "skin" of molecular dynamics codes, e.g. LAMMPS' neighbor lists): every pair closer than
// reach = support + skin is listed once, and the list serves every interaction until some particle
// has moved more than skin/2 from where the list saw it, since two particles that come within the
// support by then were within the reach when listed:
//   |r_i - r_j| < support  and  |d_i|, |d_j| <= skin/2   =>   |r_i0 - r_j0| < support + skin.
// The pair terms still test r < support with the current positions.
//
// The pairs are those of cell_pairs.hpp: particle i of cell c meets the later particles of c and the
// particles of the forward neighbours of c (E, NW, N, NE), so the colour phases still keep the cells
// of a phase from writing to the same particle, and a particle receives its terms in a fixed order.
// Wall-wall pairs are left out (walls stay walls; the other kinds change, so the pair loop tests them).
//
// Usage:
//   NeighbourList list;
//   list.build(x0, z0, type, cells, reach);   // cells built from x0, z0, cell size >= reach
//   for (const auto& phase : list.phases()) ...  // the pair loop's colour phases of those cells
//   for (int k = list.begin(i); k < list.plain_end(i); ++k) pair(i, list.neighbours()[k], 0.0);
//   for (int k = list.shifted_begin(i); k < list.end(i); ++k) pair(i, list.neighbours()[k], list.shift(k));
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sph/cell_list.hpp"

namespace hydrojump::sph {

class NeighbourList {
 public:
  // Lists the pairs closer than `reach` at positions (x, z) (the positions `cells` was built from,
  // particles in cell order, cell size >= reach). Cells run in parallel (OpenMP); the list does not
  // depend on the thread count.
  void build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>& type,
             const CellList& cells, double reach);

  // Particle i's listed neighbours in the forward stencil (j > i except across a periodic seam): entries [begin(i), plain_end(i))
  // are seen at x_j, entries [shifted_begin(i), end(i)) at x_j + shift(k) (periodic seam); the
  // entries between are unused (each particle has a slot of its candidates' size).
  int begin(int i) const { return start_[static_cast<std::size_t>(i)]; }
  int plain_end(int i) const { return plain_end_[static_cast<std::size_t>(i)]; }
  int shifted_begin(int i) const { return shifted_[static_cast<std::size_t>(i)]; }
  int end(int i) const { return start_[static_cast<std::size_t>(i) + 1]; }
  const int* neighbours() const { return j_.data(); }
  double shift(int k) const { return shift_[static_cast<std::size_t>(k)]; }
  // Particles the list was built for.
  Eigen::Index particles() const { return static_cast<Eigen::Index>(start_.size()) - 1; }
  // The first particle of slice k (0 <= k <= slices) when the particles are cut into `slices`
  // ranges of consecutive particles with about the same number of list slots each (the pair loop's
  // work): the threads' shares of the pair loop (cell_pairs.hpp).
  int slice_begin(int k, int slices) const;
  // The colour phases of the cells it was built on (cell_pairs.hpp), made once per build.
  const std::vector<std::vector<int>>& phases() const { return phases_; }

 private:
  std::vector<int> start_{0};   // size particles + 1: the slots
  std::vector<int> plain_end_;  // size particles
  std::vector<int> shifted_;    // size particles
  std::vector<int> j_;
  std::vector<double> shift_;   // size pairs; periodic grids only
  std::vector<std::vector<int>> phases_;
};

}  // namespace hydrojump::sph
