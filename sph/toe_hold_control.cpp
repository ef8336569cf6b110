#include "sph/toe_hold_control.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cases/hydraulics.hpp"

namespace hydrojump::sph {

ToeHoldLaw ToeHoldLaw::from_case(const cases::Case& c, const cases::CaseGeometry& geometry, double gravity_m_s2,
                                  double rho0) {
  ToeHoldLaw law;
  law.gains = cases::toe_hold_gains(c, geometry);
  const cases::ToeHoldGains& g = law.gains;
  const cases::InflowBoundary& in = geometry.inflows.front();
  // S = (c_t^2 - U_t^2) / (2 c_t)
  const double u_t = cases::unit_discharge(in.depth_m, in.velocity_m_s) / g.tailwater_depth_m;
  const double c_t = std::sqrt(gravity_m_s2 * g.tailwater_depth_m);
  law.outlet_gain_m_s = (c_t * c_t - u_t * u_t) / (2.0 * c_t);
  law.interval_s = c.run.output_interval_s;
  law.volume_hold_time_s = c.stilling_basin()->control.volume_hold_time_s;
  law.rho0 = rho0;
  if (!(g.outlet_x_m > g.target_toe_x_m) || !(g.tailwater_depth_m > g.inflow_depth_m))
    throw std::invalid_argument("case \"" + c.id + "\": the toe-holding control needs the basin start upstream of the "
                                "outlet and a tailwater deeper than the inflow");
  if (!(law.outlet_gain_m_s > 0.0))
    throw std::invalid_argument("case \"" + c.id + "\": the toe-holding control needs a subcritical tailwater (U_t = " +
                                std::to_string(u_t) + " m/s against sqrt(g y2*) = " + std::to_string(c_t) + " m/s)");
  return law;
}

ToeHoldState toe_hold_step(const ToeHoldLaw& law, double volume_integral_m2, double water_mass_kg_per_m,
                           double toe_x_m) {
  const double volume = water_mass_kg_per_m / law.rho0;
  const double y2 = law.gains.tailwater_depth_m;
  ToeHoldState next;
  if (volume_integral_m2 == 0.0) {  // the first output: I(0) = V(0) - P(0), V*(0) = V(0)
    next.volume_integral_m2 = volume - cases::toe_hold_proportional(law.gains, toe_x_m);
    next.volume_target_m2 = volume;
    next.outlet_depth_m = y2;
    return next;
  }
  const cases::VolumeTarget target = cases::toe_hold_volume_target(law.gains, volume_integral_m2, toe_x_m, law.interval_s);
  next.volume_integral_m2 = target.integral_m2;
  next.volume_target_m2 = target.volume_target_m2;
  // y_t(n) = y2* - (V - V*) / (T_V S), within [y2*/2, 3 y2*/2]
  const double depth = y2 - (volume - next.volume_target_m2) / (law.volume_hold_time_s * law.outlet_gain_m_s);
  next.outlet_depth_m = std::clamp(depth, 0.5 * y2, 1.5 * y2);
  return next;
}

}  // namespace hydrojump::sph
