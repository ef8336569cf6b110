// The sinusoidal bed profile: shape, slope, normals and arc-length sampling.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "cases/bed_profile.hpp"

using hydrojump::cases::BedProfile;

TEST_CASE("Sinusoidal bed: crests at the floor, troughs T below, smooth elsewhere", "[cases][bed]") {
  const double S = 0.068, T = 0.013, x0 = 0.2;
  const auto bed = BedProfile::sinusoidal(S, T, x0, x0 + 10 * S);
  CHECK(bed.elevation(0.1) == 0.0);
  CHECK(bed.elevation(x0) == Approx(0.0).margin(1e-15));
  CHECK(bed.elevation(x0 + 0.5 * S) == Approx(-T));
  CHECK(bed.elevation(x0 + 3 * S) == Approx(0.0).margin(1e-12));
  CHECK(bed.elevation(x0 + 10.25 * S) == 0.0);
  CHECK(bed.lowest_elevation() == Approx(-T));
  // Slope against a central finite difference.
  for (double x : {x0 + 0.1 * S, x0 + 0.37 * S, x0 + 4.8 * S}) {
    const double e = 1e-7;
    CHECK(bed.slope(x) == Approx((bed.elevation(x + e) - bed.elevation(x - e)) / (2 * e)).margin(1e-6));
    const auto n = bed.normal(x);
    CHECK(n.norm() == Approx(1.0));
    CHECK(n.x() * 1.0 + n.y() * bed.slope(x) == Approx(0.0).margin(1e-12));  // normal to the tangent
    CHECK(n.y() > 0.0);
  }
}

TEST_CASE("Arc length of a sinusoid against an independent fine trapezoid sum", "[cases][bed]") {
  const double S = 0.068, T = 0.022;
  const auto bed = BedProfile::sinusoidal(S, T, 0.0, 3 * S);
  const int n = 200000;
  double sum = 0.0;
  const double k = 2 * std::numbers::pi / S;
  for (int i = 0; i < n; ++i) {
    const double xa = 3 * S * i / n, xb = 3 * S * (i + 1) / n;
    const double za = -T / 2 * (1 - std::cos(k * xa)), zb = -T / 2 * (1 - std::cos(k * xb));
    sum += std::hypot(xb - xa, zb - za);
  }
  CHECK(bed.arc_length(0.0, 3 * S) == Approx(sum).epsilon(1e-8));
  CHECK(bed.arc_length(-0.1, 0.0) == Approx(0.1));
}

TEST_CASE("Points by arc length are evenly spaced and on the bed", "[cases][bed]") {
  const double S = 0.068, T = 0.013, dx = 0.004;
  const auto bed = BedProfile::sinusoidal(S, T, 0.1, 0.1 + 5 * S);
  const auto pts = bed.points_by_arc_length(0.0, 0.6, dx);
  REQUIRE(pts.size() > 10);
  CHECK(pts.front().x() == 0.0);
  CHECK(pts.back().x() == Approx(0.6));
  const double total = bed.arc_length(0.0, 0.6);
  const double ds = total / static_cast<double>(pts.size() - 1);
  CHECK(std::abs(ds - dx) < 0.5 * dx / static_cast<double>(pts.size() - 1) + 1e-12);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    CHECK(pts[i].y() == Approx(bed.elevation(pts[i].x())).margin(1e-12));
    const double chord = (pts[i] - pts[i - 1]).norm();
    CHECK(chord <= ds * (1 + 1e-6));
    CHECK(chord >= 0.98 * ds);  // chords are a little shorter than arcs on the curve
  }
}

TEST_CASE("Polyline follows the bed within the requested deviation", "[cases][bed]") {
  const double S = 0.068, T = 0.022;
  const auto bed = BedProfile::sinusoidal(S, T, 0.2, 0.2 + 4 * S);
  const double tol = 1e-4;
  const auto line = bed.polyline(0.0, 0.6, tol);
  REQUIRE(line.size() >= 2);
  CHECK(line.front().x() == Approx(0.0).margin(1e-12));
  CHECK(line.back().x() == Approx(0.6).margin(1e-12));
  for (std::size_t i = 1; i < line.size(); ++i) {
    for (int k = 1; k < 10; ++k) {
      const double t = k / 10.0;
      const auto p = (1 - t) * line[i - 1] + t * line[i];
      CHECK(std::abs(p.y() - bed.elevation(p.x())) <= 1.05 * tol);
    }
  }
}
