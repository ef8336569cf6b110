#include "sph/settings.hpp"

#include "sph/open_boundaries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "cases/spec.hpp"
#include "sph/kernel.hpp"

namespace hydrojump::sph {

namespace {
// The excursion beyond the domain box tolerated before a fluid particle counts as escaped (diagnose
// in run.hpp); the gate above the inflow is raised by it too.
double escape_margin(double h) { return 4.0 * h; }
}  // namespace

BoundaryMethod parse_boundary(const std::string& name) {
  if (name == "dbc") return BoundaryMethod::dbc;
  if (name == "mdbc") return BoundaryMethod::mdbc;
  throw std::invalid_argument("sph.boundary = \"" + name + "\" is not allowed: use \"dbc\" or \"mdbc\"");
}

TimeIntegrator parse_time_integrator(const std::string& name) {
  if (name == "symplectic") return TimeIntegrator::symplectic;
  if (name == "verlet") return TimeIntegrator::verlet;
  throw std::invalid_argument("sph.time_integrator = \"" + name + "\" is not allowed: use \"symplectic\" or \"verlet\"");
}

InflowCondition parse_inflow_condition(const std::string& name) {
  if (name == "buffer") return InflowCondition::buffer;
  if (name == "piston") return InflowCondition::piston;
  throw std::invalid_argument("sph.inflow_condition = \"" + name + "\" is not allowed: use \"buffer\" or \"piston\"");
}

int boundary_layer_count(double h, double dx, int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::ceil(2.0 * h / dx - 1e-9));
}

cases::CaseGeometry solver_geometry(const cases::Case& c, const cases::FluidProperties& fluid, double dx) {
  cases::CaseGeometry g = cases::make_geometry(c, fluid);
  if (parse_inflow_condition(c.sph.inflow_condition) == InflowCondition::piston) {
    const auto* basin = c.stilling_basin();
    if (basin == nullptr)
      throw std::invalid_argument("sph.inflow_condition = \"piston\" needs a stilling basin; case \"" + c.id +
                                  "\" is a " + c.kind);
    // The walls are as thick as the generator makes them.
    const int layers = boundary_layer_count(smoothing_length(c.sph.coef_h, dx), dx, c.sph.boundary_layers);
    const cases::PistonReservoir r = cases::add_piston_reservoir(
        g, *basin, c.sph.sluice_opening_m, c.sph.reservoir_length_m, c.run.end_time_s, layers * dx, fluid.gravity_m_s2);
    // As for y1 (at least 5 particles across the inflow depth): the jet under the gate must be resolved.
    if (r.opening_m < 5.0 * dx - 1e-12)
      throw std::invalid_argument("sph.sluice_opening_m: the sluice gate opening " + std::to_string(r.opening_m) +
                                  " m holds fewer than 5 particle spacings (dx = " + std::to_string(dx) + " m) in case \"" +
                                  c.id + "\"; allowed: >= " + std::to_string(5.0 * dx) +
                                  " m (or 0 for y1/0.611); use a finer resolution or a wider opening");
  }
  // The gate above the inflow reaches the fluid ceiling (the energy line E1); a fluid particle counts
  // as escaped only beyond the ceiling plus the domain margin 4h (diagnose in run.hpp). Raise the gate
  // by that margin and one spacing, so spray in the band cannot fly over it into the inflow unseen.
  const double raise = escape_margin(smoothing_length(c.sph.coef_h, dx)) + dx;
  for (auto& wall : g.walls) {
    if (wall.name != "inlet_gate" && wall.name != "sluice_gate") continue;
    double top = -std::numeric_limits<double>::infinity();
    for (const auto& p : wall.points) top = std::max(top, p.y());
    for (auto& p : wall.points)
      if (p.y() >= top - 1e-12) p.y() += raise;
  }
  return g;
}

