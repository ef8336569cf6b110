// Section sampling on synthetic particle and cell sets with known fields.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "compare/point_cloud.hpp"
#include "compare/sampling.hpp"
#include "compare/sph_kernel.hpp"
#include "synthetic_fields.hpp"

using namespace hydrojump::compare;
using namespace hydrojump::compare::testing;

namespace {
constexpr double g = 9.81;

// int_0^eta (A + B z)^3 dz
double cube_integral(double a, double b, double eta) {
  return (std::pow(a + b * eta, 4) - std::pow(a, 4)) / (4.0 * b);
}
// int_0^eta (a + b z)^2 dz
double square_integral(double a, double b, double eta) {
  return (std::pow(a + b * eta, 3) - std::pow(a, 3)) / (3.0 * b);
}
}  // namespace

// The lattice sum sum_j dx^2 W(x - x_j) at h = sqrt(2) dx departs from 1 by up to 6e-3 (Wendland, at a
// lattice point; 4e-3 midway between rows, 2e-4 at (0.3, -0.2) dx): 1e-2 at every probe, so a kernel
// off by a normalisation factor (2D vs 3D, 7/(4 pi h^2) vs 7/(pi h^2)) fails at all of them.
TEST_CASE("SPH kernels are normalised on a lattice and vanish at 2h", "[compare][kernel]") {
  for (const std::string name : {"wendland_c2", "cubic_spline"}) {
    const double dx = 0.01, h = std::sqrt(2.0) * dx;
    const SphKernel2D w(name, h);
    for (const auto& [px, pz] : std::vector<std::pair<double, double>>{{0.0, 0.0}, {0.5, 0.5}, {0.3, -0.2}, {0.25, 0.0}}) {
      double sum = 0.0;
      for (int i = -10; i <= 10; ++i)
        for (int k = -10; k <= 10; ++k) sum += dx * dx * w(std::hypot((i + px) * dx, (k + pz) * dx));
      INFO(name << " lattice sum at (" << px << ", " << pz << ") dx: " << sum);
      CHECK(sum == Approx(1.0).margin(1e-2));
    }
    CHECK(w(2.0 * h) == 0.0);
    CHECK(w(2.5 * h) == 0.0);
    CHECK(w(1.999 * h) > 0.0);  // compact support of radius 2h, positive inside it
  }
  CHECK_THROWS_WITH(SphKernel2D("gaussian", 0.01), Catch::Contains("wendland_c2"));
}

TEST_CASE("Point cloud radius query equals brute force", "[compare][interpolation]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 1.0), uz(-0.2, 0.3);
  std::vector<double> x(3000), z(3000);
  for (std::size_t j = 0; j < x.size(); ++j) { x[j] = ux(rng); z[j] = uz(rng); }
  const PointCloud2D cloud(x, z, 0.03);
  for (int q = 0; q < 50; ++q) {
    const double qx = ux(rng), qz = uz(rng), r = 0.01 + 0.05 * ux(rng);
    std::vector<std::size_t> found, brute;
    cloud.for_each_within(qx, qz, r, [&](std::size_t j, double, double, double) { found.push_back(j); });
    for (std::size_t j = 0; j < x.size(); ++j)
      if (std::hypot(x[j] - qx, z[j] - qz) < r) brute.push_back(j);
    std::sort(found.begin(), found.end());
    REQUIRE(found == brute);
  }
}

TEST_CASE("MLS reproduces linear fields exactly on scattered points and Shepard reproduces constants",
          "[compare][interpolation]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  StencilBuilder b;
  std::vector<double> f_lin, f_const;
  for (std::size_t j = 0; j < 12; ++j) {
    const double dx = 0.02 * d(rng), dz = 0.02 * d(rng);
    b.add(j, dx, dz, 0.1 + std::abs(d(rng)));
    f_lin.push_back(2.0 + 5.0 * (0.3 + dx) - 7.0 * (0.1 + dz));  // f at (0.3 + dx, 0.1 + dz)
    f_const.push_back(3.25);
  }
  const Stencil mls = b.build(InterpolationScheme::mls_linear, 0.02);
  REQUIRE(mls.corrected);
  CHECK(mls.apply(f_lin) == Approx(2.0 + 5.0 * 0.3 - 7.0 * 0.1).margin(1e-10));
  const Stencil shepard = b.build(InterpolationScheme::shepard, 0.02);
  CHECK(shepard.apply(f_const) == Approx(3.25).margin(1e-12));
  CHECK_THROWS_WITH(parse_interpolation_scheme("cubic"), Catch::Contains("mls_linear"));
}

