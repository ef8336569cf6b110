// The dam-break surge front against the measured one (Koshizuka & Oka 1996), in the experiment's
// time origin.
//
// Why a time shift. The experiment's gate took a finite time to lift, so its water starts later than
// a column released at once (both solvers here remove the gate at t = 0). The first measured point and
// the late front speed agree with the simulations, but from t ~ 0.2 s on the simulated front leads by
// 0.2-0.3 L, and the lead grows with resolution: the signature of a late start, not of wrong dynamics.
// Published comparisons handle it by moving the time origin: the experiment's clock started before its
// water was released, so its state at t_exp is the instantly released model's at an earlier time. In
// the dimensionless time tau = t sqrt(2 g / L) the correction is 0.175 (the Lethe CFD project's
// dam-break example against Martin & Moyce 1952 plots the simulation at tau + 0.175; an interFoam
// validation uses the same shift and reaches a mean error of 3 %), so
//
//   t_model = t_exp - dt_gate,     dt_gate = 0.175 sqrt(L / (2 g))     (0.0395 s at L = 1 m)
//
// i.e. the model's time axis moved by +dt_gate onto the experiment's clock. (The sign follows from the
// data: the instantly released front leads, so the model is read at an earlier time.)
// The unshifted comparison (dt_gate = 0) is computed beside it and printed, so the size of the
// correction stays visible.
//
// What is compared. The simulated front x(t) (any sampling; linear interpolation in between) at the
// model time of each measured point; the measured table's times are at L = 1 m and are scaled with
// sqrt(L / 1 m) (Froude similarity). A point counts while the measured front is inside the tank and
// the simulated one short of the far wall by `wall_margin_m` (one particle spacing or cell: a front
// that has reached the wall has no position), and while its model time lies within the simulated
// series. The late front speed is the least-squares slope over the points after
// 0.4 s sqrt(L / 1 m), simulated against measured.
//
// Usage
//   | function                     | returns                                                      |
//   |------------------------------|--------------------------------------------------------------|
//   | gate_opening_time_shift_s    | dt_gate = 0.175 sqrt(L / (2 g))                              |
//   | read_measured_front          | the rows of a t_s,x_front_over_L table (throws naming file)  |
//   | compare_front                | mean and max |x_sim - x_exp| / L, first-point error, speed   |
// Example:
//   const auto measured = compare::read_measured_front(run / "sph/dam_break_front.csv");
//   const auto shifted = compare::compare_front(trace, measured, {1.0, 4.0, 0.02,
//                                               compare::gate_opening_time_shift_s(1.0, 9.81)});
#pragma once

#include <filesystem>
#include <vector>

namespace hydrojump::compare {

// Delta tau of the experiment's time origin (tau = t sqrt(2 g / L)).
inline constexpr double gate_opening_time_shift_tau = 0.175;
// The measured table's column width: its times are at this scale.
inline constexpr double measured_front_column_width_m = 1.0;
// The late front speed is fitted over the measured points after this time (at L = 1 m).
inline constexpr double late_front_from_s = 0.4;

// dt_gate = 0.175 sqrt(L / (2 g)). Throws std::invalid_argument for non-positive L or g.
double gate_opening_time_shift_s(double column_width_m, double gravity_m_s2);

struct MeasuredFrontPoint {
  double t_s = 0.0;        // at L = 1 m
  double x_over_l = 0.0;   // front position / column width
};

// Reads a table with the columns t_s and x_front_over_L ('#' comment lines). Throws std::runtime_error
// naming the file when it cannot be read or holds no such rows.
std::vector<MeasuredFrontPoint> read_measured_front(const std::filesystem::path& file);

struct FrontTrace {
  std::vector<double> t_s;   // increasing
  std::vector<double> x_m;   // front position (from the column's back wall, as the measured x)
};

struct FrontSetup {
  double column_width_m = 1.0;   // L
  double tank_length_m = 4.0;
  double wall_margin_m = 0.0;    // dx or the cell size
  double time_shift_s = 0.0;     // dt_gate, or 0 for the unshifted comparison
};

struct FrontComparison {
  double time_shift_s = 0.0;
  int points = 0;                      // measured points compared
  int measured_points = 0;             // all measured points
  double mean_abs = 0.0, max_abs = 0.0;  // |x_sim - x_exp| / L over the compared points
  double first_point_error = 0.0;      // at the first compared point
  double late_speed_ratio = 0.0;       // simulated / measured slope after late_front_from_s (NaN: < 2 points)
  std::vector<double> t_exp_s;         // per compared point: experiment time at this L,
  std::vector<double> measured;        // measured x / L,
  std::vector<double> simulated;       // simulated x / L at t_exp - shift
};

FrontComparison compare_front(const FrontTrace& trace, const std::vector<MeasuredFrontPoint>& measured,
                              const FrontSetup& setup);

}  // namespace hydrojump::compare
