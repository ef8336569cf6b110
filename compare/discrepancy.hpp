// Discrepancies between the two methods and against the laboratory (and published SPH) values.
//
//   surface      time-mean free surface of SPH minus VOF at the stations on the basin (both wet):
//                RMS and maximum absolute difference (and where it occurs)
//   profiles     at each section, the L2 (root-mean-square) difference of the time-mean u(z) over the
//                heights that are under water in at least half of the frames of both methods (the VOF
//                profile linearly interpolated onto the SPH heights); also relative to U1
//   metrics      y2, Lj, Lr, eta (and toe, upstream depth): SPH, VOF, experiment, published SPH side
//                by side; the report shows the differences
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compare/jump_metrics.hpp"
#include "compare/time_statistics.hpp"

namespace hydrojump::compare {

struct SurfaceDifference {
  double rms_m = not_a_number;
  double max_abs_m = not_a_number;
  double x_of_max_m = not_a_number;
  int n_stations = 0;
};

struct ProfileDifference {
  std::string section;
  double x_m = 0.0;
  double l2_m_s = not_a_number;
  double l2_over_u1 = not_a_number;
  int n_points = 0;
};

// One quantity side by side; NaN where a value does not exist.
// A row of the metric table. `smooth_theory` is what the inputs alone give: Bélanger's y2* (sequent
// depth), eta* (eta), 1 (the bed effect y2/y2*), 0 (the bed force). `status` says whether the set-up
// held the quantity ("imposed": the toe under the toe-holding control; y2 and what follows from it,
// eta and the bed force, when the outlet holds a depth) or the methods predicted it ("predicted").
struct MetricRow {
  std::string quantity;        // "sequent_depth", "jump_length", "roller_length", "eta", ...
  std::string unit;            // "m", "%"
  double sph = not_a_number, vof = not_a_number, experiment = not_a_number,
         published_sph = not_a_number, smooth_theory = not_a_number;
  std::string status = "predicted";  // "predicted" | "imposed" | "input" | "check" (of the run: balance, steadiness)
};

struct MeasuredReference {
  std::optional<double> sequent_depth_m, jump_length_m, roller_length_m, eta_percent,
      eta_smooth_percent, published_sph_eta_percent;
};

// Both arguments may be null (a method without results). x range [x_from, x_to] limits the surface
// comparison (the basin).
SurfaceDifference surface_difference(const MethodStatistics& sph, const MethodStatistics& vof, double x_from,
                                     double x_to);
std::vector<ProfileDifference> profile_differences(const MethodStatistics& sph, const MethodStatistics& vof,
                                                   double u1);
// The inflow (y1, U1) and g give the experiment's bed force: (M1 - M2)/M1 with uniform sections at y1
// and at the measured y2 (M = h^2/2 + q^2/(g h)), the force balance Ead & Rajaratnam's shear-force
// coefficient comes from.
// `toe_held`: the case's tailwater control holds the toe at the basin start ([case.tailwater] control
// = "hold_toe"), so the toe is imposed and y2 predicted; otherwise the outlet holds a depth, and y2 is
// imposed while the toe is predicted.
std::vector<MetricRow> metric_table(const JumpMetrics* sph, const JumpMetrics* vof, const MeasuredReference& lab,
                                    double inflow_depth_m, double inflow_velocity_m_s, double gravity_m_s2,
                                    bool toe_held);

}  // namespace hydrojump::compare
