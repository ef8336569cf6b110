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

int boundary_layer_count(double h, double dx, int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::ceil(2.0 * h / dx - 1e-9));
}

cases::CaseGeometry solver_geometry(const cases::Case& c, const cases::FluidProperties& fluid, double dx) {
  cases::CaseGeometry g = cases::make_geometry(c, fluid);
  if (c.sph.inflow_condition == InflowCondition::piston) {
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
  require(viscosity.artificial_alpha >= 0.0 && viscosity.artificial_alpha <= 1.0, "artificial_viscosity_alpha", viscosity.artificial_alpha, "[0, 1]");
  require(viscosity.artificial_wall_factor >= 0.0 && viscosity.artificial_wall_factor <= 1.0, "artificial_viscosity_wall_factor",
          viscosity.artificial_wall_factor, "[0, 1]");
  require(viscosity.kinematic_viscosity >= 0.0, "fluid.kinematic_viscosity_m2_s", viscosity.kinematic_viscosity, ">= 0");
  require(density.diffusion_delta >= 0.0 && density.diffusion_delta <= 1.0, "density_diffusion_coefficient", density.diffusion_delta, "[0, 1]");
  require(time.cfl > 0.0 && time.cfl <= 1.0, "cfl_number", time.cfl, "(0, 1]");
  require(time.verlet_euler_interval >= 1, "verlet_euler_interval", time.verlet_euler_interval, ">= 1");
  require(density.max_variation > 0.0, "max_density_variation", density.max_variation, "> 0");
  require(shifting.coefficient > 0.0 && shifting.coefficient <= 10.0, "particle_shifting_coefficient", shifting.coefficient, "(0, 10]");
  require(shifting.surface_threshold >= 0.0 && shifting.surface_threshold <= 1.9, "particle_shifting_surface_threshold",
          shifting.surface_threshold, "[0, 1.9]");
  if (shifting.model != ParticleShifting::none && time.integrator != TimeIntegrator::symplectic)
    throw std::invalid_argument("sph.particle_shifting = \"fickian\" needs time_integrator = \"symplectic\" (the shift is applied "
                                "after the corrector with the corrector's concentration gradient; here \"verlet\")");
  if (shifting.correction != ShiftingCorrection::none && shifting.model == ParticleShifting::none)
    throw std::invalid_argument("sph.particle_shifting_correction is only used with particle_shifting = \"fickian\" (here \"none\")");
  require(domain.x_max > domain.x_min && domain.z_max > domain.z_min, "domain box", domain.x_max - domain.x_min, "must have positive size");
}

namespace {

// c0 = max(coef sqrt(g H_max), ratio U_max) unless given: the weakly compressible fluid needs both a
// sound speed well above the gravity-wave speed and a Mach number U/c0 <= 1/ratio (density varies
// by about (U/c0)^2), as the corrugated-bed SPH study requires (c0 >= 10 U_max).
double sound_speed(const cases::SphSettings& s, const cases::CaseGeometry& g, double gravity) {
  return s.sound_speed_m_s > 0.0 ? s.sound_speed_m_s
                                 : std::max(s.sound_speed_coefficient * std::sqrt(gravity * g.max_water_height_m),
                                            s.sound_speed_min_flow_ratio * g.max_flow_speed_m_s);
}

ViscositySettings viscosity_settings(const cases::SphSettings& s, const cases::FluidProperties& fluid, double h,
                                     double c0, double dx) {
  ViscositySettings v;
  v.model = s.viscosity;
  // nu = alpha h c0 / 8 (Monaghan 2005, Rep. Prog. Phys. 68:1703, in 2D), so alpha = 8 nu / (h c0).
  v.artificial_alpha = s.artificial_viscosity_nu_m2_s > 0.0 ? 8.0 * s.artificial_viscosity_nu_m2_s / (h * c0)
                                                            : s.artificial_viscosity_alpha;
  if (!(v.artificial_alpha <= 1.0))
    throw std::invalid_argument("sph.artificial_viscosity_nu_m2_s = " + std::to_string(s.artificial_viscosity_nu_m2_s) +
                                " m^2/s needs alpha = 8 nu / (h c0) = " + std::to_string(v.artificial_alpha) +
                                " at h = " + std::to_string(h) + " m, c0 = " + std::to_string(c0) +
                                " m/s: allowed up to alpha = 1, i.e. nu <= h c0 / 8 = " + std::to_string(h * c0 / 8.0) + " m^2/s");
  v.artificial_wall_factor = s.artificial_viscosity_wall_factor;
  v.kinematic_viscosity = fluid.kinematic_viscosity_m2_s;
  // l = sph.sps_mixing_length_m if given, else Smagorinsky's C_s dx
  v.sps_length = s.sps_mixing_length_m > 0.0 ? s.sps_mixing_length_m : s.sps_smagorinsky_constant * dx;
  v.sps_length_near_walls = s.sps_mixing_length_m > 0.0;
  v.sps_wall_distance_table = v.sps_length_near_walls && s.sps_wall_distance == cases::SpsWallDistance::whole_domain;
  // free_slip and wall_function: mDBC's slip velocity in the viscous terms; wall_function adds the
  // log law's wall shear (wall_function.hpp).
  const bool sps = s.viscosity == cases::Viscosity::laminar_sps;
  v.viscous_walls_free_slip = sps && s.viscous_wall_condition != cases::ViscousWallCondition::no_slip;
  v.wall_function_shear = sps && s.viscous_wall_condition == cases::ViscousWallCondition::wall_function;
  v.blin = s.sps_blin_constant;
  return v;
}

// The box of the case geometry; the ceiling is the higher of its top and every inflow's energy line
// z_b(x_in) + E1, E1 = y1 + U1^2 / (2 g).
DomainSettings domain_settings(const cases::CaseGeometry& g, double h, double gravity) {
  DomainSettings d;
  d.x_min = g.x_min_m;
  d.x_max = g.x_max_m;
  d.z_min = g.z_min_m;
  d.z_max = g.z_max_m;
  d.periodic_x = g.periodic_x;
  d.fluid_ceiling = d.z_max;
  for (const auto& in : g.inflows)
    d.fluid_ceiling = std::max(d.fluid_ceiling, g.bed.elevation(in.x_m) + cases::specific_energy(in.depth_m, in.depth_m * in.velocity_m_s, gravity));
  d.margin = escape_margin(h);
  return d;
}

// The tailgate's crest: sph.tailgate_height_m, or Rehbock's weir height that passes q over the
// tailwater depth y_t (cases::tailgate_height_for_depth); below the domain top, at least 2 dx.
double tailgate_height(const cases::SphSettings& s, const cases::CaseGeometry& g, double gravity, double dx) {
  if (g.outflows.empty() || g.inflows.empty())
    throw std::invalid_argument("sph.outflow_condition = \"tailgate\" needs a case with an inflow and an outflow "
                                "(a stilling basin); case kind \"" + g.kind + "\" has none");
  const double q = cases::inflow_discharge(g);
  const double y_t = g.outflows.front().tailwater_depth_m;
  const double height = s.tailgate_height_m > 0.0 ? s.tailgate_height_m : cases::tailgate_height_for_depth(q, y_t, gravity);
  const double room = g.z_max_m - g.bed.elevation(g.outflows.front().x_m);
  if (!(height < room))
    throw std::invalid_argument(
        (s.tailgate_height_m > 0.0 ? "sph.tailgate_height_m = " : "the tailgate height from the tailwater depth y_t (Rehbock), ") +
        std::to_string(height) + " m, reaches above the domain (" + std::to_string(room) +
        " m above the bed at the outflow section): use a lower gate (sph.tailgate_height_m) or a higher case.domain.air_height_m");
  if (height < 2.0 * dx)
    throw std::invalid_argument("sph tailgate: the crest height " + std::to_string(height) +
                                " m is less than 2 particle spacings (dx = " + std::to_string(dx) +
                                " m): the gate cannot be resolved; use a finer resolution or sph.tailgate_height_m");
  return height;
}

OpenBoundarySettings open_boundary_settings(const cases::SphSettings& s, const cases::CaseGeometry& g, double gravity,
                                            double dx) {
  OpenBoundarySettings o;
  o.layers = s.open_boundary_layers;
  o.outflow = s.outflow_condition;
  o.inflow = s.inflow_condition;
  if (o.outflow == OutflowCondition::tailgate) o.tailgate_height = tailgate_height(s, g, gravity, dx);
  if (s.outflow_level_reference == cases::OutflowLevelReference::downstream_section) {
    const auto down = std::find_if(g.sections.begin(), g.sections.end(),
                                   [](const cases::Section& sec) { return sec.role == cases::SectionRole::downstream; });
    if (g.outflows.empty() || o.outflow == OutflowCondition::tailgate || down == g.sections.end())
      throw std::invalid_argument("sph.outflow_level_reference = \"downstream_section\" needs an outflow buffer "
                                  "(outflow_condition \"absorbing\" or \"hydrostatic_level\") and a section with "
                                  "role \"downstream\" (a stilling basin); case kind \"" + g.kind + "\" has " +
                                  (g.outflows.empty() ? "no outflow" : down == g.sections.end() ? "no downstream section" : "a tailgate"));
    o.level_at_section = true;
    o.level_section_x = down->x_m;
    o.level_time = s.outflow_level_time_s;
  }
  return o;
}

// The one moving wall of the geometry, if any (a lifted dam-break gate, a piston).
WallMotion wall_motion(const cases::SphSettings& s, const cases::CaseGeometry& g) {
  if (g.moving_walls.size() > 1)
    throw std::invalid_argument("the SPH solver moves one wall per case; the geometry has " +
                                std::to_string(g.moving_walls.size()));
  WallMotion motion;
  for (const auto& wall : g.moving_walls)
    motion = WallMotion{wall.velocity_m_s.x(), wall.velocity_m_s.y(), wall.start_s, wall.end_s,
                        wall.held_level_m, wall.reservoir_end_x_m,
                        wall.held_level_m > 0.0 ? s.piston_level_gain_per_s : 0.0};
  return motion;
}

}  // namespace

SolverSettings make_settings(const cases::Case& c, const cases::FluidProperties& fluid, const cases::CaseGeometry& g,
                             double dx) {
  const cases::SphSettings& s = c.sph;
  const double g_abs = std::hypot(g.body_force_m_s2.x(), g.body_force_m_s2.y());
  const double gravity = fluid.gravity_m_s2 > 0.0 ? fluid.gravity_m_s2 : g_abs;
  SolverSettings out;
  out.kernel = s.kernel;
  out.boundary = s.boundary;
  out.dx = dx;
  out.h = smoothing_length(s.coef_h, dx);
  const double c0 = sound_speed(s, g, gravity);
  out.eos = TaitEquationOfState(fluid.density_kg_m3, c0);
  out.body_force_x = g.body_force_m_s2.x();
  out.body_force_z = g.body_force_m_s2.y();
  out.viscosity = viscosity_settings(s, fluid, out.h, c0, dx);
  out.density = DensitySettings{s.density_diffusion, s.density_diffusion_coefficient, s.max_density_variation};
  out.shifting = ShiftingSettings{s.particle_shifting, s.particle_shifting_coefficient, s.particle_shifting_surface_threshold,
                                  s.particle_shifting_correction};
  out.time = TimeSteppingSettings{s.time_integrator, s.cfl_number, s.verlet_euler_interval};
  out.domain = domain_settings(g, out.h, gravity);
  out.open = open_boundary_settings(s, g, gravity, dx);
  // Open boundaries: the buffer zones (layers dx upstream of the inflow, downstream of the outflow)
  // belong to the domain; their particles may be fluid for a step before their buffer takes them.
  const double buffer_length = buffer_layers(out.support(), out.dx, out.open.layers) * out.dx;
  if (!g.inflows.empty() && out.open.inflow == InflowCondition::buffer) out.domain.x_min -= buffer_length;
  if (!g.outflows.empty()) out.domain.x_max += buffer_length;
  out.wall_motion = wall_motion(s, g);
  out.validate();
  return out;
}

}  // namespace hydrojump::sph
