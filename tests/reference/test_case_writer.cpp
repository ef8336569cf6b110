// The OpenFOAM case writer: mesh plan (checked against brute-force oracles on the spec's bed profile),
// patches and their types, boundary conditions traced to the spec, sampling sections, initial water,
// and clear rejections. No OpenFOAM needed (test_openfoam_run.cpp runs the cases).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "util/child_process.hpp"
#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/spec_reader.hpp"
#include "reference/case_writer.hpp"
#include "reference/cli.hpp"
#include "reference/mesh_plan.hpp"
#include "reference/runner.hpp"
#include "reference_test_specs.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
namespace foam = hydrojump::reference::foam;
using namespace hydrojump;
using reference::testing::basin_spec;
using reference::testing::dam_break_spec;
using reference::testing::parse;
using reference::testing::tiny_hold_toe_spec;

namespace {

std::string text(const foam::Value& v) { return foam::format_value(v); }

// The vertex coordinates of blockMeshDict as (x, y, z) triples.
std::vector<std::array<double, 3>> vertices_of(const foam::Dictionary& block_mesh) {
  std::vector<std::array<double, 3>> out;
  for (const foam::Value& v : block_mesh.at("vertices").items()) {
    out.push_back({v.items()[0].number(), v.items()[1].number(), v.items()[2].number()});
  }
  return out;
}

struct Patch {
  std::string type;
  std::vector<std::array<int, 4>> faces;
};

std::map<std::string, Patch> patches_of(const foam::Dictionary& block_mesh) {
  std::map<std::string, Patch> out;
  for (const foam::Value& p : block_mesh.at("boundary").items()) {
    Patch patch;
    patch.type = p.dict().at("type").text();
    for (const foam::Value& f : p.dict().at("faces").items()) {
      patch.faces.push_back({static_cast<int>(f.items()[0].number()), static_cast<int>(f.items()[1].number()),
                             static_cast<int>(f.items()[2].number()), static_cast<int>(f.items()[3].number())});
    }
    out[p.text()] = patch;
  }
  return out;
}

}  // namespace

TEST_CASE("cartesian_cut plan: grid lines at the floor and the inflow surface, graded air, staircase bed",
          "[reference][mesh]") {
  // Air 0.15 m above the tailwater: room for the transition to the bulk cell size.
  const cases::Study study = parse(basin_spec("", 0.02, 0.01, "sinusoidal", 0.005, 0.01, 0.15));
  const cases::Case& c = study.cases.front();
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const reference::MeshPlan plan = reference::plan_mesh(c, geo, c.resolution("quick"));
  const double h = 0.005, h_bulk = 0.01, y1 = 0.0254, T = 0.013;

  const std::vector<double> x = reference::band_faces(plan.x_bands);
  const std::vector<double> z = reference::band_faces(plan.z_bands);
  CHECK(plan.columns() == static_cast<int>(std::lround(geo.x_max_m / h)));
  CHECK(x.front() == Approx(0.0).margin(1e-12));
  CHECK(x.back() == Approx(geo.x_max_m).epsilon(1e-12));
  CHECK(z.front() == Approx(-T).epsilon(1e-12));
  CHECK(z.back() == Approx(geo.z_max_m).epsilon(1e-12));
  auto has_line = [&](double value) {
    for (double f : z) if (std::abs(f - value) < 1e-12) return true;
    return false;
  };
  CHECK(has_line(0.0));  // the upstream floor
  CHECK(has_line(y1));   // the inflow surface
  // Cells: T/8 from troughs to crests (8 steps across the corrugation), graded by at most 20 % per cell
  // to about h by the inflow surface, h up to the top of the refinement band, graded to the bulk size.
  double previous = 0.0;
  int corrugation_rows = 0;
  for (std::size_t j = 0; j + 1 < z.size(); ++j) {
    const double dz = z[j + 1] - z[j];
    CHECK(dz > 0.0);
    if (z[j + 1] <= 1e-12) {
      CHECK(dz == Approx(T / 8).epsilon(1e-9));
      ++corrugation_rows;
    } else if (z[j + 1] <= plan.z_fine_top_m + 1e-12) {
      CHECK(dz <= h * (1.0 + 1e-9));
    }
    if (previous > 0.0 && (z[j] <= y1 + 1e-12 || z[j] >= plan.z_fine_top_m - 1e-12)) CHECK(dz / previous <= 1.2 + 1e-9);
    previous = dz;
  }
  CHECK(corrugation_rows == 8);
  CHECK(z[static_cast<std::size_t>(corrugation_rows) + 5] - z[static_cast<std::size_t>(corrugation_rows) + 4] > 0.6 * h);
  CHECK(z[z.size() - 1] - z[z.size() - 2] == Approx(h_bulk).epsilon(0.2));
  CHECK(plan.z_fine_top_m >= 0.06 + 0.25 * 0.06 - 1e-12);  // tailwater + default band 0.25 y2

  // Oracle: a cell is removed exactly when its centre lies below the bed z_b(x_centre), column by
  // column (the plan's runs of columns with the same count must give each column its own count).
  long removed = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double xc = 0.5 * (x[i] + x[i + 1]);
    int in_column = 0;
    for (std::size_t j = 0; j + 1 < z.size(); ++j) {
      if (0.5 * (z[j] + z[j + 1]) < geo.bed.elevation(xc)) ++in_column;
    }
    removed += in_column;
    int planned = 0;
    for (const reference::RemovedColumns& r : plan.removed)
      if (xc > r.x_begin_m && xc < r.x_end_m) planned = r.removed_cells;
    INFO("column " << i << " at x = " << xc << " m");
    CHECK(planned == in_column);
  }
  CHECK(removed > 0);
  CHECK(plan.removed_cell_count() == removed);
  CHECK(plan.cell_count() == plan.background_cells() - removed);
  for (const reference::RemovedColumns& r : plan.removed) {
    CHECK(r.z_top_m == Approx(z[static_cast<std::size_t>(r.removed_cells)]).margin(1e-15));
  }
}

