// The physical properties of a generated case: constant/g, constant/transportProperties (water from
// the spec's [fluid], air and surface tension fixed: AirProperties), constant/turbulenceProperties
// (vof.turbulence_model) and constant/fvOptions (vof.turbulence_stabilization), and the reference
// scales of the flow the turbulence fields start from.
//
// Turbulence (vof.turbulence_model; default from cases::VofSettings):
//   | model         | fields       | paper                   |
//   |---------------|--------------|-------------------------|
//   | "kOmegaSST"   | k, omega     | Menter 1994             |
//   | "kEpsilon"    | k, epsilon   | Launder & Spalding 1974 |
//   | "RNGkEpsilon" | k, epsilon   | Yakhot et al. 1992      |
//   | "laminar"     | none         | -                       |
#include <cmath>
#include <stdexcept>

#include "cases/hydraulics.hpp"
#include "reference/case_parts.hpp"

namespace hydrojump::reference {

std::vector<std::string> turbulence_fields(cases::TurbulenceModel turbulence_model) {
  switch (turbulence_model) {
    case cases::TurbulenceModel::laminar: return {};
    case cases::TurbulenceModel::kOmegaSST: return {"k", "omega"};
    case cases::TurbulenceModel::kEpsilon:
    case cases::TurbulenceModel::RNGkEpsilon: return {"k", "epsilon"};
  }
  return {};
}

namespace detail {

using foam::Dictionary;

// k = 3/2 (I U)^2;  omega = sqrt(k) / (Cmu^0.25 l), l = 0.07 D_h;  epsilon = Cmu k omega
// (= Cmu^(3/4) k^(3/2) / l: the same length scale l as omega).
FlowScales flow_scales(const CaseInputs& in) {
  const cases::CaseGeometry& geo = in.geo;
  FlowScales s;
  s.u_ref_m_s = geo.max_flow_speed_m_s > 0.0 ? geo.max_flow_speed_m_s
                                             : std::sqrt(in.study.fluid.gravity_m_s2 * geo.max_water_height_m);
  s.length_ref_m = geo.max_water_height_m;
  if (in.c.stilling_basin()) {
    const cases::InflowBoundary& inflow = geo.inflows.front();
    s.u_ref_m_s = inflow.velocity_m_s;
    s.length_ref_m = 4.0 * inflow.depth_m;  // hydraulic diameter of a wide open channel
    s.discharge_m2_s = cases::unit_discharge(inflow.depth_m, inflow.velocity_m_s);
    s.tailwater_m = geo.outflows.front().tailwater_depth_m;
    s.outlet_mean_velocity_m_s = s.discharge_m2_s / s.tailwater_m;
  }
  s.k = 1.5 * std::pow(turbulence_intensity * s.u_ref_m_s, 2);
  s.omega = std::sqrt(s.k) / (std::pow(c_mu, 0.25) * mixing_length_factor * s.length_ref_m);
  s.epsilon = c_mu * s.k * s.omega;
  return s;
}

namespace {

// constant/transportProperties: the two phases and the surface tension.
Dictionary transport_properties(const CaseInputs& in) {
  const AirProperties air;
  Dictionary tp;
  tp.directive("// water from the spec's [fluid]; air and surface tension fixed by hydrojump");
  tp.set("phases", foam::list({foam::word("water"), foam::word("air")}));
  Dictionary water;
  water.set("transportModel", foam::word("Newtonian"));
  water.set("nu", in.study.fluid.kinematic_viscosity_m2_s);
  water.set("rho", in.study.fluid.density_kg_m3);
  tp.set("water", water);
  Dictionary air_d;
  air_d.set("transportModel", foam::word("Newtonian"));
  air_d.set("nu", air.kinematic_viscosity_m2_s);
  air_d.set("rho", air.density_kg_m3);
  tp.set("air", air_d);
  tp.set("sigma", air.surface_tension_n_m);
  return tp;
}

// constant/turbulenceProperties: RAS with vof.turbulence_model, or laminar.
Dictionary turbulence_properties(cases::TurbulenceModel turbulence_model) {
  Dictionary tu;
  const std::string name(cases::option_name(turbulence_model));
  tu.directive("// vof.turbulence_model = \"" + name + "\"");
  if (!turbulence_fields(turbulence_model).empty()) {
    tu.set("simulationType", foam::word("RAS"));
    Dictionary ras;
    ras.set("RASModel", foam::word(name));
    ras.set("turbulence", foam::on_off(true));
    ras.set("printCoeffs", foam::on_off(true));
    tu.set("RAS", ras);
  } else {
    tu.set("simulationType", foam::word("laminar"));
  }
  return tu;
}

// constant/fvOptions of vof.turbulence_stabilization ("nut_limiter" or "nut_limiter_and_buoyancy"):
// OpenFOAM's multiphaseStabilizedTurbulence with its own default coefficients, written out: Cmu of
// k-epsilon, C = 1.51 (the k-omega value, the more conservative), lambda2 = 0.1 (strength of the nut
// limiter, Larsen & Fuhrman 2018) and alpha = 1/Prt = 1.36, the buoyancy sink of k where the density
// falls upwards (Devolder et al. 2017); "nut_limiter" sets alpha = 0, which removes that term and keeps
// the limiter alone.
Dictionary stabilization_fv_options(cases::TurbulenceStabilization stabilization) {
  const bool buoyancy = stabilization == cases::TurbulenceStabilization::nut_limiter_and_buoyancy;
  Dictionary coeffs;
  coeffs.set("rho", foam::word("rho"));
  coeffs.set("Cmu", c_mu);
  coeffs.set("C", 1.51);
  coeffs.set("lambda2", 0.1);
  coeffs.set("alpha", buoyancy ? 1.36 : 0.0);
  Dictionary option;
  option.set("type", foam::word("multiphaseStabilizedTurbulence"));
  option.set("active", foam::yes_no(true));
  option.set("multiphaseStabilizedTurbulenceCoeffs", coeffs);
  Dictionary fo;
  fo.directive("// vof.turbulence_stabilization = \"" + std::string(cases::option_name(stabilization)) +
               "\": the nut limiter of Larsen & Fuhrman (2018)" +
               (buoyancy ? std::string(" and the buoyancy term in k of Devolder et al. (2017)")
                         : std::string(" alone (alpha = 0: no buoyancy term)")));
  fo.set("stabilizedTurbulence", option);
  return fo;
}

}  // namespace

void add_physical_properties(VofCase& vof, const CaseInputs& in) {
  Dictionary gd;
  gd.set("dimensions", foam::dimensions({0, 1, -2, 0, 0, 0, 0}));
  gd.set("value", foam::vector(in.geo.body_force_m_s2.x(), in.geo.body_force_m_s2.y(), 0.0));
  add_file(vof, "constant/g", "uniformDimensionedVectorField", gd);
  add_file(vof, "constant/transportProperties", "dictionary", transport_properties(in));
  add_file(vof, "constant/turbulenceProperties", "dictionary", turbulence_properties(in.c.vof.turbulence_model));
  if (in.c.vof.turbulence_stabilization != cases::TurbulenceStabilization::none) {
    add_file(vof, "constant/fvOptions", "dictionary", stabilization_fv_options(in.c.vof.turbulence_stabilization));
  }
}

}  // namespace detail

}  // namespace hydrojump::reference
