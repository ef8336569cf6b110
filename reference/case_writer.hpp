// The OpenFOAM interFoam case of a hydrojump case: every dictionary of 0.orig/, constant/ and system/
// and the Allrun script, built in memory from the resolved spec and its CaseGeometry, then written.
//
// Patches of a stilling basin (2D, spanwise one cell thick):
//   | patch       | type  | U                          | alpha.water            | p_rgh            |
//   |-------------|-------|----------------------------|------------------------|------------------|
//   | inlet       | patch | fixedValue (U1 0 0)        | fixedValue 1           | fixedFluxPressure|
//   | walls       | wall  | noSlip (sluice gate above y1) | zeroGradient        | fixedFluxPressure|
//   | bed         | wall  | noSlip                     | zeroGradient           | fixedFluxPressure|
//   | outlet      | patch | outletPhaseMeanVelocity q/y2 | variableHeightFlowRate | zeroGradient   |
//   | atmosphere  | patch | pressureInletOutletVelocity| inletOutlet 0          | totalPressure 0  |
//   | frontAndBack| empty | empty                      | empty                  | empty            |
// The inlet spans exactly the inflow depth y1 above the upstream floor (a grid line lies at y1); above
// it the inflow section is closed by the sluice-gate wall, as in the flume. The outlet holds the
// tailwater by mass balance: `outletPhaseMeanVelocity` scales the outflow so that the water's mean
// velocity through the outlet is Umean = q / y2, so the steady outlet depth is y2.
// Dam break and still water: `walls` (tank ends), `bed` (floor), `atmosphere` (open top).
//
// Turbulence (vof.turbulence_model; default from cases::VofSettings):
//   | model         | default | fields       | walls                                                   |
//   |---------------|---------|--------------|---------------------------------------------------------|
//   | "kOmegaSST"   | yes     | k, omega     | kqRWallFunction, omegaWallFunction, nutkWallFunction    |
//   | "kEpsilon"    | no      | k, epsilon   | kqRWallFunction, epsilonWallFunction, nutkWallFunction  |
//   | "RNGkEpsilon" | no      | k, epsilon   | as kEpsilon                                             |
//   | "laminar"     | no      | none         | -                                                       |
// Inlet and initial values: k = 3/2 (I U)^2, I = 5 %; omega = sqrt(k) / (Cmu^0.25 l) and
// epsilon = Cmu k omega = Cmu^0.75 k^1.5 / l, with l = 0.07 D_h, D_h = 4 y1 (wide open channel) or the
// water height for tanks. Example (spec): [vof] turbulence_model = "kEpsilon".
// vof.turbulence_stabilization (k-epsilon models only; default "none") writes constant/fvOptions with
// OpenFOAM's multiphaseStabilizedTurbulence fvOption, against the over-production of turbulence at a VOF
// free surface:
//   | value                        | nut limiter (Larsen & Fuhrman 2018) | buoyancy sink of k (Devolder et al. 2017) |
//   |------------------------------|-------------------------------------|-------------------------------------------|
//   | "none"                       | -                                   | -                                         |
//   | "nut_limiter"                | lambda2 = 0.1                       | - (alpha = 0)                             |
//   | "nut_limiter_and_buoyancy"   | lambda2 = 0.1                       | alpha = 1/Prt = 1.36                      |
// (Larsen & Fuhrman 2018, J. Fluid Mech. 853:419; Devolder, Rauwoens & Troch 2017, Coastal Eng. 125:81.)
// Example:
//   [vof] turbulence_model = "kEpsilon"
//         turbulence_stabilization = "nut_limiter"
//
// Function objects in controlDict (written every output_interval_s of the spec):
//   sections          `sets`: alpha.water and U along a vertical line at each section (raw text)
//   discharge_<name>  `surfaceFieldValue`: sum of the water flux alphaPhi0.water (and phi) over the
//                     grid faces nearest to x_section (faceZone "section_<name>", made by
//                     system/topoSetDict.sections); divided by the spanwise thickness (one cell,
//                     MeshPlan::thickness_m) it is the water discharge q in m^2/s
//   discharge_inlet/_outlet  the same on the inlet and outlet patches
//   discharge_atmosphere     the same on the top (water leaving the domain there is lost to the basin;
//                     `hydrojump compare` notes it above 1 % of q)
//   freeSurface       `surfaces`: the alpha.water = 0.5 isoSurface (VTK)
//   average           `fieldAverage` of U and alpha.water over the averaging window (stilling basins)
//   floor (dam break) `sets`: alpha.water along a line half a cell above the floor (surge front)
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cases/geometry.hpp"
#include "cases/spec.hpp"
#include "reference/foam_dictionary.hpp"
#include "reference/mesh_plan.hpp"

