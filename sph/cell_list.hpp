// Neighbour search: a cell-linked list with square cells no smaller than the kernel support (2h).
// Particles are sorted by cell (counting sort, stable), so the neighbours of a particle lie in at most
// three contiguous index ranges (the three rows of the 3x3 block of cells around it), and the solver
// permutes its arrays into that order so neighbours are also close in memory.
//
// Periodic in x: positions are kept in [x_begin, x_begin + period); a neighbour seen across the
// periodic seam is reported with a shift of +-period to add to its x.
//
// Usage:
//   CellList cells;
//   cells.build(x, z, CellGrid::enclosing(x, z, 2 * h));   // or CellGrid::periodic_x(...)
//   particles.permute(cells.order());  cells.mark_sorted();  // optional: make ranges index ranges
//   cells.for_each_neighbour_range(cells.cell_of_sorted(k), [&](int begin, int end, double shift_x) {...});
#pragma once

#include <vector>

#include <Eigen/Core>

namespace hydrojump::sph {

struct CellGrid {
  double x0 = 0.0, z0 = 0.0;   // lower-left corner
  double cell_size = 1.0;      // >= support radius
  int nx = 1, nz = 1;
  bool periodic = false;       // periodic in x with period nx * cell_size
  double period() const { return nx * cell_size; }

  // Cells covering the bounding box of (x, z) with cells of size `support`, cut to the box `limit`
  // ({x_lo, x_hi, z_lo, z_hi}) when given: points outside it go to the edge cells (clamping keeps
  // every pair closer than `support` in the same or adjacent cells, so the search stays exact), so a
  // particle flung far away cannot make a huge grid before the run's checks stop it.
  struct Box {
    double x_lo, x_hi, z_lo, z_hi;
  };
  static CellGrid enclosing(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double support);
  static CellGrid enclosing(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double support, const Box& limit);
  // Periodic in x over [x_begin, x_end) (at least 3 cells, each >= support), z range from the points.
  // Throws std::invalid_argument if the period is shorter than 3 supports.
  static CellGrid periodic_x(double x_begin, double x_end, const Eigen::VectorXd& z, double support);
};

// A run [begin, end) of sorted positions in the 3x3 block of cells around a cell; a neighbour j in it
// is at x[j] + shift_x as seen from that cell.
struct NeighbourRange {
  int begin, end;
  double shift_x;
};

class CellList {
 public:
  // Assigns every particle to its cell and sorts them by cell (stable). Non-finite positions go to
  // cell 0 (the solver's checks report them).
  void build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const CellGrid& grid);
  const CellGrid& grid() const { return grid_; }
  // Declares that the particles have been permuted into cell order: order() becomes the identity.
  void mark_sorted();
  // order()[k] = index of the k-th particle in cell order.
  const std::vector<int>& order() const { return order_; }
  // Cell of the k-th particle in cell order.
  int cell_of_sorted(int k) const { return sorted_cell_[k]; }
  int cell_count() const { return grid_.nx * grid_.nz; }
  // Sorted positions [cell_start(c), cell_start(c+1)) belong to cell c.
  int cell_start(int c) const { return start_[c]; }
  // Cell containing the point (px, pz), clamped into the grid.
  int cell_of_point(double px, double pz) const;

  // Calls f(begin, end, shift_x) for every run of sorted positions in the 3x3 block of cells around
  // cell c. A neighbour j in the run is at x[j] + shift_x as seen from cell c.
  template <class F>
  void for_each_neighbour_range(int c, F&& f) const {
    const int cx = c % grid_.nx, cz = c / grid_.nx;
    for (int dz = -1; dz <= 1; ++dz) {
      const int rz = cz + dz;
      if (rz < 0 || rz >= grid_.nz) continue;
      const int row = rz * grid_.nx;
      if (!grid_.periodic) {
        const int a = cx > 0 ? cx - 1 : 0;
        const int b = cx + 1 < grid_.nx ? cx + 1 : grid_.nx - 1;
        const int begin = start_[row + a], end = start_[row + b + 1];
        if (begin < end) f(begin, end, 0.0);
      } else {
        // nx >= 3: the three columns are distinct.
        for (int dcx = -1; dcx <= 1; ++dcx) {
          int col = cx + dcx;
          double shift = 0.0;
          if (col < 0) { col += grid_.nx; shift = -grid_.period(); }
          else if (col >= grid_.nx) { col -= grid_.nx; shift = grid_.period(); }
          const int begin = start_[row + col], end = start_[row + col + 1];
          if (begin < end) f(begin, end, shift);
        }
      }
    }
  }

  // The (at most 9) runs of for_each_neighbour_range(c, ...) written to out; returns how many. Cells
  // whose particles all loop over the same neighbours gather them once per cell with this.
  int neighbour_ranges(int c, NeighbourRange (&out)[9]) const {
    int n = 0;
    for_each_neighbour_range(c, [&](int begin, int end, double shift_x) { out[n++] = NeighbourRange{begin, end, shift_x}; });
    return n;
  }

 private:
  CellGrid grid_;
  std::vector<int> cell_;         // by original index
  std::vector<int> order_;
  std::vector<int> sorted_cell_;
  std::vector<int> start_;        // size cells + 1
};

}  // namespace hydrojump::sph
