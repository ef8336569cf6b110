// The [sph] and [vof] tables of a study or a case: each key read with its range, the options parsed
// into their enums (cases/options.hpp), and the combinations a method cannot run refused by name.
#include "cases/spec_table_reader.hpp"

namespace hydrojump::cases::spec_detail {

namespace {

// The key of the mixing-length rule l = c_l y2* (cases/case_rules.hpp).
constexpr const char* kRule = "sps_mixing_length_per_sequent_depth";

// The kernel and the viscosity model with its parameters (sph/viscosity.hpp).
void read_sph_viscosity(TableReader& t, SphSettings& s) {
  s.kernel = t.choice("kernel", s.kernel);
  s.viscosity = t.choice("viscosity", s.viscosity);
  s.artificial_viscosity_alpha = t.number_or("artificial_viscosity_alpha", s.artificial_viscosity_alpha, between(0.0, 1.0));
  // nu or alpha: both in one table is an error; alpha given here overrides a nu inherited from [sph].
  if (t.has("artificial_viscosity_nu_m2_s") && t.has("artificial_viscosity_alpha"))
    t.fail_at(t.raw().get("artificial_viscosity_nu_m2_s"), "artificial_viscosity_nu_m2_s",
              "and artificial_viscosity_alpha are both given: set one (nu fixes alpha = 8 nu / (h c0) at each resolution)");
  if (t.has("artificial_viscosity_alpha")) s.artificial_viscosity_nu_m2_s = 0.0;
  s.artificial_viscosity_nu_m2_s = t.number_or("artificial_viscosity_nu_m2_s", s.artificial_viscosity_nu_m2_s,
                                                non_negative("m^2/s, 0: use artificial_viscosity_alpha", 1.0));
  if (t.has("artificial_viscosity_nu_m2_s") && s.viscosity != cases::Viscosity::artificial)
    t.fail_at(t.raw().get("artificial_viscosity_nu_m2_s"), "artificial_viscosity_nu_m2_s",
              std::string("is only used with viscosity = \"artificial\" (here \"") + std::string(cases::option_name(s.viscosity)) + "\")");
  // A case that switches to another viscosity model does not use the nu it inherits from [sph].
  if (s.viscosity != cases::Viscosity::artificial) s.artificial_viscosity_nu_m2_s = 0.0;
  s.artificial_viscosity_wall_factor = t.number_or("artificial_viscosity_wall_factor", s.artificial_viscosity_wall_factor, between(0.0, 1.0));
  s.sps_smagorinsky_constant = t.number_or("sps_smagorinsky_constant", s.sps_smagorinsky_constant, between(0.0, 1.0));
  s.sps_blin_constant = t.number_or("sps_blin_constant", s.sps_blin_constant, between(0.0, 1.0));
  // The mixing length is given in metres or by the rule l = c_l y2* (cases/case_rules.hpp): a table that
  // gives one drops the other it inherits; one that sets C_s alone means Smagorinsky's length.
  if (t.has("sps_mixing_length_m") && t.has(kRule))
    t.fail_at(t.raw().get(kRule), kRule, "and sps_mixing_length_m are both given: set one (the rule gives l = c_l y2* per case)");
  if (t.has("sps_smagorinsky_constant") && !t.has("sps_mixing_length_m") && !t.has(kRule)) {
    s.sps_mixing_length_m = 0.0;
    s.sps_mixing_length_per_sequent_depth = 0.0;
  }
  if (t.has("sps_mixing_length_m")) s.sps_mixing_length_per_sequent_depth = 0.0;
  if (t.has(kRule)) s.sps_mixing_length_m = 0.0;
  s.sps_mixing_length_m = t.number_or("sps_mixing_length_m", s.sps_mixing_length_m,
                                      non_negative("m, 0: the Smagorinsky length sps_smagorinsky_constant dx", 1.0));
  s.sps_mixing_length_per_sequent_depth = t.number_or(kRule, s.sps_mixing_length_per_sequent_depth,
                                                      between(0.0, 1.0, "l / y2*, 0: no rule"));
  s.sps_wall_distance = t.choice("sps_wall_distance", s.sps_wall_distance);
}

// The wall boundary, density diffusion, sound speed and time stepping.
void read_sph_numerics(TableReader& t, SphSettings& s) {
  s.boundary = t.choice("boundary", s.boundary);
  s.viscous_wall_condition = t.choice("viscous_wall_condition", s.viscous_wall_condition);
  // A case that switches to another viscosity model does not use the wall condition it inherits.
  if (s.viscosity != cases::Viscosity::laminar_sps) s.viscous_wall_condition = cases::ViscousWallCondition::no_slip;
  s.density_diffusion = t.choice("density_diffusion", s.density_diffusion);
  s.density_diffusion_coefficient = t.number_or("density_diffusion_coefficient", s.density_diffusion_coefficient, between(0.0, 1.0));
  s.sound_speed_coefficient = t.number_or("sound_speed_coefficient", s.sound_speed_coefficient, Range{1.0, 1000.0, false, false, "c0 / sqrt(g H_max)"});
  s.sound_speed_m_s = t.number_or("sound_speed_m_s", s.sound_speed_m_s, non_negative("m/s", 1e5));
  s.sound_speed_min_flow_ratio = t.number_or("sound_speed_min_flow_ratio", s.sound_speed_min_flow_ratio, Range{0.0, 1000.0, true, false, "c0 / expected max flow speed"});
  s.cfl_number = t.number_or("cfl_number", s.cfl_number, Range{0.01, 1.0, false, false, ""});
  s.coef_h = t.number_or("coef_h", s.coef_h, Range{0.5, 3.0, false, false, "h = coef_h sqrt(2) dx"});
  s.time_integrator = t.choice("time_integrator", s.time_integrator);
  s.verlet_euler_interval = t.integer_or("verlet_euler_interval", s.verlet_euler_interval, 1, 1000);
  s.boundary_layers = t.integer_or("boundary_layers", s.boundary_layers, 0, 20);
  s.open_boundary_layers = t.integer_or("open_boundary_layers", s.open_boundary_layers, 0, 50);
}

// The open boundaries: the inflow (buffer or piston), the outflow and where it holds its level.
void read_sph_open_boundaries(TableReader& t, SphSettings& s) {
  s.inflow_condition = t.choice("inflow_condition", s.inflow_condition);
  s.sluice_opening_m = t.number_or("sluice_opening_m", s.sluice_opening_m, non_negative("m, 0: y1 / 0.611", 100.0));
  s.reservoir_length_m = t.number_or("reservoir_length_m", s.reservoir_length_m, non_negative("m, 0: from the run's length", 1000.0));
  s.piston_level_gain_per_s = t.number_or("piston_level_gain_per_s", s.piston_level_gain_per_s,
                                          non_negative("1/s, 0: the piston keeps the speed q/H_r", 1000.0));
  for (const char* key : {"sluice_opening_m", "reservoir_length_m", "piston_level_gain_per_s"})
    if (s.inflow_condition != cases::InflowCondition::piston && t.raw().get(key))
      t.fail_at(t.raw().get(key), key, std::string("is only used with inflow_condition = \"piston\" (here \"") + std::string(cases::option_name(s.inflow_condition)) + "\")");
  s.outflow_condition = t.choice("outflow_condition", s.outflow_condition);
  s.tailgate_height_m = t.number_or("tailgate_height_m", s.tailgate_height_m, non_negative("m, 0: from the tailwater depth", 100.0));
  if (s.outflow_condition != cases::OutflowCondition::tailgate && t.raw().get("tailgate_height_m"))
    t.fail_at(t.raw().get("tailgate_height_m"), "tailgate_height_m",
              "is only used with outflow_condition = \"tailgate\" (here \"" + std::string(cases::option_name(s.outflow_condition)) + "\")");
  s.outflow_level_reference = t.choice("outflow_level_reference", s.outflow_level_reference);
  if (s.outflow_condition == cases::OutflowCondition::tailgate && s.outflow_level_reference != cases::OutflowLevelReference::outlet)
    t.fail_at(t.raw().get("outflow_level_reference") ? t.raw().get("outflow_level_reference") : t.raw().get("outflow_condition"),
              "outflow_level_reference", "= \"" + std::string(cases::option_name(s.outflow_level_reference)) +
              "\" needs an outflow buffer: a tailgate sets its level by its crest (use outflow_condition = \"absorbing\" or \"hydrostatic_level\")");
  s.outflow_level_time_s = t.number_or("outflow_level_time_s", s.outflow_level_time_s, Range{0.0, 100.0, true, false, "s, integral time of the level control"});
  if (s.outflow_level_reference != cases::OutflowLevelReference::downstream_section && t.raw().get("outflow_level_time_s"))
    t.fail_at(t.raw().get("outflow_level_time_s"), "outflow_level_time_s",
              "is only used with outflow_level_reference = \"downstream_section\" (here \"" + std::string(cases::option_name(s.outflow_level_reference)) + "\")");
  if (s.open_boundary_layers > 0) {
    // The buffers must cover the kernel support 2h = 2 sqrt(2) coef_h dx of the fluid next to them.
    const int needed = static_cast<int>(std::ceil(2.0 * std::sqrt(2.0) * s.coef_h - 1e-9)) + 1;
    if (s.open_boundary_layers < needed)
      t.fail_at(t.raw().get("open_boundary_layers"), "open_boundary_layers",
                "= " + std::to_string(s.open_boundary_layers) + " makes the inflow/outflow buffers thinner than the kernel support 2h = " +
                    util::number_text(2.0 * std::sqrt(2.0) * s.coef_h) + " dx (coef_h = " + util::number_text(s.coef_h) +
                    "): use 0 (automatic) or at least " + std::to_string(needed));
  }
}

// Particle shifting and the run-control limits.
void read_sph_shifting_and_limits(TableReader& t, SphSettings& s) {
  s.particle_shifting = t.choice("particle_shifting", s.particle_shifting);
  s.particle_shifting_coefficient = t.number_or("particle_shifting_coefficient", s.particle_shifting_coefficient,
                                                Range{0.0, 10.0, true, false, "A in delta r = -A h |v| dt grad C"});
  s.particle_shifting_surface_threshold = t.number_or("particle_shifting_surface_threshold", s.particle_shifting_surface_threshold,
                                                      Range{0.0, 1.9, false, false, "div r (2 in the bulk of a 2D fluid; at 1.98 or more every particle would count as at the surface)"});
  s.particle_shifting_correction = t.choice("particle_shifting_correction", s.particle_shifting_correction);
  s.max_density_variation = t.number_or("max_density_variation", s.max_density_variation, Range{0.0, 0.5, true, false, "|rho/rho0 - 1|"});
  s.checkpoint_interval_wall_s = t.number_or("checkpoint_interval_wall_s", s.checkpoint_interval_wall_s, positive("s", 1e6));
}

// A parameter of a model the table does not use is an error.
void check_sph_model_parameters(TableReader& t, SphSettings& s) {
  // A parameter of a model this table's settings do not use is an error (it would be silently ignored).
  // Inherited ones are not: a case that switches model drops the [sph] parameters of the old one.
  const auto only_with = [&](const char* key, bool used, const std::string& requirement) {
    if (!used && t.has(key)) t.fail_at(t.raw().get(key), key, "is only used with " + requirement);
  };
  const std::string here_viscosity = " (here \"" + std::string(cases::option_name(s.viscosity)) + "\")";
  only_with("artificial_viscosity_alpha", s.viscosity == cases::Viscosity::artificial, "viscosity = \"artificial\"" + here_viscosity);
  only_with("artificial_viscosity_wall_factor", s.viscosity == cases::Viscosity::artificial, "viscosity = \"artificial\"" + here_viscosity);
  only_with("sps_smagorinsky_constant", s.viscosity == cases::Viscosity::laminar_sps, "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with("sps_blin_constant", s.viscosity == cases::Viscosity::laminar_sps, "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with("sps_mixing_length_m", s.viscosity == cases::Viscosity::laminar_sps, "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with(kRule, s.viscosity == cases::Viscosity::laminar_sps, "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with("viscous_wall_condition", s.viscosity == cases::Viscosity::laminar_sps, "viscosity = \"laminar_sps\"" + here_viscosity);
  if (s.viscous_wall_condition != cases::ViscousWallCondition::no_slip && s.boundary != cases::BoundaryMethod::mdbc)
    t.fail_at(t.raw().get(t.has("viscous_wall_condition") ? "viscous_wall_condition" : "boundary"), "viscous_wall_condition",
              "= \"" + std::string(cases::option_name(s.viscous_wall_condition)) + "\" needs boundary = \"mdbc\" (the slip velocity is mirrored at mDBC's ghost nodes; here \"" +
                  std::string(cases::option_name(s.boundary)) + "\")");
  const bool mixing_length = s.sps_mixing_length_m > 0.0 || s.sps_mixing_length_per_sequent_depth > 0.0;
  only_with("sps_wall_distance", s.viscosity == cases::Viscosity::laminar_sps && mixing_length,
            "viscosity = \"laminar_sps\" and a mixing length, sps_mixing_length_m or " + std::string(kRule) +
                " > 0 (here \"" + std::string(cases::option_name(s.viscosity)) + "\", " + util::number_text(s.sps_mixing_length_m) + " m)");
  // A case without a mixing length does not use the distance rule it inherits, nor the length rule.
  if (s.viscosity != cases::Viscosity::laminar_sps || !mixing_length) s.sps_wall_distance = cases::SpsWallDistance::kernel_support;
  if (s.viscosity != cases::Viscosity::laminar_sps) s.sps_mixing_length_per_sequent_depth = 0.0;
  for (const char* key : {"sps_mixing_length_m", kRule})
    if (t.has(key) && t.has("sps_smagorinsky_constant") && mixing_length)
      t.fail_at(t.raw().get(key), key, "and sps_smagorinsky_constant are both given: the mixing length replaces C_s dx, set one");
  only_with("density_diffusion_coefficient", s.density_diffusion != cases::DensityDiffusion::none,
            "density_diffusion = \"molteni\" or \"fourtakas\" (here \"none\")");
  for (const char* key : {"particle_shifting_coefficient", "particle_shifting_surface_threshold", "particle_shifting_correction"})
    only_with(key, s.particle_shifting == cases::ParticleShifting::fickian, "particle_shifting = \"fickian\" (here \"" + std::string(cases::option_name(s.particle_shifting)) + "\")");
  if (s.particle_shifting != cases::ParticleShifting::none && s.time_integrator != cases::TimeIntegrator::symplectic)
    t.fail_at(t.raw().get(t.has("particle_shifting") ? "particle_shifting" : "time_integrator"), "particle_shifting",
              "= \"" + std::string(cases::option_name(s.particle_shifting)) + "\" needs time_integrator = \"symplectic\" (here \"" + std::string(cases::option_name(s.time_integrator)) + "\")");
  only_with("verlet_euler_interval", s.time_integrator == cases::TimeIntegrator::verlet,
            "time_integrator = \"verlet\" (here \"" + std::string(cases::option_name(s.time_integrator)) + "\")");
  for (const char* key : {"sound_speed_coefficient", "sound_speed_min_flow_ratio"})
    only_with(key, s.sound_speed_m_s == 0.0,
              "sound_speed_m_s = 0 (here " + util::number_text(s.sound_speed_m_s) + " m/s gives c0 directly)");
}

}  // namespace

void read_sph(TableReader& t, SphSettings& s) {
  read_sph_viscosity(t, s);
  read_sph_numerics(t, s);
  read_sph_open_boundaries(t, s);
  read_sph_shifting_and_limits(t, s);
  check_sph_model_parameters(t, s);
  t.reject_unknown_keys();
}

void read_vof(TableReader& t, VofSettings& v) {
  v.turbulence_model = t.choice("turbulence_model", v.turbulence_model);
  v.turbulence_stabilization = t.choice("turbulence_stabilization", v.turbulence_stabilization);
  // The v1912 fvOption corrects k and nut = Cmu k^2/epsilon: it needs an epsilon-based model. The check
  // runs on the merged settings, so a case's [case.vof] that changes either key is checked too.
  const bool epsilon_based = v.turbulence_model == TurbulenceModel::kEpsilon || v.turbulence_model == TurbulenceModel::RNGkEpsilon;
  if (v.turbulence_stabilization != TurbulenceStabilization::none && !epsilon_based) {
    // One of the two keys is in this table: the study's [vof] passed this check before a case overrode it.
    const std::string key = t.has("turbulence_stabilization") ? "turbulence_stabilization" : "turbulence_model";
    const std::string value(key == "turbulence_stabilization" ? option_name(v.turbulence_stabilization) : option_name(v.turbulence_model));
    t.fail_at(t.raw().get(key), key,
              "= \"" + value + "\" cannot be used: turbulence_stabilization = \"" + std::string(option_name(v.turbulence_stabilization)) +
                  "\" needs an epsilon-based turbulence_model (allowed: \"kEpsilon\", \"RNGkEpsilon\"), but turbulence_model is \"" +
                  std::string(option_name(v.turbulence_model)) + "\"");
  }
  v.max_courant = t.number_or("max_courant", v.max_courant, Range{0.01, 5.0, false, false, ""});
  v.max_alpha_courant = t.number_or("max_alpha_courant", v.max_alpha_courant, Range{0.01, 5.0, false, false, ""});
  v.max_time_step_s = t.number_or("max_time_step_s", v.max_time_step_s, Range{1e-6, 1.0, false, false, "s"});
  v.mesh_strategy = t.choice("mesh_strategy", v.mesh_strategy);
  v.surface_refinement_band_m = t.number_or("surface_refinement_band_m", v.surface_refinement_band_m, non_negative("m", 100.0));
  // The tailwater control is the case's protocol, read by both solvers ([case.tailwater] control).
  for (const char* key : {"tailwater_control", "volume_hold_time_s", "toe_hold_time_s", "toe_hold_gain"})
    if (t.has(key))
      t.fail_at(t.raw().get(key), key,
                "is no [vof] setting: the tailwater control is the case's protocol, read by both solvers: "
                "[case.tailwater] control = \"hold_toe\" (the default) or \"fixed_depth\", with its "
                "volume_hold_time_s, toe_hold_time_s and toe_hold_gain");
  v.tailwater_control_interval_s = t.number_or("tailwater_control_interval_s", v.tailwater_control_interval_s, positive("s", 100.0));
  t.reject_unknown_keys();
}

}  // namespace hydrojump::cases::spec_detail
