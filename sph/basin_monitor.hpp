// Run products of a stilling-basin case: the jump toe over time, the discharge through the inflow,
// the outflow and every section, the mass balance, a steady-state verdict and `summary.json`.
//
// Water columns. Stations x_c every dx between the inflow and the outflow section; at each
//
//   h(x_c)    = sum_i V_i Lambda((x_i - x_c)/w) / w        over the fluid particles, V_i = m_i/rho_i,
//   q(x_c)    = sum_i V_i u_i Lambda((x_i - x_c)/w) / w    Lambda(s) = max(0, 1 - |s|) (hat function)
//   zeta(x_c) = z_b(x_c) + h(x_c) - z_floor                (surface above the upstream floor = crest level)
//
// with w = dx for the toe profile and w = 2 dx at the sections. The hat weights sum to w/dx over a
// lattice of spacing dx whatever its offset, so a lattice column of depth h gives exactly h. The volume
// integral is insensitive to single splashing particles (one adds at most dx^2/w to h), unlike the
// highest particle.
//
// Jump toe: cases::find_jump_toe on zeta(x) from the "upstream" section on (cases/jump_toe.hpp: first x
// where the running mean over 0.8 y1 exceeds 1.5 y1 and stays above it over the next 2 y1).
// Inflow and outflow discharge: the mass created by the inflow buffer and removed by the outflow buffer
// between two outputs, divided by rho0 and the interval.
//
// Steady state, checked at every output time t over the preceding second [t - 1 s, t] by the window rule
// below (cases::window_balance, the discharges weighted by their intervals), and a toe in every output:
//   - |mean q_in - mean q_out| / q_prescribed < 2 %, and
//   - toe drift |slope of a least-squares line through toe(t)| * 1 s < the bed wavelength (corrugated)
//     or 2 y1 (smooth bed).
// `steady_from_s` is the first output time from which both hold at every later output; the averaging
// window was steady when steady_from_s <= the window start. The same two conditions on the window's
// means (`steady_by_window_means`): |mean q_out - mean q_in| / q < 2 % over the whole window
// (`window_outflow_minus_inflow_over_q`, > 0 for a draining basin) and the toe's least-squares trend
// over the window (`window_toe_trend_m_per_s`) times 1 s below the tolerance. Waves leaving the basin
// can keep the 1 s test failing in a run whose window means balance; a basin that is still filling or
// draining fails both.
//
// summary.json (written atomically at every output, so it is current even if the run is stopped):
// time means and standard deviations over the averaging window [average_start_s, average_end_s] of the
// inflow/outflow discharge, the toe position, and depth, surface and discharge at every section; the
// sequent depth y2 (mean depth at the "downstream" section) with y2/y1 and Belanger's ratio; the mass
// balance; the steady-state verdict; where the tailwater was held (`prescribed.tailwater_held_at`) and
// the outflow buffers' target depth (`outlet_target_depth_m`: y2 throughout when held at the outlet,
// the level control's output when held at the downstream section, outflow_level_control.hpp).
//
// Usage
//   | input         | from                                                    |
//   |---------------|---------------------------------------------------------|
//   | setup         | BasinMonitorSetup::from_case(case, geometry, dx, rho0)  |
//   | record(...)   | at every output time, with the inflow/outflow mass since t = 0 |
// Example:
//   BasinMonitor monitor(BasinMonitorSetup::from_case(c, geometry, dx, rho0));
//   monitor.record(particles, t, mass_in, mass_out);
//   write_file_atomically(dir / "basin.csv", monitor.csv());
//   write_file_atomically(dir / "summary.json", monitor.summary_json());
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "cases/geometry.hpp"
#include "cases/spec.hpp"
#include "sph/particles.hpp"

