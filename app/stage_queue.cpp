#include "app/stage_queue.hpp"

#include "compare/run_cost.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

namespace hydrojump::app {

void run_largest_first(const std::vector<double>& work, int workers, const std::function<void(std::size_t)>& run) {
  const std::vector<std::size_t> order = compare::largest_first(work);
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t k = next++; k < order.size(); k = next++) run(order[k]);
  };
  const int threads = std::clamp<int>(workers, 1, std::max<int>(1, static_cast<int>(order.size())));
  std::vector<std::jthread> pool;  // joined however this returns
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
}

}  // namespace hydrojump::app
