// Holding a hydraulic jump's toe with the tailwater, as a laboratory tailgate does
// (`[case.tailwater] control = "hold_toe"`; Ead & Rajaratnam 2002 set their tailgate so that the toe
// stood at the start of the corrugated bed).
//
// Why. The generated outlet (`outletPhaseMeanVelocity`, Umean = q / y2*) lets out a fixed discharge at
// the tailwater depth, so the water volume of the basin is free to drift, and on a smooth horizontal bed
// the jump has no preferred place: a tailwater 1 % off Bélanger's depth moves the toe at about 1 % of U1
// (3-4 cm/s for runs B and C). In a basin that keeps its water volume the jump is stable: moved
// downstream by dx, it leaves (y2 - y1) dx of water behind it, which raises the level behind the
// roller and pushes it back. So the control holds the volume, and moves it slowly to bring the toe to
// the target, once per leg of `tailwater_control_interval_s` (interFoam runs leg by leg; the outlet's
// Umean is rewritten in the latest time directory between legs):
//
//   I(n)      = I(n-1) + (y2* - y1) / T_x * (x_toe(n) - x_target) * dt          (toe: more water when the
//   V*(n)     = I(n) + k_p (y2* - y1) (x_toe(n) - x_target)                         toe lies downstream)
//   Umean(n)  = ( q + (V(n) - V*(n)) / T_V ) / y2*,   clamped to [1/4, 4] q / y2*   (volume)
//
// V(n) the water volume per unit width (m^2: the integral of alpha.water over the domain divided by
// the mesh's thickness) at the end of leg n, x_toe(n) the mean of the toe over the leg's outputs,
// dt the leg's length (the interval, less for a leg that aligns with the output times), T_V = `volume_hold_time_s` (a volume error decays by about dt / T_V per leg),
// T_x = `toe_hold_time_s` ((y2* - y1) / T_x is the volume per second that moves the toe by 1 m,
// y2* - y1 per metre of basin), k_p = `toe_hold_gain` (the proportional part, off by default: what it
// did is in sph/toe_hold_control.hpp). At the first step I(0) = V(0) - k_p (y2* - y1) (x_toe(0) - x_target) + its
// toe term, so V*(0) = V(0) + its toe term: the first leg's volume, and the control starts without a
// jump. I(n-1) is not logged: it is V*(n-1) less the proportional part of that row's toe. x_target = the basin start (`expected_toe_x_m`). A leg without a toe on any
// output counts as a toe at the outlet (the jump has left the basin downstream). At steady state the
// outlet lets out q and the toe stands at x_target: the tailwater y2 then is the depth the jump needs,
// which the comparator sets beside Bélanger's.
//
// The toe of an output is the toe criterion of cases/jump_toe.hpp applied to the free surface as
// `compare` finds it: zeta(x) = the highest point of the alpha.water = 0.5 iso-surface (the
// `freeSurface` function object's alpha_0.5.vtp) within each station of width y1/4, from the upstream
// section to the outlet. (Alpha read along a line at 1.5 y1 above the floor would not do: at the
// `default` resolution that line crosses air pockets under the roller, which put the control's toe
// 0.23 m downstream of `compare`'s on C_smooth.)
//
// Usage
//   | key                                          | default         | meaning                            |
//   |----------------------------------------------|-----------------|------------------------------------|
//   | [case.tailwater] control                     | "hold_toe"      | this control; "fixed_depth": none  |
//   | [case.tailwater] volume_hold_time_s          | 1.0             | T_V (>= dt)                        |
//   | [case.tailwater] toe_hold_time_s             | 5.0             | T_x (>= dt)                        |
//   | [case.tailwater] toe_hold_gain               | 0               | k_p, in [0, 10]                    |
//   | [vof] tailwater_control_interval_s           | whole outputs   | leg length dt, a whole number of   |
//   |                                              | within 0.5 s    | output intervals, <= end_time_s    |
// Example:
//   [case.tailwater]
//   depth_m = 0.104          # the initial level only
//   control = "hold_toe"
// Each step is logged in DIR/tailwater_control.csv (time_s, toe_x_m, toe_outputs, water_volume_m2,
// volume_target_m2, outlet_mean_velocity_m_s); `--resume` continues from its last row.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cases/geometry.hpp"
#include "cases/spec.hpp"
#include "cases/toe_hold_law.hpp"

