// Helpers of the SPH tests: load a verification case from cases/*.toml, adjust it, and build the
// solver inputs exactly as `hydrojump sph` does.
#pragma once

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>
#include <variant>

#include "cases/geometry.hpp"
#include "cases/spec_reader.hpp"
#include "sph/particle_generator.hpp"
#include "sph/settings.hpp"
#include "sph/solver.hpp"

namespace sph_test {

struct LoadedCase {
  hydrojump::cases::Study study;
  hydrojump::cases::Case spec;
  hydrojump::cases::CaseGeometry geometry;
  hydrojump::sph::SolverSettings settings;
  hydrojump::sph::ParticleSet particles;
};

// Loads cases/<file> (its first case) at particle spacing dx; `adjust` may change the case's
// [sph] settings before the geometry and settings are derived.
inline LoadedCase load_case(const std::string& file, double dx,
                            const std::function<void(hydrojump::cases::Case&)>& adjust = {}) {
  LoadedCase out;
  out.study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + (file == "basins.toml" ? "/tests/data/" : "/cases/") + file);
  out.spec = out.study.cases.front();
  if (adjust) adjust(out.spec);
  out.geometry = hydrojump::sph::solver_geometry(out.spec, out.study.fluid, dx);
  out.settings = hydrojump::sph::make_settings(out.spec, out.study.fluid, out.geometry, dx);
  out.particles = hydrojump::sph::generate_particles(out.geometry, out.settings, out.spec.sph.boundary_layers);
  return out;
}

// The viscosity of the short-basin fixtures, independent of the model the study file chooses for
// A_smooth: Monaghan's artificial viscosity alpha = 0.1 between fluid particles only (wall factor 0).
// The fixtures test open boundaries, gates and bookkeeping, and their measured figures were taken
// with this model.
inline void use_fixture_viscosity(hydrojump::cases::Case& c) {
  c.sph.viscosity = hydrojump::cases::Viscosity::artificial;
  c.sph.artificial_viscosity_alpha = 0.1;
  c.sph.artificial_viscosity_nu_m2_s = 0.0;
  c.sph.artificial_viscosity_wall_factor = 0.0;
  c.sph.sps_mixing_length_m = 0.0;
  c.sph.viscous_wall_condition = hydrojump::cases::ViscousWallCondition::no_slip;
}

// Case A_smooth of tests/data/basins.toml (the reference study frozen for the tests) (y1 = 25.4 mm, U1 = 2 m/s) on a shortened domain (0.1 m
// upstream, 0.3 m basin, 0.1 m downstream) at spacing dx, with the fixture viscosity above; `adjust`
// may change it further (its [sph] settings, run length) before the solver geometry, settings and
// particles are derived.
inline LoadedCase short_smooth_basin(double dx, const std::function<void(hydrojump::cases::Case&)>& adjust = {}) {
  LoadedCase out;
  out.study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const hydrojump::cases::Case* found = out.study.find_case("A_smooth");
  if (found == nullptr) throw std::logic_error("tests/data/basins.toml has no case A_smooth");
  out.spec = *found;
  auto& basin = std::get<hydrojump::cases::StillingBasinCase>(out.spec.data);
  basin.upstream_length_m = 0.1;
  basin.basin_length_m = 0.3;
  basin.downstream_length_m = 0.1;
  use_fixture_viscosity(out.spec);
  if (adjust) adjust(out.spec);
  out.geometry = hydrojump::sph::solver_geometry(out.spec, out.study.fluid, dx);
  out.settings = hydrojump::sph::make_settings(out.spec, out.study.fluid, out.geometry, dx);
  out.particles = hydrojump::sph::generate_particles(out.geometry, out.settings, out.spec.sph.boundary_layers);
  return out;
}

// Largest fluid speed.
inline double max_fluid_speed(const hydrojump::sph::ParticleSet& ps) {
  double v = 0.0;
  for (Eigen::Index i = 0; i < ps.size(); ++i)
    if (ps.is_fluid(i)) v = std::max(v, std::hypot(ps.u[i], ps.w[i]));
  return v;
}

}  // namespace sph_test
