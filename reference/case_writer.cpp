#include "reference/case_writer.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.hpp"
#include "cases/hydraulics.hpp"
#include "cases/jump_toe.hpp"
#include "reference/tailwater_control.hpp"

namespace hydrojump::reference {

namespace {

using foam::Dictionary;
using foam::Value;

constexpr double turbulence_intensity = 0.05;      // inlet k = 3/2 (I U)^2
constexpr double mixing_length_factor = 0.07;      // l = 0.07 D_h
constexpr double c_mu = 0.09;
const std::string fluid_set_name = "fluidCells";  // the cells kept by the cartesian cut

std::string n(double x) { return foam::format_number(x); }

// A heuristic value (not from the spec) rounded to 3 significant digits for readability.
// Through its decimal text, so that the double is the one nearest to the 3-digit decimal (255 * 1e-6
// is 0.00025499999999999996, which the dictionary then printed).
double round_significant(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  std::ostringstream text;
  text << std::setprecision(3) << x;
  return std::stod(text.str());
}

// ------------------------------------------------------------------------------ mesh geometry

struct BlockGrid {
  std::vector<double> x;                 // block boundaries along x
  std::vector<double> z;                 // block boundaries along z (bottom row may follow the bed)
  std::vector<double> z_bottom;          // per x node: the z of the lowest row
  double half_thickness = 0.0;

  std::size_t nx() const { return x.size() - 1; }
  std::size_t nz() const { return z.size() - 1; }
  int vertex(std::size_t i, std::size_t j, std::size_t k) const {
    return static_cast<int>(i + x.size() * (j + z.size() * k));
  }
  Value vertex_position(std::size_t i, std::size_t j, std::size_t k) const {
    const double zz = j == 0 ? z_bottom[i] : z[j];
    return foam::vector(x[i], zz, k == 0 ? -half_thickness : half_thickness);
  }
};

BlockGrid block_grid(const MeshPlan& plan) {
  BlockGrid grid;
  for (const GridBand& b : plan.x_bands) {
    if (grid.x.empty()) grid.x.push_back(b.begin_m);
    grid.x.push_back(b.end_m);
  }
  for (const GridBand& b : plan.z_bands) {
    if (grid.z.empty()) grid.z.push_back(b.begin_m);
    grid.z.push_back(b.end_m);
  }
  grid.z_bottom.assign(grid.x.size(), grid.z.front());
  if (plan.strategy == "body_fitted" && plan.bed_vertices.size() == grid.x.size()) {
    for (std::size_t i = 0; i < grid.x.size(); ++i) grid.z_bottom[i] = plan.bed_vertices[i].y();
  }
  grid.half_thickness = 0.5 * plan.thickness_m;
  return grid;
}

// One vertex of the block grid: index along x, along z (vertical) and spanwise (0 front, 1 back).
struct Corner {
  std::size_t i, j, k;
};

// A side of a block: left/right (x), bottom/top (z), front/back (spanwise).
enum class Side { left, right, bottom, top, front, back };

// The face of block (i, j) on one side, as the list of its four vertices in the order blockMesh
// expects for a boundary face (right-hand normal pointing out of the block).
Value block_face(const BlockGrid& g, std::size_t i, std::size_t j, Side side) {
  const std::size_t x0 = i, x1 = i + 1, z0 = j, z1 = j + 1, front = 0, back = 1;
  auto face = [&g](Corner a, Corner b, Corner c, Corner d) {
    return foam::list({g.vertex(a.i, a.j, a.k), g.vertex(b.i, b.j, b.k), g.vertex(c.i, c.j, c.k),
                       g.vertex(d.i, d.j, d.k)});
  };
  switch (side) {
    case Side::left:   return face({x0, z0, front}, {x0, z0, back}, {x0, z1, back}, {x0, z1, front});
    case Side::right:  return face({x1, z1, front}, {x1, z1, back}, {x1, z0, back}, {x1, z0, front});
    case Side::bottom: return face({x0, z0, front}, {x1, z0, front}, {x1, z0, back}, {x0, z0, back});
    case Side::top:    return face({x0, z1, front}, {x0, z1, back}, {x1, z1, back}, {x1, z1, front});
    case Side::front:  return face({x0, z0, front}, {x0, z1, front}, {x1, z1, front}, {x1, z0, front});
    case Side::back:   return face({x0, z0, back}, {x1, z0, back}, {x1, z1, back}, {x0, z1, back});
  }
  throw std::logic_error("block_face: unknown side");
}

// Which patch a block-boundary face belongs to.
struct PatchFaces {
  std::string name;
  std::string type;
  std::vector<Value> faces;
};

Dictionary block_mesh_dict(const MeshPlan& plan, bool stilling_basin, std::vector<std::string>& patch_names) {
  const BlockGrid g = block_grid(plan);
  std::vector<Value> vertices;
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t j = 0; j < g.z.size(); ++j)
      for (std::size_t i = 0; i < g.x.size(); ++i) vertices.push_back(g.vertex_position(i, j, k));

  std::vector<Value> blocks;
  for (std::size_t j = 0; j < g.nz(); ++j) {
    for (std::size_t i = 0; i < g.nx(); ++i) {
      const GridBand& bx = plan.x_bands[i];
      const GridBand& bz = plan.z_bands[j];
      blocks.push_back(foam::sequence(
          {foam::word("hex"),
           foam::list({g.vertex(i, j, 0), g.vertex(i + 1, j, 0), g.vertex(i + 1, j + 1, 0),
                       g.vertex(i, j + 1, 0), g.vertex(i, j, 1), g.vertex(i + 1, j, 1),
                       g.vertex(i + 1, j + 1, 1), g.vertex(i, j + 1, 1)}),
           foam::list({bx.cells, bz.cells, 1}), foam::word("simpleGrading"),
           foam::list({Value(bx.expansion), Value(bz.expansion), Value(1)})}));
    }
  }

