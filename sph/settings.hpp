// Resolved numerical settings of one SPH run: the case's [sph] table, the fluid, the resolution's
// particle spacing and the geometry's body force and domain, turned into the numbers the solver uses.
// String options are checked here; unknown values are rejected with the key and the allowed values.
#pragma once

#include <string>

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

enum class BoundaryMethod { dbc, mdbc };
enum class TimeIntegrator { symplectic, verlet };
// sph.outflow_condition: the outflow buffers of open_boundaries.hpp, or the weir of tailgate.hpp.
enum class OutflowCondition { hydrostatic_level, absorbing, tailgate };
// sph.inflow_condition: the inflow buffer of open_boundaries.hpp, or a piston reservoir behind a sluice
// gate (cases::add_piston_reservoir, sph/piston_inflow.hpp).
enum class InflowCondition { buffer, piston };

struct SolverSettings {
  // Options (the strings of the spec, parsed).
  KernelType kernel = KernelType::wendland_c2;
  Viscosity viscosity = Viscosity::artificial;
  BoundaryMethod boundary = BoundaryMethod::dbc;
  DensityDiffusion density_diffusion = DensityDiffusion::fourtakas;
  TimeIntegrator time_integrator = TimeIntegrator::symplectic;
  // Numbers.
  double dx = 0.01;                  // particle spacing (m)
  double h = 0.0;                    // smoothing length (m)
  TaitEquationOfState eos;           // rho0, c0, B
  double artificial_alpha = 0.01;
  double artificial_wall_factor = 1.0;  // alpha with wall (boundary) neighbours = factor * alpha
  double kinematic_viscosity = 1e-6; // nu0 (m^2/s)
  double sps_length = 0.0012;        // l in nu_t = l^2 |S| (m): C_s dx, or sph.sps_mixing_length_m
  bool sps_length_near_walls = false; // l = min(l, kappa d_wall) (Prandtl; with a mixing length)
  bool sps_wall_distance_table = false; // ... with d beyond the kernel support from the fixed walls'
                                        // distance table (sph.sps_wall_distance = "whole_domain")
  bool viscous_walls_free_slip = false; // laminar_sps + mdbc: walls mirror the tangential velocity
  bool wall_function_shear = false;     // ... and the first fluid layer takes the log law's wall shear
  ParticleShifting particle_shifting = ParticleShifting::none;  // particle_shifting.hpp
  double shifting_coefficient = 2.0;        // A in delta r = -A h |v| dt grad C
  double shifting_surface_threshold = 1.5;  // div r below this: free surface, not shifted
  ShiftingCorrection shifting_correction = ShiftingCorrection::none;  // taylor(_volume): u, w, rho moved with the shift
  double blin = 0.0066;
  double diffusion_delta = 0.1;
  double cfl = 0.2;
  int verlet_euler_interval = 40;
  double body_force_x = 0.0, body_force_z = -9.81;   // m/s^2
  // Domain: fluid outside [x_min, x_max] x [z_min, fluid_ceiling] (plus a margin) stops the run.
  double x_min = 0.0, x_max = 1.0, z_min = 0.0, z_max = 1.0;
  // The top above which fluid has escaped: z_max for closed tanks; for an open channel with an
  // inflow the energy line z_b(x_in) + E1 if higher (spray of a roller flies above the air layer,
  // but no water can rise above the total head of the inflow).
  double fluid_ceiling = 1.0;
  bool periodic_x = false;           // period x_max - x_min
  double max_density_variation = 0.05;
  double domain_margin = 0.0;        // tolerated excursion beyond the box (m)
  int open_boundary_layers = 0;      // inflow/outflow buffer columns (0: ceil(support/dx) + 1)
  InflowCondition inflow = InflowCondition::buffer;                // sph.inflow_condition
  OutflowCondition outflow = OutflowCondition::hydrostatic_level;  // sph.outflow_condition
  double tailgate_height = 0.0;      // "tailgate": crest above the bed at the outflow section (m), resolved
  // sph.outflow_level_reference = "downstream_section": the outlet's target depth is controlled so that
  // the "downstream" section at x = outflow_level_section_x holds the tailwater depth
  // (outflow_level_control.hpp), with the integral time outflow_level_time (s).
  bool outflow_level_at_section = false;
  double outflow_level_section_x = 0.0;
  double outflow_level_time = 2.0;
  WallMotion wall_motion;            // the moving_wall particles' motion (a lifted dam-break gate)

  double support() const { return 2.0 * h; }
  double eta2() const { return 0.01 * h * h; }
  // Throws std::invalid_argument naming the offending setting.
  void validate() const;
};

BoundaryMethod parse_boundary(const std::string& name);
TimeIntegrator parse_time_integrator(const std::string& name);
OutflowCondition parse_outflow_condition(const std::string& name);
InflowCondition parse_inflow_condition(const std::string& name);

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
