// Oracles of the neighbour-search tests (test_cell_list.cpp, test_neighbour_list.cpp): random and
// clustered point sets, and the brute-force O(N^2) pair search they are checked against.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include <Eigen/Core>

namespace neighbour_test {

using PairSet = std::set<std::pair<int, int>>;

inline PairSet brute_force(const Eigen::VectorXd& x, const Eigen::VectorXd& z, double radius, double period) {
  PairSet pairs;
  for (int i = 0; i < x.size(); ++i)
    for (int j = 0; j < x.size(); ++j) {
      double dx = x[i] - x[j];
      if (period > 0.0) dx -= period * std::round(dx / period);  // minimum image
      const double dz = z[i] - z[j];
      if (dx * dx + dz * dz < radius * radius) pairs.insert({i, j});
    }
  return pairs;
}

inline std::pair<Eigen::VectorXd, Eigen::VectorXd> random_set(int n, double lx, double lz, unsigned seed, bool clustered) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> ux(0.0, lx), uz(0.0, lz);
  std::normal_distribution<double> spread(0.0, 0.02);
  Eigen::VectorXd x(n), z(n);
  for (int i = 0; i < n; ++i) {
    if (clustered && i % 4 != 0) {
      // Clumps around 5 centres (some near the x edges to exercise the seam), plus exact duplicates.
      const int c = i % 5;
      const double cx = c == 0 ? 0.001 : (c == 1 ? lx - 0.001 : 0.2 * c * lx);
      x[i] = std::clamp(cx + spread(gen), 0.0, std::nextafter(lx, 0.0));
      z[i] = std::clamp(0.5 * lz + spread(gen), 0.0, lz);
      if (i % 17 == 0 && i > 0) { x[i] = x[i - 1]; z[i] = z[i - 1]; }
    } else {
      x[i] = ux(gen);
      z[i] = uz(gen);
    }
  }
  return {x, z};
}

}  // namespace neighbour_test
