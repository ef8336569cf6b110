// The jump toe: one definition for every method (the SPH run monitor, the comparator).
//
// Given the free-surface elevation zeta(x) above the upstream floor (= corrugation crest) level at
// uniformly spaced stations x_0 < x_1 < ..., the toe is the first station x_i >= x_from where the
// running mean of zeta over a centred window of `window_y1` y1 exceeds `threshold_y1` y1 and stays
// above it over the following `persistence_y1` y1:
//
//   x_toe = min { x_i >= x_from : zbar(x_k) > threshold_y1 y1  for all x_k in [x_i, x_i + persistence_y1 y1] }
//
// A bare "first x above 1.5 y1" trips on splashes and air pockets in the roller; the running mean
// (about 2 cm for y1 = 25.4 mm) with a persistence of about 5 cm was stable in trial interFoam runs
// (shared/reference/study-notes.md, section 5).
//
// Usage
//   | field           | default | meaning                                      |
//   |-----------------|---------|----------------------------------------------|
//   | threshold_y1    | 1.5     | surface rise that marks the jump, in y1      |
//   | window_y1       | 0.8     | running-mean window, in y1                   |
//   | persistence_y1  | 2.0     | how far the rise must persist, in y1         |
// Example:
//   const std::size_t i = cases::find_jump_toe(x, zeta, x_upstream, y1, cases::ToeCriterion{});
//   if (i < x.size()) toe_x = x[i];
#pragma once

#include <cstddef>
#include <vector>

namespace hydrojump::cases {

struct ToeCriterion {
  double threshold_y1 = 1.5;
  double window_y1 = 0.8;
  double persistence_y1 = 2.0;
};

// Running mean of `v` over a centred window of `half_width` samples each side (NaNs skipped; NaN
// where the window holds no finite value).
std::vector<double> running_mean(const std::vector<double>& v, int half_width);

// Index of the toe station, or x.size() if there is none (see above). `x` uniformly spaced.
std::size_t find_jump_toe(const std::vector<double>& x, const std::vector<double>& zeta, double x_from, double y1,
                          const ToeCriterion& criterion);

}  // namespace hydrojump::cases
