// The named options of a study (the [sph] and [vof] tables, and a case's bed, tailwater, gate and
// sections): one table per option lists its values and
// their names, and everything else is derived from it. The spec reader parses a name once into the
// enum (`choice<E>` in spec_reader.cpp) and quotes the table in its error message; the resolved case
// text writes the name back; the solvers only ever see the enum.
//
//   | option (spec key)                  | enum                    | values                                        |
//   |------------------------------------|-------------------------|-----------------------------------------------|
//   | sph.kernel                         | KernelType              | wendland_c2, cubic_spline                     |
//   | sph.viscosity                      | Viscosity               | artificial, laminar_sps                       |
//   | sph.sps_wall_distance              | SpsWallDistance         | kernel_support, whole_domain                  |
//   | sph.viscous_wall_condition         | ViscousWallCondition    | no_slip, free_slip, wall_function             |
//   | sph.boundary                       | BoundaryMethod          | dbc, mdbc                                     |
//   | sph.density_diffusion              | DensityDiffusion        | none, molteni, fourtakas                      |
//   | sph.time_integrator                | TimeIntegrator          | symplectic, verlet                            |
//   | sph.inflow_condition               | InflowCondition         | buffer, piston                                |
//   | sph.outflow_condition              | OutflowCondition        | hydrostatic_level, absorbing, tailgate        |
//   | sph.outflow_level_reference        | OutflowLevelReference   | outlet, downstream_section                    |
//   | sph.particle_shifting              | ParticleShifting        | none, fickian                                 |
//   | sph.particle_shifting_correction   | ShiftingCorrection      | none, taylor, taylor_volume                   |
//   | vof.turbulence_model               | TurbulenceModel         | laminar, kOmegaSST, kEpsilon, RNGkEpsilon     |
//   | vof.turbulence_stabilization       | TurbulenceStabilization | none, nut_limiter, nut_limiter_and_buoyancy   |
//   | vof.mesh_strategy                  | MeshStrategy            | cartesian_cut, body_fitted                    |
//   | case.bed.profile                   | BedShape                | smooth, sinusoidal                            |
//   | case.tailwater.control             | TailwaterControlMode    | hold_toe, fixed_depth                         |
//   | case.tailwater.rule                | TailwaterRule           | given, belanger                               |
//   | case.gate.type                     | GateOpening             | instant, lifted                               |
//   | case.sections[].role               | SectionRole             | upstream, toe, interior, downstream, gauge    |
//
// Example:
//   const auto v = cases::parse_option<cases::Viscosity>("laminar_sps");   // Viscosity::laminar_sps
//   std::string("use ") + cases::allowed_option_names<cases::Viscosity>();  // "\"artificial\" or \"laminar_sps\""
//   cases::option_name(cases::Viscosity::artificial);                        // "artificial"
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hydrojump::cases {

// The smoothing kernel (sph/kernel.hpp).
enum class KernelType { wendland_c2, cubic_spline };
// The viscosity model (sph/viscosity.hpp).
enum class Viscosity { artificial, laminar_sps };
// Where a mixing length's wall distance comes from (sph/wall_distance.hpp).
enum class SpsWallDistance { kernel_support, whole_domain };
// laminar_sps with mdbc: the walls' tangential velocity (sph/boundary_mdbc.hpp, sph/wall_function.hpp).
enum class ViscousWallCondition { no_slip, free_slip, wall_function };
// The wall boundary condition (sph/boundary_dbc.hpp, sph/boundary_mdbc.hpp).
enum class BoundaryMethod { dbc, mdbc };
// The density diffusion term (sph/density_diffusion.hpp).
enum class DensityDiffusion { none, molteni, fourtakas };
// The time integrator (sph/time_integration.hpp).
enum class TimeIntegrator { symplectic, verlet };
// The inflow: a buffer (sph/open_boundaries.hpp) or a piston reservoir behind a sluice gate
// (cases::add_piston_reservoir, sph/piston_inflow.hpp).
enum class InflowCondition { buffer, piston };
// The outflow: buffers (sph/open_boundaries.hpp) or the weir (sph/tailgate.hpp).
enum class OutflowCondition { hydrostatic_level, absorbing, tailgate };
// Where the outflow buffer holds the tailwater depth (sph/outflow_level_control.hpp).
enum class OutflowLevelReference { outlet, downstream_section };
// Particle shifting and its correction (sph/particle_shifting.hpp).
enum class ParticleShifting { none, fickian };
enum class ShiftingCorrection { none, taylor, taylor_volume };
// The interFoam turbulence model, its stabilisation and the mesh (reference/case_writer.hpp).
enum class TurbulenceModel { laminar, kOmegaSST, kEpsilon, RNGkEpsilon };
enum class TurbulenceStabilization { none, nut_limiter, nut_limiter_and_buoyancy };
enum class MeshStrategy { cartesian_cut, body_fitted };
// A stilling basin's bed (cases/bed_profile.hpp), how its tailwater is held (hold_toe: the outlet is
// steered to hold the toe at the basin start; fixed_depth: the outlet holds the depth) and where the
// depth comes from (given, or Belanger's y2*); a dam break's gate; a section's role.
enum class BedShape { smooth, sinusoidal };
enum class TailwaterControlMode { hold_toe, fixed_depth };
enum class TailwaterRule { given, belanger };
enum class GateOpening { instant, lifted };
enum class SectionRole { upstream, toe, interior, downstream, gauge };

template <class E>
struct OptionValue {
  E value;
  std::string_view name;
};

// OptionTable<E>::values: every value of E with its name in the spec, in the order messages list them.
template <class E>
struct OptionTable;

template <>
struct OptionTable<KernelType> {
  static constexpr std::array<OptionValue<KernelType>, 2> values{
      {{KernelType::wendland_c2, "wendland_c2"}, {KernelType::cubic_spline, "cubic_spline"}}};
};
template <>
struct OptionTable<Viscosity> {
  static constexpr std::array<OptionValue<Viscosity>, 2> values{
      {{Viscosity::artificial, "artificial"}, {Viscosity::laminar_sps, "laminar_sps"}}};
};
template <>
struct OptionTable<SpsWallDistance> {
  static constexpr std::array<OptionValue<SpsWallDistance>, 2> values{
      {{SpsWallDistance::kernel_support, "kernel_support"}, {SpsWallDistance::whole_domain, "whole_domain"}}};
};
template <>
struct OptionTable<ViscousWallCondition> {
  static constexpr std::array<OptionValue<ViscousWallCondition>, 3> values{
      {{ViscousWallCondition::no_slip, "no_slip"},
       {ViscousWallCondition::free_slip, "free_slip"},
       {ViscousWallCondition::wall_function, "wall_function"}}};
};
template <>
struct OptionTable<BoundaryMethod> {
  static constexpr std::array<OptionValue<BoundaryMethod>, 2> values{
      {{BoundaryMethod::dbc, "dbc"}, {BoundaryMethod::mdbc, "mdbc"}}};
};
template <>
struct OptionTable<DensityDiffusion> {
  static constexpr std::array<OptionValue<DensityDiffusion>, 3> values{{{DensityDiffusion::none, "none"},
                                                                       {DensityDiffusion::molteni, "molteni"},
                                                                       {DensityDiffusion::fourtakas, "fourtakas"}}};
};
template <>
struct OptionTable<TimeIntegrator> {
  static constexpr std::array<OptionValue<TimeIntegrator>, 2> values{
      {{TimeIntegrator::symplectic, "symplectic"}, {TimeIntegrator::verlet, "verlet"}}};
};
template <>
struct OptionTable<InflowCondition> {
  static constexpr std::array<OptionValue<InflowCondition>, 2> values{
      {{InflowCondition::buffer, "buffer"}, {InflowCondition::piston, "piston"}}};
};
template <>
struct OptionTable<OutflowCondition> {
  static constexpr std::array<OptionValue<OutflowCondition>, 3> values{
      {{OutflowCondition::hydrostatic_level, "hydrostatic_level"},
       {OutflowCondition::absorbing, "absorbing"},
       {OutflowCondition::tailgate, "tailgate"}}};
};
template <>
struct OptionTable<OutflowLevelReference> {
  static constexpr std::array<OptionValue<OutflowLevelReference>, 2> values{
      {{OutflowLevelReference::outlet, "outlet"}, {OutflowLevelReference::downstream_section, "downstream_section"}}};
};
template <>
struct OptionTable<ParticleShifting> {
  static constexpr std::array<OptionValue<ParticleShifting>, 2> values{
      {{ParticleShifting::none, "none"}, {ParticleShifting::fickian, "fickian"}}};
};
template <>
struct OptionTable<ShiftingCorrection> {
  static constexpr std::array<OptionValue<ShiftingCorrection>, 3> values{
      {{ShiftingCorrection::none, "none"},
       {ShiftingCorrection::taylor, "taylor"},
       {ShiftingCorrection::taylor_volume, "taylor_volume"}}};
};
template <>
struct OptionTable<TurbulenceModel> {
  static constexpr std::array<OptionValue<TurbulenceModel>, 4> values{{{TurbulenceModel::laminar, "laminar"},
                                                                      {TurbulenceModel::kOmegaSST, "kOmegaSST"},
                                                                      {TurbulenceModel::kEpsilon, "kEpsilon"},
                                                                      {TurbulenceModel::RNGkEpsilon, "RNGkEpsilon"}}};
};
template <>
struct OptionTable<TurbulenceStabilization> {
  static constexpr std::array<OptionValue<TurbulenceStabilization>, 3> values{
      {{TurbulenceStabilization::none, "none"},
       {TurbulenceStabilization::nut_limiter, "nut_limiter"},
       {TurbulenceStabilization::nut_limiter_and_buoyancy, "nut_limiter_and_buoyancy"}}};
};
template <>
struct OptionTable<MeshStrategy> {
  static constexpr std::array<OptionValue<MeshStrategy>, 2> values{
      {{MeshStrategy::cartesian_cut, "cartesian_cut"}, {MeshStrategy::body_fitted, "body_fitted"}}};
};

template <>
struct OptionTable<BedShape> {
  static constexpr std::array<OptionValue<BedShape>, 2> values{
      {{BedShape::smooth, "smooth"}, {BedShape::sinusoidal, "sinusoidal"}}};
};
template <>
struct OptionTable<TailwaterControlMode> {
  static constexpr std::array<OptionValue<TailwaterControlMode>, 2> values{
      {{TailwaterControlMode::hold_toe, "hold_toe"}, {TailwaterControlMode::fixed_depth, "fixed_depth"}}};
};
template <>
struct OptionTable<TailwaterRule> {
  static constexpr std::array<OptionValue<TailwaterRule>, 2> values{
      {{TailwaterRule::given, "given"}, {TailwaterRule::belanger, "belanger"}}};
};
template <>
struct OptionTable<GateOpening> {
  static constexpr std::array<OptionValue<GateOpening>, 2> values{
      {{GateOpening::instant, "instant"}, {GateOpening::lifted, "lifted"}}};
};
template <>
struct OptionTable<SectionRole> {
  static constexpr std::array<OptionValue<SectionRole>, 5> values{{{SectionRole::upstream, "upstream"},
                                                                  {SectionRole::toe, "toe"},
                                                                  {SectionRole::interior, "interior"},
                                                                  {SectionRole::downstream, "downstream"},
                                                                  {SectionRole::gauge, "gauge"}}};
};

// The name of a value in the spec ("laminar_sps").
template <class E>
constexpr std::string_view option_name(E value) {
  for (const auto& v : OptionTable<E>::values)
    if (v.value == value) return v.name;
  return "?";
}

// The value a name stands for, or nothing if the name is not one of E's.
template <class E>
constexpr std::optional<E> parse_option(std::string_view name) {
  for (const auto& v : OptionTable<E>::values)
    if (v.name == name) return v.value;
  return std::nullopt;
}

// The allowed names as messages quote them: "\"a\"", "\"a\" or \"b\"", "\"a\", \"b\" or \"c\"".
template <class E>
std::string allowed_option_names() {
  const auto& values = OptionTable<E>::values;
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) text += i + 1 == values.size() ? " or " : ", ";
    text += '"';
    text += values[i].name;
    text += '"';
  }
  return text;
}

// The value of a name given outside a spec (a command line, a test), or std::invalid_argument naming
// `what` and the allowed names.
template <class E>
E option_from_name(std::string_view what, std::string_view name) {
  if (const std::optional<E> v = parse_option<E>(name)) return *v;
  throw std::invalid_argument(std::string(what) + " = \"" + std::string(name) +
                              "\" is not allowed: use " + allowed_option_names<E>());
}

}  // namespace hydrojump::cases