OutflowCondition parse_outflow_condition(const std::string& name) {
  if (name == "hydrostatic_level") return OutflowCondition::hydrostatic_level;
  if (name == "absorbing") return OutflowCondition::absorbing;
  if (name == "tailgate") return OutflowCondition::tailgate;
  throw std::invalid_argument("sph.outflow_condition = \"" + name +
                              "\" is not allowed: use \"hydrostatic_level\", \"absorbing\" or \"tailgate\"");
}


namespace {
void require(bool ok, const std::string& key, double value, const std::string& range) {
  if (ok) return;
  std::ostringstream s;
  s << "sph setting " << key << " = " << value << " is out of range: " << range;
  throw std::invalid_argument(s.str());
}
}  // namespace

void SolverSettings::validate() const {
  require(dx > 0.0 && std::isfinite(dx), "particle_spacing_m", dx, "must be > 0");
  require(h > 0.0, "h", h, "must be > 0 (coef_h > 0)");
  require(eos.rho0 > 0.0, "fluid.density_kg_m3", eos.rho0, "must be > 0");
  require(eos.c0 > 0.0 && std::isfinite(eos.c0), "sound speed c0 (m/s)", eos.c0, "must be > 0");
  require(artificial_alpha >= 0.0 && artificial_alpha <= 1.0, "artificial_viscosity_alpha", artificial_alpha, "[0, 1]");
  require(artificial_wall_factor >= 0.0 && artificial_wall_factor <= 1.0, "artificial_viscosity_wall_factor",
          artificial_wall_factor, "[0, 1]");
  require(kinematic_viscosity >= 0.0, "fluid.kinematic_viscosity_m2_s", kinematic_viscosity, ">= 0");
  require(diffusion_delta >= 0.0 && diffusion_delta <= 1.0, "density_diffusion_coefficient", diffusion_delta, "[0, 1]");
  require(cfl > 0.0 && cfl <= 1.0, "cfl_number", cfl, "(0, 1]");
  require(verlet_euler_interval >= 1, "verlet_euler_interval", verlet_euler_interval, ">= 1");
  require(max_density_variation > 0.0, "max_density_variation", max_density_variation, "> 0");
  require(shifting_coefficient > 0.0 && shifting_coefficient <= 10.0, "particle_shifting_coefficient", shifting_coefficient, "(0, 10]");
  require(shifting_surface_threshold >= 0.0 && shifting_surface_threshold <= 1.9, "particle_shifting_surface_threshold",
          shifting_surface_threshold, "[0, 1.9]");
  if (particle_shifting != ParticleShifting::none && time_integrator != TimeIntegrator::symplectic)
    throw std::invalid_argument("sph.particle_shifting = \"fickian\" needs time_integrator = \"symplectic\" (the shift is applied "
                                "after the corrector with the corrector's concentration gradient; here \"verlet\")");
  if (shifting_correction != ShiftingCorrection::none && particle_shifting == ParticleShifting::none)
    throw std::invalid_argument("sph.particle_shifting_correction is only used with particle_shifting = \"fickian\" (here \"none\")");
  require(x_max > x_min && z_max > z_min, "domain box", x_max - x_min, "must have positive size");
}

