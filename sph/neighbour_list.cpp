#include "sph/neighbour_list.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "sph/parallel.hpp"
#include "sph/particles.hpp"

namespace hydrojump::sph {

namespace {

// The running sum of `count` into `start` (size count + 1); throws past 2^31 entries, which only
// particles piled into a few cells (a run blowing up) reach; its checks then stop it.
void prefix_sum(const std::vector<int>& count, std::vector<int>& start) {
  start.assign(count.size() + 1, 0);
  std::int64_t total = 0;
  for (std::size_t i = 0; i < count.size(); ++i) {
    total += count[i];
    if (total > std::numeric_limits<int>::max()) throw std::runtime_error("neighbour list: over 2^31 candidate pairs (particles piled up)");
    start[i + 1] = static_cast<int>(total);
  }
}

}  // namespace

void NeighbourList::build(const Eigen::VectorXd& x, const Eigen::VectorXd& z, const Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>& type,
                          const CellList& cells, double reach, bool walls_pair_fluid) {
  const Eigen::Index n = x.size();
  const auto size = static_cast<std::size_t>(n);
  const double reach2 = reach * reach;
  const std::uint8_t* t = type.data();
  const int n_cells = cells.cell_count();
  const bool periodic = cells.grid().periodic;
  const auto listed = [&](int i) { return walls_pair_fluid || !is_wall_type(t[i]); };
  // Each particle gets a slot of its candidates' size (its 3x3 block of cells; one distance pass
  // instead of a counting one and a filling one); non-walls fill it from the front, walls from the back.
  std::vector<int>& count = slot_fill_;
  count.assign(size, 0);
#pragma omp parallel for schedule(dynamic, 64) if (use_threads(n))
  for (int c = 0; c < n_cells; ++c) {
    NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(c, ranges);
    int candidates = 0;
    for (int r = 0; r < n_ranges; ++r) candidates += ranges[r].end - ranges[r].begin;
    for (int i = cells.cell_start(c); i < cells.cell_start(c + 1); ++i) count[static_cast<std::size_t>(i)] = listed(i) ? candidates : 0;
  }
  prefix_sum(count, slot_start_);
  slot_j_.resize(static_cast<std::size_t>(slot_start_.back()));
  slot_shift_.assign(periodic ? slot_j_.size() : 0, 0.0);
  slot_wall_.assign(size, 0);
#pragma omp parallel for schedule(dynamic, 64) if (use_threads(n))
  for (int c = 0; c < n_cells; ++c) {
    NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(c, ranges);
    for (int i = cells.cell_start(c); i < cells.cell_start(c + 1); ++i) {
      if (!listed(i)) continue;
      const bool i_wall = is_wall_type(t[i]);
      std::size_t front = static_cast<std::size_t>(slot_start_[static_cast<std::size_t>(i)]);
      std::size_t back = static_cast<std::size_t>(slot_start_[static_cast<std::size_t>(i) + 1]);
      const std::size_t first = front, last = back;
      // Branch-free: j is written at both free ends of the slot and kept by advancing one of them.
      // The slot holds every candidate, i among them, so at least one free entry stays between
      // front and back (back - 1 >= front) and neither write touches a kept entry.
      for (int r = 0; r < n_ranges; ++r) {
        const double shift = ranges[r].shift_x;
        for (int j = ranges[r].begin; j < ranges[r].end; ++j) {
          const bool j_wall = is_wall_type(t[j]);
          const double dx = x[i] - (x[j] + shift), dz = z[i] - z[j];
          const bool keep = (dx * dx + dz * dz < reach2) & (j != i) & !(i_wall & j_wall);
          slot_j_[front] = j;
          slot_j_[back - 1] = j;
          if (periodic) {
            slot_shift_[front] = shift;
            slot_shift_[back - 1] = shift;
          }
          front += static_cast<std::size_t>(keep & !j_wall);
          back -= static_cast<std::size_t>(keep & j_wall);
        }
      }
      count[static_cast<std::size_t>(i)] = static_cast<int>((front - first) + (last - back));
      slot_wall_[static_cast<std::size_t>(i)] = static_cast<int>(front - first);
    }
  }
  // Compact: each particle's non-walls (a non-wall's padded with itself to a multiple of
  // kSimdPadding), then its walls in the order they were met.
  const auto padded = [](int m) { return (m + kSimdPadding - 1) / kSimdPadding * kSimdPadding; };
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto s = static_cast<std::size_t>(i);
    if (!listed(static_cast<int>(i))) count[s] = 0;
    else if (!is_wall_type(t[i])) count[s] += padded(slot_wall_[s]) - slot_wall_[s];
  }
  prefix_sum(count, start_);
  wall_start_.resize(size);
  j_.resize(static_cast<std::size_t>(start_.back()));
  shift_.assign(periodic ? j_.size() : 0, 0.0);
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto s = static_cast<std::size_t>(i);
    const std::size_t from = static_cast<std::size_t>(slot_start_[s]), to = static_cast<std::size_t>(start_[s]);
    const std::size_t met = static_cast<std::size_t>(slot_wall_[s]);
    const std::size_t fluid_side = is_wall_type(t[i]) ? met : static_cast<std::size_t>(padded(slot_wall_[s]));
    const std::size_t walls = static_cast<std::size_t>(count[s]) - fluid_side;
    wall_start_[s] = static_cast<int>(to + fluid_side);
    const std::size_t slot_end = static_cast<std::size_t>(slot_start_[s + 1]);
    for (std::size_t k = 0; k < met; ++k) j_[to + k] = slot_j_[from + k];
    for (std::size_t k = met; k < fluid_side; ++k) j_[to + k] = static_cast<int>(i);
    for (std::size_t k = 0; k < walls; ++k) j_[to + fluid_side + k] = slot_j_[slot_end - 1 - k];
    if (periodic) {
      for (std::size_t k = 0; k < met; ++k) shift_[to + k] = slot_shift_[from + k];
      for (std::size_t k = 0; k < walls; ++k) shift_[to + fluid_side + k] = slot_shift_[slot_end - 1 - k];
    }
  }
}

int NeighbourList::slice_begin(int k, int slices) const {
  const auto n = static_cast<int>(particles());
  if (k <= 0) return 0;
  if (k >= slices) return n;
  // Work of particles [0, i): start_[i] + i (entries plus a fixed cost each), which does not decrease:
  // the first particle whose work before it reaches k/slices of the total.
  const std::int64_t target = (static_cast<std::int64_t>(start_.back()) + n) * k / slices;
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (static_cast<std::int64_t>(start_[static_cast<std::size_t>(mid)]) + mid < target) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

}  // namespace hydrojump::sph
