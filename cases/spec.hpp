// The study spec: one TOML file describes every case of a study and the method settings of both
// solvers. This header is the data model; `load_study` in spec_reader.hpp fills it and validates it.
//
// Everything downstream (SPH particle generator, OpenFOAM writer, comparator) reads a `Study` and a
// `CaseGeometry` (geometry.hpp); none of them re-reads the TOML or re-derives geometry.
//
// Units are SI throughout; spec keys carry their unit as a suffix (`depth_m`, `velocity_m_s`).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cases/options.hpp"

namespace hydrojump::cases {

// [fluid]
struct FluidProperties {
  double density_kg_m3 = 1000.0;
  double kinematic_viscosity_m2_s = 1.0e-6;
  double gravity_m_s2 = 9.81;
};

// [sph] — method settings of the SPH solver (defaults as in DualSPHysics where it has one).
// Options are enums parsed from their names by one table each (cases/options.hpp), never integers.
struct SphSettings {
  KernelType kernel = KernelType::wendland_c2;              // "wendland_c2" | "cubic_spline"
  Viscosity viscosity = Viscosity::artificial;            // "artificial" | "laminar_sps"
  double artificial_viscosity_alpha = 0.01;        // Monaghan alpha
  double artificial_viscosity_nu_m2_s = 0.0;       // > 0: alpha = 8 nu / (h c0) instead, the same viscosity
                                                   // at every resolution (2D: nu = alpha h c0 / 8)
  double artificial_viscosity_wall_factor = 1.0;   // alpha between fluid and wall particles = factor * alpha
  double sps_smagorinsky_constant = 0.12;          // Cs
  double sps_blin_constant = 0.0066;               // CI
  double sps_mixing_length_m = 0.0;               // > 0: nu_t = l^2 |S| with this l instead of (Cs dx)
  double sps_mixing_length_per_sequent_depth = 0.0; // > 0 (stilling basins): l = this * y2*, resolved per
                                                    // case into sps_mixing_length_m (cases/case_rules.hpp)
  SpsWallDistance sps_wall_distance = SpsWallDistance::kernel_support; // with a mixing length: "kernel_support" | "whole_domain"
                                                    // (where d in l = min(l_m, kappa d) is measured; sph/wall_distance.hpp)
  ViscousWallCondition viscous_wall_condition = ViscousWallCondition::no_slip;  // laminar_sps with mdbc: "no_slip" | "free_slip" | "wall_function"
  BoundaryMethod boundary = BoundaryMethod::dbc;                    // "dbc" | "mdbc"
  DensityDiffusion density_diffusion = DensityDiffusion::fourtakas;     // "none" | "molteni" | "fourtakas"
  double density_diffusion_coefficient = 0.1;      // delta
  double sound_speed_coefficient = 10.0;           // c0 = coef * sqrt(g * H_max) ...
  double sound_speed_m_s = 0.0;                    // ... unless > 0: then c0 is given directly
  double sound_speed_min_flow_ratio = 10.0;        // and c0 >= ratio * expected max flow speed (Mach <= 0.1)
  double cfl_number = 0.2;
  double coef_h = 1.0;                             // h = coef_h * sqrt(2) * dx
  TimeIntegrator time_integrator = TimeIntegrator::symplectic;      // "symplectic" | "verlet"
  int verlet_euler_interval = 40;                  // Verlet: an Euler step every N steps
  int boundary_layers = 0;                         // 0: enough layers for the kernel support
  int open_boundary_layers = 0;                    // inflow/outflow buffer columns; 0: ceil(2h/dx) + 1
  InflowCondition inflow_condition = InflowCondition::buffer;         // "buffer" (open_boundaries.hpp) | "piston" (a reservoir
                                                   // pushed by a piston behind a sluice gate, geometry.hpp)
  double sluice_opening_m = 0.0;                   // "piston": gate opening; 0: y1 / 0.611
  double reservoir_length_m = 0.0;                 // "piston": 0: piston travel over the run + 2 H_r
  double piston_level_gain_per_s = 10.0;           // "piston": K of u_p = q/H_r + K (H_r - H); 0: fixed speed
  OutflowCondition outflow_condition = OutflowCondition::hydrostatic_level;  // "hydrostatic_level" | "absorbing" (open_boundaries.hpp)
                                                   // | "tailgate" (sph/tailgate.hpp)
  double tailgate_height_m = 0.0;                  // "tailgate": crest above the local bed; 0: from the
                                                   // tailwater depth by Rehbock's weir formula
  OutflowLevelReference outflow_level_reference = OutflowLevelReference::outlet;  // where the outflow buffer holds the tailwater depth:
                                                   // "outlet" | "downstream_section" (sph/outflow_level_control.hpp)
  double outflow_level_time_s = 2.0;               // "downstream_section": integral time T_c of the control
  ParticleShifting particle_shifting = ParticleShifting::none;          // "none" | "fickian" (sph/particle_shifting.hpp)
  double particle_shifting_coefficient = 2.0;      // "fickian": A in delta r = -A h |v| dt grad C, (0, 10]
  double particle_shifting_surface_threshold = 1.5; // "fickian": div r below this is the free surface, [0, 1.9]
  ShiftingCorrection particle_shifting_correction = ShiftingCorrection::none; // "fickian": "none" | "taylor" | "taylor_volume" (particle_shifting.hpp)
  double max_density_variation = 0.05;             // |rho/rho0 - 1| above this stops the run
  double checkpoint_interval_wall_s = 300.0;       // wall-clock seconds between checkpoints
};

// [vof] — method settings of the OpenFOAM interFoam reference.
struct VofSettings {
  TurbulenceModel turbulence_model = TurbulenceModel::kOmegaSST; // "laminar" | "kOmegaSST" | "kEpsilon" | "RNGkEpsilon"
  // "none" | "nut_limiter" | "nut_limiter_and_buoyancy": OpenFOAM's multiphaseStabilizedTurbulence
  // fvOption (k-epsilon models only) with the nut limiter of Larsen & Fuhrman (2018) alone, or also with
  // the buoyancy sink of k at the interface of Devolder et al. (2017)
  TurbulenceStabilization turbulence_stabilization = TurbulenceStabilization::none;
  double max_courant = 0.8;
  double max_alpha_courant = 0.8;
  double max_time_step_s = 1.0e-3;
  MeshStrategy mesh_strategy = MeshStrategy::cartesian_cut; // "cartesian_cut" | "body_fitted"
  double surface_refinement_band_m = 0.0;          // 0: derived from y1 and y2 (stilling basins)
  // Stilling basins with [case.tailwater] control = "hold_toe": the runner resets the outlet's Umean
  // between legs of this length (reference/tailwater_control.hpp); a whole number of output intervals.
  // 0 (unset): 0.5 s, or the whole number of output intervals that fits a shorter run (resolved by
  // the reader).
  double tailwater_control_interval_s = 0.0;
};

// [resolution.<name>] — one named resolution level.
struct Resolution {
  std::string name;                     // "quick" | "default" | "fine" (or any other name in the file)
  double particle_spacing_m = 0.0;      // SPH dx
  double vof_cell_size_bed_m = 0.0;     // VOF cell size near the bed and the free surface
  double vof_cell_size_bulk_m = 0.0;    // VOF cell size elsewhere
};

// [case.run]
// Each output time is one file per method (particles, OpenFOAM time directory): a run has at most this many.
inline constexpr double max_outputs_per_run = 100000.0;
// The longest run a case may ask for (s of simulated time).
inline constexpr double max_end_time_s = 1.0e5;

struct RunSettings {
  double end_time_s = 0.0;
  double output_interval_s = 0.05;
  double average_start_s = 0.0;   // averaging window [average_start_s, average_end_s]
  double average_end_s = 0.0;     // defaults to end_time_s

