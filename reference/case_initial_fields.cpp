// The initial state of a generated case: the fields of 0.orig/ (U, alpha.water, p_rgh and the
// turbulence fields k, omega or epsilon, nut) with the boundary condition of every patch, and
// system/setFieldsDict, the spec's initial water surface column by column.
//
// Patches of a stilling basin (2D, spanwise one cell thick):
//   | patch       | U                            | alpha.water            | p_rgh             |
//   |-------------|------------------------------|------------------------|-------------------|
//   | inlet       | fixedValue (U1 0 0)          | fixedValue 1           | fixedFluxPressure |
//   | walls, bed  | noSlip                       | zeroGradient           | fixedFluxPressure |
//   | outlet      | outletPhaseMeanVelocity q/y2 | variableHeightFlowRate | zeroGradient      |
//   | atmosphere  | pressureInletOutletVelocity  | inletOutlet 0          | totalPressure 0   |
//   | frontAndBack| empty                        | empty                  | empty             |
// The turbulence fields: wall functions on walls and bed (kqR-, omega- or epsilon-, nutkWallFunction),
// the inlet values fixed at the inlet, inletOutlet at the outlet and the atmosphere.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "reference/case_parts.hpp"

namespace hydrojump::reference::detail {

namespace {

using foam::Dictionary;
using foam::Value;

// The boundary condition of each patch (by name) for one field.
using PatchConditions = std::map<std::string, Dictionary>;

Dictionary type_only(const std::string& type) {
  Dictionary d;
  d.set("type", foam::word(type));
  return d;
}

Dictionary with_value(const std::string& type, const Value& value) {
  Dictionary d;
  d.set("type", foam::word(type));
  d.set("value", value);
  return d;
}

Dictionary inlet_outlet(const Value& value) {
  Dictionary d;
  d.set("type", foam::word("inletOutlet"));
  d.set("inletValue", value);
  d.set("value", value);
  return d;
}

Dictionary field_file(const std::array<int, 7>& dims, const Value& internal,
                      const std::vector<std::string>& patch_names, const PatchConditions& patch_conditions,
                      const std::vector<std::string>& trace) {
  Dictionary d;
  for (const std::string& line : trace) d.directive("// " + line);
  d.set("dimensions", foam::dimensions(dims));
  d.set("internalField", internal);
  Dictionary& bf = d.subdict("boundaryField");
  for (const std::string& p : patch_names) {
    if (p == "frontAndBack") {
      bf.set(p, type_only("empty"));
      continue;
    }
    const auto it = patch_conditions.find(p);
    if (it == patch_conditions.end()) throw std::logic_error("no boundary condition for patch " + p);
    bf.set(p, it->second);
  }
  return d;
}

// The patch conditions of every field of 0.orig/; `dissipation` is omega (kOmegaSST) or epsilon
// (kEpsilon, RNGkEpsilon), the second turbulence field.
struct FieldConditions {
  PatchConditions u, alpha, p, k, dissipation, nut;
};

FieldConditions field_conditions(const CaseInputs& in, const FlowScales& s) {
  FieldConditions f;
  const bool k_omega = in.c.vof.turbulence_model == cases::TurbulenceModel::kOmegaSST;
  const double diss_in = k_omega ? s.omega : s.epsilon;
  for (const std::string& wall : {std::string("walls"), std::string("bed")}) {
    f.u[wall] = type_only("noSlip");
    f.alpha[wall] = type_only("zeroGradient");
    f.p[wall] = type_only("fixedFluxPressure");
    f.k[wall] = with_value("kqRWallFunction", foam::uniform(s.k));
    f.dissipation[wall] = with_value(k_omega ? "omegaWallFunction" : "epsilonWallFunction", foam::uniform(diss_in));
    f.nut[wall] = with_value("nutkWallFunction", foam::uniform(0));
  }
  Dictionary pu;
  pu.set("type", foam::word("pressureInletOutletVelocity"));
  pu.set("value", foam::uniform(foam::vector(0, 0, 0)));
  f.u["atmosphere"] = pu;
  f.alpha["atmosphere"] = inlet_outlet(foam::uniform(0));
  Dictionary tp;
  tp.set("type", foam::word("totalPressure"));
  tp.set("p0", foam::uniform(0));
  f.p["atmosphere"] = tp;
  f.k["atmosphere"] = inlet_outlet(foam::uniform(s.k));
  f.dissipation["atmosphere"] = inlet_outlet(foam::uniform(diss_in));
  f.nut["atmosphere"] = with_value("calculated", foam::uniform(0));
  if (!in.c.stilling_basin()) return f;

  const cases::InflowBoundary& inflow = in.geo.inflows.front();
  f.u["inlet"] = with_value("fixedValue", foam::uniform(foam::vector(inflow.velocity_m_s, 0, 0)));
  f.alpha["inlet"] = with_value("fixedValue", foam::uniform(1));
  f.p["inlet"] = type_only("fixedFluxPressure");
  f.k["inlet"] = with_value("fixedValue", foam::uniform(s.k));
  f.dissipation["inlet"] = with_value("fixedValue", foam::uniform(diss_in));
  f.nut["inlet"] = with_value("calculated", foam::uniform(0));

  Dictionary uo;
  uo.set("type", foam::word("outletPhaseMeanVelocity"));
  uo.set("alpha", foam::word("alpha.water"));
  uo.set("Umean", s.outlet_mean_velocity_m_s);
  uo.set("value", foam::uniform(foam::vector(s.outlet_mean_velocity_m_s, 0, 0)));
  f.u["outlet"] = uo;
  Dictionary ao;
  ao.set("type", foam::word("variableHeightFlowRate"));
  ao.set("lowerBound", 0);
  ao.set("upperBound", 1);
  ao.set("value", foam::uniform(0));
  f.alpha["outlet"] = ao;
  f.p["outlet"] = type_only("zeroGradient");
  f.k["outlet"] = inlet_outlet(foam::uniform(s.k));
  f.dissipation["outlet"] = inlet_outlet(foam::uniform(diss_in));
  f.nut["outlet"] = with_value("calculated", foam::uniform(0));
  return f;
}

// One run of neighbouring columns whose water reaches the same cell row with the same velocity.
struct WaterColumns {
  double x0, x1, z_top, u;
  std::size_t cells;
};

// The columns of cells whose centres lie below the initial surface, merged into runs; U = q / depth.
std::vector<WaterColumns> initial_water_columns(const CaseInputs& in) {
  const std::vector<double> x = band_faces(in.plan.x_bands);
  const std::vector<double> z = band_faces(in.plan.z_bands);
  const cases::InitialWater& w = in.geo.initial_water;
  std::vector<WaterColumns> runs;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double xc = 0.5 * (x[i] + x[i + 1]);
    if (xc < w.x_begin_m || xc > w.x_end_m) continue;
    const double surface = w.surface_at(xc);
    const double depth = surface - in.geo.bed.elevation(xc);
    if (depth <= 0.0) continue;
    std::size_t top = 0;
    while (top + 1 < z.size() && 0.5 * (z[top] + z[top + 1]) < surface) ++top;
    if (top == 0) continue;
    const double u = w.discharge_m2_s > 0.0 ? w.discharge_m2_s / depth : 0.0;
    if (!runs.empty() && runs.back().cells == top && std::abs(runs.back().u - u) <= 1e-12 * (1 + u) &&
        std::abs(runs.back().x1 - x[i]) < 1e-12) {
      runs.back().x1 = x[i + 1];
    } else {
      runs.push_back(WaterColumns{x[i], x[i + 1], z[top], u, top});
    }
  }
  return runs;
}

}  // namespace