  PatchFaces inlet{"inlet", "patch", {}}, walls{"walls", "wall", {}}, bed{"bed", "wall", {}},
      outlet{"outlet", "patch", {}}, atmosphere{"atmosphere", "patch", {}},
      front_and_back{"frontAndBack", "empty", {}};
  const std::size_t I = g.nx(), J = g.nz();
  const double eps = 1e-9;
  for (std::size_t j = 0; j < J; ++j) {
    Value left = block_face(g, 0, j, Side::left);
    Value right = block_face(g, I - 1, j, Side::right);
    if (stilling_basin) {
      const double z_lo = j == 0 ? g.z_bottom[0] : g.z[j];
      const double z_hi = g.z[j + 1];
      if (z_lo >= plan.z_floor_m - eps && z_hi <= plan.z_inflow_top_m + eps) {
        inlet.faces.push_back(left);
      } else if (z_hi <= plan.z_floor_m + eps) {
        bed.faces.push_back(left);   // below the upstream floor: cut away with its cells
      } else {
        walls.faces.push_back(left);  // the sluice gate above the inflow
      }
      outlet.faces.push_back(right);
    } else {
      walls.faces.push_back(left);
      walls.faces.push_back(right);
    }
  }
  for (std::size_t i = 0; i < I; ++i) {
    bed.faces.push_back(block_face(g, i, 0, Side::bottom));
    atmosphere.faces.push_back(block_face(g, i, J - 1, Side::top));
    for (std::size_t j = 0; j < J; ++j) {
      front_and_back.faces.push_back(block_face(g, i, j, Side::front));
      front_and_back.faces.push_back(block_face(g, i, j, Side::back));
    }
  }

  std::vector<PatchFaces> patches;
  if (stilling_basin) patches.push_back(inlet);
  patches.push_back(outlet);
  patches.push_back(walls);
  patches.push_back(bed);
  patches.push_back(atmosphere);
  patches.push_back(front_and_back);
  std::vector<Value> boundary;
  patch_names.clear();
  for (const PatchFaces& p : patches) {
    if (p.faces.empty()) continue;
    Dictionary d;
    d.set("type", foam::word(p.type));
    d.set("faces", foam::list(p.faces));
    boundary.push_back(foam::named_dict(p.name, d));
    patch_names.push_back(p.name);
  }

  Dictionary dict;
  dict.directive("// Background mesh planned by hydrojump (reference/mesh_plan.hpp): x along the channel,");
  dict.directive("// y vertical (the spec's z), z spanwise (one cell, empty).");
  dict.set("scale", 1);
  dict.set("vertices", foam::list(vertices));
  dict.set("blocks", foam::list(blocks));
  dict.set("edges", foam::list({}));
  dict.set("boundary", foam::list(boundary));
  dict.set("mergePatchPairs", foam::list({}));
  return dict;
}

Dictionary topo_set_dict(const MeshPlan& plan, double z_low) {
  std::vector<Value> boxes;
  const double t = plan.thickness_m;
  for (const RemovedColumns& r : plan.removed) {
    boxes.push_back(foam::vector(r.x_begin_m, z_low - 1.0, -t));
    boxes.push_back(foam::vector(r.x_end_m, r.z_top_m, t));
  }
  Dictionary select;
  select.set("name", foam::word(fluid_set_name));
  select.set("type", foam::word("cellSet"));
  select.set("action", foam::word("new"));
  select.set("source", foam::word("boxToCell"));
  select.set("boxes", foam::list(boxes));
  Dictionary invert;
  invert.set("name", foam::word(fluid_set_name));
  invert.set("type", foam::word("cellSet"));
  invert.set("action", foam::word("invert"));
  Dictionary dict;
  dict.directive("// Staircase bed: the boxes hold the cells whose centres lie below the bed z_b(x) of");
  dict.directive("// the spec (one box per run of columns); the set is then inverted to the fluid cells");
  dict.directive("// kept by `subsetMesh " + fluid_set_name + " -patch bed -overwrite`.");
  dict.set("actions", foam::list({Value(select), Value(invert)}));
  return dict;
}

// Face zones "section_<name>" at the grid faces nearest to each section, for the discharge.
Dictionary section_zones_dict(const MeshPlan& plan, const cases::CaseGeometry& geo) {
  const std::vector<double> x = band_faces(plan.x_bands);
  std::vector<Value> actions;
  for (const cases::Section& s : geo.sections) {
    auto nearest = std::min_element(x.begin(), x.end(), [&](double a, double b) {
      return std::abs(a - s.x_m) < std::abs(b - s.x_m);
    });
    const double xf = *nearest;
    const double tol = 0.25 * plan.thickness_m;
    Dictionary faces;
    faces.set("name", foam::word("section_" + s.name + "_faces"));
    faces.set("type", foam::word("faceSet"));
    faces.set("action", foam::word("new"));
    faces.set("source", foam::word("boxToFace"));
    faces.set("box", foam::sequence({foam::vector(xf - tol, geo.z_min_m - 1.0, -plan.thickness_m),
                                     foam::vector(xf + tol, geo.z_max_m + 1.0, plan.thickness_m)}));
    Dictionary zone;
    zone.set("name", foam::word("section_" + s.name));
    zone.set("type", foam::word("faceZoneSet"));
    zone.set("action", foam::word("new"));
    zone.set("source", foam::word("setToFaceZone"));
    zone.set("faceSet", foam::word("section_" + s.name + "_faces"));
    actions.push_back(Value(faces));
    actions.push_back(Value(zone));
  }
  Dictionary dict;
  dict.directive("// Face zones for the discharge through each section of the spec: the grid faces");
  dict.directive("// nearest to x_section (within half a cell); run after the mesh is cut.");
  dict.set("actions", foam::list(actions));
  return dict;
}

// ------------------------------------------------------------------------------ fields

struct FieldBoundary {
  std::map<std::string, Dictionary> patches;
};

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
                      const std::vector<std::string>& patch_names,
                      const std::map<std::string, Dictionary>& patch_conditions,
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

// ------------------------------------------------------------------------------ function objects

Dictionary output_control(double interval) {
  Dictionary d;
  d.set("writeControl", foam::word("adjustableRunTime"));
  d.set("writeInterval", interval);
  return d;
}

void merge(Dictionary& into, const Dictionary& from) {
  for (const std::string& k : from.keys()) into.set(k, from.at(k));
}

Value libs(const std::string& lib) { return foam::list({foam::string(lib)}); }

}  // namespace

