// Density outliers: fluid particles whose density has left the range a liquid holds, removed from the
// run as DualSPHysics removes them ("RhopOut", on by default with [700, 1300] kg/m^3 for water;
// Crespo et al. 2015, Comput. Phys. Commun. 187:204-216, and Dominguez et al. 2022, Comput. Part.
// Mech. 9:867-895, "DualSPHysics: from fluid dynamics to multiphysics problems").
//
// A single particle thrown out of a breaking surface (the spray where a start-up jet meets the
// tailwater, a droplet falling back onto the roller) can see its neighbours leave or pile up within a
// few steps; its density, integrated from the continuity equation, then runs away although the water
// around it is fine. Removing it keeps the run; the mass it carried is counted (SolverClock, the run
// log) and a run that would lose more than a small share of its water this way stops instead
// (diagnose() in sph/run.hpp): the water itself is unhealthy then.
//
//   | rule      | condition (fluid particle i)                        | action                           |
//   |-----------|-----------------------------------------------------|----------------------------------|
//   | outlier   | rho_i < 0.7 rho0  or  rho_i > 1.3 rho0              | removed, its mass counted        |
//   | too many  | removed mass > 1 % of the water mass (both, kg/m)   | the run stops with a diagnosis   |
//
// sph.max_density_variation (the run's stop) still applies to every particle that is kept: below 0.3
// it stops the run first, unless one step takes a particle past both limits (it is then removed).
// "The water" is what is in the domain now: fluid and outflow-buffer particles (with a piston, its
// reservoir too).
// Example:
//   const DensityOutliers out = remove_density_outliers(particles, settings);
//   clock.outlier_particles += out.particles;  clock.outlier_mass += out.mass;
#pragma once

#include <cstdint>
#include <vector>

#include "sph/particles.hpp"
#include "sph/settings.hpp"

namespace hydrojump::sph {

// DualSPHysics' default RhopOut range for water, 700-1300 kg/m^3, as a fraction of rho0.
inline constexpr double kOutlierDensityLow = 0.7;
inline constexpr double kOutlierDensityHigh = 1.3;
// The share of the water a run may lose as outliers before it stops.
inline constexpr double kOutlierMassShareLimit = 0.01;

struct DensityOutliers {
  std::int64_t particles = 0;
  double mass = 0.0;                // kg/m
  std::vector<double> x_m, mass_kg;  // where each removed particle was, and its mass (kg/m)
};

// Whether fluid particle density rho is an outlier: rho < 0.7 rho0 or rho > 1.3 rho0 (NaN is not).
inline bool is_density_outlier(double rho, double rho0) {
  return rho < kOutlierDensityLow * rho0 || rho > kOutlierDensityHigh * rho0;
}

// Removes the fluid particles whose density is an outlier and that are otherwise healthy (finite state,
// inside the domain: sph/particle_health.hpp), keeping the order of the others. A particle that is
// also non-finite, below the bed or out of the domain stays for the run's check to name: a leak
// through a wall or a blow-up is a failure, not spray.
DensityOutliers remove_density_outliers(ParticleSet& particles, const SolverSettings& settings);

}  // namespace hydrojump::sph
