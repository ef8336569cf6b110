#include "compare/jump_structure.hpp"

#include <cmath>

namespace hydrojump::compare {

// Lj = 6 y2*
double usbr_jump_length(double belanger_sequent_depth_m, double froude_number) {
  if (!(belanger_sequent_depth_m > 0.0) || !(froude_number >= 4.0 && froude_number <= 20.0)) return not_a_number;
  return 6.0 * belanger_sequent_depth_m;
}

// u / u_m = 1.48 eta^(1/7) [1 - erf(0.68 eta)]
double wall_jet_profile(double eta) {
  if (!(eta >= 0.0)) return not_a_number;
  return 1.48 * std::pow(eta, 1.0 / 7.0) * (1.0 - std::erf(0.68 * eta));
}

namespace {

bool usable(const ColumnStatistics& s, std::size_t i) {
  return i < s.u_mean.size() && i < s.wet_fraction.size() && s.wet_fraction[i] >= 0.5 && std::isfinite(s.u_mean[i]);
}

}  // namespace

WallJetFit fit_wall_jet(const ColumnStatistics& s) {
  WallJetFit fit;
  std::size_t best = s.z.size();
  for (std::size_t i = 0; i < s.z.size(); ++i)
    if (usable(s, i) && (best == s.z.size() || s.u_mean[i] > s.u_mean[best])) best = i;
  if (best == s.z.size()) return fit;
  const double um = s.u_mean[best], z_bed = s.spec.z_bed_m;
  fit.max_velocity_m_s = um;
  fit.max_height_m = s.z[best] - z_bed;
  if (!(um > 0.0)) return fit;  // no forward flow: no half-velocity height
  // delta: the first height above u_m where u falls to u_m / 2 (linear between the grid heights).
  std::size_t below = best;
  for (std::size_t i = best + 1; i < s.z.size(); ++i) {
    if (!usable(s, i)) continue;
    if (s.u_mean[i] <= 0.5 * um) {
      const double t = (s.u_mean[below] - 0.5 * um) / (s.u_mean[below] - s.u_mean[i]);
      fit.half_velocity_height_m = s.z[below] + t * (s.z[i] - s.z[below]) - z_bed;
      break;
    }
    below = i;
  }
  if (!(fit.half_velocity_height_m > 0.0)) return fit;
  // RMS of u/u_m - f(eta) over 0 < eta <= 1
  double ss = 0.0;
  for (std::size_t i = 0; i < s.z.size(); ++i) {
    const double eta = (s.z[i] - z_bed) / fit.half_velocity_height_m;
    if (!usable(s, i) || !(eta > 0.0) || eta > 1.0) continue;
    const double d = s.u_mean[i] / um - wall_jet_profile(eta);
    ss += d * d;
    ++fit.points;
  }
  if (fit.points > 0) fit.deviation = std::sqrt(ss / fit.points);
  return fit;
}

bool classic_structure(double jet_height_fraction, double wall_jet_deviation) {
  return jet_height_fraction < classic_jet_height_limit && wall_jet_deviation <= classic_wall_jet_deviation_limit;
}

}  // namespace hydrojump::compare
