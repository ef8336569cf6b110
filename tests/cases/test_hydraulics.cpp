// Derived hydraulic quantities against hand-computed values (issue 2 acceptance).
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "cases/hydraulics.hpp"
#include "cases/spec_reader.hpp"

using namespace hydrojump::cases;

TEST_CASE("Run A derived quantities match hand computation", "[cases][hydraulics]") {
  // y1 = 25.4 mm, U1 = 2.00 m/s, g = 9.81:
  //   q = 0.0254 * 2 = 0.0508 m^2/s; Fr1 = 2 / sqrt(9.81 * 0.0254) = 4.00662;
  //   y2* = 0.0254/2 (sqrt(1 + 8 * 4.00662^2) - 1) = 0.131781 m;
  //   E1 = 0.0254 + 0.0508^2/(2*9.81*0.0254^2) = 0.229274 m;
  //   E2* = 0.131781 + 0.0508^2/(2*9.81*0.131781^2) = 0.139355 m;
  //   eta* = 1 - E2*/E1 = 39.219 %  (the study's table lists 39.36 %: see the next test cases)
  const auto j = jump_hydraulics(0.0254, 2.00, 0.104, 9.81);
  CHECK(j.discharge_m2_s == Approx(0.0508).epsilon(1e-12));
  CHECK(j.froude1 == Approx(4.00662).margin(1e-5));
  CHECK(j.belanger_y2_m == Approx(0.131781).margin(1e-6));
  CHECK(j.e1_m == Approx(0.229274).margin(1e-6));
  CHECK(100.0 * j.eta_smooth == Approx(39.219).margin(1e-3));
}

TEST_CASE("Belanger's ratio and energy identities", "[cases][hydraulics]") {
  // For Fr1 = 1 the jump degenerates: y2 = y1 and no loss.
  CHECK(belanger_sequent_depth(0.1, 1.0) == Approx(0.1));
  // Smooth-bed energy loss equals (y2 - y1)^3 / (4 y1 y2) (momentum + continuity).
  for (double fr : {2.0, 4.0, 6.0, 8.0}) {
    const double y1 = 0.03, g = 9.81, u1 = fr * std::sqrt(g * y1), q = y1 * u1;
    const double y2 = belanger_sequent_depth(y1, fr);
    const double loss = specific_energy(y1, q, g) - specific_energy(y2, q, g);
    CHECK(loss == Approx(std::pow(y2 - y1, 3) / (4 * y1 * y2)).epsilon(1e-9));
  }
  CHECK(energy_dissipation_rate(2.0, 1.0) == Approx(0.5));
}

// The study's table (Bo et al. 2019) lists eta on a smooth bed for each run's y1 and U1. Its values
// differ from the exact formula by up to 0.43 points (run B: 56.48 vs 56.05; A 39.22 vs 39.36),
// presumably from rounded inputs; this test checks that the spec's y1 and U1 are the study's runs
// (a wrong run would be several points off), not the formula, which is checked exactly above.
TEST_CASE("Smooth-bed eta of all five runs matches the study's table within 0.5 points",
          "[cases][hydraulics]") {
  const Study study = load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/ead2002.toml");
  struct Row { const char* id; double eta_smooth; };
  for (const Row row : {Row{"A", 39.36}, Row{"B", 56.05}, Row{"C", 66.12}, Row{"D", 54.97}, Row{"E", 54.97}}) {
    const auto* b = study.find_case(row.id)->stilling_basin();
    REQUIRE(b);
    const auto j = jump_hydraulics(b->inflow_depth_m, b->inflow_velocity_m_s, b->tailwater_depth_m, 9.81);
    INFO("run " << row.id << ": eta* = " << 100 * j.eta_smooth);
    CHECK(std::abs(100.0 * j.eta_smooth - row.eta_smooth) < 0.5);
  }
}

TEST_CASE("Rehbock's sharp-crested weir: hand value, inverse and tailgate height", "[cases][hydraulics]") {
  // P = 0.1 m, H = 0.05 m: Cd = 0.611 + 0.08 * 0.5 = 0.651, q = 2/3 * 0.651 * sqrt(19.62) * 0.05^1.5
  // = 0.434 * 4.429447 * 0.0111803 = 0.0214929 m^2/s (by hand).
  CHECK(rehbock_weir_discharge(0.05, 0.1, 9.81) == Approx(0.0214929).epsilon(1e-5));
  CHECK(rehbock_weir_discharge(0.0, 0.1, 9.81) == 0.0);
  for (const double p : {0.01, 0.05, 0.3}) {
    for (const double head : {0.005, 0.05, 0.2}) {
      const double q = rehbock_weir_discharge(head, p, 9.81);
      CHECK(rehbock_weir_head(q, p, 9.81) == Approx(head).epsilon(1e-10));
    }
  }
  // The tailgate that holds run A's smooth-bed tailwater y2* = 0.132 m at q = 0.0508 m^2/s.
  const double q = 0.0508, y = 0.132;
  const double p = tailgate_height_for_depth(q, y, 9.81);
  const double head = rehbock_weir_head(q, p, 9.81);
  CHECK(p + head == Approx(y).epsilon(1e-10));
  CHECK(rehbock_weir_discharge(head, p, 9.81) == Approx(q).epsilon(1e-10));
  CHECK(p > 0.0);
  CHECK(p < y);
  CHECK_THROWS_AS(rehbock_weir_head(0.0, 0.1, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(rehbock_weir_head(0.05, 0.0, 9.81), std::invalid_argument);
  CHECK_THROWS_AS(tailgate_height_for_depth(0.05, -1.0, 9.81), std::invalid_argument);
}

TEST_CASE("A classical jump's roller surface: tanh(1.5 X) from the toe", "[cases][hydraulics]") {
  CHECK(roller_surface_fraction(-0.5) == 0.0);
  CHECK(roller_surface_fraction(0.0) == 0.0);
  CHECK(roller_surface_fraction(1.0) == Approx(0.90515).epsilon(1e-4));  // tanh 1.5
  CHECK(roller_surface_fraction(3.0) == Approx(1.0).epsilon(3e-4));
  // Hager's roller length by hand: y1 = 0.0254 m, Fr1 = 4: 0.0254 (-12 + 160 tanh 0.2) = 0.4973 m.
  CHECK(hager_roller_length(0.0254, 4.0) == Approx(0.4973).epsilon(1e-3));
  CHECK(std::isnan(hager_roller_length(0.0254, 2.0)));
}