void add_initial_fields(VofCase& vof, const CaseInputs& in, const FlowScales& s) {
  const std::vector<std::string>& patches = vof.patches;
  const std::string& provenance = in.provenance;
  const FieldConditions f = field_conditions(in, s);
  const Value zero_vec = foam::uniform(foam::vector(0, 0, 0));
  std::vector<std::string> u_trace = {provenance};
  if (in.c.stilling_basin()) {
    u_trace.push_back("inlet: U1 = inflow.velocity_m_s = " + n(in.geo.inflows.front().velocity_m_s) + " m/s");
    u_trace.push_back("outlet: Umean = q / y2 = " + n(s.discharge_m2_s) + " / " + n(s.tailwater_m) + " = " +
                      n(s.outlet_mean_velocity_m_s) + " m/s (holds the tailwater depth y2)");
  }
  add_file(vof, "0.orig/U", "volVectorField", field_file({0, 1, -1, 0, 0, 0, 0}, zero_vec, patches, f.u, u_trace));
  add_file(vof, "0.orig/alpha.water", "volScalarField",
           field_file({0, 0, 0, 0, 0, 0, 0}, foam::uniform(0), patches, f.alpha,
                      {provenance, "initial water set by setFields from the spec's initial water surface"}));
  add_file(vof, "0.orig/p_rgh", "volScalarField",
           field_file({1, -1, -2, 0, 0, 0, 0}, foam::uniform(0), patches, f.p, {provenance}));
  if (turbulence_fields(in.c.vof.turbulence_model).empty()) return;
  const bool k_omega = in.c.vof.turbulence_model == cases::TurbulenceModel::kOmegaSST;
  const std::string scales = "k = 3/2 (I U)^2 with I = " + n(turbulence_intensity) + ", U = " + n(s.u_ref_m_s) +
                             " m/s; omega = sqrt(k)/(Cmu^0.25 l), l = 0.07 * " + n(s.length_ref_m) + " m" +
                             (k_omega ? std::string() : "; epsilon = Cmu k omega");
  add_file(vof, "0.orig/k", "volScalarField",
           field_file({0, 2, -2, 0, 0, 0, 0}, foam::uniform(s.k), patches, f.k, {provenance, scales}));
  if (k_omega) {
    add_file(vof, "0.orig/omega", "volScalarField",
             field_file({0, 0, -1, 0, 0, 0, 0}, foam::uniform(s.omega), patches, f.dissipation, {provenance, scales}));
  } else {
    add_file(vof, "0.orig/epsilon", "volScalarField",
             field_file({0, 2, -3, 0, 0, 0, 0}, foam::uniform(s.epsilon), patches, f.dissipation,
                        {provenance, scales}));
  }
  add_file(vof, "0.orig/nut", "volScalarField",
           field_file({0, 2, -1, 0, 0, 0, 0}, foam::uniform(0), patches, f.nut, {provenance}));
}