TEST_CASE("basin columns: bed-size cells to one y2 past the last section, then graded to the bulk size",
          "[reference][mesh]") {
  // Outlet 0.4023 m past the basin: the last section at 0.42 m + y2 = 0.06 m leaves 0.29 m to grade,
  // and the domain (0.7723 m) is no whole number of 5 mm cells, so columns fitted to [0, 0.48] would
  // not be the uniform grid's.
  std::string spec = basin_spec("", 0.02, 0.01, "sinusoidal", 0.005, 0.01, 0.15);
  const std::string short_reach = "downstream_length_m = 0.1";
  spec.replace(spec.find(short_reach), short_reach.size(), "downstream_length_m = 0.4023");
  const cases::Study study = parse(spec);
  const cases::Case& c = study.cases.front();
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const reference::MeshPlan plan = reference::plan_mesh(c, geo, c.resolution("quick"));
  const double h = 0.005, h_bulk = 0.01;
  // Oracle: the lines of uniform columns inlet to outlet, and the first of them at or past x_s + y2.
  const int n = static_cast<int>(std::lround(geo.x_max_m / h));
  std::vector<double> uniform;
  for (int i = 0; i <= n; ++i) uniform.push_back(geo.x_max_m * i / n);
  const double x_grade = *std::find_if(uniform.begin(), uniform.end(), [](double f) { return f >= 0.42 + 0.06 - 1e-12; });
  REQUIRE(x_grade < 0.42 + 0.06 + h);

  const std::vector<double> x = reference::band_faces(plan.x_bands);
  REQUIRE(x.size() > 2);
  CHECK(x.front() == Approx(0.0).margin(1e-12));
  CHECK(x.back() == Approx(geo.x_max_m).epsilon(1e-12));
  CHECK(std::count_if(x.begin(), x.end(), [&](double f) { return std::abs(f - x_grade) < 1e-12; }) == 1);
  double previous = 0.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double dx = x[i + 1] - x[i];
    INFO("column " << i << " from x = " << x[i] << " m");
    if (x[i + 1] <= x_grade + 1e-12) {
      CHECK(x[i + 1] == Approx(uniform[i + 1]).margin(1e-12));  // the jump and every section: the uniform grid's
      CHECK(dx == Approx(h).epsilon(0.02));
    } else {
      // Growing to the outlet (the bulk cells sized to a whole number of them: within 2 % of h_bulk).
      CHECK(dx >= std::min(previous, 0.98 * h_bulk) * (1.0 - 1e-9));
      CHECK(dx / previous <= 1.2 + 1e-9);
      CHECK(dx <= h_bulk * 1.2);
    }
    previous = dx;
  }
  CHECK(x[x.size() - 1] - x[x.size() - 2] == Approx(h_bulk).epsilon(0.2));
  CHECK(plan.columns() < static_cast<int>(std::lround(geo.x_max_m / h)) - 20);
  // Oracle: the staircase cut column by column on the graded columns.
  const std::vector<double> z = reference::band_faces(plan.z_bands);
  long removed = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double zb = geo.bed.elevation(0.5 * (x[i] + x[i + 1]));
    for (std::size_t j = 0; j + 1 < z.size(); ++j) removed += 0.5 * (z[j] + z[j + 1]) < zb ? 1 : 0;
  }
  CHECK(removed > 0);
  CHECK(plan.removed_cell_count() == removed);
}

TEST_CASE("a short reach past the last section keeps bed-size columns to the outlet", "[reference][mesh]") {
  // basin_spec's outlet lies 0.052 m past its last section: less than y2 = 0.06 m, nothing to grade.
  const cases::Study study = parse(basin_spec());
  const cases::Case& c = study.cases.front();
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const reference::MeshPlan plan = reference::plan_mesh(c, geo, c.resolution("quick"));
  REQUIRE(plan.x_bands.size() == 1);
  CHECK(plan.x_bands.front().expansion == 1.0);
  CHECK(plan.columns() == static_cast<int>(std::lround(geo.x_max_m / 0.005)));
}

TEST_CASE("a smooth bed is not cut", "[reference][mesh]") {
  const cases::Study study = parse(basin_spec("", 0.02, 0.01, "smooth"));
  const cases::Case& c = study.cases.front();
  const reference::MeshPlan plan = reference::plan_mesh(c, cases::make_geometry(c, study.fluid), c.resolution("quick"));
  CHECK(plan.removed.empty());
  CHECK(reference::band_faces(plan.z_bands).front() == 0.0);
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  CHECK(vof.files.count("system/topoSetDict") == 0);
  CHECK(vof.mesh_steps.front().application == "blockMesh");
  CHECK(vof.mesh_steps.size() == 2);  // blockMesh, topoSet for the section zones
}

