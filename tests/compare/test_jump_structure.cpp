// The classical jump's published structure (compare/jump_structure.hpp): Hager's roller length and
// USBR's jump length against hand-computed values, Verhoff's wall-jet profile against its defining
// properties, and the wall-jet fit on synthetic profiles with known answers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "compare/jump_structure.hpp"

using namespace hydrojump::compare;

namespace {

// A section over a flat bed at z = 0 on a 1 mm grid up to `top`, every height wet, u(z) given.
template <class Profile>
ColumnStatistics section_with(Profile u, double top) {
  ColumnStatistics s;
  s.spec.z_bed_m = 0.0;
  s.n_wet = 10;
  for (double z = 0.0005; z < top; z += 0.001) {
    s.z.push_back(z);
    s.u_mean.push_back(u(z));
    s.wet_fraction.push_back(1.0);
  }
  return s;
}

}  // namespace

TEST_CASE("Hager's roller length and USBR's jump length give the hand-computed values inside their ranges only",
          "[compare][structure]") {
  // Fr1 = 4: -12 + 160 tanh(0.2) = -12 + 160 x 0.197375 = 19.580 y1; y1 = 25.4 mm: 0.4973 m.
  CHECK(hager_roller_length(0.0254, 4.0) == Approx(0.0254 * 19.580).epsilon(1e-4));
  // Fr1 = 8: -12 + 160 tanh(0.4) = -12 + 160 x 0.379949 = 48.792 y1.
  CHECK(hager_roller_length(0.01, 8.0) == Approx(0.48792).epsilon(1e-4));
  CHECK(std::isnan(hager_roller_length(0.0254, 2.0)));
  CHECK(std::isnan(hager_roller_length(0.0254, 25.0)));
  CHECK(std::isnan(hager_roller_length(0.0, 4.0)));
  CHECK(usbr_jump_length(0.1318, 4.0) == Approx(0.7908));
  CHECK(std::isnan(usbr_jump_length(0.1318, 3.0)));
}

TEST_CASE("Verhoff's wall-jet profile peaks at 1 and falls to one half at eta = 1", "[compare][structure]") {
  // Its defining properties: u/u_m reaches 1 at the maximum and 1/2 at z = delta (within the fit's 1 %).
  double peak = 0.0, at = 0.0;
  for (double eta = 0.0; eta <= 3.0; eta += 1e-4) {
    if (wall_jet_profile(eta) > peak) { peak = wall_jet_profile(eta); at = eta; }
  }
  CHECK(peak == Approx(1.0).margin(0.01));
  CHECK(at == Approx(0.16).margin(0.03));
  CHECK(wall_jet_profile(1.0) == Approx(0.5).margin(0.01));
  CHECK(wall_jet_profile(0.0) == 0.0);
  CHECK(wall_jet_profile(3.0) < 0.05);
  CHECK(std::isnan(wall_jet_profile(-1.0)));
}

TEST_CASE("The wall-jet fit recovers a wall jet's half-velocity height and tells it from a surface jet",
          "[compare][structure]") {
  SECTION("a wall jet under a roller's reverse flow: delta recovered, deviation near zero, classic") {
    const double um = 2.0, delta = 0.03;
    const auto s = section_with([&](double z) { return z < 2.0 * delta ? um * wall_jet_profile(z / delta) : -0.3; }, 0.12);
    const WallJetFit fit = fit_wall_jet(s);
    CHECK(fit.half_velocity_height_m == Approx(delta).margin(0.001));
    CHECK(fit.max_velocity_m_s == Approx(um).margin(0.01));
    CHECK(fit.deviation < 0.02);
    CHECK(fit.points >= 25);
    CHECK(classic_structure(fit.max_height_m / 0.12, fit.deviation));
  }
  SECTION("a surface jet (fastest at the surface, reverse flow at the bed) has no half-velocity height") {
    const auto s = section_with([](double z) { return -0.5 + 20.0 * z; }, 0.12);
    const WallJetFit fit = fit_wall_jet(s);
    CHECK(fit.max_height_m == Approx(0.1195).margin(1e-6));
    CHECK(std::isnan(fit.half_velocity_height_m));
    CHECK(std::isnan(fit.deviation));
    CHECK_FALSE(classic_structure(fit.max_height_m / 0.12, fit.deviation));
  }
  SECTION("a wall jet of another shape (a triangle peaking at mid-height of delta) is measured off the profile") {
    // u/u_m = z/0.02 up to 0.02 m, then down to 0 at 0.06 m: delta = 0.04 m. Below eta = 0.5 it lies
    // under Verhoff's profile by up to ~0.8 (at eta = 0.05: 0.1 against 0.93).
    const auto s = section_with([](double z) { return z < 0.02 ? z / 0.02 : std::max(0.0, (0.06 - z) / 0.04); }, 0.1);
    const WallJetFit fit = fit_wall_jet(s);
    CHECK(fit.half_velocity_height_m == Approx(0.04).margin(0.001));
    CHECK(fit.deviation > 0.2);
    CHECK_FALSE(classic_structure(0.2, fit.deviation));
  }
  SECTION("heights that were mostly dry do not count, and a dry section gives nothing") {
    auto s = section_with([](double) { return 1.0; }, 0.05);
    for (auto& f : s.wet_fraction) f = 0.2;
    CHECK(std::isnan(fit_wall_jet(s).max_velocity_m_s));
  }
}
