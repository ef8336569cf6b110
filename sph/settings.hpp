// Resolved numerical settings of one SPH run: the case's [sph] table, the fluid, the resolution's
// particle spacing and the geometry's body force and domain, turned into the numbers the solver uses.
// String options are checked here; unknown values are rejected with the key and the allowed values.
#pragma once

#include <string>

#include "cases/options.hpp"
#include "sph/density_diffusion.hpp"
#include "sph/kernel.hpp"
#include "sph/particle_shifting.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/viscosity.hpp"
#include "sph/wall_motion.hpp"

namespace hydrojump::cases {
struct Case;
struct FluidProperties;
struct CaseGeometry;
}  // namespace hydrojump::cases

namespace hydrojump::sph {

// The spec's options (cases/options.hpp), used by the solver as they are.
using cases::BoundaryMethod;
using cases::TimeIntegrator;
using cases::OutflowCondition;  // the outflow buffers of open_boundaries.hpp, or the weir of tailgate.hpp
using cases::InflowCondition;   // the inflow buffer, or a piston reservoir behind a sluice gate (piston_inflow.hpp)

// The models' settings, grouped by concept; each group names the file of its model.

// Viscosity (viscosity.hpp, wall_function.hpp, wall_distance.hpp).
struct ViscositySettings {
  Viscosity model = Viscosity::artificial;
  double artificial_alpha = 0.01;
  double artificial_wall_factor = 1.0;  // alpha with wall (boundary) neighbours = factor * alpha
  double kinematic_viscosity = 1e-6;    // nu0 (m^2/s)
  double sps_length = 0.0012;           // l in nu_t = l^2 |S| (m): C_s dx, or sph.sps_mixing_length_m
  double blin = 0.0066;                 // C_I of the SPS isotropic term
  bool sps_length_near_walls = false;   // l = min(l, kappa d_wall) (Prandtl; with a mixing length)
  bool sps_wall_distance_table = false; // ... with d beyond the kernel support from the fixed walls'
                                        // distance table (sph.sps_wall_distance = "whole_domain")
  bool viscous_walls_free_slip = false; // laminar_sps + mdbc: walls mirror the tangential velocity
  bool wall_function_shear = false;     // ... and the first fluid layer takes the log law's wall shear
};

// Density: the diffusion term (density_diffusion.hpp) and the variation that stops a run.
struct DensitySettings {
  DensityDiffusion diffusion = DensityDiffusion::fourtakas;
  double diffusion_delta = 0.1;
  double max_variation = 0.05;          // |rho/rho0 - 1| above this stops the run
};

// Particle shifting (particle_shifting.hpp).
struct ShiftingSettings {
  ParticleShifting model = ParticleShifting::none;
  double coefficient = 2.0;             // A in delta r = -A h |v| dt grad C
  double surface_threshold = 1.5;       // div r below this: free surface, not shifted
  ShiftingCorrection correction = ShiftingCorrection::none;  // taylor(_volume): u, w, rho moved with the shift
};

// Time stepping (time_integration.hpp).
struct TimeSteppingSettings {
  TimeIntegrator integrator = TimeIntegrator::symplectic;
  double cfl = 0.2;
  int verlet_euler_interval = 40;
};

// The domain: fluid outside [x_min, x_max] x [z_min, fluid_ceiling] (plus a margin) stops the run.
struct DomainSettings {
  double x_min = 0.0, x_max = 1.0, z_min = 0.0, z_max = 1.0;
  // The top above which fluid has escaped: z_max for closed tanks; for an open channel with an
  // inflow the energy line z_b(x_in) + E1 if higher (spray of a roller flies above the air layer,
  // but no water can rise above the total head of the inflow).
  double fluid_ceiling = 1.0;
  bool periodic_x = false;              // period x_max - x_min
  double margin = 0.0;                  // tolerated excursion beyond the box (m)
};

// Open boundaries (open_boundaries.hpp, piston_inflow.hpp, tailgate.hpp, outflow_level_control.hpp).
struct OpenBoundarySettings {
  int layers = 0;                       // inflow/outflow buffer columns (0: ceil(support/dx) + 1)
  InflowCondition inflow = InflowCondition::buffer;                // sph.inflow_condition
  OutflowCondition outflow = OutflowCondition::hydrostatic_level;  // sph.outflow_condition
  double tailgate_height = 0.0;         // "tailgate": crest above the bed at the outflow section (m), resolved
  // sph.outflow_level_reference = "downstream_section": the outlet's target depth is controlled so that
  // the "downstream" section at x = level_section_x holds the tailwater depth
  // (outflow_level_control.hpp), with the integral time level_time (s).
  bool level_at_section = false;
  double level_section_x = 0.0;
  double level_time = 2.0;
};

struct SolverSettings {
  KernelType kernel = KernelType::wendland_c2;
  BoundaryMethod boundary = BoundaryMethod::dbc;
  double dx = 0.01;                     // particle spacing (m)
  double h = 0.0;                       // smoothing length (m)
  TaitEquationOfState eos;              // rho0, c0, B
  double body_force_x = 0.0, body_force_z = -9.81;   // m/s^2
  ViscositySettings viscosity;
  DensitySettings density;
  ShiftingSettings shifting;
  TimeSteppingSettings time;
  DomainSettings domain;
  OpenBoundarySettings open;
  WallMotion wall_motion;               // the moving_wall particles' motion (a lifted dam-break gate)

  double support() const { return 2.0 * h; }
  double eta2() const { return 0.01 * h * h; }
  // Throws std::invalid_argument naming the offending setting.
  void validate() const;
};

// Number of boundary-particle layers: `requested` if positive, else enough layers of spacing dx to
// cover the kernel support 2h (n = ceil(2h/dx)). Used by the generator for every wall and by
// solver_geometry for the sluice plate's thickness.
int boundary_layer_count(double h, double dx, int requested);

// The geometry the SPH solver runs: cases::make_geometry, plus the piston reservoir of
// sph.inflow_condition = "piston" (cases::add_piston_reservoir, its sluice plate as thick as the
// boundary layers at spacing dx). Every SPH entry point (run, generate, tests) uses this.
cases::CaseGeometry solver_geometry(const cases::Case& c, const cases::FluidProperties& fluid, double dx);

// Settings of case `c` at particle spacing `dx` with the geometry `g` (domain, body force, H_max).
SolverSettings make_settings(const cases::Case& c, const cases::FluidProperties& fluid,
                             const cases::CaseGeometry& g, double dx);

}  // namespace hydrojump::sph