// Discretisation of every interFoam case written here: Euler in time, linearUpwind momentum,
// vanLeer + interface compression for alpha, upwind for the turbulence fields of `turbulence_model`
// (k and omega for "kOmegaSST", k and epsilon for "kEpsilon" and "RNGkEpsilon", none for "laminar").
foam::Dictionary interfoam_fv_schemes(const std::string& turbulence_model) {
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

std::vector<std::string> turbulence_fields(const std::string& turbulence_model) {
  if (turbulence_model == "laminar") return {};
  if (turbulence_model == "kOmegaSST") return {"k", "omega"};
  if (turbulence_model == "kEpsilon" || turbulence_model == "RNGkEpsilon") return {"k", "epsilon"};
  throw std::invalid_argument("vof.turbulence_model = \"" + turbulence_model +
                              "\" is unknown: allowed \"laminar\", \"kOmegaSST\", \"kEpsilon\", \"RNGkEpsilon\"");
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
  Dictionary d;
  d.directive("// Simple decomposition along the channel (x); `hydrojump vof --np N` rewrites this.");
  d.set("numberOfSubdomains", subdomains);
  d.set("method", foam::word("simple"));
  Dictionary coeffs;
  coeffs.set("n", foam::list({subdomains, 1, 1}));
  d.set("coeffs", coeffs);
  return d;
}

std::optional<std::string> vof_unsupported_reason(const cases::Case& c) {
  if (const auto* dam = c.dam_break(); dam && dam->gate != "instant") {
    return "case \"" + c.id + "\": gate.type = \"" + dam->gate +
           "\" cannot be modelled by the OpenFOAM reference (a moving gate needs a moving mesh, not "
           "available on this build): allowed \"instant\"";
  }
  if (!c.stilling_basin() && !c.dam_break() && !c.still_water()) {
    return "case \"" + c.id + "\": kind \"" + c.kind +
           "\" has no OpenFOAM reference (supported: stilling_basin, dam_break, still_water); the "
           "periodic single-phase Poiseuille channel is an SPH verification case";
  }
  return std::nullopt;
}

VofCase build_vof_case(const cases::Study& study, const cases::Case& c, const std::string& resolution) {
  const cases::Resolution& res = c.resolution(resolution);
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  if (const auto reason = vof_unsupported_reason(c)) throw std::invalid_argument(*reason);
  const auto* basin = c.stilling_basin();
  const auto* dam = c.dam_break();
  // The tailgate: hydrojump vof sets the outlet's Umean between legs of the run (tailwater_control.hpp).
  const bool hold_toe = c.holds_toe();
  std::vector<std::string> transported;
  try {
    transported = turbulence_fields(c.vof.turbulence_model);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("case \"" + c.id + "\": " + e.what());
  }
  const bool turbulent = !transported.empty();
  const bool k_omega = c.vof.turbulence_model == "kOmegaSST";
  const double g = study.fluid.gravity_m_s2;
  const double h = res.vof_cell_size_bed_m;

  VofCase vof;
  vof.case_id = c.id;
  vof.resolution = resolution;
  vof.mesh = plan_mesh(c, geo, res);
  const MeshPlan& plan = vof.mesh;
  const double z_low = plan.z_bands.front().begin_m;
  const std::string provenance =
      "case \"" + c.id + "\" of study \"" + study.name + "\", resolution \"" + resolution + "\"";

  auto add = [&](const std::string& path, const std::string& cls, const Dictionary& d) {
    const auto slash = path.find('/');
    const std::string location = path.substr(0, slash);
    const std::string object = path.substr(slash + 1);
    vof.headers[path] = foam::FileHeader{cls, location, object};
    vof.files[path] = d;
  };

  // ---- mesh
  Dictionary bmd = block_mesh_dict(plan, basin != nullptr, vof.patches);
  bmd.directive("// " + provenance + ": cell size " + n(h) + " m near the bed and the surface (vof_cell_size_bed_m), " +
                n(res.vof_cell_size_bulk_m) + " m in the bulk (vof_cell_size_bulk_m)");
  add("system/blockMeshDict", "dictionary", bmd);
  vof.mesh_steps.push_back({"blockMesh", {}});
  if (!plan.removed.empty()) {
    add("system/topoSetDict", "dictionary", topo_set_dict(plan, z_low));
    vof.mesh_steps.push_back({"topoSet", {}});
    vof.mesh_steps.push_back({"subsetMesh", {fluid_set_name, "-patch", "bed", "-overwrite"}});
  }
  if (basin && !geo.sections.empty()) {
    add("system/topoSetDict.sections", "dictionary", section_zones_dict(plan, geo));
    vof.headers["system/topoSetDict.sections"].object = "topoSetDict";
    vof.mesh_steps.push_back({"topoSet", {"-dict", "system/topoSetDict.sections"}});
  }

  // ---- reference scales for the initial step and turbulence
  double u_ref = geo.max_flow_speed_m_s > 0.0 ? geo.max_flow_speed_m_s : std::sqrt(g * geo.max_water_height_m);
  double length_ref = geo.max_water_height_m;
  double discharge = 0.0, tailwater = 0.0, outlet_mean_velocity = 0.0;
  if (basin) {
    const cases::InflowBoundary& in = geo.inflows.front();
    u_ref = in.velocity_m_s;
    length_ref = 4.0 * in.depth_m;  // hydraulic diameter of a wide open channel
    discharge = cases::unit_discharge(in.depth_m, in.velocity_m_s);
    tailwater = geo.outflows.front().tailwater_depth_m;
    outlet_mean_velocity = discharge / tailwater;
  }
  const double k_in = 1.5 * std::pow(turbulence_intensity * u_ref, 2);
  const double omega_in = std::sqrt(k_in) / (std::pow(c_mu, 0.25) * mixing_length_factor * length_ref);
  // epsilon = Cmu^(3/4) k^(3/2) / l = Cmu k omega (the same length scale l as omega)
  const double epsilon_in = c_mu * k_in * omega_in;

  // ---- constant/
  {
    Dictionary gd;
    gd.set("dimensions", foam::dimensions({0, 1, -2, 0, 0, 0, 0}));
    gd.set("value", foam::vector(geo.body_force_m_s2.x(), geo.body_force_m_s2.y(), 0.0));
    add("constant/g", "uniformDimensionedVectorField", gd);

    const AirProperties air;
    Dictionary tp;
    tp.directive("// water from the spec's [fluid]; air and surface tension fixed by hydrojump");
    tp.set("phases", foam::list({foam::word("water"), foam::word("air")}));
    Dictionary water;
    water.set("transportModel", foam::word("Newtonian"));
    water.set("nu", study.fluid.kinematic_viscosity_m2_s);
    water.set("rho", study.fluid.density_kg_m3);
    tp.set("water", water);
    Dictionary air_d;
    air_d.set("transportModel", foam::word("Newtonian"));
    air_d.set("nu", air.kinematic_viscosity_m2_s);
    air_d.set("rho", air.density_kg_m3);
    tp.set("air", air_d);
    tp.set("sigma", air.surface_tension_n_m);
    add("constant/transportProperties", "dictionary", tp);

    Dictionary tu;
    tu.directive("// vof.turbulence_model = \"" + c.vof.turbulence_model + "\"");
    if (turbulent) {
      tu.set("simulationType", foam::word("RAS"));
      Dictionary ras;
      ras.set("RASModel", foam::word(c.vof.turbulence_model));
      ras.set("turbulence", foam::on_off(true));
      ras.set("printCoeffs", foam::on_off(true));
      tu.set("RAS", ras);
    } else {
      tu.set("simulationType", foam::word("laminar"));
    }
    add("constant/turbulenceProperties", "dictionary", tu);

    if (c.vof.turbulence_stabilization != "none") {
      // OpenFOAM's multiphaseStabilizedTurbulence with its own default coefficients, written out: Cmu of
      // k-epsilon, C = 1.51 (the k-omega value, the more conservative), lambda2 = 0.1 (strength of the
      // nut limiter) and alpha = 1/Prt = 1.36, the buoyancy sink of k where the density falls upwards;
      // "nut_limiter" sets alpha = 0, which removes that term and keeps the limiter alone.
      const bool buoyancy = c.vof.turbulence_stabilization == "nut_limiter_and_buoyancy";
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
      fo.directive("// vof.turbulence_stabilization = \"" + c.vof.turbulence_stabilization +
                   "\": the nut limiter of Larsen & Fuhrman (2018)" +
                   (buoyancy ? std::string(" and the buoyancy term in k of Devolder et al. (2017)")
                             : std::string(" alone (alpha = 0: no buoyancy term)")));
      fo.set("stabilizedTurbulence", option);
      add("constant/fvOptions", "dictionary", fo);
    }
  }

  // ---- 0.orig/
  const std::vector<std::string>& patches = vof.patches;
  {
    // omega (kOmegaSST) or epsilon (kEpsilon, RNGkEpsilon): the second turbulence field
    std::map<std::string, Dictionary> u, alpha, p, k, dissipation, nut;
    const double diss_in = k_omega ? omega_in : epsilon_in;
    const Value zero_vec = foam::uniform(foam::vector(0, 0, 0));
    for (const std::string& wall : {std::string("walls"), std::string("bed")}) {
      u[wall] = type_only("noSlip");
      alpha[wall] = type_only("zeroGradient");
      p[wall] = type_only("fixedFluxPressure");
      k[wall] = with_value("kqRWallFunction", foam::uniform(k_in));
      dissipation[wall] = with_value(k_omega ? "omegaWallFunction" : "epsilonWallFunction", foam::uniform(diss_in));
      nut[wall] = with_value("nutkWallFunction", foam::uniform(0));
    }
    {
      Dictionary pu;
      pu.set("type", foam::word("pressureInletOutletVelocity"));
      pu.set("value", zero_vec);
      u["atmosphere"] = pu;
      alpha["atmosphere"] = inlet_outlet(foam::uniform(0));
      Dictionary tp;
      tp.set("type", foam::word("totalPressure"));
      tp.set("p0", foam::uniform(0));
      p["atmosphere"] = tp;
      k["atmosphere"] = inlet_outlet(foam::uniform(k_in));
      dissipation["atmosphere"] = inlet_outlet(foam::uniform(diss_in));
      nut["atmosphere"] = with_value("calculated", foam::uniform(0));
    }
    if (basin) {
      const cases::InflowBoundary& in = geo.inflows.front();
      u["inlet"] = with_value("fixedValue", foam::uniform(foam::vector(in.velocity_m_s, 0, 0)));
      alpha["inlet"] = with_value("fixedValue", foam::uniform(1));
      p["inlet"] = type_only("fixedFluxPressure");
      k["inlet"] = with_value("fixedValue", foam::uniform(k_in));
      dissipation["inlet"] = with_value("fixedValue", foam::uniform(diss_in));
      nut["inlet"] = with_value("calculated", foam::uniform(0));

      Dictionary uo;
      uo.set("type", foam::word("outletPhaseMeanVelocity"));
      uo.set("alpha", foam::word("alpha.water"));
      uo.set("Umean", outlet_mean_velocity);
      uo.set("value", foam::uniform(foam::vector(outlet_mean_velocity, 0, 0)));
      u["outlet"] = uo;
      Dictionary ao;
      ao.set("type", foam::word("variableHeightFlowRate"));
      ao.set("lowerBound", 0);
      ao.set("upperBound", 1);
      ao.set("value", foam::uniform(0));
      alpha["outlet"] = ao;
      p["outlet"] = type_only("zeroGradient");
      k["outlet"] = inlet_outlet(foam::uniform(k_in));
      dissipation["outlet"] = inlet_outlet(foam::uniform(diss_in));
      nut["outlet"] = with_value("calculated", foam::uniform(0));
    }
    std::vector<std::string> u_trace = {provenance};
    if (basin) {
      u_trace.push_back("inlet: U1 = inflow.velocity_m_s = " + n(geo.inflows.front().velocity_m_s) + " m/s");
      u_trace.push_back("outlet: Umean = q / y2 = " + n(discharge) + " / " + n(tailwater) + " = " +
                        n(outlet_mean_velocity) + " m/s (holds the tailwater depth y2)");
    }
    add("0.orig/U", "volVectorField",
        field_file({0, 1, -1, 0, 0, 0, 0}, zero_vec, patches, u, u_trace));
    add("0.orig/alpha.water", "volScalarField",
        field_file({0, 0, 0, 0, 0, 0, 0}, foam::uniform(0), patches, alpha,
                   {provenance, "initial water set by setFields from the spec's initial water surface"}));
    add("0.orig/p_rgh", "volScalarField",
        field_file({1, -1, -2, 0, 0, 0, 0}, foam::uniform(0), patches, p, {provenance}));
    if (turbulent) {
      const std::string scales = "k = 3/2 (I U)^2 with I = " + n(turbulence_intensity) + ", U = " + n(u_ref) +
                                 " m/s; omega = sqrt(k)/(Cmu^0.25 l), l = 0.07 * " + n(length_ref) + " m" +
                                 (k_omega ? std::string() : "; epsilon = Cmu k omega");
      add("0.orig/k", "volScalarField",
          field_file({0, 2, -2, 0, 0, 0, 0}, foam::uniform(k_in), patches, k, {provenance, scales}));
      if (k_omega) {
        add("0.orig/omega", "volScalarField",
            field_file({0, 0, -1, 0, 0, 0, 0}, foam::uniform(omega_in), patches, dissipation, {provenance, scales}));
      } else {
        add("0.orig/epsilon", "volScalarField",
            field_file({0, 2, -3, 0, 0, 0, 0}, foam::uniform(epsilon_in), patches, dissipation, {provenance, scales}));
      }
      add("0.orig/nut", "volScalarField",
          field_file({0, 2, -1, 0, 0, 0, 0}, foam::uniform(0), patches, nut, {provenance}));
    }
  }

  // ---- system/setFieldsDict: the initial water, column by column, from the spec's surface
  {
    const std::vector<double> x = band_faces(plan.x_bands);
    const std::vector<double> z = band_faces(plan.z_bands);
    const cases::InitialWater& w = geo.initial_water;
    struct Run {
      double x0, x1, z_top, u;
      std::size_t cells;
    };
    std::vector<Run> runs;
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
      const double xc = 0.5 * (x[i] + x[i + 1]);
      if (xc < w.x_begin_m || xc > w.x_end_m) continue;
      const double surface = w.surface_at(xc);
      const double depth = surface - geo.bed.elevation(xc);
      if (depth <= 0.0) continue;
      std::size_t top = 0;
      while (top + 1 < z.size() && 0.5 * (z[top] + z[top + 1]) < surface) ++top;
      if (top == 0) continue;
      const double u = w.discharge_m2_s > 0.0 ? w.discharge_m2_s / depth : 0.0;
      if (!runs.empty() && runs.back().cells == top && std::abs(runs.back().u - u) <= 1e-12 * (1 + u) &&
          std::abs(runs.back().x1 - x[i]) < 1e-12) {
        runs.back().x1 = x[i + 1];
      } else {
        runs.push_back(Run{x[i], x[i + 1], z[top], u, top});
      }
    }
    std::vector<Value> regions;
    for (const Run& r : runs) {
      Dictionary box;
      box.set("box", foam::sequence({foam::vector(r.x0, z_low - 1.0, -plan.thickness_m),
                                     foam::vector(r.x1, r.z_top, plan.thickness_m)}));
      std::vector<Value> values = {foam::word("volScalarFieldValue alpha.water 1")};
      if (r.u != 0.0) {
        values.push_back(foam::sequence({foam::word("volVectorFieldValue U"), foam::vector(r.u, 0, 0)}));
      }
      box.set("fieldValues", foam::list(values));
      regions.push_back(foam::named_dict("boxToCell", box));
    }
    Dictionary sf;
    sf.directive("// Initial water of " + provenance + " (cases::CaseGeometry::initial_water): cells whose");
    sf.directive("// centres lie below the surface; U = q / local depth, q = " + n(w.discharge_m2_s) + " m^2/s.");
    sf.set("defaultFieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 0"),
                                             foam::sequence({foam::word("volVectorFieldValue U"),
                                                             foam::vector(0, 0, 0)})}));
    sf.set("regions", foam::list(regions));
    add("system/setFieldsDict", "dictionary", sf);
  }

  // ---- system/controlDict with the sampling function objects
  {
    const double interval = c.run.output_interval_s;
    Dictionary cd;
    cd.directive("// " + provenance);
    cd.directive("// SIGUSR2 (12) makes interFoam write the current time and stop (used by `hydrojump vof` on Ctrl-C).");
    cd.subdict("OptimisationSwitches").set("stopAtWriteNowSignal", 12);
    cd.set("application", foam::word("interFoam"));
    cd.set("startFrom", foam::word("latestTime"));
    cd.set("startTime", 0);
    cd.set("stopAt", foam::word("endTime"));
    cd.directive("// endTime = run.end_time_s; writeInterval = run.output_interval_s");
    cd.set("endTime", c.run.end_time_s);
    cd.directive("// first time step: 0.1 maxCo h / U (then adjusted by interFoam)");
    cd.set("deltaT", std::min(c.vof.max_time_step_s, round_significant(0.1 * c.vof.max_courant * h / u_ref)));
    cd.set("writeControl", foam::word("adjustable"));
    cd.set("writeInterval", interval);
    cd.set("purgeWrite", 0);
    cd.set("writeFormat", foam::word("ascii"));
    cd.set("writePrecision", 8);
    if (hold_toe) {
      cd.directive("// uncompressed: tailwater.control = \"hold_toe\" rewrites the outlet's Umean in the latest U "
                   "between legs (reference/tailwater_control.hpp)");
    }
    cd.set("writeCompression", foam::on_off(!hold_toe));
    cd.set("timeFormat", foam::word("general"));
    cd.set("timePrecision", 8);
    cd.set("runTimeModifiable", foam::yes_no(true));
    cd.directive("// maxCo = vof.max_courant; maxAlphaCo = vof.max_alpha_courant; maxDeltaT = vof.max_time_step_s");
    cd.set("adjustTimeStep", foam::yes_no(true));
    cd.set("maxCo", c.vof.max_courant);
    cd.set("maxAlphaCo", c.vof.max_alpha_courant);
    cd.set("maxDeltaT", c.vof.max_time_step_s);

    Dictionary functions;
    // A straight sampling line from (x0, z0) to (x1, z1) along `axis`, two points per cell of size h
    // over its length (at least 10).
    const auto uniform_line = [&](const std::string& name, const char* axis, double x0, double z0, double x1,
                                  double z1, double length_m) {
      Dictionary line;
      line.set("type", foam::word("uniform"));
      line.set("axis", foam::word(axis));
      line.set("start", foam::vector(x0, z0, 0));
      line.set("end", foam::vector(x1, z1, 0));
      line.set("nPoints", std::max(10, static_cast<int>(std::ceil(2.0 * length_m / h)) + 1));
      return foam::named_dict(name, line);
    };
    // Vertical lines at the sections, from the bed to the top of the domain.
    std::vector<Value> sets;
    for (const cases::Section& s : geo.sections) {
      double zb = geo.bed.elevation(s.x_m);
      for (const RemovedColumns& r : plan.removed) {
        if (s.x_m >= r.x_begin_m && s.x_m <= r.x_end_m) zb = std::max(zb, r.z_top_m);
      }
      zb += 0.01 * h;  // inside the lowest fluid cell of the staircase
      const double top = geo.z_max_m - 0.01 * h;
      sets.push_back(uniform_line(s.name, "y", s.x_m, zb, s.x_m, top, top - zb));
    }
    // Lines along x through the whole domain at height z: two samples per cell of size h.
    const auto horizontal_line = [&](const std::string& name, double z) {
      return uniform_line(name, "x", geo.x_min_m + 1e-6, z, geo.x_max_m - 1e-6, z, geo.x_max_m - geo.x_min_m);
    };
    if (dam) sets.push_back(horizontal_line("floor", 0.5 * plan.z_bands.front().end_m / plan.z_bands.front().cells));
    if (!sets.empty()) {
      Dictionary fo;
      fo.directive(std::string("// vertical lines at the spec's sections (x_m), bed to top: alpha.water and U") +
                   (dam ? "; the floor line of a dam break" : ""));
      fo.set("type", foam::word("sets"));
      fo.set("libs", libs("libsampling.so"));
      merge(fo, output_control(interval));
      fo.set("interpolationScheme", foam::word("cellPoint"));
      fo.set("setFormat", foam::word("raw"));
      fo.set("fields", foam::list({foam::word("alpha.water"), foam::word("U")}));
      fo.set("sets", foam::list(sets));
      functions.set("sections", fo);
    }
    // Water discharge through each section: the sum of the face fluxes alphaPhi0.water over the
    // grid faces nearest to x_section (a faceZone made by topoSetDict.sections), and over the inlet
    // and outlet patches; divided by the spanwise thickness it is q in m^2/s.
    auto discharge_fo = [&](const std::string& region_type, const std::string& name) {
      Dictionary fo;
      fo.directive("// sum of alphaPhi0.water (m^3/s) / thickness " + n(plan.thickness_m) +
                   " m = water discharge q (m^2/s)");
      fo.set("type", foam::word("surfaceFieldValue"));
      fo.set("libs", libs("libfieldFunctionObjects.so"));
      merge(fo, output_control(interval));
      fo.set("log", foam::word("false"));
      fo.set("writeFields", foam::word("false"));
      fo.set("regionType", foam::word(region_type));
      fo.set("name", foam::word(name));
      fo.set("operation", foam::word("sum"));
      fo.set("fields", foam::list({foam::word("alphaPhi0.water"), foam::word("phi")}));
      return fo;
    };
    if (basin) {
      for (const cases::Section& s : geo.sections) {
        functions.set("discharge_" + s.name, discharge_fo("faceZone", "section_" + s.name));
      }
      functions.set("discharge_inlet", discharge_fo("patch", "inlet"));
      functions.set("discharge_outlet", discharge_fo("patch", "outlet"));
      // Water thrown out through the top is lost to the basin: `hydrojump compare` reports it.
      functions.set("discharge_atmosphere", discharge_fo("patch", "atmosphere"));
    }
    if (hold_toe) {
      Dictionary fo;
      fo.directive("// the water volume (m^3) every time step, / thickness " + n(plan.thickness_m) +
                   " m = V (m^2) of the tailwater control");
      fo.set("type", foam::word("volFieldValue"));
      fo.set("libs", libs("libfieldFunctionObjects.so"));
      // every time step (writeInterval's default, 1: an entry here would be rewritten by a leg's controlDict
      // when the output interval is 1 s)
      fo.set("writeControl", foam::word("timeStep"));
      fo.set("log", foam::word("false"));
      fo.set("writeFields", foam::word("false"));
      fo.set("regionType", foam::word("all"));
      fo.set("operation", foam::word("volIntegrate"));
      fo.set("fields", foam::list({foam::word("alpha.water")}));
      functions.set(water_volume_function, fo);
    }
    {
      Dictionary iso;
      iso.set("type", foam::word("isoSurface"));
      iso.set("isoField", foam::word("alpha.water"));
      iso.set("isoValue", 0.5);
      iso.set("interpolate", foam::word("true"));
      Dictionary fo;
      fo.set("type", foam::word("surfaces"));
      fo.set("libs", libs("libsampling.so"));
      merge(fo, output_control(interval));
      fo.set("surfaceFormat", foam::word("vtk"));
      fo.set("interpolationScheme", foam::word("cellPoint"));
      fo.set("fields", foam::list({foam::word("U")}));
      fo.set("surfaces", foam::list({foam::named_dict("alpha_0.5", iso)}));
      functions.set(free_surface_function, fo);  // also the tailwater control's toe
    }
    if (basin) {
      Dictionary fo;
      fo.directive("// averaging window = [run.average_start_s, run.average_end_s]");
      fo.set("type", foam::word("fieldAverage"));
      fo.set("libs", libs("libfieldFunctionObjects.so"));
      fo.set("timeStart", c.run.average_start_s);
      fo.set("timeEnd", c.run.average_end_s > 0.0 ? c.run.average_end_s : c.run.end_time_s);
      fo.set("writeControl", foam::word("writeTime"));
      Dictionary mean;
      mean.set("mean", foam::on_off(true));
      mean.set("prime2Mean", foam::on_off(false));
      mean.set("base", foam::word("time"));
      fo.set("fields", foam::list({foam::named_dict("U", mean), foam::named_dict("alpha.water", mean)}));
      functions.set("average", fo);
    }
    cd.set("functions", functions);
    add("system/controlDict", "dictionary", cd);
  }

  // ---- system/fvSchemes, fvSolution, decomposeParDict
  {
    const Dictionary fs = interfoam_fv_schemes(c.vof.turbulence_model);
    add("system/fvSchemes", "dictionary", fs);

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
    pimple.set("nNonOrthogonalCorrectors", plan.strategy == "body_fitted" ? 1 : 0);
    sol.subdict("relaxationFactors").subdict("equations").set("\".*\"", 1);
    add("system/fvSolution", "dictionary", sol);

    add("system/decomposeParDict", "dictionary", decompose_par_dict(2));
  }

  // ---- Allrun
  {
    std::ostringstream s;
    s << "#!/bin/sh\n"
      << "# OpenFOAM interFoam case written by hydrojump from " << provenance << ".\n";
    if (hold_toe) {
      // interFoam alone would run the outlet at the fixed Umean = q/y2, the set-up the control exists
      // to replace (the jump drifts or swings, reference/README.md): refused, with the way to run it.
      s << "# [case.tailwater] control = \"hold_toe\": the outlet's Umean is set between legs of the run by\n"
        << "# `hydrojump vof DIR [--np N]` (reference/tailwater_control.hpp); interFoam alone cannot do that,\n"
        << "# so this case is not run by hand. Mesh: " << plan.strategy << ", " << plan.cell_count() << " cells.\n"
        << "echo \"Allrun: this case holds its jump's toe with the tailgate ([case.tailwater] control = \\\"hold_toe\\\"),\"\n"
        << "echo \"which only \\`hydrojump vof <this directory>\\` drives: run it that way, or regenerate it with\"\n"
        << "echo \"control = \\\"fixed_depth\\\" to run it by hand at the fixed outlet velocity\"\n"
        << "exit 1\n";
      vof.allrun = s.str();
      return vof;
    }
    s << "# Run by hand:   ./Allrun            (serial)\n"
      << "#                ./Allrun -np 4      (MPI: decomposePar, mpirun, reconstructPar)\n"
      << "# or with `hydrojump vof DIR [--np N]`, which adds checks, progress, divergence detection and\n"
      << "# resuming. Mesh: " << plan.strategy << ", " << plan.cell_count() << " cells.\n"
      << "case \"$0\" in */*) cd \"${0%/*}\" || exit 1 ;; esac\n"
      << "export WM_PROJECT_DIR=\"${WM_PROJECT_DIR:-/usr/share/openfoam}\"\n"
      << "np=1\n"
      << "case \"$#:$1\" in\n"
      << "    0:) ;;\n"
      << "    2:-np) np=\"$2\"\n"
      << "         case \"$np\" in\n"
      << "             \"\"|*[!0-9]*) echo \"Allrun: -np needs a whole number of MPI ranks, 1 or more (got '$np')\"; exit 1 ;;\n"
      << "         esac\n"
      << "         [ \"$np\" -ge 1 ] || { echo \"Allrun: -np needs a whole number of MPI ranks, 1 or more (got '$np')\"; exit 1; } ;;\n"
      << "    *) echo \"usage: ./Allrun [-np N]\"; exit 1 ;;\n"
      << "esac\n";
    s << "# A fresh start only: controlDict starts from the latest time, so the results of an earlier run\n"
      << "# would be continued (or met by a new mesh they do not fit).\n"
      << "for d in *; do\n"
      << "    case \"$d\" in\n"
      << "        0|0.orig) ;;\n"
      << "        [0-9]*|processor*|postProcessing)\n"
      << "            echo \"Allrun: this directory holds the results of an earlier run ($d); remove them first\"\n"
      << "            echo \"(foamListTimes -rm; rm -rf processor* postProcessing) or continue that run with\"\n"
      << "            echo \"\\`hydrojump vof <this directory> --resume\\`\"\n"
      << "            exit 1 ;;\n"
      << "    esac\n"
      << "done\n"
      << "# run LOG APPLICATION [ARGUMENTS]: stops at the first failure with the end of its log\n"
      << "run() {\n"
      << "    log=\"$1\"; app=\"$2\"; shift 2\n"
      << "    echo \"Running $app $*\"\n"
      << "    \"$app\" \"$@\" > \"$log\" 2>&1 || { echo \"$app failed: see $log\"; tail -n 20 \"$log\"; exit 1; }\n"
      << "}\n";
    std::map<std::string, int> used;
    for (const FoamStep& step : vof.mesh_steps) {
      const int k = used[step.application]++;
      s << "run log." << step.application << (k > 0 ? "." + std::to_string(k + 1) : std::string()) << ' '
        << step.application;
      for (const std::string& a : step.arguments) s << ' ' << a;
      s << '\n';
    }
    s << "run log.checkMesh checkMesh\n"
      << "grep -q \"Mesh OK.\" log.checkMesh || { echo \"checkMesh found a bad mesh: see log.checkMesh\"; exit 1; }\n"
      << "{ rm -rf 0 && cp -r 0.orig 0; } || { echo \"Allrun: cannot copy 0.orig to 0\"; exit 1; }\n"
      << "run log.setFields setFields\n"
      << "if [ \"$np\" -gt 1 ]; then\n"
      << "    run log.foamDictionary.ranks foamDictionary -entry numberOfSubdomains -set \"$np\" system/decomposeParDict\n"
      << "    run log.foamDictionary.split foamDictionary -entry coeffs/n -set \"($np 1 1)\" system/decomposeParDict\n"
      << "    run log.decomposePar decomposePar -force\n"
      << "    root=\"\"; [ \"$(id -u)\" = 0 ] && root=\"--allow-run-as-root\"\n"
      << "    echo \"Running mpirun -np $np interFoam -parallel\"\n"
      << "    # --oversubscribe: Open MPI refuses more ranks than cores without it, and it is harmless otherwise\n"
      << "    mpirun $root --oversubscribe -np \"$np\" -x WM_PROJECT_DIR interFoam -parallel > log.interFoam 2>&1 || "
         "{ echo \"interFoam failed: see log.interFoam\"; tail -n 20 log.interFoam; exit 1; }\n"
      << "    run log.reconstructPar reconstructPar\n"
      << "else\n"
      << "    run log.interFoam interFoam\n"
      << "fi\n";
    vof.allrun = s.str();
  }
  return vof;
}

void write_vof_files(const VofCase& vof, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (const auto& [path, dict] : vof.files) {
    util::write_file_atomically(dir / path, foam::format_file(vof.headers.at(path), dict));
  }
  util::write_file_atomically(dir / "Allrun", vof.allrun);
  std::filesystem::permissions(dir / "Allrun",
                               std::filesystem::perms::owner_exec | std::filesystem::perms::group_exec |
                                   std::filesystem::perms::others_exec,
                               std::filesystem::perm_options::add);
}

}  // namespace hydrojump::reference
