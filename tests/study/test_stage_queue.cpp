// The study's stage order (app/stage_queue.hpp): the largest task first, every task once, the workers
// taking the next one as they become free.
#include <catch2/catch.hpp>

#include <algorithm>
#include <mutex>
#include <random>
#include <vector>

#include "app/stage_queue.hpp"

using hydrojump::app::largest_first;
using hydrojump::app::run_largest_first;

TEST_CASE("Stage queue: the largest task first, ties in index order", "[study]") {
  CHECK(largest_first({}).empty());
  CHECK(largest_first({1.0, 5.0, 3.0, 5.0, 0.0}) == std::vector<std::size_t>{1, 3, 2, 0, 4});
}

TEST_CASE("Stage queue: every task runs once on any number of workers, and one worker runs them largest first",
          "[study]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> size(0.0, 10.0);
  for (const int workers : {1, 2, 3, 8}) {
    for (const std::size_t tasks : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{13}}) {
      std::vector<double> work(tasks);
      for (auto& w : work) w = std::floor(size(random));  // repeated values: ties
      std::mutex mutex;
      std::vector<std::size_t> started;
      run_largest_first(work, workers, [&](std::size_t k) {
        const std::lock_guard lock(mutex);
        started.push_back(k);
      });
      INFO(workers << " workers, " << tasks << " tasks");
      // Brute-force oracle: each index once, and the starts never go from a smaller task to a larger one.
      std::vector<std::size_t> sorted = started;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::size_t> all(tasks);
      for (std::size_t k = 0; k < tasks; ++k) all[k] = k;
      CHECK(sorted == all);
      if (workers == 1) CHECK(started == largest_first(work));
      for (std::size_t k = 1; k < started.size() && workers == 1; ++k) CHECK(work[started[k - 1]] >= work[started[k]]);
    }
  }
}
