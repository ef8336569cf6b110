#include "sph/neighbour_list.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "sph/cell_pairs.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

namespace hydrojump::sph {

namespace {

// Calls f(i, j, shift_x) for every pair of cell c's particles i with the later particles of c and
// the particles of c's forward neighbours (cell_pairs.hpp), in the pair loop's order.
template <class F>
void for_each_forward_pair(const CellList& cells, int c, F&& f) {
  const int first = cells.cell_start(c), last = cells.cell_start(c + 1);
  if (first == last) return;
  CellRun runs[4];
  const int n_runs = forward_runs(cells, c, runs);
  // The cell's own later particles and, when it follows them in sorted order, the first forward run.
  const bool first_follows = n_runs > 0 && runs[0].begin == last && runs[0].shift_x == 0.0;
  const int own_end = first_follows ? runs[0].end : last;
  for (int i = first; i < last; ++i) {
    for (int j = i + 1; j < own_end; ++j) f(i, j, 0.0);
    for (int r = first_follows ? 1 : 0; r < n_runs; ++r)
      for (int j = runs[r].begin; j < runs[r].end; ++j) f(i, j, runs[r].shift_x);
  }
}

// Candidates of each particle of cell c (no distance test): its slot's size in the list.
void count_candidates(const CellList& cells, int c, std::vector<int>& slot) {
  const int first = cells.cell_start(c), last = cells.cell_start(c + 1);
  if (first == last) return;
  CellRun runs[4];
  const int n_runs = forward_runs(cells, c, runs);
  int in_runs = 0;
  for (int r = 0; r < n_runs; ++r) in_runs += runs[r].end - runs[r].begin;
  for (int i = first; i < last; ++i) slot[static_cast<std::size_t>(i)] = (last - i - 1) + in_runs;
}

}  // namespace

void NeighbourList::build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>& type,
                          const CellList& cells, double reach) {
  const Eigen::Index n = x.size();
  const auto size = static_cast<std::size_t>(n);
  const double reach2 = reach * reach;
  const std::uint8_t* t = type.data();
  // Each particle gets a slot of its candidates' size (one distance pass instead of a counting one
  // and a filling one); the unshifted neighbours fill it from the front, the periodic images from the back.
  std::vector<int> slot(size, 0);
  const int n_cells = cells.cell_count();
  phases_ = colour_phases(cells.grid());
  for (int c = 0; c < n_cells; ++c) count_candidates(cells, c, slot);
  start_.assign(size + 1, 0);
  std::int64_t total = 0;
  for (std::size_t i = 0; i < size; ++i) {
    total += slot[i];
    // Only particles piled into a few cells (a run blowing up) get here; its checks then stop it.
    if (total > std::numeric_limits<int>::max()) throw std::runtime_error("neighbour list: over 2^31 candidate pairs (particles piled up)");
    start_[i + 1] = static_cast<int>(total);
  }
  plain_end_.assign(start_.begin(), start_.end() - 1);  // empty until filled
  shifted_.assign(start_.begin() + 1, start_.end());
  j_.resize(static_cast<std::size_t>(start_[size]));
  shift_.assign(cells.grid().periodic ? j_.size() : 0, 0.0);
#pragma omp parallel for schedule(dynamic, 16) if (use_threads(n))
  for (int c = 0; c < n_cells; ++c) {
    int current = -1;
    std::size_t front = 0, back = 0;
    const auto close = [&] {
      if (current < 0) return;
      plain_end_[static_cast<std::size_t>(current)] = static_cast<int>(front);
      shifted_[static_cast<std::size_t>(current)] = static_cast<int>(back);
    };
    for_each_forward_pair(cells, c, [&](int i, int j, double shift) {
      if (i != current) {
        close();
        current = i;
        front = static_cast<std::size_t>(start_[static_cast<std::size_t>(i)]);
        back = static_cast<std::size_t>(start_[static_cast<std::size_t>(i) + 1]);
      }
      if (is_wall_type(t[i]) && is_wall_type(t[j])) return;
      const double dx = x[i] - (x[j] + shift), dz = z[i] - z[j];
      if (dx * dx + dz * dz >= reach2) return;
      if (shift == 0.0) {
        j_[front++] = j;
      } else {
        j_[--back] = j;
        shift_[back] = shift;
      }
    });
    close();
  }
}

int NeighbourList::slice_begin(int k, int slices) const {
  const auto n = static_cast<int>(particles());
  if (k <= 0) return 0;
  if (k >= slices) return n;
  // start_ does not decrease: the first particle whose slot starts at or after k/slices of all slots.
  const std::int64_t target = static_cast<std::int64_t>(start_.back()) * k / slices;
  const auto slot = std::lower_bound(start_.begin(), start_.end() - 1, target, [](int s, std::int64_t t) { return s < t; });
  return static_cast<int>(slot - start_.begin());
}

}  // namespace hydrojump::sph