  // The latest end time a run of these settings may be given (`--end-time`): max_end_time_s, and at
  // most max_outputs_per_run outputs.
  double latest_end_time_s() const {
    const double by_outputs = output_interval_s * max_outputs_per_run;
    return by_outputs < max_end_time_s ? by_outputs : max_end_time_s;
  }
};

// [run] (study level) — the run of every stilling basin that has no [case.run], from its sloshing
// period T_s = 2 L / sqrt(g y2*) (cases/case_rules.hpp):
//   | key                       | default | meaning                                                |
//   |---------------------------|---------|--------------------------------------------------------|
//   | output_interval_s         | 0.1     | s between outputs                                      |
//   | start_up_sloshing_periods | 2       | average_start = N_s T_s (start-up left out), [0.5, 100]|
//   | window_sloshing_periods   | 1       | window (and run end) N_w T_s later, (0, 100]           |
// Example:
//   [run]
//   start_up_sloshing_periods = 2.0
//   window_sloshing_periods = 1.0
struct RunRule {
  double output_interval_s = 0.1;
  double start_up_sloshing_periods = 2.0;
  double window_sloshing_periods = 1.0;
  // The toe-holding control's time T_x of a stilling basin without its own [case.tailwater]
  // toe_hold_time_s, in sloshing periods (cases/case_rules.hpp); unset: that key's default.
  std::optional<double> toe_hold_sloshing_periods;
};

// [[case.sections]]: a named x position where both results are compared (a vertical line from the
// bed to the top).
//   | key  | default    | meaning                                                              |
//   |------|------------|----------------------------------------------------------------------|
//   | name | (required) | unique within the case; 1-64 letters, digits, '_', '-' (OpenFOAM     |
//   |      |            | set and file names)                                                  |
//   | x_m  | (required) | station, inside the domain                                           |
//   | role | "interior" | "upstream" (section 1-1, supercritical: y1, E1; at most one; in a    |
//   |      |            | stilling basin upstream of the basin start), "downstream" (section   |
//   |      |            | 3-3, tailwater: y2, E2; at most one, downstream of the upstream one, |
//   |      |            | in a stilling basin downstream of the basin start), "toe",           |
//   |      |            | "interior", or "gauge" (verification)                                |
// Example:
//   [[case.sections]]
//   name = "up"
//   x_m = 0.05
//   role = "upstream"
struct Section {
  std::string name;
  double x_m = 0.0;
  SectionRole role = SectionRole::interior;
};

// [case.bed]
struct BedSpec {
  BedShape profile = BedShape::smooth;  // "smooth" | "sinusoidal"
  double wavelength_m = 0.0;            // S
  double height_m = 0.0;                // T, trough to crest
  double reach_start_m = 0.0;           // x where the corrugations start (a crest)
  double reach_end_m = 0.0;             // x where they end (a crest): whole wavelengths
};

// [case.measured] — laboratory and published values (all optional).
struct MeasuredValues {
  std::optional<double> sequent_depth_m;          // y2, experiment
  std::optional<double> jump_length_m;            // Lj, experiment
  std::optional<double> roller_length_m;          // Lr, experiment
  std::optional<double> eta_percent;              // energy dissipation rate, experiment
  std::optional<double> eta_smooth_percent;       // smooth-bed value listed by the study
  std::optional<double> published_sph_eta_percent;  // Bo et al. (2019) SPH
  std::string source;                             // citation
  std::string note;                               // what is known about the values as published (a
                                                  // flaw, a conflict), printed with them in reports
};

// [case.tailwater] control — what sets the tailwater of a stilling basin, read by both solvers.
//   "hold_toe"    the flume's protocol (Ead & Rajaratnam 2002 set their tailgate so that the toe stood
//                 at the start of the bed, then measured y2): the outlet is steered until the time-mean
//                 toe stands at the basin start, with the water volume held; the tailwater depth is
//                 the initial level only, and y2, eta, Lj, Lr are predictions (the default). SPH:
//                 sph/toe_hold_control.hpp; VOF: reference/tailwater_control.hpp.
//   "fixed_depth" the outlet holds the tailwater depth; the toe goes where the jump takes it (where
//                 does the jump stand at this tailwater?), and its distance from the basin start is
//                 the result to score.
struct TailwaterControl {
  TailwaterControlMode mode = TailwaterControlMode::hold_toe;  // "hold_toe" | "fixed_depth"
  double volume_hold_time_s = 1.0;      // "hold_toe": T_V, time to drain a volume error
  double toe_hold_time_s = 5.0;         // "hold_toe": T_x, time to bring the toe to the basin start
  // "hold_toe": k_p, the water added at once per metre the toe stands downstream of the basin start,
  // in units of y2* - y1 (the proportional part of the toe control; 0: integral only).
  double toe_hold_gain = 0.0;
  bool holds_toe() const { return mode == TailwaterControlMode::hold_toe; }
};

// kind = "stilling_basin": supercritical inflow into a basin, tailwater held at the outlet.
// x = 0 is the inflow boundary; the floor upstream of the basin is at z = 0; the sinusoidal reach
// lies below it (crests at z = 0, troughs at z = -T).
struct StillingBasinCase {
  BedSpec bed;
  double inflow_depth_m = 0.0;          // y1
  double inflow_velocity_m_s = 0.0;     // U1
  std::optional<double> stated_discharge_m2_s;  // checked against y1*U1 (2 %)
  std::optional<double> stated_froude;           // checked against U1/sqrt(g y1) (2 %)
  TailwaterRule tailwater_rule = TailwaterRule::given;  // "given" | "belanger" (y2* from y1 and Fr1)
  double tailwater_depth_m = 0.0;       // resolved tailwater depth (after the rule); with control
                                        // "hold_toe" the initial level only
  TailwaterControl control;
  double upstream_length_m = 0.0;       // inflow to basin start (expected toe)
  double basin_length_m = 0.0;
  double downstream_length_m = 0.0;     // basin end to outlet
  double air_height_m = 0.0;            // above the highest water level
  // Where the initial state's supercritical layer ends and its roller up to the tailwater begins
  // (`[case.domain] initial_toe_x_m`); unset: the basin start. Only the start-up depends on it.
  std::optional<double> initial_toe_x_m;
  MeasuredValues measured;
};

// kind = "dam_break": a water column released into a dry tank (Koshizuka & Oka 1996 set-up).
// The column's bottom-left corner is at (0, 0).
struct DamBreakCase {
  double column_width_m = 0.0;
  double column_height_m = 0.0;
  double tank_length_m = 0.0;
  double tank_height_m = 0.0;
  GateOpening gate = GateOpening::instant;  // "instant" | "lifted"
  double gate_lift_speed_m_s = 0.0;     // for "lifted"
  std::vector<double> gauges_x_m;       // water-level gauges
  std::filesystem::path measured_front_file;  // CSV t_s,x_front_over_L (absolute after loading)
};

// kind = "still_water": a closed tank at rest (hydrostatic verification).
struct StillWaterCase {
  double tank_length_m = 0.0;
  double tank_height_m = 0.0;
  double water_depth_m = 0.0;
};

// kind = "poiseuille": plane channel flow between two plates, periodic in x, driven by a body force.
// Plates at z = 0 and z = channel_width_m. Analytic steady profile u(z) = f/(2 nu) z (W - z).
struct PoiseuilleCase {
  double channel_width_m = 0.0;
  double channel_length_m = 0.0;        // periodic length
  double body_force_m_s2 = 0.0;         // along +x
};

using CaseKindData = std::variant<StillingBasinCase, DamBreakCase, StillWaterCase, PoiseuilleCase>;

// One [[case]] entry with the method settings resolved (study defaults, then the case's overrides).
struct Case {
  std::string id;
  std::string kind;                     // "stilling_basin" | "dam_break" | "still_water" | "poiseuille"
  std::string description;
  SphSettings sph;
  VofSettings vof;
  RunSettings run;
  std::map<std::string, Resolution> resolutions;  // by name, case overrides applied
  std::vector<Section> sections;        // explicit, or derived defaults (see geometry.hpp)
  bool sections_given = false;          // true when the spec listed them
  CaseKindData data;

