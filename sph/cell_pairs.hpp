// The cells of a symmetric pair loop, which evaluates each pair of particles once and adds its terms
// to both (Newton's third law; as in DualSPHysics' CPU and LAMMPS' half neighbour stencils):
//
// - the forward half stencil: every cell meets itself and its four forward neighbours E (cx+1, cz),
//   NW (cx-1, cz+1), N (cx, cz+1) and NE (cx+1, cz+1), so every pair of adjacent cells meets once;
// - the colouring: a cell writes to the particles of itself and of its forward neighbours, columns
//   cx-1..cx+1 and rows cz..cz+1, so cells whose columns differ by 3 or rows by 2 never write to the
//   same particle. Phases group the cells by (cx mod 3, cz mod 2); the cells of one phase run in
//   parallel, the phases one after another. Every particle then receives its pair terms in the same
//   order whatever the number of threads (a periodic grid whose column count is not a multiple of 3
//   puts its last one or two columns in phases of their own).
//
// Usage:
//   const std::vector<std::vector<int>> phases = colour_phases(cells.grid());
//   for (const auto& phase : phases)  // in parallel over the cells of a phase
//     for (int c : phase) { CellRun runs[4]; int n = forward_runs(cells, c, runs); ... }
#pragma once

#include <vector>

#include "sph/cell_list.hpp"

namespace hydrojump::sph {

// A forward neighbour cell's sorted positions [begin, end); x_j + shift_x is its particle's x as
// seen from the cell.
struct CellRun {
  int begin, end;
  double shift_x;
};

// The particles of the non-empty forward neighbours of cell c as runs of sorted positions (adjacent
// cells of a row merged into one run) written to out, in the order E, NW, N, NE; returns how many.
int forward_runs(const CellList& cells, int c, CellRun (&out)[4]);

// The cells of the grid in phases (see above); every cell is in exactly one phase.
std::vector<std::vector<int>> colour_phases(const CellGrid& grid);

}  // namespace hydrojump::sph
