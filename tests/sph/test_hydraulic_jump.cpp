// SPH hydraulic jumps in stilling basins (issue 4), the full runs: tagged [slow] (each is a 10 s
// simulation, 15-40 minutes on 2 cores); run them with scripts/validate.sh -R jump.
//
// Smooth-bed twin of run A (cases/ead2002.toml A_smooth: y1 = 25.4 mm, U1 = 2 m/s, Fr1 = 4, tailwater
// at Belanger's y2*) at the quick resolution, driven exactly as `hydrojump sph` drives it. The run's
// summary.json (sph/basin_monitor.hpp) is checked against the acceptance criteria of the issue:
//   - time-averaged inflow discharge within 2 % of the prescribed q = y1 U1;
//   - mass balance: change of the water in the domain = inflow - outflow within 0.5 % of the inflow;
//   - the jump stays in the basin: toe found in every frame of the averaging window, standard deviation
//     below 2 y1;
//   - y2/y1 within 5 % of Belanger's ratio (1/2)(sqrt(1 + 8 Fr1^2) - 1).
// The run directory is kept in the build tree (validation/sph_A_smooth) for inspection in ParaView.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "cases/fingerprint.hpp"
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

}  // namespace

TEST_CASE("SPH smooth-bed jump A_smooth holds in the basin at Belanger's ratio", "[sph][jump][slow]") {
  const auto study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml");
  const cases::Case* c = study.find_case("A_smooth");
  REQUIRE(c != nullptr);
  const fs::path dir = fs::current_path() / "validation" / "sph_A_smooth";
  fs::remove_all(dir);
  sph::write_sph_input(study, *c, "quick", dir);
  sph::SphOptions opt;
  opt.dir = dir.string();
  opt.quiet = true;
  REQUIRE(sph::run_sph_directory(opt) == 0);
  const std::string json = cases::read_text_file(dir / "summary.json");
  std::cout << json;
  const double q_error = json_number_after(json, "inflow_discharge_relative_error");
  const double mass_error = json_number_after(json, "relative_to_injected");
  const double toe_std_y1 = json_number_after(json, "toe_std_over_y1");
  const double toe_missing = json_number_after(json, "toe_missing_samples");
  const double ratio_error = json_number_after(json, "y2_over_y1_relative_to_belanger");
  CHECK(std::abs(q_error) < 0.02);
  CHECK(std::abs(mass_error) < 0.005);
  CHECK(toe_missing == 0.0);
  CHECK(toe_std_y1 < 2.0);
  CHECK(std::abs(ratio_error) < 0.05);
}