TEST_CASE("stilling basin: patches and their types with faces on the right boundaries", "[reference][case]") {
  const cases::Study study = parse(basin_spec());
  const cases::Case& c = study.cases.front();
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  const foam::Dictionary& bmd = vof.files.at("system/blockMeshDict");
  const auto patches = patches_of(bmd);
  const auto v = vertices_of(bmd);
  const double y1 = 0.0254, L = 0.472, top = 0.1;

  CHECK(vof.patches == std::vector<std::string>{"inlet", "outlet", "walls", "bed", "atmosphere", "frontAndBack"});
  CHECK(patches.at("inlet").type == "patch");
  CHECK(patches.at("outlet").type == "patch");
  CHECK(patches.at("walls").type == "wall");
  CHECK(patches.at("bed").type == "wall");
  CHECK(patches.at("atmosphere").type == "patch");
  CHECK(patches.at("frontAndBack").type == "empty");
  auto all_vertices = [&](const std::string& patch, auto predicate) {
    for (const auto& f : patches.at(patch).faces)
      for (int id : f)
        if (!predicate(v.at(static_cast<std::size_t>(id)))) return false;
    return true;
  };
  CHECK(all_vertices("inlet", [&](auto p) { return p[0] == 0.0 && p[1] >= -1e-12 && p[1] <= y1 + 1e-12; }));
  CHECK(all_vertices("walls", [&](auto p) { return p[0] == 0.0 && p[1] >= y1 - 1e-12; }));
  CHECK(all_vertices("outlet", [&](auto p) { return std::abs(p[0] - L) < 1e-12; }));
  CHECK(all_vertices("atmosphere", [&](auto p) { return std::abs(p[1] - top) < 1e-12; }));
  CHECK(all_vertices("bed", [&](auto p) { return std::abs(p[1] + 0.013) < 1e-12 || (p[0] == 0.0 && p[1] <= 1e-12); }));
  // The blocks hold the whole background grid.
  long cells = 0;
  for (const foam::Value& b : bmd.at("blocks").items()) {
    const auto& n = b.items()[2].items();
    cells += static_cast<long>(n[0].number() * n[1].number() * n[2].number());
    CHECK(n[2].number() == 1.0);
  }
  CHECK(cells == vof.mesh.background_cells());
  // One cell thick, centred on z = 0.
  for (const auto& p : v) CHECK(std::abs(std::abs(p[2]) - 0.5 * vof.mesh.thickness_m) < 1e-15);
  // Mesh steps: cut below the bed, then the section face zones.
  REQUIRE(vof.mesh_steps.size() == 4);
  CHECK(vof.mesh_steps[1].application == "topoSet");
  CHECK(vof.mesh_steps[2].application == "subsetMesh");
  CHECK(vof.mesh_steps[2].arguments == std::vector<std::string>{"fluidCells", "-patch", "bed", "-overwrite"});
}

TEST_CASE("stilling basin: boundary conditions follow the spec", "[reference][case]") {
  const cases::Study study = parse(basin_spec());
  const cases::Case& c = study.cases.front();
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  const double y1 = 0.0254, u1 = 2.0, y2 = 0.06, q = y1 * u1;
  for (const char* field : {"0.orig/U", "0.orig/alpha.water", "0.orig/p_rgh", "0.orig/k", "0.orig/omega", "0.orig/nut"}) {
    INFO(field);
    REQUIRE(vof.files.count(field) == 1);
    CHECK(vof.files.at(field).subdict_at("boundaryField").keys() == vof.patches);
  }
  const auto& u = vof.files.at("0.orig/U").subdict_at("boundaryField");
  CHECK(u.subdict_at("inlet").at("type").text() == "fixedValue");
  CHECK(text(u.subdict_at("inlet").at("value")) == "uniform (2 0 0)");
  CHECK(u.subdict_at("outlet").at("type").text() == "outletPhaseMeanVelocity");
  CHECK(u.subdict_at("outlet").at("Umean").number() == Approx(q / y2).epsilon(1e-14));
  CHECK(u.subdict_at("bed").at("type").text() == "noSlip");
  CHECK(u.subdict_at("atmosphere").at("type").text() == "pressureInletOutletVelocity");
  const auto& a = vof.files.at("0.orig/alpha.water").subdict_at("boundaryField");
  CHECK(text(a.subdict_at("inlet").at("value")) == "uniform 1");
  CHECK(a.subdict_at("outlet").at("type").text() == "variableHeightFlowRate");
  CHECK(a.subdict_at("atmosphere").at("type").text() == "inletOutlet");
  const auto& p = vof.files.at("0.orig/p_rgh").subdict_at("boundaryField");
  CHECK(p.subdict_at("atmosphere").at("type").text() == "totalPressure");
  CHECK(p.subdict_at("bed").at("type").text() == "fixedFluxPressure");
  // k-omega SST: inlet k = 3/2 (0.05 U1)^2, omega = sqrt(k) / (0.09^0.25 * 0.07 * 4 y1), wall functions.
  const double k = 1.5 * std::pow(0.05 * u1, 2);
  const double omega = std::sqrt(k) / (std::pow(0.09, 0.25) * 0.07 * 4.0 * y1);
  const auto& kb = vof.files.at("0.orig/k").subdict_at("boundaryField");
  CHECK(kb.subdict_at("inlet").at("value").items()[1].number() == Approx(k).epsilon(1e-12));
  CHECK(kb.subdict_at("bed").at("type").text() == "kqRWallFunction");
  const auto& ob = vof.files.at("0.orig/omega").subdict_at("boundaryField");
  CHECK(ob.subdict_at("inlet").at("value").items()[1].number() == Approx(omega).epsilon(1e-12));
  CHECK(ob.subdict_at("walls").at("type").text() == "omegaWallFunction");
  CHECK(vof.files.at("0.orig/nut").subdict_at("boundaryField").subdict_at("bed").at("type").text() ==
        "nutkWallFunction");
  CHECK(vof.files.at("constant/turbulenceProperties").subdict_at("RAS").at("RASModel").text() == "kOmegaSST");
  CHECK(text(vof.files.at("constant/g").at("value")) == "(0 -9.81 0)");
  CHECK(vof.files.at("constant/transportProperties").subdict_at("water").at("nu").number() == 1e-6);
}