namespace hydrojump::reference {

inline constexpr const char* tailwater_control_log = "tailwater_control.csv";
inline constexpr const char* free_surface_function = "freeSurface";  // the case writer's isoSurface
inline constexpr const char* free_surface_file = "alpha_0.5.vtp";
inline constexpr const char* water_volume_function = "water_volume";

struct TailwaterControlLaw {
  cases::ToeHoldGains gains;          // y1, y2*, x_target, the outlet (the toe of a leg without one), T_x, k_p
  double discharge_m2_s = 0.0;        // q
  double toe_search_from_m = 0.0;     // the upstream section
  double interval_s = 0.5;            // the legs' length
  double output_interval_s = 0.1;     // the case's output times k dt_out, where the toes are read
  double volume_hold_time_s = 1.0;    // T_V
};

// The law of a stilling-basin case with tailwater_control = "hold_toe" and its geometry (throws
// std::invalid_argument for another case).
TailwaterControlLaw tailwater_control_law(const cases::Case& c, const cases::CaseGeometry& geo);

struct TailwaterControlStep {
  double time_s = 0.0;
  double toe_x_m = 0.0;                  // the leg's mean toe (NaN: none found)
  int toe_outputs = 0;                   // outputs with a toe
  double water_volume_m2 = 0.0;          // V(n)
  double volume_target_m2 = 0.0;         // V*(n)
  double outlet_mean_velocity_m_s = 0.0; // Umean(n), for the next leg
};

// One step of the law above after a leg of `leg_s` seconds (dt: the interval, or less for an aligning
// or closing leg). `previous_integral`: I(n-1), nothing at the first step.
TailwaterControlStep tailwater_control_step(const TailwaterControlLaw& law, std::optional<double> previous_integral,
                                            double time_s, double leg_s, const std::vector<double>& output_toes_x_m,
                                            double water_volume_m2);

// Drops the log's rows after `time_s` (a run resumed from an earlier time); removes the log when
// `time_s` is nothing (a fresh start).
void truncate_tailwater_control_log(const std::filesystem::path& case_dir, std::optional<double> time_s);

// The toe of a free surface given as points (x_m[i], z_m[i]) (z above the upstream floor): zeta at
// stations x_from + k y1/4 up to x_to = the highest point within half a station, then the criterion of
// cases/jump_toe.hpp; NaN without one.
double toe_on_surface(const std::vector<double>& x_m, const std::vector<double>& z_m, double x_from, double x_to,
                      double inflow_depth_m);

// The points (x, z) of an iso-surface written by OpenFOAM's `surfaces` function object as VTK XML
// PolyData (.vtp). Throws std::runtime_error naming the file when it cannot be read.
void read_surface_points(const std::filesystem::path& vtp, std::vector<double>& x_m, std::vector<double>& z_m);

// The outlet's Umean in an OpenFOAM U field file (the `outlet` entry of boundaryField, uncompressed):
// read, and replaced (written to a temporary file, then renamed). Throw std::runtime_error naming the
// file when it has no such entry.
double read_outlet_mean_velocity(const std::filesystem::path& u_file);
void write_outlet_mean_velocity(const std::filesystem::path& u_file, double umean_m_s);

// The log: every row, and a row appended (the file rewritten whole, atomically).
std::vector<TailwaterControlStep> read_tailwater_control_log(const std::filesystem::path& case_dir);
void append_tailwater_control_log(const std::filesystem::path& case_dir, const TailwaterControlStep& step);

}  // namespace hydrojump::reference
