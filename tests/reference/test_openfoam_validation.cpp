// Validation of the OpenFOAM reference against theory and laboratory data (long: tagged [slow]; run
// with `ctest -L slow -R reference` or `reference_validation_tests "[slow]"`).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cases/spec_reader.hpp"
#include "util/time_directories.hpp"
#include "reference/cli.hpp"
#include "reference/line_samples.hpp"
#include "reference/runner.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump;
using hydrojump::testing::TempDir;

namespace {

// Run A's smooth-bed twin (Ead & Rajaratnam 2002): y1 = 25.4 mm, U1 = 2 m/s (Fr1 = 4.01), tailwater at
// Belanger's y2*, basin 1.36 m, k-omega SST, the quick resolution (5 mm near the bed and surface).
const char* smooth_basin_spec = R"(
[study]
name = "validation"
description = "smooth-bed jump, Fr1 = 4"
[fluid]
density_kg_m3 = 1000.0
kinematic_viscosity_m2_s = 1.0e-6
gravity_m_s2 = 9.81
[vof]
turbulence_model = "kOmegaSST"
max_courant = 0.8
max_alpha_courant = 0.8
[resolution.quick]
particle_spacing_m = 0.005
vof_cell_size_bed_m = 0.005
vof_cell_size_bulk_m = 0.01
[[case]]
id = "A_smooth"
kind = "stilling_basin"
description = "smooth twin of run A"
[case.run]
end_time_s = 10.0
output_interval_s = 0.1
average_start_s = 6.0
average_end_s = 10.0
[case.bed]
profile = "smooth"
[case.inflow]
depth_m = 0.0254
velocity_m_s = 2.0
[case.tailwater]
rule = "belanger"
[case.domain]
upstream_length_m = 0.2
basin_length_m = 1.36
downstream_length_m = 0.2
air_height_m = 0.1
)";

struct Window {
  std::vector<double> toe_depth, x2_depth, downstream_depth;
};

Window sample_window(const fs::path& dir, double t0, double t1) {
  Window w;
  for (const auto& [t, path] : util::time_directories(dir / "postProcessing/sections")) {
    if (t < t0 - 1e-9 || t > t1 + 1e-9) continue;
    w.toe_depth.push_back(reference::water_depth(reference::read_line_sample(path / "toe_alpha.water.xy")));
    w.x2_depth.push_back(reference::water_depth(reference::read_line_sample(path / "x_2y2_alpha.water.xy")));
    w.downstream_depth.push_back(
        reference::water_depth(reference::read_line_sample(path / "downstream_alpha.water.xy")));
  }
  return w;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? std::nan("") : s / static_cast<double>(v.size());
}

// Mean of the first data column after time over [t0, t1], from every restart directory.
double mean_discharge(const fs::path& function_dir, double t0, double t1) {
  std::vector<double> values;
  for (const auto& [start, path] : util::time_directories(function_dir)) {
    std::ifstream in(path / "surfaceFieldValue.dat");
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream ss(line);
      double t = 0.0, flux = 0.0;
      if (ss >> t >> flux && t >= t0 - 1e-9 && t <= t1 + 1e-9) values.push_back(std::abs(flux));
    }
  }
  return mean(values);
}

// Writes the case into dir (a directory not there yet, inside a test's TempDir), runs it and returns dir.
fs::path run_smooth_basin(const fs::path& dir, int np) {
  const cases::Study study = cases::parse_study(smooth_basin_spec, "<validation>", fs::temp_directory_path());
  reference::write_vof_case(study, study.cases.front(), "quick", dir);
  reference::RunOptions options;
  options.np = np;
  options.progress_interval_s = 60.0;
  std::ostringstream out;
  reference::run_vof_case(dir, options, out);
  return dir;
}

}  // namespace

TEST_CASE("smooth bed with Fr1 = 4 and the tailwater at Belanger's y2*: the jump stays at the basin start and "
          "y2/y1 is within 5 % of Belanger's ratio",
          "[reference][openfoam][validation][slow]") {
  const double y1 = 0.0254, u1 = 2.0, g = 9.81;
  const double fr1 = u1 / std::sqrt(g * y1);
  const double belanger_ratio = 0.5 * (std::sqrt(1.0 + 8.0 * fr1 * fr1) - 1.0);
  const TempDir tmp("validation-serial");
  const fs::path dir = run_smooth_basin(tmp.path() / "case", 1);
  const Window w = sample_window(dir, 6.0, 10.0);
  REQUIRE(w.downstream_depth.size() >= 40);
  const double ratio = mean(w.downstream_depth) / y1;
  WARN("VOF y2/y1 = " << ratio << ", Belanger " << belanger_ratio << " (difference "
                      << 100.0 * (ratio / belanger_ratio - 1.0) << " %)");
  CHECK(ratio == Approx(belanger_ratio).epsilon(0.05));
  // The jump stays put: supercritical at the basin start, subcritical 2 y2* downstream, at every sample.
  for (double d : w.toe_depth) CHECK(d < 1.5 * y1);
  for (double d : w.x2_depth) CHECK(d > 0.6 * belanger_ratio * y1);
  // Steady over the window: the outlet passes the inflow discharge within 3 %.
  const double q_in = mean_discharge(dir / "postProcessing/discharge_inlet", 6.0, 10.0);
  const double q_out = mean_discharge(dir / "postProcessing/discharge_outlet", 6.0, 10.0);
  CHECK(q_out == Approx(q_in).epsilon(0.03));
}

TEST_CASE("an MPI run (--np 2) gives the same time-averaged y2 as the serial run within 1 %",
          "[reference][openfoam][validation][slow]") {
  const TempDir tmp("validation-mpi");
  const fs::path serial = run_smooth_basin(tmp.path() / "np1", 1);
  const fs::path parallel = run_smooth_basin(tmp.path() / "np2", 2);
  const double y2_serial = mean(sample_window(serial, 6.0, 10.0).downstream_depth);
  const double y2_parallel = mean(sample_window(parallel, 6.0, 10.0).downstream_depth);
  WARN("time-averaged y2: serial " << y2_serial << " m, 2 ranks " << y2_parallel << " m");
  CHECK(y2_parallel == Approx(y2_serial).epsilon(0.01));
}