TEST_CASE("laminar cases have no turbulence fields", "[reference][case]") {
  const cases::Study study = parse(basin_spec("turbulence_model = \"laminar\""));
  const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
  CHECK(vof.files.count("0.orig/k") == 0);
  CHECK(vof.files.count("0.orig/omega") == 0);
  CHECK(vof.files.at("constant/turbulenceProperties").at("simulationType").text() == "laminar");
}

TEST_CASE("k-epsilon models write k and epsilon with epsilon wall functions", "[reference][case]") {
  for (const std::string model : {"kEpsilon", "RNGkEpsilon"}) {
    INFO(model);
    const cases::Study study = parse(basin_spec("turbulence_model = \"" + model + "\""));
    const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
    CHECK(vof.files.at("constant/turbulenceProperties").subdict_at("RAS").at("RASModel").text() == model);
    CHECK(vof.files.count("0.orig/omega") == 0);
    REQUIRE(vof.files.count("0.orig/epsilon") == 1);
    // epsilon = Cmu^0.75 k^1.5 / l with k = 3/2 (0.05 U1)^2 and l = 0.07 * 4 y1 (U1 = 2 m/s, y1 = 25.4 mm)
    const double k = 1.5 * std::pow(0.05 * 2.0, 2);
    const double epsilon = std::pow(0.09, 0.75) * std::pow(k, 1.5) / (0.07 * 4.0 * 0.0254);
    const auto& eb = vof.files.at("0.orig/epsilon").subdict_at("boundaryField");
    CHECK(eb.subdict_at("inlet").at("value").items()[1].number() == Approx(epsilon).epsilon(1e-12));
    CHECK(eb.subdict_at("bed").at("type").text() == "epsilonWallFunction");
    CHECK(eb.subdict_at("walls").at("type").text() == "epsilonWallFunction");
    CHECK(eb.subdict_at("outlet").at("type").text() == "inletOutlet");
    CHECK(vof.files.at("0.orig/k").subdict_at("boundaryField").subdict_at("bed").at("type").text() ==
          "kqRWallFunction");
    const auto& div = vof.files.at("system/fvSchemes").subdict_at("divSchemes");
    CHECK(div.at("div(phi,epsilon)").text() == "Gauss upwind");
    CHECK_FALSE(div.contains("div(phi,omega)"));
    CHECK(vof.files.at("system/fvSolution").subdict_at("solvers").contains("\"(U|k|omega|epsilon).*\""));
  }
  CHECK_THROWS_WITH(parse(basin_spec("turbulence_model = \"kOmega\"")),
                    Catch::Contains("turbulence_model") && Catch::Contains("RNGkEpsilon"));
}