namespace hydrojump::sph {

struct BasinMonitorSetup {
  std::string case_id;
  double dx = 0.0;                  // particle spacing (m)
  double rho0 = 1000.0;             // reference density (kg/m^3)
  double inflow_depth_m = 0.0;      // y1
  double discharge_m2_s = 0.0;      // q = y1 U1, prescribed
  double froude1 = 0.0;
  double tailwater_depth_m = 0.0;   // imposed at the outflow
  // Where the tailwater depth is held: "outlet", "downstream_section" (outflow_level_control.hpp),
  // "tailgate" (by the weir's crest), or "toe_held" (not held: the outlet is steered to hold the toe at
  // the basin start, toe_hold_control.hpp, and the tailwater is a prediction).
  std::string tailwater_held_at = "outlet";
  double belanger_y2_m = 0.0;
  double floor_z_m = 0.0;           // upstream floor = crest level
  double x_inflow_m = 0.0, x_outflow_m = 0.0;
  // A piston reservoir's water lies upstream of x_inflow and is not the basin's; with an inflow
  // buffer all fluid is (a particle the roller pushes back upstream of x_inflow still counts).
  bool reservoir_upstream = false;
  double toe_search_from_m = 0.0;   // the "upstream" section (or the inflow)
  double drift_tolerance_m = 0.0;   // wavelength (corrugated) or 2 y1 (smooth)
  double average_start_s = 0.0, average_end_s = 0.0;
  double output_interval_s = 0.0;   // the window accepts outputs within 1 % of it (cases/output_times.hpp)
  std::vector<cases::Section> sections;
  std::function<double(double)> bed_elevation;
  // Measured values of the spec, copied into the summary for comparison (NaN when absent).
  double measured_sequent_depth_m = 0.0;

  static BasinMonitorSetup from_case(const cases::Case& c, const cases::CaseGeometry& geometry, double dx,
                                     double rho0);
};

// One output time.
struct BasinSample {
  double t = 0.0;
  double toe_x = 0.0;                  // NaN when no toe is found
  double q_in = 0.0, q_out = 0.0;      // m^2/s over the interval before t (NaN for the first sample)
  double mass_in = 0.0, mass_out = 0.0;  // kg/m created at the inflow / removed at the outflow since t = 0
  double fluid_mass = 0.0;             // kg/m of water in the domain now (fluid + outflow-buffer particles)
  double outlet_target_depth = 0.0;    // the outflow buffers' target depth y_t (m; NaN: none)
  double mass_removed = 0.0;           // kg/m removed as density outliers since t = 0 (density_outliers.hpp)
  std::vector<double> depth, surface, discharge;           // per section
};

class BasinMonitor {
 public:
  explicit BasinMonitor(BasinMonitorSetup setup);

  // Samples the particles at time t; mass_in/mass_out are the totals since t = 0 (kg/m);
  // outlet_target_depth the outflow buffers' target depth now (m; NaN: none); mass_removed the
  // density outliers' total since t = 0 (kg/m), which the mass balance counts as leaving.
  void record(const ParticleSet& particles, double t, double mass_in, double mass_out,
              double outlet_target_depth = std::numeric_limits<double>::quiet_NaN(), double mass_removed = 0.0);

  // The table of all samples (basin.csv).
  std::string csv() const;
  // summary.json (see above).
  std::string summary_json() const;
  // One line for the terminal: toe, q_in, q_out, steady or not.
  std::string status_line() const;

  const std::vector<BasinSample>& samples() const { return samples_; }
  // Restores the samples of a resumed run (from the rows of basin.csv kept in the checkpoint).
  void restore(const std::vector<std::string>& csv_rows);
  std::vector<std::string> csv_rows() const;

  // The water columns of width w at x_c (exposed for tests).
  struct Column {
    double depth = 0.0, discharge = 0.0;
  };
  static std::vector<Column> columns(const ParticleSet& particles, const std::vector<double>& x_centres, double width);

  // First output time from which the steady-state conditions hold at every later output (NaN if none).
  double steady_from() const;

  // Where the jump is in the latest sample: "in_basin"; "swept_downstream" (no toe between the upstream
  // section and the outflow: the tailwater is too low to hold it); "at_inflow" (the surface is already
  // raised at the upstream section: the jump is drowned against the sluice gate, the tailwater is too
  // high); "none" before the first sample.
  std::string jump_state() const;

 private:
  // Every sample's time, discharges and toe: the inputs of cases::window_balance.
  struct BalanceSeries {
    std::vector<double> t, q_in, q_out, toe_x;
  };
  BalanceSeries balance_series() const;
  // The 1 s test at sample k on the whole series (window_balance keeps the outputs in [t_k - 1 s, t_k]).
  bool steady_at(const BalanceSeries& series, std::size_t k) const;
  double steady_from(const BalanceSeries& series) const;
  BasinMonitorSetup setup_;
  std::vector<double> stations_;
  std::vector<BasinSample> samples_;
};

}  // namespace hydrojump::sph