TEST_CASE("SPH flat free surface is found within 0.1 dx", "[compare][sph]") {
  const double dx = 0.01, depth = 0.2;
  const ParticleFrame f = lattice_particles(0.6, depth, dx, 3, [](double, double) { return 1.0; },
                                            [](double, double) { return 0.0; });
  for (const std::string kernel : {"wendland_c2", "cubic_spline"}) {
    SphSamplingSettings s;
    s.kernel = kernel;
    s.particle_spacing_m = dx;
    s.smoothing_length_m = std::sqrt(2.0) * dx;
    const auto sampler = make_sph_sampler(f, s);
    for (double x : {0.2, 0.2537, 0.31, 0.4049}) {
      const ColumnSample c = sampler->sample_column(x, 0.0, 21, g);
      INFO(kernel << " x = " << x << " surface " << c.surface_z_m << " integral check "
                  << c.surface_from_fraction_m);
      CHECK(std::abs(c.surface_z_m - depth) < 0.1 * dx);
      CHECK(std::abs(c.surface_from_fraction_m - depth) < 0.1 * dx);
    }
  }
}

TEST_CASE("SPH linear velocity field gives exact section values", "[compare][sph]") {
  const double dx = 0.01, depth = 0.2;
  auto u = [](double x, double z) { return 1.2 + 0.5 * x + 3.0 * z; };
  auto w = [](double x, double z) { return 0.1 - 0.2 * x + 0.4 * z; };
  const ParticleFrame f = lattice_particles(0.6, depth, dx, 3, u, w);
  SphSamplingSettings s;
  s.particle_spacing_m = dx;
  s.smoothing_length_m = std::sqrt(2.0) * dx;
  const auto sampler = make_sph_sampler(f, s);
  const double x = 0.3037;
  const ColumnSample c = sampler->sample_column(x, 0.0, 41, g);
  REQUIRE(c.wet());
  for (std::size_t k = 0; k < c.z.size(); ++k) {
    INFO("z = " << c.z[k]);
    CHECK(c.u[k] == Approx(u(x, c.z[k])).margin(1e-6));
    CHECK(c.w[k] == Approx(w(x, c.z[k])).margin(1e-6));
  }
  // Integrals over the detected depth h: exact for a linear u (Simpson is exact for cubics).
  const double h = c.depth_m, a = 1.2 + 0.5 * x, b = 3.0;
  const double q = a * h + 0.5 * b * h * h;
  CHECK(c.discharge_m2_s == Approx(q).margin(1e-6));
  CHECK(c.mean_velocity_m_s == Approx(q / h).margin(1e-6));
  CHECK(c.max_velocity_m_s == Approx(u(x, h)).margin(1e-6));
  const double alpha = cube_integral(a, b, h) / (std::pow(q / h, 3) * h);
  CHECK(c.energy_coefficient == Approx(alpha).margin(1e-6));
  CHECK(c.specific_energy_m == Approx(h + alpha * (q / h) * (q / h) / (2 * g)).margin(1e-6));
  const double beta = square_integral(a, b, h) / (std::pow(q / h, 2) * h);
  CHECK(c.momentum_coefficient == Approx(beta).margin(1e-6));
  CHECK(c.specific_force_m2 == Approx(0.5 * h * h + beta * q * q / (g * h)).margin(1e-9));
}

TEST_CASE("SPH quadratic velocity field is within the MLS interpolation error bound",
          "[compare][sph]") {
  const double dx = 0.01, depth = 0.2, h_sml = std::sqrt(2.0) * dx;
  auto u = [](double x, double z) { return 1.0 + 0.5 * x * x + 4.0 * z * z; };
  auto zero = [](double, double) { return 0.0; };
  const ParticleFrame f = lattice_particles(0.6, depth, dx, 3, u, zero);
  for (const auto scheme : {InterpolationScheme::mls_linear}) {
    SphSamplingSettings s;
    s.particle_spacing_m = dx;
    s.smoothing_length_m = h_sml;
    s.scheme = scheme;
    const auto sampler = make_sph_sampler(f, s);
    const double x = 0.3037;
    const ColumnSample c = sampler->sample_column(x, 0.0, 41, g);
    REQUIRE(c.wet());
    REQUIRE(c.z.size() == 41u);
    // Linear MLS of f: error = 1/2 sum_j phi_j d_j^T H d_j with |d_j| < 2h, so
    // |error| <= 1/2 max|f''| (2h)^2 sum_j |phi_j|; we state sum_j |phi_j| <= 3 at walls/surfaces.
    const double bound = 0.5 * 8.0 * (2 * h_sml) * (2 * h_sml) * 3.0;
    double worst = 0.0;
    for (std::size_t k = 0; k < c.z.size(); ++k) worst = std::max(worst, std::abs(c.u[k] - u(x, c.z[k])));
    INFO("max interpolation error " << worst << " m/s, bound " << bound);
    CHECK(worst < bound);
    // Interior points (more than 2h from bed and surface) see a full symmetric lattice: much closer.
    for (std::size_t k = 0; k < c.z.size(); ++k)
      if (c.z[k] > 2 * h_sml && c.z[k] < c.surface_z_m - 2 * h_sml)
        CHECK(std::abs(c.u[k] - u(x, c.z[k])) < 0.5 * 8.0 * h_sml * h_sml);
  }
}

