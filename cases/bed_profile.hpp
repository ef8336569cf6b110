// Bed profile z_b(x) of a stilling basin: a horizontal floor at z = 0 with an optional sinusoidal
// corrugated reach sunk below it, crests level with the floor (Ead & Rajaratnam 2002):
//
//   z_b(x) = -T/2 * (1 - cos(2 pi (x - x0) / S))    for x0 <= x <= x1,   0 elsewhere,
//
// with S the wavelength, T the trough-to-crest height and [x0, x1] a whole number of wavelengths.
// A smooth bed is the same object with T = 0.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace hydrojump::cases {

class BedProfile {
 public:
  BedProfile() = default;
  // A flat floor at z = floor_z_m.
  static BedProfile flat(double floor_z_m = 0.0);
  // A floor at z = 0 with corrugations of wavelength S and height T over [reach_start, reach_end].
  static BedProfile sinusoidal(double wavelength_m, double height_m, double reach_start_m,
                               double reach_end_m);

  double elevation(double x) const;  // z_b(x)
  double slope(double x) const;      // dz_b/dx
  // Unit normal pointing up out of the bed into the fluid:  n = (-z_b', 1) / sqrt(1 + z_b'^2).
  Eigen::Vector2d normal(double x) const;
  double lowest_elevation() const;   // trough level (floor level for a flat bed)
  bool corrugated() const { return height_m_ > 0.0; }
  double wavelength_m() const { return wavelength_m_; }
  double height_m() const { return height_m_; }
  double reach_start_m() const { return reach_start_m_; }
  double reach_end_m() const { return reach_end_m_; }

  // Arc length of the bed between x_a and x_b (x_a <= x_b), by adaptive Simpson quadrature.
  double arc_length(double x_a, double x_b) const;
  // Points along the bed from x_a to x_b spaced `spacing_m` apart in arc length (the last gap is
  // stretched or shrunk evenly so both ends are included). Used for boundary particles.
  std::vector<Eigen::Vector2d> points_by_arc_length(double x_a, double x_b, double spacing_m) const;
  // Polyline vertices that follow the bed within `max_deviation_m` (for walls and meshes).
  std::vector<Eigen::Vector2d> polyline(double x_a, double x_b, double max_deviation_m) const;

 private:
  double floor_z_m_ = 0.0;
  double wavelength_m_ = 0.0;
  double height_m_ = 0.0;
  double reach_start_m_ = 0.0;
  double reach_end_m_ = 0.0;
};

}  // namespace hydrojump::cases
