// The non-orthogonal-face self-test (runner.hpp, self_test_non_orthogonal): still water, 16 x 16 cells
// half full, run by interFoam for 100 fixed steps of 1 ms in a 0.1 m box whose faces are aligned with the
// axes and in the same box sheared by 2 degrees. A healthy interFoam keeps the water at rest in both
// (Courant number ~1e-5); Debian's v1912 build blows up in the sheared box, so `hydrojump vof` refuses a
// body_fitted mesh on it.
//
// The case is written here with the dictionary writer (foam_dictionary.hpp), with the schemes and the
// alpha and U solvers of the generated cases (case_writer.hpp), and is laminar, with fixed time steps:
//   | file                                | content                                                   |
//   |-------------------------------------|-----------------------------------------------------------|
//   | system/blockMeshDict                | one block, 16 x 16 x 1 cells; its top shifted by `shear`  |
//   | system/controlDict                  | 100 steps of 1 ms, never written                          |
//   | system/setFieldsDict                | alpha.water = 1 below half the height                     |
//   | system/fvSchemes, fvSolution        | interfoam_fv_schemes("laminar"), MULES, PCG for p_rgh     |
//   | constant/g, transportProperties ... | water 1000 kg/m^3, air 1 kg/m^3, laminar                  |
//   | 0/U, alpha.water, p_rgh             | walls: noSlip; atmosphere: open top                       |
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>

#include <unistd.h>

#include "reference/case_writer.hpp"
#include "reference/foam_dictionary.hpp"
#include "reference/foam_process.hpp"
#include "reference/solver_log.hpp"
#include "util/atomic_file.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

namespace {

using foam::Dictionary;

constexpr double box_size_m = 0.1;       // L: the box's width and height
constexpr double box_thickness_m = 0.01;  // the one spanwise cell

// Writes `d` as the file `path` ("system/controlDict") of class `cls` of the case in `dir`.
void write_file(const fs::path& dir, const std::string& path, const std::string& cls, const Dictionary& d) {
  const auto slash = path.find('/');
  util::write_file_atomically(dir / path, foam::format_file({cls, path.substr(0, slash), path.substr(slash + 1)}, d));
}

// One block of 16 x 16 cells; the top edge shifted by `shear_m` along x.
Dictionary block_mesh_dict(double shear_m) {
  const double L = box_size_m, t = box_thickness_m;
  Dictionary bm;
  std::vector<foam::Value> v;
  for (double z : {-0.5 * t, 0.5 * t}) {
    v.push_back(foam::vector(0, 0, z));
    v.push_back(foam::vector(L, 0, z));
    v.push_back(foam::vector(L + shear_m, L, z));
    v.push_back(foam::vector(shear_m, L, z));
  }
  bm.set("scale", 1);
  bm.set("vertices", foam::list(v));
  bm.set("blocks", foam::list({foam::sequence({foam::word("hex"), foam::list({0, 1, 2, 3, 4, 5, 6, 7}),
                                               foam::list({16, 16, 1}), foam::word("simpleGrading"),
                                               foam::list({1, 1, 1})})}));
  auto patch = [](const std::string& type, std::vector<foam::Value> faces) {
    Dictionary p;
    p.set("type", foam::word(type));
    p.set("faces", foam::list(std::move(faces)));
    return p;
  };
  bm.set("boundary",
         foam::list({foam::named_dict("walls", patch("wall", {foam::list({0, 4, 7, 3}), foam::list({2, 6, 5, 1}),
                                                               foam::list({1, 5, 4, 0})})),
                     foam::named_dict("atmosphere", patch("patch", {foam::list({3, 7, 6, 2})})),
                     foam::named_dict("frontAndBack", patch("empty", {foam::list({0, 3, 2, 1}),
                                                                      foam::list({4, 5, 6, 7})}))}));
  return bm;
}

// 100 fixed steps of 1 ms, no time written.
Dictionary control_dict() {
  Dictionary cd;
  cd.set("application", foam::word("interFoam"));
  cd.set("startFrom", foam::word("startTime"));
  cd.set("startTime", 0);
  cd.set("stopAt", foam::word("endTime"));
  cd.set("endTime", 0.1);
  cd.set("deltaT", 0.001);
  cd.set("writeControl", foam::word("timeStep"));
  cd.set("writeInterval", 100000);
  cd.set("runTimeModifiable", foam::word("no"));
  cd.set("adjustTimeStep", foam::word("no"));
  cd.set("maxCo", 1);
  cd.set("maxAlphaCo", 1);
  return cd;
}

// Water below half the box's height.
Dictionary set_fields_dict() {
  Dictionary sf;
  sf.set("defaultFieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 0")}));
  Dictionary box;
  box.set("box", foam::sequence({foam::vector(-1, -1, -1), foam::vector(1, 0.5 * box_size_m, 1)}));
  box.set("fieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 1")}));
  sf.set("regions", foam::list({foam::named_dict("boxToCell", box)}));
  return sf;
}

