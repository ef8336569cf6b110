// Neighbour search (issue 3, verification case 2): the cell-linked list finds exactly the pairs a
// brute-force O(N^2) search finds, on random and clustered sets, with and without periodic wrap.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "sph/cell_list.hpp"
#include "neighbour_sets.hpp"

using hydrojump::sph::CellGrid;
using hydrojump::sph::CellList;

namespace {

using neighbour_test::PairSet;
using neighbour_test::brute_force;
using neighbour_test::random_set;

PairSet cell_search(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double radius, const CellGrid& grid) {
  CellList cells;
  cells.build(x, z, grid);
  PairSet pairs;
  const auto& order = cells.order();
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    const int i = order[k];
    // The solver's loops gather the runs once per cell (neighbour_ranges); they must be exactly the
    // runs for_each_neighbour_range visits.
    hydrojump::sph::NeighbourRange ranges[9];
    const int n_ranges = cells.neighbour_ranges(cells.cell_of_sorted(k), ranges);
    int visited = 0;
    cells.for_each_neighbour_range(cells.cell_of_sorted(k), [&](int begin, int end, double shift) {
      REQUIRE(visited < n_ranges);
      REQUIRE(ranges[visited].begin == begin);
      REQUIRE(ranges[visited].end == end);
      REQUIRE(ranges[visited].shift_x == shift);
      ++visited;
    });
    REQUIRE(visited == n_ranges);
    for (int r = 0; r < n_ranges; ++r) {
      for (int m = ranges[r].begin; m < ranges[r].end; ++m) {
        const int j = order[m];
        const double dx = x[i] - (x[j] + ranges[r].shift_x), dz = z[i] - z[j];
        if (dx * dx + dz * dz < radius * radius) {
          const bool fresh = pairs.insert({i, j}).second;
          REQUIRE(fresh);  // no pair is visited twice
        }
      }
    }
  }
  return pairs;
}

}  // namespace

TEST_CASE("cell list equals brute force on random and clustered sets", "[sph][neighbours]") {
  const double radius = 0.05;
  for (const bool clustered : {false, true}) {
    for (const unsigned seed : {1u, 2u, 3u}) {
      auto [x, z] = random_set(1500, 1.0, 0.4, seed, clustered);
      const PairSet expected = brute_force(x, z, radius, 0.0);
      const PairSet found = cell_search(x, z, radius, CellGrid::enclosing(x, z, radius));
      INFO("clustered " << clustered << " seed " << seed);
      CHECK(found.size() == expected.size());
      CHECK(found == expected);
    }
  }
}

TEST_CASE("cell list equals brute force with periodic wrap in x", "[sph][neighbours]") {
  for (const double length : {1.0, 0.17, 0.153}) {  // many cells; a non-integer number of supports
    const double radius = 0.05;
    for (const bool clustered : {false, true}) {
      auto [x, z] = random_set(1200, length, 0.3, 7u, clustered);
      const PairSet expected = brute_force(x, z, radius, length);
      const PairSet found = cell_search(x, z, radius, CellGrid::periodic_x(0.0, length, z, radius));
      INFO("length " << length << " clustered " << clustered);
      CHECK(found == expected);
      // Some pairs really do cross the seam.
      int across = 0;
      for (const auto& [i, j] : expected) across += std::abs(x[i] - x[j]) > 0.5 * length ? 1 : 0;
      CHECK(across > 0);
    }
  }
  auto [x, z] = random_set(10, 0.12, 0.3, 1u, false);
  CHECK_THROWS_WITH(CellGrid::periodic_x(0.0, 0.12, z, 0.05), Catch::Contains("shorter than 3 kernel supports"));
}

TEST_CASE("a grid cut to a limit box stays small and exact with points far outside it", "[sph][neighbours]") {
  const double radius = 0.05;
  auto [x, z] = random_set(1000, 1.0, 0.4, 11u, true);
  // Points beyond the limit box: a clump just outside each side (they still have neighbours there)
  // and one particle flung 1 km away.
  for (int i = 0; i < 40; ++i) {
    x[i] = (i % 2 == 0 ? -0.3 : 1.3) + 0.01 * (i % 5);
    z[i] = 0.6 + 0.01 * (i % 7);
  }
  x[40] = 1000.0;
  z[40] = -1000.0;
  const CellGrid::Box limit{-0.1, 1.1, -0.1, 0.5};
  const CellGrid grid = CellGrid::enclosing(x, z, radius, limit);
  CHECK(grid.nx <= std::lround(1.2 / radius) + 1);  // 25 cells of 0.05 m, not 20,000
  CHECK(grid.nz <= std::lround(0.6 / radius) + 1);
  CHECK(cell_search(x, z, radius, grid) == brute_force(x, z, radius, 0.0));
}

TEST_CASE("the cell of a point: floor of its grid coordinate, clamped into the grid or wrapped around the period",
          "[sph][neighbours]") {
  // The rule written out: f = (p - p0) / cell size clamped into [-1, n], then floor; cx taken modulo nx
  // with periodic wrap (a point just outside the period), then both clamped into [0, n - 1]; a
  // non-finite point goes to cell 0.
  const auto expected = [](const CellGrid& g, double px, double pz) {
    const double fx = (px - g.x0) / g.cell_size, fz = (pz - g.z0) / g.cell_size;
    if (!std::isfinite(fx) || !std::isfinite(fz)) return 0;
    long cx = static_cast<long>(std::floor(std::min(std::max(fx, -1.0), static_cast<double>(g.nx))));
    if (g.periodic) cx = ((cx % g.nx) + g.nx) % g.nx;
    cx = std::min<long>(std::max<long>(cx, 0), g.nx - 1);
    const long cz = std::min<long>(std::max<long>(static_cast<long>(std::floor(std::min(std::max(fz, -1.0), double(g.nz)))), 0), g.nz - 1);
    return static_cast<int>(cz * g.nx + cx);
  };
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const bool periodic : {false, true}) {
    CellGrid g;
    g.x0 = -0.3, g.z0 = 0.2, g.cell_size = 0.1, g.nx = 7, g.nz = 4, g.periodic = periodic;
    Eigen::VectorXd x(1), z(1);
    x << 0.0;
    z << 0.3;
    CellList cells;
    cells.build(x, z, g);
    std::vector<double> xs{-1e300, -inf, nan, inf, 1e300, -0.0, 0.0};
    std::vector<double> zs{-1e300, -inf, nan, inf, 1e300, -0.0, 0.0};
    for (int k = -25; k <= 95; ++k) {  // every cell face, and just either side of it, within and beyond the grid
      xs.push_back(g.x0 + 0.1 * k * g.cell_size), xs.push_back(std::nextafter(g.x0 + 0.1 * k * g.cell_size, -inf));
      zs.push_back(g.z0 + 0.06 * k * g.cell_size), zs.push_back(std::nextafter(g.z0 + 0.06 * k * g.cell_size, inf));
    }
    for (double px : xs)
      for (double pz : zs) {
        INFO("periodic " << periodic << ", point (" << px << ", " << pz << ")");
        REQUIRE(cells.cell_of_point(px, pz) == expected(g, px, pz));
      }
  }
}
