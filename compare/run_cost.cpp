#include "compare/run_cost.hpp"

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

}  // namespace hydrojump::compare