TEST_CASE("turbulence stabilization writes OpenFOAM's fvOption and needs a k-epsilon model", "[reference][case]") {
  // "nut_limiter" is the fvOption with its buoyancy coefficient alpha set to 0; "nut_limiter_and_buoyancy"
  // keeps the fvOption's own alpha = 1/Prt = 1.36. Both keep its lambda2 = 0.1 and C = 1.51.
  for (const auto& [value, alpha] : std::vector<std::pair<std::string, double>>{{"nut_limiter", 0.0}, {"nut_limiter_and_buoyancy", 1.36}}) {
    for (const std::string model : {"kEpsilon", "RNGkEpsilon"}) {
      INFO(model << " " << value);
      const cases::Study study =
          parse(basin_spec("turbulence_model = \"" + model + "\"\nturbulence_stabilization = \"" + value + "\"\n"));
      const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
      REQUIRE(vof.files.count("constant/fvOptions") == 1);
      CHECK(vof.headers.at("constant/fvOptions").class_name == "dictionary");
      const auto& option = vof.files.at("constant/fvOptions").subdict_at("stabilizedTurbulence");
      CHECK(option.at("type").text() == "multiphaseStabilizedTurbulence");
      const auto& coeffs = option.subdict_at("multiphaseStabilizedTurbulenceCoeffs");
      CHECK(coeffs.at("rho").text() == "rho");
      CHECK(coeffs.at("lambda2").number() == 0.1);
      CHECK(coeffs.at("C").number() == 1.51);
      CHECK(coeffs.at("alpha").number() == alpha);
    }
  }
  // Without the key (the default "none") there is no fvOptions file.
  const cases::Study plain = parse(basin_spec("turbulence_model = \"kEpsilon\""));
  CHECK(reference::build_vof_case(plain, plain.cases.front(), "quick").files.count("constant/fvOptions") == 0);
  // k-omega SST (the default model) and laminar are refused, naming the file, the key and the allowed models.
  const std::string stabilized = "turbulence_stabilization = \"nut_limiter\"\n";
  CHECK_THROWS_WITH(parse(basin_spec(stabilized)),
                    Catch::Contains("vof.turbulence_stabilization") && Catch::Contains("\"kEpsilon\", \"RNGkEpsilon\"") &&
                        Catch::Contains("turbulence_model is \"kOmegaSST\""));
  CHECK_THROWS_WITH(parse(basin_spec("turbulence_model = \"laminar\"\n" + stabilized)),
                    Catch::Contains("turbulence_model is \"laminar\""));
  // A case that overrides the study's model is checked on the merged settings, at its own key.
  std::string spec = basin_spec("turbulence_model = \"kEpsilon\"\n" + stabilized);
  spec.replace(spec.find("[case.run]"), 0, "[case.vof]\nturbulence_model = \"kOmegaSST\"\n");
  CHECK_THROWS_WITH(parse(spec), Catch::Contains("case \"basin\": vof.turbulence_model = \"kOmegaSST\" cannot be used"));
  CHECK_THROWS_WITH(parse(basin_spec("turbulence_model = \"kEpsilon\"\nturbulence_stabilization = \"on\"")),
                    Catch::Contains("turbulence_stabilization") && Catch::Contains("\"nut_limiter_and_buoyancy\""));
}

TEST_CASE("controlDict: run settings and sampling of every section", "[reference][case]") {
  const cases::Study study = parse(basin_spec("", 3.5, 0.05));
  const cases::Case& c = study.cases.front();
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  const foam::Dictionary& cd = vof.files.at("system/controlDict");
  CHECK(cd.at("endTime").number() == 3.5);
  CHECK(cd.at("writeInterval").number() == 0.05);
  CHECK(cd.at("maxCo").number() == 0.7);
  CHECK(cd.at("maxAlphaCo").number() == 0.6);
  CHECK(cd.at("maxDeltaT").number() == 0.002);
  CHECK(cd.at("startFrom").text() == "latestTime");
  const foam::Dictionary& fo = cd.subdict_at("functions");
  const auto& sets = fo.subdict_at("sections").at("sets").items();
  REQUIRE(sets.size() == c.sections.size());
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  for (std::size_t i = 0; i < sets.size(); ++i) {
    INFO(c.sections[i].name);
    CHECK(sets[i].text() == c.sections[i].name);
    const auto& start = sets[i].dict().at("start").items();
    const auto& end = sets[i].dict().at("end").items();
    CHECK(start[0].number() == c.sections[i].x_m);
    CHECK(end[0].number() == c.sections[i].x_m);
    CHECK(start[1].number() >= geo.bed.elevation(c.sections[i].x_m));
    CHECK(start[1].number() <= geo.bed.elevation(c.sections[i].x_m) + 0.005);
    CHECK(end[1].number() == Approx(geo.z_max_m).margin(1e-4));
    CHECK(fo.contains("discharge_" + c.sections[i].name));
    CHECK(fo.subdict_at("discharge_" + c.sections[i].name).at("name").text() == "section_" + c.sections[i].name);
  }
  CHECK(fo.contains("discharge_inlet"));
  CHECK(fo.contains("discharge_outlet"));
  CHECK(fo.subdict_at("discharge_atmosphere").at("regionType").text() == "patch");
  CHECK(fo.subdict_at("discharge_atmosphere").at("name").text() == "atmosphere");
  CHECK(fo.subdict_at("freeSurface").at("surfaces").items()[0].dict().at("isoValue").number() == 0.5);
  CHECK(fo.subdict_at("average").at("timeEnd").number() == 3.5);
  // The discharge face zones sit on the grid faces nearest to each section.
  const auto& actions = vof.files.at("system/topoSetDict.sections").at("actions").items();
  REQUIRE(actions.size() == 2 * c.sections.size());
  const std::vector<double> x = reference::band_faces(vof.mesh.x_bands);
  for (std::size_t i = 0; i < c.sections.size(); ++i) {
    const auto& box = actions[2 * i].dict().at("box").items();
    const double xf = 0.5 * (box[0].items()[0].number() + box[1].items()[0].number());
    double nearest = 1e9;
    for (double f : x) nearest = std::min(nearest, std::abs(f - c.sections[i].x_m));
    CHECK(std::abs(xf - c.sections[i].x_m) == Approx(nearest).margin(1e-12));
    CHECK(nearest <= 0.5 * 0.005 + 1e-12);
  }
}