TEST_CASE("VOF cells give the flat surface and alpha integral and exact linear fields", "[compare][vof]") {
  const double surface = 0.1234;
  auto u = [](double x, double z) { return 0.8 - 0.3 * x + 2.0 * z; };
  auto w = [](double x, double z) { return 0.05 + 0.1 * x - 0.2 * z; };
  const CellFrame f = cartesian_cells(0.6, 0.0, 0.3, 60, 40, surface, u, w);
  const double dz = 0.3 / 40;
  const auto sampler = make_vof_sampler(f, InterpolationScheme::mls_linear);
  for (double x : {0.2, 0.2537, 0.305}) {
    const ColumnSample c = sampler->sample_column(x, 0.0, 41, g);
    REQUIRE(c.wet());
    INFO("x = " << x << " surface " << c.surface_z_m);
    CHECK(std::abs(c.surface_z_m - surface) <= dz / 12.0 + 1e-12);
    CHECK(c.surface_from_fraction_m == Approx(surface).margin(1e-12));
    for (std::size_t k = 0; k < c.z.size(); ++k) {
      CHECK(c.u[k] == Approx(u(x, c.z[k])).margin(1e-6));
      CHECK(c.w[k] == Approx(w(x, c.z[k])).margin(1e-6));
    }
    const double h = c.depth_m, a = 0.8 - 0.3 * x, b = 2.0;
    const double q = a * h + 0.5 * b * h * h;
    CHECK(c.discharge_m2_s == Approx(q).margin(1e-6));
    CHECK(c.energy_coefficient == Approx(cube_integral(a, b, h) / (std::pow(q / h, 3) * h)).margin(1e-6));
  }
}

TEST_CASE("VOF quadratic field is within the MLS interpolation error bound", "[compare][vof]") {
  auto u = [](double x, double z) { return 1.0 + 0.5 * x * x + 4.0 * z * z; };
  auto zero = [](double, double) { return 0.0; };
  const CellFrame f = cartesian_cells(0.6, 0.0, 0.3, 60, 40, 0.2, u, zero);
  const auto sampler = make_vof_sampler(f, InterpolationScheme::mls_linear);
  const ColumnSample c = sampler->sample_column(0.3037, 0.0, 41, g);
  REQUIRE(c.wet());
  // Stencil radius R = 1.6 max(dx, dz) = 0.016 m; same bound as for SPH with |d_j| < R.
  const double r = 1.6 * 0.01;
  const double bound = 0.5 * 8.0 * r * r * 3.0;
  double worst = 0.0;
  for (std::size_t k = 0; k < c.z.size(); ++k) worst = std::max(worst, std::abs(c.u[k] - u(0.3037, c.z[k])));
  INFO("max interpolation error " << worst << " m/s, bound " << bound);
  CHECK(worst < bound);
}

TEST_CASE("A dry column and bad profile sizes are handled", "[compare][sph]") {
  const ParticleFrame f = lattice_particles(0.3, 0.1, 0.01, 3, [](double, double) { return 1.0; },
                                            [](double, double) { return 0.0; });
  SphSamplingSettings s;
  s.particle_spacing_m = 0.01;
  s.smoothing_length_m = std::sqrt(2.0) * 0.01;
  const auto sampler = make_sph_sampler(f, s);
  CHECK_FALSE(sampler->sample_column(2.0, 0.0, 21, g).wet());   // far outside the particles
  CHECK_THROWS_WITH(sampler->sample_column(0.15, 0.0, 20, g), Catch::Contains("odd"));
}

