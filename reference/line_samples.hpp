// Reading what the `sections` function object of a generated case wrote
// (postProcessing/sections/<time>/<line>_alpha.water.xy, raw format: coordinate along the line, value)
// and the two quantities the VOF reference needs directly from it:
//
//   water depth along a vertical line        h = integral of alpha.water dz  (trapezoidal rule)
//   surge front along the floor line         the largest x reached by water (alpha >= 0.5) that is
//                                            connected to the water at the start of the line
//                                            through dry gaps no longer than `max_gap_m`
//
// (The comparator samples the full fields itself; these are for the runner's own checks, the tests
// and quick looks.)
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace hydrojump::reference {

struct LineSample {
  std::vector<double> position_m;   // coordinate along the line (y for vertical lines, x for the floor)
  std::vector<double> alpha;        // alpha.water
};

// Reads a raw `.xy` file with two columns. Throws std::runtime_error naming the file if it cannot be
// read or has no data.
LineSample read_line_sample(const std::filesystem::path& file);

// h = integral of alpha d(position) over the line.
double water_depth(const LineSample& line);

// The furthest wet position connected to the start of the line (nothing if the start is dry).
std::optional<double> surge_front(const LineSample& line, double max_gap_m);

}  // namespace hydrojump::reference