// The generated cases' alpha and U solvers, PCG for the pressure, a non-orthogonal corrector.
Dictionary fv_solution() {
  Dictionary sol;
  Dictionary& solvers = sol.subdict("solvers");
  solvers.set("\"alpha.water.*\"", mules_alpha_solver());
  Dictionary pcg;
  pcg.set("solver", foam::word("PCG"));
  pcg.set("preconditioner", foam::word("DIC"));
  pcg.set("tolerance", 1e-8);
  pcg.set("relTol", 0);
  solvers.set("\"(pcorr|p_rgh).*\"", pcg);
  solvers.set("\"U.*\"", smooth_solver(1e-8));
  Dictionary& pimple = sol.subdict("PIMPLE");
  pimple.set("momentumPredictor", foam::word("no"));
  pimple.set("nOuterCorrectors", 1);
  pimple.set("nCorrectors", 3);
  pimple.set("nNonOrthogonalCorrectors", 1);
  return sol;
}

// constant/: gravity, water and the damBreak tutorial's air, laminar.
void write_constant(const fs::path& dir) {
  Dictionary g;
  g.set("dimensions", foam::dimensions({0, 1, -2, 0, 0, 0, 0}));
  g.set("value", foam::vector(0, -9.81, 0));
  write_file(dir, "constant/g", "uniformDimensionedVectorField", g);
  Dictionary tp;
  tp.set("phases", foam::list({foam::word("water"), foam::word("air")}));
  Dictionary water, air;
  water.set("transportModel", foam::word("Newtonian"));
  water.set("nu", 1e-6);
  water.set("rho", 1000);
  air.set("transportModel", foam::word("Newtonian"));
  air.set("nu", 1.48e-5);
  air.set("rho", 1);
  tp.set("water", water);
  tp.set("air", air);
  tp.set("sigma", 0.07);
  write_file(dir, "constant/transportProperties", "dictionary", tp);
  Dictionary tu;
  tu.set("simulationType", foam::word("laminar"));
  write_file(dir, "constant/turbulenceProperties", "dictionary", tu);
}

// 0/: U, alpha.water and p_rgh at rest, with the walls' and the open top's conditions.
void write_initial_fields(const fs::path& dir) {
  auto field = [&](const std::string& name, const std::string& cls, const std::array<int, 7>& dims,
                   const foam::Value& internal, const Dictionary& walls, const Dictionary& atmosphere) {
    Dictionary f;
    f.set("dimensions", foam::dimensions(dims));
    f.set("internalField", internal);
    Dictionary& bf = f.subdict("boundaryField");
    bf.set("walls", walls);
    bf.set("atmosphere", atmosphere);
    Dictionary empty;
    empty.set("type", foam::word("empty"));
    bf.set("frontAndBack", empty);
    write_file(dir, "0/" + name, cls, f);
  };
  Dictionary no_slip, zero_grad, ffp, piov, io, tot;
  no_slip.set("type", foam::word("noSlip"));
  zero_grad.set("type", foam::word("zeroGradient"));
  ffp.set("type", foam::word("fixedFluxPressure"));
  piov.set("type", foam::word("pressureInletOutletVelocity"));
  piov.set("value", foam::uniform(foam::vector(0, 0, 0)));
  io.set("type", foam::word("inletOutlet"));
  io.set("inletValue", foam::uniform(0));
  io.set("value", foam::uniform(0));
  tot.set("type", foam::word("totalPressure"));
  tot.set("p0", foam::uniform(0));
  field("U", "volVectorField", {0, 1, -1, 0, 0, 0, 0}, foam::uniform(foam::vector(0, 0, 0)), no_slip, piov);
  field("alpha.water", "volScalarField", {0, 0, 0, 0, 0, 0, 0}, foam::uniform(0), zero_grad, io);
  field("p_rgh", "volScalarField", {1, -1, -2, 0, 0, 0, 0}, foam::uniform(0), ffp, tot);
}