TEST_CASE("SPH Shepard interpolation is exact for constants and first order near boundaries",
          "[compare][sph]") {
  const double dx = 0.01, depth = 0.2, h = std::sqrt(2.0) * dx;
  auto u = [](double x, double z) { return 1.2 + 0.5 * x + 3.0 * z; };
  auto zero = [](double, double) { return 0.0; };
  SphSamplingSettings s;
  s.particle_spacing_m = dx;
  s.smoothing_length_m = h;
  s.scheme = InterpolationScheme::shepard;
  const auto constant = make_sph_sampler(lattice_particles(0.6, depth, dx, 3, [](double, double) { return 0.7; }, zero), s);
  const ColumnSample c0 = constant->sample_column(0.3037, 0.0, 21, 9.81);
  REQUIRE(c0.z.size() == 21u);
  for (double v : c0.u) CHECK(v == Approx(0.7).margin(1e-12));
  // A linear field: the error is bounded by |grad u| times the support radius 2h (one-sided
  // neighbourhoods at the bed and the surface) -- that is why "mls_linear" is the default.
  const auto linear = make_sph_sampler(lattice_particles(0.6, depth, dx, 3, u, zero), s);
  const ColumnSample c1 = linear->sample_column(0.3037, 0.0, 21, 9.81);
  double worst = 0.0;
  for (std::size_t k = 0; k < c1.z.size(); ++k) worst = std::max(worst, std::abs(c1.u[k] - u(0.3037, c1.z[k])));
  INFO("Shepard max error " << worst << " m/s");
  CHECK(worst < std::hypot(0.5, 3.0) * 2.0 * h);
  CHECK(worst > 1e-3);  // and it is not exact there (the MLS correction is what makes it exact)
}

TEST_CASE("Droplets above the water do not count as the free surface", "[compare][sph][vof]") {
  const double dx = 0.01, depth = 0.2;
  auto one = [](double, double) { return 1.0; };
  auto zero = [](double, double) { return 0.0; };
  ParticleFrame f = lattice_particles(0.6, depth, dx, 3, one, zero);
  // a 2 x 2 cluster of particles 6 cm above the water at x = 0.3
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      f.x.push_back(0.295 + i * dx); f.z.push_back(0.26 + k * dx);
      f.u.push_back(1.0); f.w.push_back(0.0); f.type.push_back(0); f.density.push_back(1000.0);
      f.pressure.push_back(0.0);
    }
  SphSamplingSettings s;
  s.particle_spacing_m = dx;
  s.smoothing_length_m = std::sqrt(2.0) * dx;
  const auto sampler = make_sph_sampler(f, s);
  INFO("kernel sum in the droplet " << sampler->sample_point(0.3, 0.265).fraction);
  CHECK(std::abs(sampler->sample_column(0.3, 0.0, 21, 9.81).surface_z_m - depth) < 0.1 * dx);

  CellFrame cells = cartesian_cells(0.6, 0.0, 0.3, 60, 40, 0.1234, one, zero);
  // one wet cell high above the water in the column at x = 0.305 (cells 0.01 x 0.0075)
  const std::size_t droplet = 35 * 60 + 30;
  cells.alpha[droplet] = 1.0;
  const auto vof = make_vof_sampler(cells, InterpolationScheme::mls_linear);
  CHECK(std::abs(vof->sample_column(0.305, 0.0, 21, 9.81).surface_z_m - 0.1234) <= 0.3 / 40 / 12 + 1e-12);
}

