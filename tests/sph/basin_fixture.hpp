// A schematic jump on particles for the run-monitor tests (tests/sph/test_basin_monitor.cpp) and the
// comparator's reading of its summary (tests/compare/test_real_writers.cpp): fluid on a lattice of
// spacing dx, depth y1 (u = q / y1) upstream of x_step and y2 (u = q / y2) beyond, from x = 0 to 1 m
// over a flat floor at z = 0; and a monitor set-up for that channel.
#pragma once

#include <cmath>

#include "sph/basin_monitor.hpp"

namespace basin_fixture {

constexpr double dx = 0.005, rho0 = 1000.0, depth1 = 0.025, depth2 = 0.13, q = 0.05;

inline hydrojump::sph::ParticleSet step_particles(double x_step) {
  hydrojump::sph::ParticleSet ps;
  const int columns = static_cast<int>(std::lround(1.0 / dx));
  Eigen::Index n = 0;
  for (int c = 0; c < columns; ++c) {
    const double x = (c + 0.5) * dx;
    const int rows = static_cast<int>(std::lround((x < x_step ? depth1 : depth2) / dx));
    ps.resize(n + rows);
    for (int r = 0; r < rows; ++r, ++n) {
      ps.assign(n, hydrojump::sph::ParticleType::fluid, x, (r + 0.5) * dx, rho0, rho0 * dx * dx, n);
      ps.u[n] = q / (rows * dx);
    }
  }
  return ps;
}

// Averaging window 1.5-3 s; sections "upstream" at 0.0525 m and "downstream" at 0.8025 m.
inline hydrojump::sph::BasinMonitorSetup setup() {
  hydrojump::sph::BasinMonitorSetup s;
  s.case_id = "step";
  s.dx = dx;
  s.rho0 = rho0;
  s.inflow_depth_m = depth1;
  s.discharge_m2_s = q;
  s.belanger_y2_m = depth2;
  s.x_inflow_m = 0.0;
  s.x_outflow_m = 1.0;
  s.toe_search_from_m = 0.05;
  s.drift_tolerance_m = 0.068;
  s.average_start_s = 1.5;
  s.average_end_s = 3.0;
  s.sections = {{"upstream", 0.0525, hydrojump::cases::SectionRole::upstream}, {"downstream", 0.8025, hydrojump::cases::SectionRole::downstream}};
  s.bed_elevation = [](double) { return 0.0; };
  return s;
}

}  // namespace basin_fixture