// setFields reads and rewrites every field it sets from disk once per region (OpenFOAM's
// setCellFieldType), so the regions are few: alpha.water = 1 in one region holding every column's box,
// and U = q / depth in one region per distinct velocity. The boxes span whole cells (their faces are
// cell faces), so no cell centre lies in two boxes and the regions' order does not matter: the fields
// are those of one region per column. (A at fine: 1,085 regions setting both fields took 4 min.)
void add_set_fields_dict(VofCase& vof, const CaseInputs& in) {
  const MeshPlan& plan = in.plan;
  const double z_low = plan.z_bands.front().begin_m;
  std::vector<Value> water_boxes;
  std::vector<std::pair<double, std::vector<Value>>> velocity_boxes;  // u and its boxes, in x order
  for (const WaterColumns& r : initial_water_columns(in)) {
    const Value low = foam::vector(r.x0, z_low - 1.0, -plan.thickness_m);
    const Value high = foam::vector(r.x1, r.z_top, plan.thickness_m);
    water_boxes.push_back(low);
    water_boxes.push_back(high);
    if (r.u == 0.0) continue;
    auto same = std::find_if(velocity_boxes.begin(), velocity_boxes.end(), [&](const auto& v) { return v.first == r.u; });
    if (same == velocity_boxes.end()) same = velocity_boxes.insert(velocity_boxes.end(), {r.u, {}});
    same->second.push_back(low);
    same->second.push_back(high);
  }
  std::vector<Value> regions;
  if (!water_boxes.empty()) {
    Dictionary water;
    water.set("boxes", foam::list(water_boxes));
    water.set("fieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 1")}));
    regions.push_back(foam::named_dict("boxToCell", water));
  }
  for (const auto& [u, boxes] : velocity_boxes) {
    Dictionary moving;
    moving.set("boxes", foam::list(boxes));
    moving.set("fieldValues", foam::list({foam::sequence({foam::word("volVectorFieldValue U"), foam::vector(u, 0, 0)})}));
    regions.push_back(foam::named_dict("boxToCell", moving));
  }
  Dictionary sf;
  sf.directive("// Initial water of " + in.provenance + " (cases::CaseGeometry::initial_water): cells whose");
  sf.directive("// centres lie below the surface; U = q / local depth, q = " + n(in.geo.initial_water.discharge_m2_s) +
               " m^2/s.");
  sf.set("defaultFieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 0"),
                                           foam::sequence({foam::word("volVectorFieldValue U"),
                                                           foam::vector(0, 0, 0)})}));
  sf.set("regions", foam::list(regions));
  add_file(vof, "system/setFieldsDict", "dictionary", sf);
}

}  // namespace hydrojump::reference::detail
