#include "sph/bench.hpp"

#include <chrono>
#include <ctime>
#include <sstream>
#include <stdexcept>

#include <omp.h>
#include <sys/resource.h>

#include "cases/geometry.hpp"
#include "cases/spec_reader.hpp"
#include "sph/particle_generator.hpp"
#include "sph/settings.hpp"
#include "sph/solver.hpp"

namespace hydrojump::sph {

namespace {

// The benchmark case, as a study file (parsed and validated like any other spec): the [sph] table of
// the shared keys and the chosen model's, then the case.
constexpr const char* kStudyTable = R"(
[study]
name = "benchmark"
description = "hydrojump bench: dam break"

[fluid]
density_kg_m3 = 1000.0
kinematic_viscosity_m2_s = 1.0e-6
gravity_m_s2 = 9.81
)";

// The [sph] keys both models share, then each model's own.
constexpr const char* kCommonSph = R"(
[sph]
kernel = "wendland_c2"
density_diffusion = "fourtakas"
density_diffusion_coefficient = 0.1
sound_speed_coefficient = 20.0
cfl_number = 0.2
coef_h = 1.0
)";

// DualSPHysics-comparable settings.
constexpr const char* kDualSphysicsModel = R"(
viscosity = "artificial"
artificial_viscosity_alpha = 0.02
boundary = "dbc"
time_integrator = "verlet"
)";

// Every costly path at once (`--model jump` up to commit 2851cbb).
constexpr const char* kCostliestModel = R"(
viscosity = "laminar_sps"
sps_mixing_length_m = 0.1
sps_wall_distance = "whole_domain"
viscous_wall_condition = "wall_function"
boundary = "mdbc"
time_integrator = "symplectic"
particle_shifting = "fickian"
)";

constexpr const char* kBenchmarkCase = R"(
[resolution.bench]
particle_spacing_m = 0.01
vof_cell_size_bed_m = 0.01
vof_cell_size_bulk_m = 0.01

[[case]]
id = "dam_break_bench"
kind = "dam_break"
description = "Water column 1 m x 2 m in a tank 4 m long"
[case.run]
end_time_s = 0.3
output_interval_s = 0.1
[case.column]
width_m = 1.0
height_m = 2.0
[case.tank]
length_m = 4.0
height_m = 3.0
[case.gate]
type = "instant"
)";

// Each model's name and its own [sph] keys: the one list the option's allowed values come from.
struct NamedModel {
  const char* name;
  const char* sph_keys;
};
// "jump" parses with the DualSPHysics keys and then takes its [sph] from a study (study_model).
constexpr NamedModel kModels[] = {
    {"dualsphysics", kDualSphysicsModel}, {"jump", kDualSphysicsModel}, {"costliest", kCostliestModel}};

// The [sph] settings of the first stilling basin of `spec_file` (empty: the embedded study), after its
// rules, for the closed dam-break tank: the open-boundary settings of a basin (inflow, outflow, level
// control, tailgate, piston) are left at their defaults, which a closed tank does not use.
cases::SphSettings study_model(const std::string& spec_file, std::string& source) {
  const cases::Study study = spec_file.empty() ? cases::load_embedded_default_study() : cases::load_study(spec_file);
  for (const cases::Case& c : study.cases) {
    if (c.stilling_basin() == nullptr) continue;
    cases::SphSettings s = c.sph;
    const cases::SphSettings closed;
    s.inflow_condition = closed.inflow_condition;
    s.sluice_opening_m = closed.sluice_opening_m;
    s.reservoir_length_m = closed.reservoir_length_m;
    s.piston_level_gain_per_s = closed.piston_level_gain_per_s;
    s.outflow_condition = closed.outflow_condition;
    s.tailgate_height_m = closed.tailgate_height_m;
    s.outflow_level_reference = closed.outflow_level_reference;
    s.outflow_level_time_s = closed.outflow_level_time_s;
    s.open_boundary_layers = closed.open_boundary_layers;
    source = "[sph] of case \"" + c.id + "\" in " + (spec_file.empty() ? std::string("the embedded study") : spec_file);
    return s;
  }
  throw std::invalid_argument("hydrojump bench --model jump: " + (spec_file.empty() ? std::string("the embedded study") : spec_file) +
                              " has no stilling-basin case whose [sph] model to run");
}

}  // namespace

const std::vector<std::string>& benchmark_models() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const NamedModel& m : kModels) v.emplace_back(m.name);
    return v;
  }();
  return names;
}

BenchmarkResult run_benchmark(const BenchmarkOptions& options) {
  const char* model = nullptr;
  std::string allowed;
  for (const NamedModel& m : kModels) {
    if (options.model == m.name) model = m.sph_keys;
    allowed += (allowed.empty() ? "\"" : ", \"") + std::string(m.name) + "\"";
  }
  if (model == nullptr)
    throw std::invalid_argument("hydrojump bench: model \"" + options.model + "\" is not allowed: use one of " + allowed);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const std::string text = std::string(kStudyTable) + kCommonSph + model + kBenchmarkCase;
  cases::Study study = cases::parse_study(text, "<hydrojump bench, model " + options.model + ">", ".");
  std::string source;
  if (options.model == "jump") study.cases.front().sph = study_model(options.spec_file, source);
  else if (!options.spec_file.empty())
    throw std::invalid_argument("hydrojump bench: --spec is only used with --model jump (here \"" + options.model + "\")");
  const cases::Case& c = study.cases.front();
  const cases::CaseGeometry geometry = cases::make_geometry(c, study.fluid);
  const SolverSettings settings = make_settings(c, study.fluid, geometry, options.particle_spacing_m);
  Solver solver(settings, generate_particles(geometry, settings, c.sph.boundary_layers));

  BenchmarkResult r;
  r.particles = solver.particles().size();
  r.fluid_particles = solver.particles().fluid_count();
  r.threads = omp_get_max_threads();
  r.model = options.model;
  r.model_source = source;
  timespec cpu0{}, cpu1{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu0);
  const auto t0 = std::chrono::steady_clock::now();
  while (solver.time() < options.end_time_s && (options.max_steps < 0 || r.steps < options.max_steps)) {
    solver.step();
    ++r.steps;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu1);
  r.cpu_seconds = static_cast<double>(cpu1.tv_sec - cpu0.tv_sec) + 1e-9 * static_cast<double>(cpu1.tv_nsec - cpu0.tv_nsec);
  r.simulated_time_s = solver.time();
  r.particle_steps_per_second = static_cast<double>(r.particles) * static_cast<double>(r.steps) / r.seconds;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  r.peak_memory_bytes = static_cast<std::int64_t>(usage.ru_maxrss) * 1024;
  return r;
}

std::string to_json(const BenchmarkResult& r) {
  std::ostringstream o;
  o << "{\"model\": \"" << r.model << "\", \"particles\": " << r.particles << ", \"steps\": " << r.steps << ", \"threads\": " << r.threads
    << ", \"particle_steps_per_second\": " << static_cast<std::int64_t>(r.particle_steps_per_second)
    << ", \"peak_memory_bytes\": " << r.peak_memory_bytes << "}";
  return o.str();
}

}  // namespace hydrojump::sph
