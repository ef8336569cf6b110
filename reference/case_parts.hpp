// The parts of the OpenFOAM case writer (internal to reference/): build_vof_case (case_writer.cpp)
// is a short script over one function per group of dictionaries, each in its own file:
//   | part                         | file                       | writes                                        |
//   |------------------------------|----------------------------|-----------------------------------------------|
//   | add_mesh_dictionaries        | case_mesh.cpp              | blockMeshDict, topoSetDict(.sections), steps  |
//   | add_physical_properties      | case_properties.cpp        | g, transportProperties, turbulence, fvOptions |
//   | add_initial_fields           | case_initial_fields.cpp    | 0.orig/* (U, alpha.water, p_rgh, k, ...)      |
//   | add_set_fields_dict          | case_initial_fields.cpp    | system/setFieldsDict (the initial water)      |
//   | add_control_dict             | case_control_dict.cpp      | system/controlDict and its function objects   |
//   | add_numerics                 | case_numerics.cpp          | fvSchemes, fvSolution, decomposeParDict       |
//   | allrun_script                | case_allrun.cpp            | the Allrun script                             |
#pragma once

#include <string>

#include "cases/geometry.hpp"
#include "cases/spec.hpp"
#include "reference/case_writer.hpp"
#include "reference/foam_dictionary.hpp"
#include "reference/mesh_plan.hpp"

namespace hydrojump::reference::detail {

// The cellSet kept by the cartesian cut (topoSetDict, then `subsetMesh fluidCells`).
inline constexpr const char* fluid_set_name = "fluidCells";

// What every part reads: the spec, its geometry and mesh plan, and the line naming them in comments.
struct CaseInputs {
  const cases::Study& study;
  const cases::Case& c;
  const cases::CaseGeometry& geo;
  const MeshPlan& plan;
  std::string provenance;       // case "<id>" of study "<name>", resolution "<resolution>"
  double cell_size_bed_m;       // h: vof_cell_size_bed_m
  double cell_size_bulk_m;      // vof_cell_size_bulk_m
};

// The reference scales of the flow, for the first time step and the turbulence fields:
//   k = 3/2 (I U)^2, I = 5 %;  omega = sqrt(k) / (Cmu^0.25 l), l = 0.07 D_h;  epsilon = Cmu k omega
// with U = U1 and D_h = 4 y1 for a stilling basin (a wide open channel), else the largest flow speed
// (sqrt(g H) at rest) and the water height H. A stilling basin's outlet holds Umean = q / y2.
struct FlowScales {
  double u_ref_m_s = 0.0;
  double length_ref_m = 0.0;
  double discharge_m2_s = 0.0;           // q (stilling basins, else 0)
  double tailwater_m = 0.0;              // y2
  double outlet_mean_velocity_m_s = 0.0; // q / y2
  double k = 0.0, omega = 0.0, epsilon = 0.0;
};
FlowScales flow_scales(const CaseInputs& in);

// Turbulence constants of the inlet values (case_properties.cpp).
inline constexpr double turbulence_intensity = 0.05;  // inlet k = 3/2 (I U)^2
inline constexpr double mixing_length_factor = 0.07;  // l = 0.07 D_h
inline constexpr double c_mu = 0.09;

// A number as the dictionaries write it (the shortest text that reads back exactly).
inline std::string n(double x) { return foam::format_number(x); }

// Adds `d` as the file `path` ("system/controlDict") of class `cls`, its header's location and object
// taken from the path.
void add_file(VofCase& vof, const std::string& path, const std::string& cls, const foam::Dictionary& d);

// system/blockMeshDict (and vof.patches), the cut's system/topoSetDict and the sections' face zones
// (system/topoSetDict.sections), with the mesh steps that run them.
void add_mesh_dictionaries(VofCase& vof, const CaseInputs& in);
// constant/g, transportProperties, turbulenceProperties and, with a stabilisation, fvOptions.
void add_physical_properties(VofCase& vof, const CaseInputs& in);
// 0.orig/: U, alpha.water, p_rgh and the turbulence fields, with every patch's condition.
void add_initial_fields(VofCase& vof, const CaseInputs& in, const FlowScales& scales);
// system/setFieldsDict: the spec's initial water, column by column.
void add_set_fields_dict(VofCase& vof, const CaseInputs& in);
// system/controlDict with the sampling function objects.
void add_control_dict(VofCase& vof, const CaseInputs& in, const FlowScales& scales);
// system/fvSchemes, fvSolution and decomposeParDict (2 ranks).
void add_numerics(VofCase& vof, const CaseInputs& in);
// The Allrun script of `vof` (its mesh steps), or under hold_toe one that refuses to run.
std::string allrun_script(const VofCase& vof, const CaseInputs& in);

}  // namespace hydrojump::reference::detail
