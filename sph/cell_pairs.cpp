#include "sph/cell_pairs.hpp"

#include <algorithm>

namespace hydrojump::sph {

int forward_runs(const CellList& cells, int c, CellRun (&out)[4]) {
  const CellGrid& g = cells.grid();
  const int cx = c % g.nx, cz = c / g.nx;
  constexpr int offsets[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};  // E, NW, N, NE
  int n = 0;
  for (const auto& o : offsets) {
    int col = cx + o[0];
    const int row = cz + o[1];
    if (row >= g.nz) continue;
    double shift = 0.0;
    if (col < 0 || col >= g.nx) {
      if (!g.periodic) continue;
      shift = col < 0 ? -g.period() : g.period();
      col = col < 0 ? col + g.nx : col - g.nx;
    }
    const int d = row * g.nx + col;
    const int begin = cells.cell_start(d), end = cells.cell_start(d + 1);
    if (begin == end) continue;
    // Cells next to each other in a row are next to each other in sorted order: one run.
    if (n > 0 && out[n - 1].end == begin && out[n - 1].shift_x == shift) out[n - 1].end = end;
    else out[n++] = CellRun{begin, end, shift};
  }
  return n;
}

std::vector<std::vector<int>> colour_phases(const CellGrid& grid) {
  // Columns 0 .. 3m-1 by cx mod 3; a periodic grid's leftover columns 3m .. nx-1 one class each (a
  // class's columns must be 3 apart around the period too). Then rows by cz mod 2.
  const int full = grid.periodic ? 3 * (grid.nx / 3) : grid.nx;
  const int column_classes = 3 + (grid.nx - full);
  std::vector<std::vector<int>> phases(static_cast<std::size_t>(2 * column_classes));
  for (int cz = 0; cz < grid.nz; ++cz)
    for (int cx = 0; cx < grid.nx; ++cx) {
      const int column_class = cx < full ? cx % 3 : 3 + (cx - full);
      phases[static_cast<std::size_t>(2 * column_class + cz % 2)].push_back(cz * grid.nx + cx);
    }
  return phases;
}

std::span<const int> phase_cells_in(const std::vector<int>& phase, const CellList& cells, int first, int last) {
  const auto starts_before = [&](int c, int particle) { return cells.cell_start(c) < particle; };
  const auto begin = std::lower_bound(phase.begin(), phase.end(), first, starts_before);
  const auto end = std::lower_bound(begin, phase.end(), last, starts_before);
  return {begin, end};
}

}  // namespace hydrojump::sph
