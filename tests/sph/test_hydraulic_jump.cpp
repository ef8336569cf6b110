// SPH hydraulic jumps in stilling basins (issue 4), the full runs: tagged [slow] (each is a 10 s
// simulation, 15-40 minutes on 2 cores); run them with scripts/validate.sh -R jump.
//
// Smooth-bed twin of run A (tests/data/basins.toml A_smooth: y1 = 25.4 mm, U1 = 2 m/s, Fr1 = 4, tailwater
// at Belanger's y2*) at the quick resolution, driven exactly as `hydrojump sph` drives it. The run's
// summary.json (sph/basin_monitor.hpp) is checked against the acceptance criteria of the issue:
//   - time-averaged inflow discharge within 2 % of the prescribed q = y1 U1: the buffer's count of the
//     mass it turned into fluid, and the discharge the particles carry through the upstream section
//     (their velocities, measured independently of that count);
//   - mass balance: change of the water in the domain = inflow - outflow (bookkeeping, exact to
//     round-off: 1e-9 of the inflow);
//   - the jump stays in the basin: toe found in every frame of the averaging window, its mean between
//     the basin start and the downstream section, the monitor's verdict "in_basin" (not pushed to the
//     inflow or swept to the outlet), standard deviation below 2 y1;
//   - y2/y1 within 5 % of Belanger's ratio (1/2)(sqrt(1 + 8 Fr1^2) - 1).
// The run directory is kept in the build tree (validation/sph_A_smooth) for inspection in ParaView.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "sph/cli.hpp"

namespace fs = std::filesystem;
using namespace hydrojump;

namespace {

// The number after "\"key\": " in a JSON text (NaN for null or a missing key).
double json_number_after(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  const auto at = json.find(needle);
  if (at == std::string::npos) return std::nan("");
  const char* begin = json.c_str() + at + needle.size();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  return end == begin ? std::nan("") : v;
}

// The part of `json` from the first "\"key\"" on (empty when it is missing).
std::string from_key(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\"");
  return at == std::string::npos ? std::string() : json.substr(at);
}

// The entry of summary.json's "sections" list named `section` (empty when it is missing).
std::string section_text(const std::string& json, const std::string& section) {
  const auto at = json.find("{\"name\": \"" + section + "\"");
  if (at == std::string::npos) return {};
  return json.substr(at, json.find("{\"name\": ", at + 1) - at);
}

}  // namespace

TEST_CASE("SPH smooth-bed jump A_smooth holds in the basin at Belanger's ratio", "[sph][jump][slow]") {
  const auto study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const cases::Case* c = study.find_case("A_smooth");
  REQUIRE(c != nullptr);
  const fs::path dir = fs::current_path() / "validation" / "sph_A_smooth";
  fs::remove_all(dir);
  sph::write_sph_input(study, *c, "quick", dir);
  sph::SphOptions opt;
  opt.dir = dir.string();
  opt.quiet = true;
  REQUIRE(sph::run_sph_directory(opt) == 0);
  const std::string json = util::read_text_file(dir / "summary.json");
  std::cout << json;
  const double q_error = json_number_after(json, "inflow_discharge_relative_error");
  const double mass_error = json_number_after(json, "relative_to_injected");
  const double toe_std_y1 = json_number_after(json, "toe_std_over_y1");
  const double toe_missing = json_number_after(json, "toe_missing_samples");
  const double ratio_error = json_number_after(json, "y2_over_y1_relative_to_belanger");
  const cases::StillingBasinCase* basin = c->stilling_basin();
  REQUIRE(basin != nullptr);
  const double q = basin->inflow_depth_m * basin->inflow_velocity_m_s;
  const double q_upstream = json_number_after(from_key(section_text(json, "upstream"), "discharge_m2_s"), "mean");
  const double toe_mean = json_number_after(from_key(json, "toe_x_m"), "mean");
  const double downstream_x = json_number_after(section_text(json, "downstream"), "x_m");
  CHECK(json.find("\"window_complete\": true") != std::string::npos);
  CHECK(std::abs(q_error) < 0.02);
  CHECK(std::abs(q_upstream / q - 1.0) < 0.02);
  CHECK(std::abs(mass_error) < 1e-9);
  CHECK(toe_missing == 0.0);
  CHECK(json.find("\"jump_state\": \"in_basin\"") != std::string::npos);
  // The held toe's time mean at the basin start within 2 y1 (the smooth bed's steadiness tolerance):
  // the control holds it there, so it lies on either side by its fluctuation (sd ~1.6 y1 here).
  CHECK(std::abs(toe_mean - basin->upstream_length_m) < 2.0 * basin->inflow_depth_m);
  CHECK(toe_mean < downstream_x);
  CHECK(toe_std_y1 < 2.0);
  CHECK(std::abs(ratio_error) < 0.05);
}
