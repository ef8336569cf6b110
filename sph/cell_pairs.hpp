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
//   puts its last one or two columns in phases of their own);
// - the threads' shares: each thread takes, in every phase, the cells that start in its own slice of
//   consecutive particles (a band of cell rows, cells being numbered row by row), so it writes to the
//   same particles from phase to phase and from step to step and cache lines seldom travel between
//   cores (on two cores 1.35x the throughput of handing the cells out dynamically).
//
// Usage:
//   const std::vector<std::vector<int>> phases = colour_phases(cells.grid());
//   for (const auto& phase : phases)  // every thread, a barrier after each phase
//     for (int c : phase_cells_in(phase, cells, first, last)) {  // [first, last): the thread's slice
//       CellRun runs[4]; int n = forward_runs(cells, c, runs); ...
//     }
#pragma once

#include <span>
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

// The cells of `phase` (increasing, as colour_phases makes them) whose first particle lies in
// [first, last): one thread's share of the phase. Slices that cut the particles into consecutive
// ranges share every phase out with each cell in exactly one share.
std::span<const int> phase_cells_in(const std::vector<int>& phase, const CellList& cells, int first, int last);

}  // namespace hydrojump::sph
