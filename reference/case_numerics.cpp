// The numerics of a generated case: system/fvSchemes (Euler in time, linearUpwind momentum, vanLeer
// with interface compression for alpha, upwind turbulence fields), system/fvSolution (semi-implicit
// MULES with 2 correctors, GAMG for p_rgh, PIMPLE) and system/decomposeParDict (simple, along x).
#include <stdexcept>

#include "reference/case_parts.hpp"

namespace hydrojump::reference {

// Discretisation of every interFoam case written here: Euler in time, linearUpwind momentum,
// vanLeer + interface compression for alpha, upwind for the turbulence fields of `turbulence_model`
// (k and omega for "kOmegaSST", k and epsilon for "kEpsilon" and "RNGkEpsilon", none for "laminar").
foam::Dictionary interfoam_fv_schemes(cases::TurbulenceModel turbulence_model) {
  using foam::Dictionary;
  const std::vector<std::string> transported = turbulence_fields(turbulence_model);
  Dictionary fs;
  fs.subdict("ddtSchemes").set("default", foam::word("Euler"));
  fs.subdict("gradSchemes").set("default", foam::word("Gauss linear"));
  Dictionary& div = fs.subdict("divSchemes");
  div.set("default", foam::word("none"));
  div.set("div(rhoPhi,U)", foam::word("Gauss linearUpwind grad(U)"));
  div.set("div(phi,alpha)", foam::word("Gauss vanLeer"));
  div.set("div(phirb,alpha)", foam::word("Gauss linear"));
  for (const std::string& f : transported) div.set("div(phi," + f + ")", foam::word("Gauss upwind"));
  div.set("div(((rho*nuEff)*dev2(T(grad(U)))))", foam::word("Gauss linear"));
  fs.subdict("laplacianSchemes").set("default", foam::word("Gauss linear corrected"));
  fs.subdict("interpolationSchemes").set("default", foam::word("linear"));
  fs.subdict("snGradSchemes").set("default", foam::word("corrected"));
  if (!transported.empty()) fs.subdict("wallDist").set("method", foam::word("meshWave"));
  return fs;
}

// A symmetric Gauss-Seidel smoothSolver to an absolute tolerance (relTol 0).
foam::Dictionary smooth_solver(double tolerance) {
  foam::Dictionary d;
  d.set("solver", foam::word("smoothSolver"));
  d.set("smoother", foam::word("symGaussSeidel"));
  d.set("tolerance", tolerance);
  d.set("relTol", 0);
  return d;
}

// interFoam's phase fraction: 2 MULES correctors, no sub-cycling, interface compression cAlpha = 1,
// semi-implicit MULES with 5 limiter iterations, then a smoothSolver to 1e-8.
foam::Dictionary mules_alpha_solver() {
  foam::Dictionary d;
  d.set("nAlphaCorr", 2);
  d.set("nAlphaSubCycles", 1);
  d.set("cAlpha", 1);
  d.set("MULESCorr", foam::yes_no(true));
  d.set("nLimiterIter", 5);
  d.set("solver", foam::word("smoothSolver"));
  d.set("smoother", foam::word("symGaussSeidel"));
  d.set("tolerance", 1e-8);
  d.set("relTol", 0);
  return d;
}

foam::Dictionary decompose_par_dict(int subdomains) {
  if (subdomains < 1) throw std::invalid_argument("decomposeParDict: subdomains must be >= 1");
  foam::Dictionary d;
  d.directive("// Simple decomposition along the channel (x); `hydrojump vof --np N` rewrites this.");
  d.set("numberOfSubdomains", subdomains);
  d.set("method", foam::word("simple"));
  foam::Dictionary coeffs;
  coeffs.set("n", foam::list({subdomains, 1, 1}));
  d.set("coeffs", coeffs);
  return d;
}

namespace detail {

namespace {

// system/fvSolution: MULES for alpha, PCG for pcorr, GAMG for p_rgh (relTol 0.05, 0 in the final
// corrector), smoothSolver for U and the turbulence fields; PIMPLE with 3 pressure correctors and a
// non-orthogonal corrector on a body-fitted mesh.
foam::Dictionary fv_solution(const MeshPlan& plan) {
  using foam::Dictionary;
  Dictionary sol;
  Dictionary& solvers = sol.subdict("solvers");
  solvers.set("\"alpha.water.*\"", mules_alpha_solver());
  Dictionary pcorr;
  pcorr.set("solver", foam::word("PCG"));
  pcorr.set("preconditioner", foam::word("DIC"));
  pcorr.set("tolerance", 1e-5);
  pcorr.set("relTol", 0);
  solvers.set("\"pcorr.*\"", pcorr);
  Dictionary prgh;
  prgh.set("solver", foam::word("GAMG"));
  prgh.set("smoother", foam::word("DIC"));
  prgh.set("tolerance", 1e-7);
  prgh.set("relTol", 0.05);
  solvers.set("p_rgh", prgh);
  Dictionary prgh_final;
  prgh_final.directive("$p_rgh;");
  prgh_final.set("relTol", 0);
  solvers.set("p_rghFinal", prgh_final);
  solvers.set("\"(U|k|omega|epsilon).*\"", smooth_solver(1e-7));
  Dictionary& pimple = sol.subdict("PIMPLE");
  pimple.set("momentumPredictor", foam::word("no"));
  pimple.set("nOuterCorrectors", 1);
  pimple.set("nCorrectors", 3);
  pimple.set("nNonOrthogonalCorrectors", plan.strategy == cases::MeshStrategy::body_fitted ? 1 : 0);
  sol.subdict("relaxationFactors").subdict("equations").set("\".*\"", 1);
  return sol;
}

}  // namespace

void add_numerics(VofCase& vof, const CaseInputs& in) {
  add_file(vof, "system/fvSchemes", "dictionary", interfoam_fv_schemes(in.c.vof.turbulence_model));
  add_file(vof, "system/fvSolution", "dictionary", fv_solution(in.plan));
  add_file(vof, "system/decomposeParDict", "dictionary", decompose_par_dict(2));
}

}  // namespace detail

}  // namespace hydrojump::reference