  const StillingBasinCase* stilling_basin() const { return std::get_if<StillingBasinCase>(&data); }
  const DamBreakCase* dam_break() const { return std::get_if<DamBreakCase>(&data); }
  const StillWaterCase* still_water() const { return std::get_if<StillWaterCase>(&data); }
  const PoiseuilleCase* poiseuille() const { return std::get_if<PoiseuilleCase>(&data); }
  // A stilling basin whose tailwater is steered to hold the toe at the basin start ([case.tailwater]
  // control = "hold_toe").
  bool holds_toe() const { return stilling_basin() != nullptr && stilling_basin()->control.holds_toe(); }
  // The resolution called `name`; throws SpecError listing the defined names if there is none.
  const Resolution& resolution(const std::string& name) const;
};

// The whole file.
struct Study {
  std::filesystem::path source_file;    // where it was loaded from ("<embedded>" for the built-in)
  std::string name;
  std::string description;
  std::vector<std::string> citations;
  FluidProperties fluid;
  std::optional<RunRule> run_rule;      // [run], when the file has one
  // [resolution] for_inflow_depth_m: the levels' spacings are for this inflow depth y1, and each
  // stilling basin's are scaled by its own y1 over it (the same particles and cells across every
  // basin's inflow); a case's own [case.resolution.*] values are taken as given.
  std::optional<double> resolution_for_inflow_depth_m;
  std::vector<Case> cases;

  const Case* find_case(const std::string& id) const;
};

}  // namespace hydrojump::cases