TEST_CASE("setFields: the initial water follows the spec's surface and carries q, in few regions", "[reference][case]") {
  const cases::Study study = parse(basin_spec());
  const cases::Case& c = study.cases.front();
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  const auto& regions = vof.files.at("system/setFieldsDict").at("regions").items();
  REQUIRE(regions.size() >= 2);
  // The first region: alpha.water = 1 in every column's box, the boxes side by side (never overlapping,
  // so the regions' order cannot matter), covering the channel.
  const auto& water = regions[0].dict();
  REQUIRE(water.at("fieldValues").items().size() == 1);
  CHECK(water.at("fieldValues").items()[0].text() == "volScalarFieldValue alpha.water 1");
  const auto& boxes = water.at("boxes").items();
  REQUIRE(boxes.size() % 2 == 0);
  double covered = 0.0, previous_x1 = -1e9;
  std::map<double, double> box_of_x0;  // x0 -> x1
  for (std::size_t k = 0; k < boxes.size(); k += 2) {
    const double x0 = boxes[k].items()[0].number(), x1 = boxes[k + 1].items()[0].number();
    const double z_top = boxes[k + 1].items()[1].number();
    CHECK(x0 >= previous_x1 - 1e-12);
    previous_x1 = x1;
    covered += x1 - x0;
    box_of_x0[x0] = x1;
    for (double xc = x0 + 0.0025; xc < x1; xc += 0.005) {
      // The box top is the face between the last water cell (centre below the surface) and the next.
      const double surface = geo.initial_water.surface_at(xc);
      CHECK(std::abs(z_top - surface) <= 0.5 * 0.005 + 1e-9);
    }
  }
  CHECK(covered == Approx(geo.x_max_m).epsilon(1e-9));
  // The others: U = q / local depth, one region per velocity, each box one of the water boxes.
  std::set<double> velocities;
  std::size_t moving_boxes = 0;
  for (std::size_t i = 1; i < regions.size(); ++i) {
    const auto& values = regions[i].dict().at("fieldValues").items();
    REQUIRE(values.size() == 1);
    const double u = values[0].items()[1].items()[0].number();
    CHECK(velocities.insert(u).second);
    const auto& own = regions[i].dict().at("boxes").items();
    for (std::size_t k = 0; k < own.size(); k += 2) {
      const double x0 = own[k].items()[0].number(), x1 = own[k + 1].items()[0].number();
      REQUIRE(box_of_x0.count(x0) == 1);
      CHECK(box_of_x0[x0] == x1);
      const double xm = 0.5 * (x0 + x1);
      CHECK(u == Approx(0.0254 * 2.0 / (geo.initial_water.surface_at(xm) - geo.bed.elevation(xm))).epsilon(0.05));
      ++moving_boxes;
    }
  }
  CHECK(moving_boxes == boxes.size() / 2);  // every column of this basin moves
}

TEST_CASE("dam break: closed tank, grid line at the gate, water column and floor line", "[reference][case]") {
  const cases::Study study = parse(dam_break_spec());
  const cases::Case& c = study.cases.front();
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  CHECK(vof.patches == std::vector<std::string>{"walls", "bed", "atmosphere", "frontAndBack"});
  const std::vector<double> x = reference::band_faces(vof.mesh.x_bands);
  CHECK(std::count_if(x.begin(), x.end(), [](double f) { return std::abs(f - 0.1) < 1e-12; }) == 1);
  CHECK(vof.mesh.cell_count() == 40L * vof.mesh.rows());
  const auto& regions = vof.files.at("system/setFieldsDict").at("regions").items();
  REQUIRE(regions.size() == 1);
  const auto& box = regions[0].dict().at("boxes").items();
  REQUIRE(box.size() == 2);
  CHECK(box[1].items()[0].number() == Approx(0.1).margin(1e-12));
  CHECK(box[1].items()[1].number() == Approx(0.2).margin(1e-12));
  CHECK(regions[0].dict().at("fieldValues").items().size() == 1);  // at rest: alpha only
  const auto& sets = vof.files.at("system/controlDict").subdict_at("functions").subdict_at("sections").at("sets").items();
  std::set<std::string> names;
  for (const auto& s : sets) names.insert(s.text());
  CHECK(names == std::set<std::string>{"H1", "H2", "floor"});
  CHECK(vof.files.count("system/topoSetDict") == 0);
  CHECK(vof.files.at("constant/turbulenceProperties").at("simulationType").text() == "laminar");
}

TEST_CASE("body_fitted plan follows the bed and removes nothing", "[reference][mesh]") {
  const cases::Study study = parse(basin_spec("mesh_strategy = \"body_fitted\""));
  const cases::Case& c = study.cases.front();
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const reference::VofCase vof = reference::build_vof_case(study, c, "quick");
  CHECK(vof.mesh.strategy == hydrojump::cases::MeshStrategy::body_fitted);
  CHECK(vof.mesh.removed.empty());
  CHECK(vof.mesh.cell_count() == vof.mesh.background_cells());
  REQUIRE(vof.mesh.bed_vertices.size() == vof.mesh.x_bands.size() + 1);
  for (const auto& p : vof.mesh.bed_vertices) CHECK(p.y() == Approx(geo.bed.elevation(p.x())).margin(1e-12));
  // The bottom row of blockMesh vertices lies on the bed.
  const auto v = vertices_of(vof.files.at("system/blockMeshDict"));
  for (std::size_t i = 0; i < vof.mesh.bed_vertices.size(); ++i) {
    CHECK(v[i][0] == vof.mesh.bed_vertices[i].x());
    CHECK(v[i][1] == vof.mesh.bed_vertices[i].y());
  }
  CHECK(vof.files.at("system/fvSolution").subdict_at("PIMPLE").at("nNonOrthogonalCorrectors").number() == 1);
}

