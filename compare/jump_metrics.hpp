// Hydraulic-jump metrics from the time-averaged results of one method.
//
// Definitions (x positions from the stations, a uniform line of columns along the channel; zeta(x) is
// the time-mean surface elevation above the upstream floor level z_floor, smoothed by a centred running
// mean over `toe_window_y1` * y1):
//   toe x_t      the first x (from the inflow downstream) where zeta > toe_threshold_y1 * y1 and stays
//                above it over the following toe_persistence_y1 * y1. Experience with interFoam runs
//                (study notes, section 5): a bare "first x above 1.5 y1" trips on splashes and air
//                pockets; a ~2 cm running mean that must stay above the threshold for ~5 cm,
//                time-averaged, was stable. Defaults: 1.5 y1, window 0.8 y1, persistence 2 y1
//                (2 cm and 5 cm for y1 = 25.4 mm). The same criterion applied to every frame's
//                instantaneous surface gives the toe's standard deviation over the window and its
//                trend (least-squares slope of the frames' toes against time, m/s; > 0 downstream).
//   y2           sequent depth: time-mean surface at the "downstream" section minus z_floor (depth above
//                the corrugation crests, as measured in the flume). When the toe lies downstream of that
//                section (a jump swept downstream), or no toe is found at all, y2, E2, eta, M2, the bed
//                force, Lr and Lj are NaN with a note. When the toe is at the search start (the "upstream"
//                section: the mean surface already stands above the threshold there, the jump reaches
//                it), E1, eta, M1, the bed force, Lr and Lj are NaN with a note; frames whose toe is at
//                the search start are counted (toe_frames_at_search_start) and named in a note.
//   roller end   the last x in (x_t, x_down] where the time-mean near-surface velocity u(eta - 0.1 h) is
//                negative ("end of the reverse surface flow"); Lr = x_roller - x_t. NaN (with a note)
//                when no reverse surface flow is found.
//   jump end     the first x >= x_roller (x >= x_t without a roller) from which zeta stays within
//                settle_tolerance * (y2 - y1) of y2 up to the downstream section ("the surface has
//                settled"); Lj = x_end - x_t. The experiments' sections lie in the order toe (1-1),
//                roller end (2-2), settled surface (3-3) (Bo et al. 2019, Fig. 7), so Lj >= Lr: a flat
//                roller whose mean surface is already inside the band ends the jump at the roller end.
//   eta          (E1 - E2)/E1 with E = z_b + h + alpha U^2/(2g) time-averaged at the "upstream" (E1)
//                and "downstream" (E2) sections; eta_alpha1 the same with alpha = 1 (the laboratory
//                convention E = y + U^2/(2g)); eta_crest_depth with E = y + q^2/(2 g y^2), y the mean
//                surface above the floor/crest level and q the section's mean discharge (how the
//                experiments' values were computed; it differs from eta when a section lies over a trough).
//   bed force    the momentum balance between the "upstream" and "downstream" sections: with the
//                specific force M = h^2/2 + beta q^2/(g h) (time mean of each frame's value, h above
//                the local bed), bed_force_fraction = (M1 - M2)/M1 is the share of the upstream force
//                the bed (and the walls) took between the sections. Belanger's jump on a frictionless
//                smooth bed has M1 = M2 (0); the corrugations' drag makes it positive, which is why
//                they hold a jump at a lower tailwater. A jump that drifts upstream in a run shows
//                M2 > M1 at the sections (negative): more force downstream than the inflow can carry.
//   jet height   at the section "x_2y2" (two tailwater depths past the basin start), the height of the
//                time-mean maximum forward velocity above the bed over the mean depth there. A jump is a
//                wall jet under a surface roller (Rajaratnam 1965, The hydraulic jump as a wall jet,
//                J. Hydraul. Div. 91(HY5)): the fastest forward flow stays near the bed, a small
//                fraction; a surface jet over reverse flow at the bed puts it near 1. Heights where
//                fewer than half the frames had water do not count.
//   wall jet     at the same section, the RMS deviation of the time-mean profile u/u_m from the plane
//                wall jet's (Verhoff 1963) up to the half-velocity height (jump_structure.hpp).
//   velocity decay  u_max(x)/U1 and U(x)/U1 along the stations from the toe; the settling distance is
//                the first x - x_t from which u_max stays within 10 % of its value at the downstream
//                section.
#pragma once