SolverSettings make_settings(const cases::Case& c, const cases::FluidProperties& fluid, const cases::CaseGeometry& g,
                             double dx) {
  const cases::SphSettings& s = c.sph;
  SolverSettings out;
  out.kernel = parse_kernel(s.kernel);
  out.viscosity = parse_viscosity(s.viscosity);
  out.boundary = parse_boundary(s.boundary);
  out.density_diffusion = parse_density_diffusion(s.density_diffusion);
  out.time_integrator = parse_time_integrator(s.time_integrator);
  out.dx = dx;
  out.h = smoothing_length(s.coef_h, dx);
  const double g_abs = std::hypot(g.body_force_m_s2.x(), g.body_force_m_s2.y());
  const double gravity = fluid.gravity_m_s2 > 0.0 ? fluid.gravity_m_s2 : g_abs;
  // c0 = max(coef sqrt(g H_max), ratio U_max) unless given: the weakly compressible fluid needs both a
  // sound speed well above the gravity-wave speed and a Mach number U/c0 <= 1/ratio (density varies
  // by about (U/c0)^2), as the corrugated-bed SPH study requires (c0 >= 10 U_max).
  const double c0 = s.sound_speed_m_s > 0.0
                        ? s.sound_speed_m_s
                        : std::max(s.sound_speed_coefficient * std::sqrt(gravity * g.max_water_height_m),
                                   s.sound_speed_min_flow_ratio * g.max_flow_speed_m_s);
  out.eos = TaitEquationOfState(fluid.density_kg_m3, c0);
  // nu = alpha h c0 / 8 (Monaghan 2005, Rep. Prog. Phys. 68:1703, in 2D), so alpha = 8 nu / (h c0).
  out.artificial_alpha = s.artificial_viscosity_nu_m2_s > 0.0 ? 8.0 * s.artificial_viscosity_nu_m2_s / (out.h * c0)
                                                               : s.artificial_viscosity_alpha;
  if (!(out.artificial_alpha <= 1.0))
    throw std::invalid_argument("sph.artificial_viscosity_nu_m2_s = " + std::to_string(s.artificial_viscosity_nu_m2_s) +
                                " m^2/s needs alpha = 8 nu / (h c0) = " + std::to_string(out.artificial_alpha) +
                                " at h = " + std::to_string(out.h) + " m, c0 = " + std::to_string(c0) +
                                " m/s: allowed up to alpha = 1, i.e. nu <= h c0 / 8 = " + std::to_string(out.h * c0 / 8.0) + " m^2/s");
  out.artificial_wall_factor = s.artificial_viscosity_wall_factor;
  out.kinematic_viscosity = fluid.kinematic_viscosity_m2_s;
  // l = sph.sps_mixing_length_m if given, else Smagorinsky's C_s dx
  out.sps_length = s.sps_mixing_length_m > 0.0 ? s.sps_mixing_length_m : s.sps_smagorinsky_constant * dx;
  out.sps_length_near_walls = s.sps_mixing_length_m > 0.0;
  out.sps_wall_distance_table = out.sps_length_near_walls && s.sps_wall_distance == "whole_domain";
  // free_slip and wall_function: mDBC's slip velocity in the viscous terms; wall_function adds the
  // log law's wall shear (wall_function.hpp).
  out.viscous_walls_free_slip = s.viscosity == "laminar_sps" && s.viscous_wall_condition != "no_slip";
  out.wall_function_shear = s.viscosity == "laminar_sps" && s.viscous_wall_condition == "wall_function";
  out.particle_shifting = parse_particle_shifting(s.particle_shifting);
  out.shifting_coefficient = s.particle_shifting_coefficient;
  out.shifting_surface_threshold = s.particle_shifting_surface_threshold;
  out.shifting_correction = parse_shifting_correction(s.particle_shifting_correction);
  out.blin = s.sps_blin_constant;
  out.diffusion_delta = s.density_diffusion_coefficient;
  out.cfl = s.cfl_number;
  out.verlet_euler_interval = s.verlet_euler_interval;
  out.body_force_x = g.body_force_m_s2.x();
  out.body_force_z = g.body_force_m_s2.y();
  out.x_min = g.x_min_m;
  out.x_max = g.x_max_m;
  out.z_min = g.z_min_m;
  out.z_max = g.z_max_m;
  out.periodic_x = g.periodic_x;
  out.fluid_ceiling = out.z_max;
  for (const auto& in : g.inflows)
    out.fluid_ceiling = std::max(out.fluid_ceiling, g.bed.elevation(in.x_m) + cases::specific_energy(in.depth_m, in.depth_m * in.velocity_m_s, gravity));
  out.max_density_variation = s.max_density_variation;
  out.domain_margin = escape_margin(out.h);
  // Open boundaries: the buffer zones (layers dx upstream of the inflow, downstream of the outflow)
  // belong to the domain; their particles may be fluid for a step before their buffer takes them.
  out.open_boundary_layers = s.open_boundary_layers;
  out.outflow = parse_outflow_condition(s.outflow_condition);
  if (out.outflow == OutflowCondition::tailgate) {
    if (g.outflows.empty() || g.inflows.empty())
      throw std::invalid_argument("sph.outflow_condition = \"tailgate\" needs a case with an inflow and an outflow "
                                  "(a stilling basin); case kind \"" + g.kind + "\" has none");
    const double q = cases::inflow_discharge(g);
    const double y_t = g.outflows.front().tailwater_depth_m;
    out.tailgate_height = s.tailgate_height_m > 0.0 ? s.tailgate_height_m
                                                    : cases::tailgate_height_for_depth(q, y_t, gravity);
    const double room = g.z_max_m - g.bed.elevation(g.outflows.front().x_m);
    if (!(out.tailgate_height < room))
      throw std::invalid_argument(
          (s.tailgate_height_m > 0.0 ? "sph.tailgate_height_m = " : "the tailgate height from the tailwater depth y_t (Rehbock), ") +
          std::to_string(out.tailgate_height) + " m, reaches above the domain (" + std::to_string(room) +
          " m above the bed at the outflow section): use a lower gate (sph.tailgate_height_m) or a higher case.domain.air_height_m");
    if (out.tailgate_height < 2.0 * dx)
      throw std::invalid_argument("sph tailgate: the crest height " + std::to_string(out.tailgate_height) +
                                  " m is less than 2 particle spacings (dx = " + std::to_string(dx) +
                                  " m): the gate cannot be resolved; use a finer resolution or sph.tailgate_height_m");
  }
  if (s.outflow_level_reference == "downstream_section") {
    const auto down = std::find_if(g.sections.begin(), g.sections.end(),
                                   [](const cases::Section& sec) { return sec.role == "downstream"; });
    if (g.outflows.empty() || out.outflow == OutflowCondition::tailgate || down == g.sections.end())
      throw std::invalid_argument("sph.outflow_level_reference = \"downstream_section\" needs an outflow buffer "
                                  "(outflow_condition \"absorbing\" or \"hydrostatic_level\") and a section with "
                                  "role \"downstream\" (a stilling basin); case kind \"" + g.kind + "\" has " +
                                  (g.outflows.empty() ? "no outflow" : down == g.sections.end() ? "no downstream section" : "a tailgate"));
    out.outflow_level_at_section = true;
    out.outflow_level_section_x = down->x_m;
    out.outflow_level_time = s.outflow_level_time_s;
  } else if (s.outflow_level_reference != "outlet") {
    throw std::invalid_argument("sph.outflow_level_reference = \"" + s.outflow_level_reference +
                                "\" is not allowed: use \"outlet\" or \"downstream_section\"");
  }
  out.inflow = parse_inflow_condition(s.inflow_condition);
  const double buffer_length = buffer_layers(out.support(), out.dx, out.open_boundary_layers) * out.dx;
  if (!g.inflows.empty() && out.inflow == InflowCondition::buffer) out.x_min -= buffer_length;
  if (!g.outflows.empty()) out.x_max += buffer_length;
  if (g.moving_walls.size() > 1)
    throw std::invalid_argument("the SPH solver moves one wall per case; the geometry has " +
                                std::to_string(g.moving_walls.size()));
  for (const auto& wall : g.moving_walls)
    out.wall_motion = WallMotion{wall.velocity_m_s.x(), wall.velocity_m_s.y(), wall.start_s, wall.end_s,
                                 wall.held_level_m, wall.reservoir_end_x_m,
                                 wall.held_level_m > 0.0 ? s.piston_level_gain_per_s : 0.0};
  out.validate();
  return out;
}

}  // namespace hydrojump::sph