TEST_CASE("cases the VOF reference cannot run are rejected with a clear message", "[reference][case]") {
  {
    const cases::Study study = parse(basin_spec("", 0.02, 0.01, "sinusoidal", 0.02, 0.02));
    CHECK_THROWS_WITH(reference::build_vof_case(study, study.cases.front(), "quick"),
                      Catch::Contains("vof_cell_size_bed_m") && Catch::Contains("inflow depth"));
  }
  {
    const cases::Study study = parse(dam_break_spec("type = \"lifted\"\nlift_speed_m_s = 1.0"));
    CHECK_THROWS_WITH(reference::build_vof_case(study, study.cases.front(), "quick"),
                      Catch::Contains("gate") && Catch::Contains("instant"));
    // `generate` still succeeds for such a study: the vof/ directory explains why it has no case.
    const hydrojump::testing::TempDir tmp("reference-lifted");
    const fs::path dir = tmp.path() / "case";  // not there yet: write_vof_case creates it
    reference::write_vof_case(study, study.cases.front(), "quick", dir);
    CHECK(fs::exists(dir / "README.txt"));
    CHECK_FALSE(fs::exists(dir / "system"));
  }
  {
    const cases::Study study = parse(basin_spec());
    CHECK_THROWS_AS(reference::build_vof_case(study, study.cases.front(), "fine"), std::exception);
  }
}

TEST_CASE("a case path with a blank or a quote is refused for OpenFOAM, naming it", "[reference][case]") {
  CHECK_FALSE(reference::openfoam_path_problem("/tmp/runs/A/vof").has_value());
  CHECK_THAT(*reference::openfoam_path_problem("/tmp/my runs/A/vof"),
             Catch::Contains("/tmp/my runs/A/vof: its path holds a blank"));
  CHECK(reference::openfoam_path_problem("/tmp/it's/A/vof").has_value());
  CHECK(reference::openfoam_path_problem("/tmp/tab\there").has_value());
  std::ostringstream out;
  CHECK_THROWS_WITH(reference::run_vof_case("/tmp/no such dir/vof", reference::RunOptions{}, out),
                    Catch::Contains("OpenFOAM cannot run a case in /tmp/no such dir/vof"));
}

TEST_CASE("a mesh of more than ten million cells is refused with the cell size it needs", "[reference][mesh]") {
  const cases::Study study = parse(basin_spec("", 0.02, 0.01, "sinusoidal", 1e-5, 1e-5));
  CHECK_THROWS_WITH(reference::build_vof_case(study, study.cases.front(), "quick"),
                    Catch::Contains("vof_cell_size_bed_m = 1e-05 m gives up to") &&
                        Catch::Contains("cells: must be at most 10000000, i.e. vof_cell_size_bed_m >= "));
}

TEST_CASE("write_vof_case writes a complete case directory with its resolved spec", "[reference][case]") {
  const cases::Study study = parse(basin_spec());
  const hydrojump::testing::TempDir tmp("reference-write");
  const fs::path dir = tmp.path() / "case";  // not there yet: write_vof_case creates it
  reference::write_vof_case(study, study.cases.front(), "quick", dir);
  const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
  for (const auto& [path, dict] : vof.files) {
    INFO(path);
    REQUIRE(fs::exists(dir / path));
  }
  CHECK((fs::status(dir / "Allrun").permissions() & fs::perms::owner_exec) != fs::perms::none);
  const cases::Study again = cases::load_study(dir / "case.toml");
  REQUIRE(again.cases.size() == 1);
  CHECK(again.cases.front().id == "basin");
  // Regenerating from the resolved spec gives the same case.
  const reference::VofCase vof2 = reference::build_vof_case(again, again.cases.front(), "quick");
  CHECK(vof2.mesh.cell_count() == vof.mesh.cell_count());
  CHECK(foam::format_file(vof2.headers.at("system/controlDict"), vof2.files.at("system/controlDict")) ==
        foam::format_file(vof.headers.at("system/controlDict"), vof.files.at("system/controlDict")));
}

TEST_CASE("a case.toml edited after generate is refused before a new run, naming the line", "[reference][case]") {
  const cases::Study study = parse(basin_spec());
  const hydrojump::testing::TempDir tmp("reference-edited");
  const fs::path dir = tmp.path() / "case";
  reference::write_vof_case(study, study.cases.front(), "quick", dir);
  const std::string written = util::read_text_file(dir / "case.toml");
  CHECK(util::read_text_file(dir / reference::generated_case_file_name) == written);
  // The inflow velocity changed by hand: setFieldsDict and the inlet still carry the old one.
  std::string edited = written;
  const std::string key = "velocity_m_s = 2";
  REQUIRE(edited.find(key) != std::string::npos);
  edited.replace(edited.find(key), key.size(), "velocity_m_s = 3");
  std::ofstream(dir / "case.toml") << edited;
  std::ostringstream out;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                    Catch::Contains((dir / "case.toml").string() + " was edited after `hydrojump generate`") &&
                        Catch::Contains("velocity_m_s = 3") && Catch::Contains("Run `hydrojump generate` again"));
  CHECK_FALSE(fs::exists(dir / "results_case.toml"));
  CHECK_FALSE(fs::exists(dir / "log.blockMesh"));
  // Also after a first run that failed before writing a time (its log is there, no time directory).
  std::ofstream(dir / "log.interFoam") << "Time = 0.001\n";
  CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                    Catch::Contains("was edited after `hydrojump generate`"));
}

