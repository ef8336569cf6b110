// Running a case to its end time with outputs, checks, checkpoints and progress:
//
//   DIR/particles.pvd, DIR/particles_NNNN.vtp   particle snapshots every output interval (ParaView)
//   DIR/run_log.csv    t, step, dt, fluid mass, kinetic and potential energy, max |rho/rho0 - 1|,
//                      fluid particles, mass injected at the inflows and removed at the outflows
//                      since t = 0 (open boundaries; 0 for closed cases), and the mass of the density
//                      outliers removed since t = 0 (sph/density_outliers.hpp)
//   DIR/gauges.csv     at every gauge x: free-surface elevation and the velocity (u, w) at mid-depth
//                      (Shepard kernel interpolation); for dam breaks also the surge front
//   DIR/basin.csv      stilling basins: jump toe, inflow/outflow discharge, depth, surface and
//                      discharge at every section, per output time (sph/basin_monitor.hpp)
//   DIR/summary.json   stilling basins: averages over the averaging window and the steady-state verdict
//   DIR/checkpoint.bin restart file, every checkpoint interval of wall-clock time and at exit
//   DIR/failure.txt, DIR/failure_state.vtp   only when the run goes unstable
//
// The run stops with a SimulationFailure (a diagnosis naming particles, positions and the time) on
// NaN/Inf, a particle leaving the domain, |rho/rho0 - 1| above sph.max_density_variation, density
// outliers removed beyond 1 % of the water (sph/density_outliers.hpp), or a time step collapsing below
// 1e-3 of the acoustic step CFL h / c0; the last good checkpoint and outputs
// are kept. A stop request (SIGINT/SIGTERM: the flag) writes a checkpoint and returns.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sph/basin_monitor.hpp"
#include "sph/toe_hold_control.hpp"
#include "sph/checkpoint.hpp"
#include "sph/solver.hpp"

namespace hydrojump::sph {

class SimulationFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Gauge {
  std::string name;
  double x_m = 0.0;
};

struct RunOptions {
  std::filesystem::path dir;
  double end_time_s = 1.0;
  double output_interval_s = 0.05;
  double checkpoint_interval_wall_s = 300.0;
  std::int64_t max_steps = -1;             // stop after this many steps of this invocation (-1: no limit)
  std::vector<Gauge> gauges;               // free-surface and velocity gauges
  std::function<double(double)> bed_elevation = [](double) { return 0.0; };  // floor z at x (m)
  std::optional<BasinMonitorSetup> basin;  // stilling basins: basin.csv and summary.json
  std::optional<ToeHoldLaw> toe_hold;      // with `basin`: the outlet steered to hold the toe at every
                                           // output on the grid (toe_hold_control.hpp)
  bool record_front = false;               // dam break: surge front x in gauges.csv
  double front_layer_m = 0.0;              // front: fluid within this height of the floor
  std::string fingerprint;                 // of the resolved case, stored in checkpoints
  std::ostream* progress = nullptr;        // progress lines (nullptr: silent)
  bool progress_is_terminal = false;       // \r-updated line instead of periodic lines
  const std::atomic<bool>* stop_requested = nullptr;
};

enum class RunStatus { finished, interrupted, step_limit };

// Runs from `solver`'s state (fresh) or from `resume` (a checkpoint of the same case).
RunStatus run_case(Solver& solver, const RunOptions& options, const std::optional<Checkpoint>& resume = std::nullopt);

// The diagnosis of the current state, or an empty string if it is healthy.
std::string diagnose(const Solver& solver);

// Surface elevation at x: highest fluid particle within dx of x, plus dx/2 (NaN if none).
double surface_elevation_at(const ParticleSet& ps, double x, double dx);

// Dam-break surge front: walking downstream along the fluid particles lower than `layer_m`
// (measured from the floor at z = 0), the last one before a gap wider than 2 dx (droplets thrown
// ahead do not count), plus dx/2 for the particle's own extent. NaN without fluid in the layer.
double surge_front_x(const ParticleSet& ps, double dx, double layer_m);

// Velocity at (x, z) by Shepard-normalised kernel interpolation over the fluid particles,
//   v(x) = sum_j V_j v_j W(x - x_j) / sum_j V_j W(x - x_j);  (NaN, NaN) with no fluid within 2h.
std::pair<double, double> velocity_at(const ParticleSet& ps, const SolverSettings& s, double x, double z);

std::filesystem::path checkpoint_path(const std::filesystem::path& dir);

}  // namespace hydrojump::sph
