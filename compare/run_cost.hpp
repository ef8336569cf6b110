// The rough size and work of a stilling-basin run, from the case's own inputs: for the estimated wall
// times of the runs not yet recorded (docs/validation.md) and for the order in which `hydrojump study`
// starts its solver stages (the largest first: longest-processing-time-first list scheduling, Graham
// 1969), and the time such a schedule takes.
//
//   size:  SPH  N = L y_t / dx^2                     (the water under the tailwater level)
//          VOF  N = L (y_t + air) / (dz_bed dx_bulk) (the water and the air above it)
//   work:  N T U1 / dx                               (steps ~ T U1 / dx: the sound speed, ~U1, over
//                                                     dx in SPH; the Courant number over the bed
//                                                     cell size in VOF)
// with L the domain's length, y_t the tailwater depth, T the simulated time. Rough counts, for ratios
// between runs of one method.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cases/spec.hpp"

namespace hydrojump::compare {

// N of `b` at resolution `level` for `method` ("sph" or "vof").
double run_size(const cases::StillingBasinCase& b, const cases::Resolution& level, const std::string& method);

// N T U1 / dx of case `c` at `resolution` for `method`; 0 for a case that is not a stilling basin or
// has no such resolution.
double run_work(const cases::Case& c, const std::string& resolution, const std::string& method);

// Task indices 0..n-1 by `work`, largest first; equal work keeps the lower index first.
std::vector<std::size_t> largest_first(const std::vector<double>& work);

// The time `workers` identical workers (at least one) take for tasks lasting `seconds`, each worker
// taking the next task of `order` as soon as it is free (list scheduling): the latest finish.
double list_schedule_seconds(const std::vector<double>& seconds, const std::vector<std::size_t>& order, int workers);

}  // namespace hydrojump::compare
