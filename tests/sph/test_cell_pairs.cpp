// The symmetric pair loop's cells (sph/cell_pairs.hpp): each cell with itself (later particles) and
// its forward runs meets every pair a brute-force O(N^2) search finds exactly once, and the cells of
// one colour phase never write to the same particle, on random and clustered sets, with and without
// periodic wrap (a column count that is and is not a multiple of 3).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "neighbour_sets.hpp"
#include "sph/cell_pairs.hpp"
#include "sph/neighbour_list.hpp"

using hydrojump::sph::CellGrid;
using hydrojump::sph::CellList;
using hydrojump::sph::CellRun;

namespace {

using PairSet = neighbour_test::PairSet;  // here (lower index, higher index)

// The pairs i < j closer than `radius` (minimum image with period > 0), by brute force.
PairSet brute_force_once(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double radius, double period) {
  PairSet once;
  for (const auto& [i, j] : neighbour_test::brute_force(x, z, radius, period))
    if (i < j) once.insert({i, j});
  return once;
}

// The pairs the half stencil meets (original indices), each required to be met once, and for each
// cell the particles it writes to (itself and its forward runs).
PairSet half_stencil_pairs(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double radius, const CellList& cells,
                           std::vector<std::set<int>>& written) {
  const auto& order = cells.order();
  PairSet pairs;
  written.assign(static_cast<std::size_t>(cells.cell_count()), {});
  for (int c = 0; c < cells.cell_count(); ++c) {
    CellRun runs[4];
    const int n_runs = hydrojump::sph::forward_runs(cells, c, runs);
    std::vector<CellRun> all{CellRun{cells.cell_start(c), cells.cell_start(c + 1), 0.0}};
    all.insert(all.end(), runs, runs + n_runs);
    for (int a = cells.cell_start(c); a < cells.cell_start(c + 1); ++a)
      for (std::size_t r = 0; r < all.size(); ++r)
        for (int b = r == 0 ? a + 1 : all[r].begin; b < all[r].end; ++b) {
          const int i = order[a], j = order[b];
          const double dx = x[i] - (x[j] + all[r].shift_x), dz = z[i] - z[j];
          written[c].insert(a);
          written[c].insert(b);
          if (dx * dx + dz * dz >= radius * radius) continue;
          const bool fresh = pairs.insert({std::min(i, j), std::max(i, j)}).second;
          REQUIRE(fresh);  // no pair is met twice
        }
  }
  return pairs;
}

void require_phases_disjoint(const CellList& cells, const std::vector<std::set<int>>& written) {
  const std::vector<std::vector<int>> phases = hydrojump::sph::colour_phases(cells.grid());
  std::vector<int> seen(static_cast<std::size_t>(cells.cell_count()), 0);
  for (const auto& phase : phases) {
    std::set<int> touched;
    for (int c : phase) {
      ++seen[static_cast<std::size_t>(c)];
      for (int k : written[static_cast<std::size_t>(c)]) {
        const bool fresh = touched.insert(k).second;
        REQUIRE(fresh);  // two cells of one phase never write to the same particle
      }
    }
  }
  for (int n : seen) REQUIRE(n == 1);  // every cell in exactly one phase
}

}  // namespace

TEST_CASE("the half stencil meets every pair once and colour phases never share a particle", "[sph][neighbours]") {
  const double radius = 0.05;
  for (const bool clustered : {false, true}) {
    auto [x, z] = neighbour_test::random_set(1200, 1.0, 0.4, 5u, clustered);
    CellList cells;
    cells.build(x, z, CellGrid::enclosing(x, z, radius));
    std::vector<std::set<int>> written;
    const PairSet found = half_stencil_pairs(x, z, radius, cells, written);
    INFO("clustered " << clustered);
    CHECK(found == brute_force_once(x, z, radius, 0.0));
    require_phases_disjoint(cells, written);
  }
}

TEST_CASE("the half stencil and its phases with periodic wrap in x", "[sph][neighbours]") {
  const double radius = 0.05;
  // 20 columns, 3 (the fewest), 4 and 5 (one or two columns left over from a multiple of 3).
  for (const double length : {1.0, 0.16, 0.21, 0.26}) {
    for (const bool clustered : {false, true}) {
      auto [x, z] = neighbour_test::random_set(900, length, 0.3, 9u, clustered);
      CellList cells;
      cells.build(x, z, CellGrid::periodic_x(0.0, length, z, radius));
      std::vector<std::set<int>> written;
      const PairSet found = half_stencil_pairs(x, z, radius, cells, written);
      INFO("length " << length << " (" << cells.grid().nx << " columns) clustered " << clustered);
      const PairSet expected = brute_force_once(x, z, radius, length);
      CHECK(found == expected);
      require_phases_disjoint(cells, written);
      int across = 0;  // some pairs really do cross the seam
      for (const auto& [i, j] : expected) across += std::abs(x[i] - x[j]) > 0.5 * length ? 1 : 0;
      CHECK(across > 0);
    }
  }
}

// The pair loop's thread shares (NeighbourList::slice_begin, phase_cells_in): for any number of
// slices, every phase's cells fall into the slices' shares once each, in order, and each slice holds
// at most its even part of the list slots plus one particle's slot.
TEST_CASE("the threads' slices share out every phase's cells once and evenly", "[sph][neighbours]") {
  const double radius = 0.05;
  for (const bool clustered : {false, true}) {
    auto [x0, z0] = neighbour_test::random_set(1500, 1.0, 0.4, 11u, clustered);
    CellList unsorted;
    unsorted.build(x0, z0, CellGrid::enclosing(x0, z0, radius));
    Eigen::VectorXd x(x0.size()), z(z0.size());  // the particles in cell order, as the solver keeps them
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      x[k] = x0[unsorted.order()[static_cast<std::size_t>(k)]];
      z[k] = z0[unsorted.order()[static_cast<std::size_t>(k)]];
    }
    CellList cells;
    cells.build(x, z, CellGrid::enclosing(x, z, radius));
    cells.mark_sorted();
    hydrojump::sph::NeighbourList list;
    list.build(x, z, Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>::Zero(x.size()), cells, radius);
    const int n = static_cast<int>(x.size());
    int largest_slot = 0;
    for (int i = 0; i < n; ++i) largest_slot = std::max(largest_slot, list.end(i) - list.begin(i));
    for (const int slices : {1, 2, 3, 7}) {
      INFO("clustered " << clustered << ", " << slices << " slices");
      CHECK(list.slice_begin(0, slices) == 0);
      CHECK(list.slice_begin(slices, slices) == n);
      for (int k = 0; k < slices; ++k) {
        const int first = list.slice_begin(k, slices), last = list.slice_begin(k + 1, slices);
        REQUIRE(first <= last);
        CHECK(list.begin(last) - list.begin(first) <= list.end(n - 1) / slices + largest_slot + 1);
      }
      for (const auto& phase : list.phases()) {
        std::vector<int> shared;
        for (int k = 0; k < slices; ++k) {
          const auto share = hydrojump::sph::phase_cells_in(phase, cells, list.slice_begin(k, slices), list.slice_begin(k + 1, slices));
          shared.insert(shared.end(), share.begin(), share.end());
        }
        CHECK(shared == phase);
      }
    }
  }
}
