#include "cases/hydraulics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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

// Lr / y1 = -12 + 160 tanh(Fr1 / 20)
double hager_roller_length(double inflow_depth_m, double froude_number) {
  if (!(inflow_depth_m > 0.0) || !(froude_number >= 2.5 && froude_number <= 20.0))
    return std::numeric_limits<double>::quiet_NaN();
  return inflow_depth_m * (-12.0 + 160.0 * std::tanh(froude_number / 20.0));
}

// Y = tanh(1.5 X), 0 upstream of the toe
double roller_surface_fraction(double x_over_roller_length) {
  return x_over_roller_length > 0.0 ? std::tanh(1.5 * x_over_roller_length) : 0.0;
}

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

double solve_increasing(const std::function<double(double)>& f, double target, double lo, double hi,
                        double rel_tol) {
  const double width = hi - lo;
  for (int k = 0; k < 200 && hi - lo > rel_tol * width; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// q = 2/3 (0.611 + 0.08 H/P) sqrt(2 g) H^(3/2)
double rehbock_weir_discharge(double head_m, double weir_height_m, double gravity_m_s2) {
  if (!(head_m > 0.0)) return 0.0;
  const double cd = 0.611 + 0.08 * head_m / weir_height_m;
  return 2.0 / 3.0 * cd * std::sqrt(2.0 * gravity_m_s2) * std::pow(head_m, 1.5);
}

// H with rehbock_weir_discharge(H, P) = q, by bisection (the discharge grows monotonically with H).
double rehbock_weir_head(double discharge_m2_s, double weir_height_m, double gravity_m_s2) {
  if (!(discharge_m2_s > 0.0) || !(weir_height_m > 0.0) || !(gravity_m_s2 > 0.0))
    throw std::invalid_argument("weir head: discharge, weir height and gravity must be positive (q = " +
                                std::to_string(discharge_m2_s) + " m^2/s, P = " + std::to_string(weir_height_m) + " m)");
  // Cd >= 0.611 bounds H from above: H <= (3 q / (2 0.611 sqrt(2 g)))^(2/3).
  const double hi = std::pow(1.5 * discharge_m2_s / (0.611 * std::sqrt(2.0 * gravity_m_s2)), 2.0 / 3.0);
  return solve_increasing([&](double h) { return rehbock_weir_discharge(h, weir_height_m, gravity_m_s2); },
                          discharge_m2_s, 0.0, hi);
}

// P with P + H(q, P) = y, by bisection on 0 < P < y.
double tailgate_height_for_depth(double discharge_m2_s, double upstream_depth_m, double gravity_m_s2) {
  if (!(discharge_m2_s > 0.0) || !(upstream_depth_m > 0.0))
    throw std::invalid_argument("tailgate height: discharge and upstream depth must be positive (q = " +
                                std::to_string(discharge_m2_s) + " m^2/s, y = " + std::to_string(upstream_depth_m) + " m)");
  return solve_increasing([&](double p) { return p + rehbock_weir_head(discharge_m2_s, p, gravity_m_s2); },
                          upstream_depth_m, 0.0, upstream_depth_m);
}

}  // namespace hydrojump::cases