// A void below the surface (an air pocket under a roller; an empty cavity in single-phase SPH) that is
// thinner than the kernel support: velocities interpolated into it from the water around it must not
// count as discharge. Uniform u = 1 m/s, so q must equal the water depth h_w (not the column height).
TEST_CASE("A void below the surface carries no discharge", "[compare][sph][vof]") {
  const double dx = 0.01, depth = 0.2;
  auto one = [](double, double) { return 1.0; };
  auto zero = [](double, double) { return 0.0; };
  const ParticleFrame full = lattice_particles(0.6, depth, dx, 3, one, zero);
  // remove the rows with centres at z = 0.095 .. 0.125 (a 4 cm void between z = 0.09 and 0.13)
  // over 0.2 < x < 0.4: the void is 2.8 h thick, so every point in it still has water neighbours
  ParticleFrame f;
  for (std::size_t j = 0; j < full.x.size(); ++j) {
    if (full.x[j] > 0.2 && full.x[j] < 0.4 && full.z[j] > 0.09 && full.z[j] < 0.13) continue;
    f.x.push_back(full.x[j]); f.z.push_back(full.z[j]); f.u.push_back(full.u[j]); f.w.push_back(full.w[j]);
    f.type.push_back(full.type[j]); f.density.push_back(full.density[j]); f.pressure.push_back(full.pressure[j]);
  }
  SphSamplingSettings s;
  s.particle_spacing_m = dx;
  s.smoothing_length_m = std::sqrt(2.0) * dx;
  const auto sph = make_sph_sampler(f, s);
  const double void_m = 0.04;
  const ColumnSample c = sph->sample_column(0.3, 0.0, 41, g);
  REQUIRE(c.wet());
  INFO("SPH surface " << c.surface_z_m << " q " << c.discharge_m2_s << " void fraction " << c.void_fraction);
  CHECK(std::abs(c.surface_z_m - depth) < 0.1 * dx);
  // the void's edges located to within 0.1 dx by the c = 0.5 crossings between profile points
  CHECK(std::abs(c.discharge_m2_s - (depth - void_m)) < 0.1 * dx);
  CHECK(std::abs(c.void_fraction - void_m / depth) < 0.1 * dx / depth);
  CHECK(c.mean_velocity_m_s == Approx(c.discharge_m2_s / c.depth_m));
  const ColumnSample full_column = sph->sample_column(0.1, 0.0, 41, g);
  CHECK(full_column.void_fraction == Approx(0.0).margin(1e-12));
  CHECK(full_column.discharge_m2_s == Approx(full_column.depth_m).epsilon(1e-6));

  // VOF: 60 x 40 cells of 0.01 x 0.0075 m, surface 0.1234 m; cell rows 6-8 (z 0.045-0.0675) empty
  // over 0.2 < x < 0.4. alpha is linear between the centres, so the void is 0.0225 m thick.
  CellFrame cells = cartesian_cells(0.6, 0.0, 0.3, 60, 40, 0.1234, one, zero);
  for (int k = 6; k <= 8; ++k)
    for (int i = 20; i < 40; ++i) cells.alpha[static_cast<std::size_t>(k * 60 + i)] = 0.0;
  const auto vof = make_vof_sampler(cells, InterpolationScheme::mls_linear);
  const ColumnSample v = vof->sample_column(0.305, 0.0, 41, g);
  REQUIRE(v.wet());
  const double vof_void = 0.0225, dz = 0.3 / 40;
  INFO("VOF surface " << v.surface_z_m << " q " << v.discharge_m2_s << " void fraction " << v.void_fraction);
  CHECK(std::abs(v.surface_z_m - 0.1234) <= dz / 12 + 1e-12);
  CHECK(std::abs(v.discharge_m2_s - (0.1234 - vof_void)) < 0.1 * dz);
  CHECK(std::abs(v.void_fraction - vof_void / 0.1234) < 0.1 * dz / 0.1234);
}

// The near-surface velocity u(eta - 0.1 h) (the roller detector's input) reads water only: a void at
// that height gives the highest water point below it, not the value interpolated into the void.
TEST_CASE("The near-surface velocity skips a void at eta - 0.1 h", "[compare]") {
  ColumnSample c;
  c.z_bed_m = 0.0;
  c.surface_z_m = 0.2;
  c.depth_m = 0.2;
  for (int k = 0; k <= 20; ++k) {
    c.z.push_back(0.01 * k);
    c.u.push_back(1.0 + 0.01 * k);  // u = 1 + z
    c.fraction.push_back(1.0);
  }
  c.w.assign(c.z.size(), 0.0);
  c.pressure.assign(c.z.size(), 0.0);
  integrate_column(c, g);
  // no void: linear interpolation at z = 0.18 is exact for a linear profile
  CHECK(c.near_surface_velocity_m_s == Approx(1.18).epsilon(1e-12));
  // a void over z = 0.17 .. 0.19 with a spurious velocity interpolated into it
  for (int k = 17; k <= 19; ++k) {
    c.fraction[static_cast<std::size_t>(k)] = 0.1;
    c.u[static_cast<std::size_t>(k)] = -5.0;
  }
  integrate_column(c, g);
  CHECK(c.near_surface_velocity_m_s == Approx(1.16).epsilon(1e-12));  // the water point at z = 0.16
  // a void only just above the query height (z = 0.18 .. 0.19): the interval [0.18, 0.19) has a void end
  c.fraction.assign(c.z.size(), 1.0);
  for (int k = 0; k <= 20; ++k) c.u[static_cast<std::size_t>(k)] = 1.0 + 0.01 * k;
  c.fraction[19] = 0.2;
  c.u[19] = -5.0;
  integrate_column(c, g);
  CHECK(c.near_surface_velocity_m_s == Approx(1.18).epsilon(1e-12));  // z = 0.18 itself is water
}
