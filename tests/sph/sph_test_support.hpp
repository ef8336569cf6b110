// Helpers of the SPH tests: load a verification case from cases/*.toml, adjust it, and build the
// solver inputs exactly as `hydrojump sph` does.
#pragma once

#include <algorithm>
#include <functional>
#include <string>

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
  out.study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/cases/" + file);
  out.spec = out.study.cases.front();
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
