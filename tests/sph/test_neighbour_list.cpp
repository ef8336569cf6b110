// The full Verlet list (sph/neighbour_list.hpp) against a brute-force O(N^2) search: every particle
// lists exactly the other particles closer than the reach (minimum image across a periodic seam, with
// the shift that places them), non-walls before walls, walls listing no walls (and nothing when
// walls take nothing from the pair loop), a non-wall's non-wall part padded with itself to the SIMD
// width; on random and clustered sets with mixed kinds. And the threads' slices cut the work evenly.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "neighbour_sets.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/particles.hpp"

using hydrojump::sph::CellGrid;
using hydrojump::sph::CellList;
using hydrojump::sph::NeighbourList;
using Types = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>;

namespace {

// A point set in cell order (as the solver keeps its particles) with every third point a wall and
// every seventh an inflow buffer particle.
struct SortedSet {
  Eigen::VectorXd x, z;
  Types type;
  CellList cells;
};

SortedSet sorted_set(int n, double lx, double lz, unsigned seed, bool clustered, double radius, bool periodic) {
  auto [x0, z0] = neighbour_test::random_set(n, lx, lz, seed, clustered);
  const auto grid = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& z) {
    return periodic ? CellGrid::periodic_x(0.0, lx, z, radius) : CellGrid::enclosing(x, z, radius);
  };
  CellList unsorted;
  unsorted.build(x0, z0, grid(x0, z0));
  SortedSet s{Eigen::VectorXd(n), Eigen::VectorXd(n), Types(n), {}};
  for (int k = 0; k < n; ++k) {
    const int i = unsorted.order()[static_cast<std::size_t>(k)];
    s.x[k] = x0[i], s.z[k] = z0[i];
    const auto kind = i % 3 == 0 ? hydrojump::sph::ParticleType::boundary
                                 : (i % 7 == 0 ? hydrojump::sph::ParticleType::inflow : hydrojump::sph::ParticleType::fluid);
    s.type[k] = static_cast<std::uint8_t>(kind);
  }
  s.cells.build(s.x, s.z, grid(s.x, s.z));
  s.cells.mark_sorted();
  return s;
}

void require_matches_brute_force(const SortedSet& s, double radius, double period, bool walls_pair_fluid) {
  NeighbourList list;
  list.build(s.x, s.z, s.type, s.cells, radius, walls_pair_fluid);
  REQUIRE(list.particles() == s.x.size());
  REQUIRE(list.periodic() == (period > 0.0));
  const auto wall = [&](int i) { return hydrojump::sph::is_wall_type(s.type[i]); };
  std::vector<std::set<int>> expected(static_cast<std::size_t>(s.x.size()));
  for (const auto& [i, j] : neighbour_test::brute_force(s.x, s.z, radius, period))
    if (i != j && !(wall(i) && wall(j)) && (walls_pair_fluid || !wall(i))) expected[static_cast<std::size_t>(i)].insert(j);
  int across = 0;
  for (int i = 0; i < s.x.size(); ++i) {
    std::set<int> got;
    if (!wall(i)) REQUIRE((list.wall_begin(i) - list.begin(i)) % NeighbourList::kSimdPadding == 0);
    for (int k = list.begin(i); k < list.end(i); ++k) {
      const int j = list.neighbours()[k];
      INFO("particle " << i << " entry " << k << " = " << j);
      if (j == i) {  // padding: only in a non-wall's non-wall part, at r = 0
        REQUIRE((!wall(i) && k < list.wall_begin(i) && list.shift(k) == 0.0));
        continue;
      }
      REQUIRE((k < list.wall_begin(i) ? !wall(j) : wall(j)));  // non-walls first, then walls
      REQUIRE(got.insert(j).second);                          // each once
      const double dx = s.x[i] - (s.x[j] + list.shift(k)), dz = s.z[i] - s.z[j];
      REQUIRE(dx * dx + dz * dz < radius * radius);           // the shift places it within the reach
      across += list.shift(k) != 0.0 ? 1 : 0;
    }
    INFO("particle " << i);
    REQUIRE(got == expected[static_cast<std::size_t>(i)]);
  }
  if (period > 0.0) CHECK(across > 0);  // some pairs really do cross the seam
}

}  // namespace

TEST_CASE("the full list holds every pair closer than the reach from both particles", "[sph][neighbours]") {
  const double radius = 0.05;
  for (const bool clustered : {false, true})
    for (const bool walls_pair_fluid : {true, false}) {
      INFO("clustered " << clustered << ", walls listed " << walls_pair_fluid);
      require_matches_brute_force(sorted_set(1200, 1.0, 0.4, 5u, clustered, radius, false), radius, 0.0, walls_pair_fluid);
    }
}

TEST_CASE("the full list with periodic wrap in x", "[sph][neighbours]") {
  const double radius = 0.05;
  for (const double length : {1.0, 0.16, 0.21})  // 20 columns, 3 (the fewest), 4
    for (const bool clustered : {false, true}) {
      INFO("length " << length << ", clustered " << clustered);
      require_matches_brute_force(sorted_set(900, length, 0.3, 9u, clustered, radius, true), radius, length, true);
    }
}

// The pair loop's thread shares (NeighbourList::slice_begin): for any number of slices they cut the
// particles into consecutive ranges, each with at most its even part of the work (entries plus one
// per particle) plus one particle's.
TEST_CASE("the threads' slices cut the list's work evenly", "[sph][neighbours]") {
  const double radius = 0.05;
  for (const bool clustered : {false, true}) {
    const SortedSet s = sorted_set(1500, 1.0, 0.4, 11u, clustered, radius, false);
    NeighbourList list;
    list.build(s.x, s.z, s.type, s.cells, radius);
    const int n = static_cast<int>(s.x.size());
    const auto work = [&](int first, int last) { return list.begin(last) - list.begin(first) + (last - first); };
    int largest = 0;
    for (int i = 0; i < n; ++i) largest = std::max(largest, work(i, i + 1));
    for (const int slices : {1, 2, 3, 7}) {
      INFO("clustered " << clustered << ", " << slices << " slices");
      CHECK(list.slice_begin(0, slices) == 0);
      CHECK(list.slice_begin(slices, slices) == n);
      for (int k = 0; k < slices; ++k) {
        const int first = list.slice_begin(k, slices), last = list.slice_begin(k + 1, slices);
        REQUIRE(first <= last);
        CHECK(work(first, last) <= work(0, n) / slices + largest + 1);
      }
    }
  }
}
