#include "compare/run_cost.hpp"

#include <algorithm>
#include <functional>
#include <numeric>
#include <queue>

namespace hydrojump::compare {

double run_size(const cases::StillingBasinCase& b, const cases::Resolution& level, const std::string& method) {
  const double length = b.upstream_length_m + b.basin_length_m + b.downstream_length_m;
  if (method == "sph") return length * b.tailwater_depth_m / (level.particle_spacing_m * level.particle_spacing_m);
  return length * (b.tailwater_depth_m + b.air_height_m) / (level.vof_cell_size_bed_m * level.vof_cell_size_bulk_m);
}

double run_work(const cases::Case& c, const std::string& resolution, const std::string& method) {
  const auto* b = c.stilling_basin();
  const auto level = c.resolutions.find(resolution);
  if (b == nullptr || level == c.resolutions.end()) return 0.0;
  const double dx = method == "sph" ? level->second.particle_spacing_m : level->second.vof_cell_size_bed_m;
  return run_size(*b, level->second, method) * c.run.end_time_s * b->inflow_velocity_m_s / dx;
}

std::vector<std::size_t> largest_first(const std::vector<double>& work) {
  std::vector<std::size_t> order(work.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return work[a] > work[b]; });
  return order;
}

double list_schedule_seconds(const std::vector<double>& seconds, const std::vector<std::size_t>& order, int workers) {
  // The workers' finish times, the earliest on top: the next task goes to the worker free first.
  std::priority_queue<double, std::vector<double>, std::greater<>> free_at;
  for (int w = 0; w < std::max(1, workers); ++w) free_at.push(0.0);
  double end = 0.0;
  for (const std::size_t k : order) {
    const double finish = free_at.top() + seconds.at(k);
    free_at.pop();
    free_at.push(finish);
    end = std::max(end, finish);
  }
  return end;
}

}  // namespace hydrojump::compare