namespace hydrojump::reference {

// The copy of case.toml the dictionaries were written from, beside it (write_vof_case): `hydrojump
// vof` refuses to start a run when case.toml's settings no longer agree with it (edited after
// `generate`).
inline constexpr const char* generated_case_file_name = ".generated_case.toml";

// One OpenFOAM utility run: the application and its arguments.
struct FoamStep {
  std::string application;
  std::vector<std::string> arguments;
};

// Properties not in the spec, fixed here and written into transportProperties: the air of OpenFOAM's
// damBreak tutorial (density 1 kg/m^3, where air at 20 C has 1.2: a density ratio of 1000 instead of
// 830, kept so that every VOF result reported so far stays comparable; not varied), a clean air-water
// interface.
struct AirProperties {
  double density_kg_m3 = 1.0;
  double kinematic_viscosity_m2_s = 1.48e-5;
  double surface_tension_n_m = 0.07;
};

struct VofCase {
  std::string case_id;
  std::string resolution;
  MeshPlan mesh;
  std::vector<std::string> patches;                 // in blockMeshDict order
  std::map<std::string, foam::FileHeader> headers;  // by relative path, e.g. "system/controlDict"
  std::map<std::string, foam::Dictionary> files;    // by relative path
  std::vector<FoamStep> mesh_steps;                 // blockMesh, [topoSet, subsetMesh]
  std::string allrun;                               // the Allrun script
};

// Why the OpenFOAM reference cannot model `c` (nothing when it can): the periodic Poiseuille channel
// is an SPH verification case only, and a dam-break gate lifted at a finite speed would need a moving
// mesh. `generate` writes this reason into vof/README.txt instead of a case; `hydrojump vof` refuses.
std::optional<std::string> vof_unsupported_reason(const cases::Case& c);
inline bool has_vof_reference(const cases::Case& c) { return !vof_unsupported_reason(c).has_value(); }

// Builds the case of `c` at resolution `resolution` (no file is written). Throws
// std::invalid_argument with a clear message for kinds or settings the VOF reference cannot run.
VofCase build_vof_case(const cases::Study& study, const cases::Case& c, const std::string& resolution);

// Writes `vof` into `dir` (created): 0.orig/, constant/, system/, Allrun. Every file is written
// atomically. Existing time directories and logs are left alone.
void write_vof_files(const VofCase& vof, const std::filesystem::path& dir);

// Updates system/decomposeParDict for `subdomains` MPI ranks (simple decomposition along x).
foam::Dictionary decompose_par_dict(int subdomains);

// A symmetric Gauss-Seidel smoothSolver entry of fvSolution with the given tolerance and relTol 0.
foam::Dictionary smooth_solver(double tolerance);

// The "alpha.water.*" entry of fvSolution: interFoam's MULES settings and a smoothSolver to 1e-8.
foam::Dictionary mules_alpha_solver();

// The transported turbulence fields of a vof.turbulence_model: none for "laminar", k and omega for
// "kOmegaSST", k and epsilon for "kEpsilon" and "RNGkEpsilon". Throws std::invalid_argument naming the
// allowed values for any other name.
std::vector<std::string> turbulence_fields(cases::TurbulenceModel turbulence_model);

// system/fvSchemes of the interFoam cases (with the schemes of the model's turbulence fields).
foam::Dictionary interfoam_fv_schemes(cases::TurbulenceModel turbulence_model);

}  // namespace hydrojump::reference