#include <string>
#include <vector>

#include "compare/time_statistics.hpp"

namespace hydrojump::compare {

struct JumpMetricOptions {
  double toe_threshold_y1 = 1.5;
  double toe_window_y1 = 0.8;
  double toe_persistence_y1 = 2.0;
  double settle_tolerance = 0.05;
  double velocity_settle_tolerance = 0.10;
  double surface_peak_tolerance = 0.2;  // a mean surface above (1 + this) y2 is reported as a standing wave
};

struct JumpInputs {
  double inflow_depth_m = 0.0;         // y1
  double inflow_velocity_m_s = 0.0;    // U1
  double floor_z_m = 0.0;              // upstream floor (= corrugation crest) level
  double gravity_m_s2 = 9.81;
  JumpMetricOptions options;
};

struct JumpMetrics {
  double toe_x_m = not_a_number;
  double toe_mean_of_frames_x_m = not_a_number;  // the toe criterion on each frame's surface: mean,
  double toe_std_m = not_a_number;              // standard deviation (steadiness of the jump)
  int toe_frames_found = 0;                     // and the number of frames with a toe,
  int toe_frames_at_search_start = 0;           // of which at the upstream section (the roller reaches it)
  double toe_trend_m_per_s = not_a_number;      // least-squares slope of the frames' toes over time
  // The run's water balance over the window, from its own discharge records (case_comparison.hpp's
  // RunBalance): (outflow - inflow) / q, and steady by the window means (1), not (0), unknown (NaN).
  double window_imbalance = not_a_number;
  double steady_by_means = not_a_number;
  std::vector<double> toe_frames_x_m;           // each frame's toe (NaN: none), aligned with the frames' times
  double sequent_depth_m = not_a_number;       // y2
  double sequent_depth_std_m = not_a_number;
  double upstream_depth_m = not_a_number;      // depth at the upstream section (check against y1)
  double jump_end_x_m = not_a_number;
  double jump_length_m = not_a_number;         // Lj
  double roller_end_x_m = not_a_number;
  double roller_length_m = not_a_number;       // Lr
  double e1_m = not_a_number, e2_m = not_a_number;
  double eta = not_a_number;                   // fraction
  double eta_alpha1 = not_a_number;            // fraction, alpha = 1
  double eta_crest_depth = not_a_number;       // fraction, laboratory convention (see above)
  double specific_force_upstream_m2 = not_a_number;    // M1
  double specific_force_downstream_m2 = not_a_number;  // M2
  double bed_force_fraction = not_a_number;    // (M1 - M2)/M1
  double velocity_settling_distance_m = not_a_number;
  double jet_height_fraction = not_a_number;    // z(u_max) above the bed / depth at section x_2y2
  double wall_jet_deviation = not_a_number;     // its profile against Verhoff's wall jet (jump_structure.hpp)
  double surface_peak_m = not_a_number;         // highest time-mean depth above the floor from the toe to
  double surface_peak_x_m = not_a_number;       // the downstream section (running mean), and where
  std::vector<std::string> notes;              // why a metric is missing
};

// E at a section with the time-mean values: z_b + h + alpha U^2/(2g) (alpha = 1 if `alpha_one`).
double section_energy(const ColumnStatistics& s, double gravity, bool alpha_one);

// eta = (E1 - E2) / E1
double dissipation_rate(double e1, double e2);

// M = h^2/2 + q^2/(g h): the specific force of a uniform section (beta = 1), m^2.
double specific_force(double depth_m, double discharge_m2_s, double gravity_m_s2);

// Index of the toe station by the criterion above (cases/jump_toe.hpp) on the surface zeta(x) above the floor (x evenly
// spaced), searching from x_from on; x.size() when there is none.
std::size_t find_toe(const std::vector<double>& x, const std::vector<double>& zeta, double x_from,
                     const JumpInputs& in);

JumpMetrics compute_jump_metrics(const MethodStatistics& m, const JumpInputs& in);

}  // namespace hydrojump::compare
