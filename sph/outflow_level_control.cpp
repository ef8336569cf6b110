#include "sph/outflow_level_control.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sph/basin_monitor.hpp"

namespace hydrojump::sph {

OutflowLevelControl::OutflowLevelControl(double section_x_m, double target_depth_m, double time_constant_s,
                                         double column_width_m)
    : section_x_(section_x_m),
      target_depth_(target_depth_m),
      time_constant_(time_constant_s),
      column_width_(column_width_m) {
  if (!(target_depth_m > 0.0) || !(time_constant_s > 0.0) || !(column_width_m > 0.0) || !std::isfinite(section_x_m))
    throw std::invalid_argument("outflow level control: the target depth (" + std::to_string(target_depth_m) +
                                " m), integral time (" + std::to_string(time_constant_s) + " s) and column width (" +
                                std::to_string(column_width_m) + " m) must be positive and the section finite");
}

// y_t <- clamp(y_t - (dt_c / T_c) (h_s - y2), 0.5 y2, 1.5 y2)
double OutflowLevelControl::next_outlet_depth(double outlet_depth_m, double section_depth_m) const {
  const double y = outlet_depth_m - control_interval_s / time_constant_ * (section_depth_m - target_depth_);
  return std::clamp(y, 0.5 * target_depth_, 1.5 * target_depth_);
}

std::optional<double> OutflowLevelControl::update(const ParticleSet& particles, double t, double dt,
                                                  double outlet_depth_m) const {
  // A control instant k dt_c in (t, t + dt]?
  if (std::floor((t + dt) / control_interval_s) <= std::floor(t / control_interval_s)) return std::nullopt;
  const double h_s = BasinMonitor::columns(particles, std::vector<double>{section_x_}, column_width_).front().depth;
  return next_outlet_depth(outlet_depth_m, h_s);
}

}  // namespace hydrojump::sph