void write_self_test_case(const fs::path& dir, double shear_m) {
  write_file(dir, "system/blockMeshDict", "dictionary", block_mesh_dict(shear_m));
  write_file(dir, "system/controlDict", "dictionary", control_dict());
  write_file(dir, "system/setFieldsDict", "dictionary", set_fields_dict());
  // Schemes and solvers as in the generated cases.
  write_file(dir, "system/fvSchemes", "dictionary", interfoam_fv_schemes(cases::TurbulenceModel::laminar));
  write_file(dir, "system/fvSolution", "dictionary", fv_solution());
  write_constant(dir);
  write_initial_fields(dir);
}

// Runs one self-test box; returns the largest Courant number (inf when the solver crashed).
double run_self_test_box(const fs::path& dir, double shear_m) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_self_test_case(dir, shear_m);
  // A stop request (Ctrl-C while `hydrojump vof` runs it) ends the self-test at once.
  const auto run_stoppable = [&dir](const std::string& app) {
    const auto ended = detail::wait_unless_stop_requested(detail::spawn({app}, dir, dir / ("log." + app), false), 0);
    if (!ended) throw OpenFoamError("interrupted: the self-test of interFoam was stopped on request");
    return ended->status();
  };
  for (const char* app : {"blockMesh", "setFields"}) {
    if (run_stoppable(app) != 0) {
      throw OpenFoamError(std::string("self-test: ") + app + " failed in " + dir.string() + ":\n" +
                          detail::tail_file(dir / (std::string("log.") + app)));
    }
  }
  const int rc = run_stoppable("interFoam");
  SolverLog log(DivergenceLimits{1.0, 1e300, 0.0});
  std::ifstream in(dir / "log.interFoam");
  std::string line;
  double worst = 0.0;
  while (std::getline(in, line)) {
    log.add_line(line);
    if (line.rfind("Courant Number mean:", 0) == 0 && log.courant_max()) {
      worst = std::isfinite(*log.courant_max()) ? std::max(worst, *log.courant_max())
                                                : std::numeric_limits<double>::infinity();
    }
  }
  if (rc != 0) return std::numeric_limits<double>::infinity();
  return worst;
}

}  // namespace

std::string SelfTestResult::summary() const {
  auto co = [](double c) { return std::isfinite(c) ? detail::format_seconds(c) : std::string("inf (crashed)"); };
  return "still water for 100 steps: axis-aligned box max Courant " + co(axis_aligned_courant) +
         (axis_aligned_ok ? " (ok)" : " (FAILED)") + "; box sheared by 2 degrees max Courant " +
         co(sheared_courant) + (sheared_ok ? " (ok)" : " (FAILED)");
}

SelfTestResult self_test_non_orthogonal(const fs::path& work_dir) {
  const detail::ScratchDirectory root(work_dir / (".hydrojump-selftest-" + std::to_string(::getpid())));
  SelfTestResult r;
  const double healthy = 1e-2;  // a resting fluid stays far below this Courant number
  r.axis_aligned_courant = run_self_test_box(root.path() / "aligned", 0.0);
  r.sheared_courant = run_self_test_box(root.path() / "sheared", 0.1 * std::tan(2.0 * M_PI / 180.0));
  r.axis_aligned_ok = r.axis_aligned_courant < healthy;
  r.sheared_ok = r.sheared_courant < healthy;
  return r;
}

}  // namespace hydrojump::reference
