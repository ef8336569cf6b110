#include "cases/hydraulics.hpp"

#include <cmath>

namespace hydrojump::cases {

// q = y U
double unit_discharge(double depth_m, double velocity_m_s) { return depth_m * velocity_m_s; }

// Fr = U / sqrt(g y)
double froude_number(double depth_m, double velocity_m_s, double gravity_m_s2) {
  return velocity_m_s / std::sqrt(gravity_m_s2 * depth_m);
}

// y2* = y1/2 (sqrt(1 + 8 Fr1^2) - 1)
double belanger_sequent_depth(double y1_m, double froude1) {
  return 0.5 * y1_m * (std::sqrt(1.0 + 8.0 * froude1 * froude1) - 1.0);
}

// E = y + q^2 / (2 g y^2)
double specific_energy(double depth_m, double discharge_m2_s, double gravity_m_s2) {
  return depth_m + discharge_m2_s * discharge_m2_s / (2.0 * gravity_m_s2 * depth_m * depth_m);
}

// eta = (E1 - E2) / E1
double energy_dissipation_rate(double e1_m, double e2_m) { return (e1_m - e2_m) / e1_m; }

JumpHydraulics jump_hydraulics(double y1_m, double u1_m_s, double tailwater_m, double gravity_m_s2) {
  JumpHydraulics j;
  j.discharge_m2_s = unit_discharge(y1_m, u1_m_s);
  j.froude1 = froude_number(y1_m, u1_m_s, gravity_m_s2);
  j.belanger_y2_m = belanger_sequent_depth(y1_m, j.froude1);
  j.e1_m = specific_energy(y1_m, j.discharge_m2_s, gravity_m_s2);
  j.e2_m = specific_energy(tailwater_m, j.discharge_m2_s, gravity_m_s2);
  j.eta = energy_dissipation_rate(j.e1_m, j.e2_m);
  j.eta_smooth = energy_dissipation_rate(
      j.e1_m, specific_energy(j.belanger_y2_m, j.discharge_m2_s, gravity_m_s2));
  return j;
}

}  // namespace hydrojump::cases