TEST_CASE("SPH-only cases get a note instead of an OpenFOAM case and the runner refuses them",
          "[reference][case]") {
  const cases::Study study = parse(
      "[study]\nname = \"p\"\ndescription = \"p\"\n"
      "[fluid]\ndensity_kg_m3 = 1000.0\nkinematic_viscosity_m2_s = 1.0e-6\ngravity_m_s2 = 9.81\n"
      "[resolution.quick]\nparticle_spacing_m = 0.001\nvof_cell_size_bed_m = 0.001\nvof_cell_size_bulk_m = 0.001\n"
      "[[case]]\nid = \"channel\"\nkind = \"poiseuille\"\ndescription = \"p\"\n"
      "[case.run]\nend_time_s = 1.0\noutput_interval_s = 0.1\naverage_start_s = 0.0\naverage_end_s = 1.0\n"
      "[case.channel]\nwidth_m = 0.02\nlength_m = 0.01\nbody_force_m_s2 = 0.0001\n");
  const cases::Case& c = study.cases.front();
  CHECK_FALSE(reference::has_vof_reference(c));
  CHECK_THROWS_WITH(reference::build_vof_case(study, c, "quick"), Catch::Contains("poiseuille"));
  const hydrojump::testing::TempDir tmp("reference-poiseuille");
  const fs::path dir = tmp.path() / "case";  // not there yet: write_vof_case creates it
  reference::write_vof_case(study, c, "quick", dir);
  CHECK(fs::exists(dir / "README.txt"));
  CHECK(fs::exists(dir / "case.toml"));
  CHECK_FALSE(fs::exists(dir / "system"));
  std::ostringstream out;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                    Catch::Contains("no OpenFOAM reference") && Catch::Contains("poiseuille"));
}

// The generated Allrun stops with a message before any OpenFOAM program runs (so these run without
// OpenFOAM): on a bad -np, on the results of an earlier run (controlDict starts from the latest time,
// which a fresh mesh would not fit), and for a case under the tailgate control, which only
// `hydrojump vof` can drive (interFoam alone would hold the outlet at a fixed velocity).
TEST_CASE("the generated Allrun refuses a bad -np, earlier results and a tailgate case, naming the way out", "[reference][case]") {
  const hydrojump::testing::TempDir tmp("reference-allrun-refusals");
  const auto allrun = [&](const fs::path& dir, const std::vector<std::string>& args, const std::string& name) {
    std::vector<std::string> argv = {"sh", (dir / "Allrun").string()};
    argv.insert(argv.end(), args.begin(), args.end());
    util::ChildCommand command(argv, tmp.path() / (name + ".out"));
    // No program at all may be reached (OpenFOAM's are in /usr/bin): every refusal is the shell's own.
    command.environment = {"PATH=/nonexistent"};
    const util::ChildExit e = util::run_child(command);
    return std::make_pair(e.status(), util::read_text_file(tmp.path() / (name + ".out")));
  };
  const cases::Study study = parse(basin_spec());
  const fs::path dir = tmp.path() / "plain";
  reference::write_vof_case(study, study.cases.front(), "quick", dir);
  for (const std::string& bad : std::vector<std::string>{"x", "0", "-2", "1.5", ""}) {
    INFO("-np '" << bad << "'");
    const auto [status, out] = allrun(dir, {"-np", bad}, "np");
    CHECK(status == 1);
    CHECK_THAT(out, Catch::Contains("-np needs a whole number of MPI ranks, 1 or more (got '" + bad + "')"));
  }
  for (const auto& args : std::vector<std::vector<std::string>>{{"--parallel"}, {"-np"}, {"-np", "1", "extra"}}) {
    INFO(args.size() << " arguments");
    const auto [usage_status, usage] = allrun(dir, args, "usage");
    CHECK(usage_status == 1);
    CHECK_THAT(usage, Catch::Contains("usage: ./Allrun [-np N]"));
  }

  for (const std::string& earlier : std::vector<std::string>{"0.01", "processor0", "postProcessing"}) {
    INFO(earlier);
    fs::create_directory(dir / earlier);
    const auto [status, out] = allrun(dir, {}, "earlier");
    CHECK(status == 1);
    CHECK_THAT(out, Catch::Contains("holds the results of an earlier run (" + earlier + ")") &&
                        Catch::Contains("hydrojump vof <this directory> --resume"));
    fs::remove(dir / earlier);
  }

  const cases::Study held = parse(tiny_hold_toe_spec());
  const fs::path held_dir = tmp.path() / "held";
  reference::write_vof_case(held, held.cases.front(), "quick", held_dir);
  const auto [held_status, held_out] = allrun(held_dir, {}, "held");
  CHECK(held_status == 1);
  CHECK_THAT(held_out, Catch::Contains("[case.tailwater] control = \"hold_toe\"") &&
                           Catch::Contains("hydrojump vof <this directory>") && Catch::Contains("control = \"fixed_depth\""));
}
