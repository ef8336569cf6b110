// The order in which `hydrojump study` runs its solver stages: the largest first, so that no long
// stage is left to run alone at the end while the other workers idle (longest-processing-time-first
// scheduling, Graham 1969; the study orders by an estimate of each case's work, not each stage's own
// time, so Graham's 4/3 bound on the total time is not claimed).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace hydrojump::app {

// Runs tasks 0..n-1 on `workers` threads (at least one; no more than there are tasks), each thread
// taking the next task of compare::largest_first(work) as it becomes free; returns when all have run. `run(k)`
// runs task k and must not throw.
void run_largest_first(const std::vector<double>& work, int workers, const std::function<void(std::size_t)>& run);

}  // namespace hydrojump::app
