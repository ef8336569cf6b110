// The SPH benchmark: the dam break of cases/dam_break.toml (column 1 m x 2 m, tank 4 m) at particle
// spacing 0.01 m (20,000 fluid particles), Wendland C2, h = sqrt(2) dx, artificial viscosity 0.02,
// Fourtakas density diffusion 0.1, DBC, Verlet, CFL 0.2, c0 = 20 sqrt(g 2 m), 0.3 s of physical time:
// the configuration of DualSPHysics' 2D dam-break example, so that the two run side by side (README,
// Performance).
// Only the time steps are timed (not the set-up).
//
// model = "dualsphysics" (the default) is that configuration. model = "jump" runs the same dam break
// with exactly the SPH model a study's stilling-basin runs use: the [sph] settings of the study's first
// stilling basin after its rules (spec_file; empty: the embedded study, cases/ead2002.toml), with the
// open-boundary settings of a basin left out (the tank is closed). model = "costliest" runs every
// costly path at once, as `--model jump` did up to commit 2851cbb: symplectic (two interactions a
// step), mDBC, laminar + SPS viscosity with a mixing length of 0.1 m limited by the whole-domain wall
// distance, the log-law wall function and Fickian particle shifting (A = 2).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hydrojump::sph {

struct BenchmarkOptions {
  double particle_spacing_m = 0.01;
  double end_time_s = 0.3;
  std::int64_t max_steps = -1;   // stop earlier
  int threads = 0;               // 0: OpenMP default
  std::string model = "dualsphysics";  // or "jump", "costliest"
  std::string spec_file;               // model "jump": the study whose [sph] is run (empty: the embedded one)
};

// The allowed values of BenchmarkOptions::model.
const std::vector<std::string>& benchmark_models();

struct BenchmarkResult {
  std::int64_t particles = 0;        // all particles (fluid + boundary)
  std::int64_t fluid_particles = 0;
  std::int64_t steps = 0;
  int threads = 1;
  std::string model;
  std::string model_source;          // model "jump": the study and case whose [sph] ran
  double seconds = 0.0;              // wall time of the time loop
  double cpu_seconds = 0.0;          // CPU time of the process during the loop (all threads)
  double simulated_time_s = 0.0;
  double particle_steps_per_second = 0.0;
  std::int64_t peak_memory_bytes = 0;
};

BenchmarkResult run_benchmark(const BenchmarkOptions& options);

// {"model": ..., "particles": ..., "steps": ..., "threads": ..., "particle_steps_per_second": ..., "peak_memory_bytes": ...}
std::string to_json(const BenchmarkResult& r);

}  // namespace hydrojump::sph
