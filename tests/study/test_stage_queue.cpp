// The study's stage order (app/stage_queue.hpp): the largest task first, every task once, the workers
// taking the next one as they become free.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <random>
#include <set>
#include <vector>

#include "app/stage_queue.hpp"
#include "compare/run_cost.hpp"

using hydrojump::app::run_largest_first;
using hydrojump::compare::largest_first;
using hydrojump::compare::list_schedule_seconds;

TEST_CASE("Stage queue: the largest task first, ties in index order", "[study]") {
  CHECK(largest_first({}).empty());
  CHECK(largest_first({1.0, 5.0, 3.0, 5.0, 0.0}) == std::vector<std::size_t>{1, 3, 2, 0, 4});
}

TEST_CASE("Stage queue: the time of a list schedule", "[study]") {
  // By hand: 5 and 4 start; the 4's worker is free at 4 and takes a 3 (to 7), the 5's at 5 (to 8), the
  // first again at 7 (to 10). (The best split, 5 + 4 against 3 + 3 + 3, takes 9: largest-first is a rule
  // of thumb, not an optimum.)
  const std::vector<double> seconds{3.0, 5.0, 3.0, 4.0, 3.0};
  CHECK(list_schedule_seconds(seconds, largest_first(seconds), 2) == Approx(10.0));
  CHECK(list_schedule_seconds(seconds, largest_first(seconds), 1) == Approx(18.0));
  CHECK(list_schedule_seconds(seconds, largest_first(seconds), 8) == Approx(5.0));
  CHECK(list_schedule_seconds({}, {}, 2) == 0.0);
  // Against a second, plain implementation (each task to the worker free first, by a linear scan).
  std::mt19937 random(3);
  std::uniform_real_distribution<double> size(0.0, 10.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> t(1 + trial % 9);
    for (auto& x : t) x = size(random);
    const int workers = 1 + trial % 4;
    std::vector<double> free_at(static_cast<std::size_t>(workers), 0.0);
    for (const std::size_t k : largest_first(t)) *std::min_element(free_at.begin(), free_at.end()) += t[k];
    CHECK(list_schedule_seconds(t, largest_first(t), workers) == Approx(*std::max_element(free_at.begin(), free_at.end())));
  }
}

TEST_CASE("Stage queue: every task runs once, and the first `workers` run side by side and are the largest", "[study]") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> size(0.0, 10.0);
  for (const int workers : {1, 2, 3, 8}) {
    for (const std::size_t tasks : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{13}}) {
      std::vector<double> work(tasks);
      for (auto& w : work) w = std::floor(size(random));  // repeated values: ties
      // Each task waits (up to 10 s) until as many tasks have started as can run at once: the first
      // ones all run side by side, so they are the ones the queue handed out first.
      const std::size_t at_once = std::min<std::size_t>(static_cast<std::size_t>(workers), tasks);
      std::mutex mutex;
      std::condition_variable all_started;
      std::vector<std::size_t> started;
      run_largest_first(work, workers, [&](std::size_t k) {
        std::unique_lock lock(mutex);
        started.push_back(k);
        all_started.notify_all();
        all_started.wait_for(lock, std::chrono::seconds(10), [&] { return started.size() >= at_once; });
      });
      INFO(workers << " workers, " << tasks << " tasks");
      // Brute-force oracle: each index once, sorted by hand against largest_first.
      std::vector<std::size_t> sorted = started;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::size_t> all(tasks);
      for (std::size_t k = 0; k < tasks; ++k) all[k] = k;
      CHECK(sorted == all);
      const std::vector<std::size_t> order = largest_first(work);
      for (std::size_t k = 1; k < order.size(); ++k) {
        CHECK(work[order[k - 1]] >= work[order[k]]);
        if (work[order[k - 1]] == work[order[k]]) CHECK(order[k - 1] < order[k]);
      }
      // The first `at_once` started are the largest `at_once` (as a set: they start side by side).
      CHECK(std::set<std::size_t>(started.begin(), started.begin() + static_cast<long>(at_once)) ==
            std::set<std::size_t>(order.begin(), order.begin() + static_cast<long>(at_once)));
      if (workers == 1) CHECK(started == order);
    }
  }
}
