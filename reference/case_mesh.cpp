// The mesh dictionaries of a generated case: system/blockMeshDict (the block grid of the mesh plan,
// with its patches), system/topoSetDict (the cartesian cut: the cells below the bed) and
// system/topoSetDict.sections (face zones at the spec's sections, for the discharge), and the mesh
// steps that run them (blockMesh, [topoSet, subsetMesh], [topoSet -dict system/topoSetDict.sections]).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "reference/case_parts.hpp"

namespace hydrojump::reference::detail {

namespace {

using foam::Dictionary;
using foam::Value;

// The blocks of blockMeshDict: the mesh plan's band boundaries, the lowest row on the bed when body-fitted.
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
  if (plan.strategy == cases::MeshStrategy::body_fitted && plan.bed_vertices.size() == grid.x.size()) {
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
  dict.directive(std::string("// kept by `subsetMesh ") + fluid_set_name + " -patch bed -overwrite`.");
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

}  // namespace

void add_mesh_dictionaries(VofCase& vof, const CaseInputs& in) {
  const MeshPlan& plan = in.plan;
  const auto* basin = in.c.stilling_basin();
  Dictionary bmd = block_mesh_dict(plan, basin != nullptr, vof.patches);
  bmd.directive("// " + in.provenance + ": cell size " + n(in.cell_size_bed_m) +
                " m near the bed and the surface (vof_cell_size_bed_m), " + n(in.cell_size_bulk_m) +
                " m in the bulk (vof_cell_size_bulk_m)");
  add_file(vof, "system/blockMeshDict", "dictionary", bmd);
  vof.mesh_steps.push_back({"blockMesh", {}});
  if (!plan.removed.empty()) {
    add_file(vof, "system/topoSetDict", "dictionary", topo_set_dict(plan, plan.z_bands.front().begin_m));
    vof.mesh_steps.push_back({"topoSet", {}});
    vof.mesh_steps.push_back({"subsetMesh", {fluid_set_name, "-patch", "bed", "-overwrite"}});
  }
  if (basin && !in.geo.sections.empty()) {
    add_file(vof, "system/topoSetDict.sections", "dictionary", section_zones_dict(plan, in.geo));
    vof.headers["system/topoSetDict.sections"].object = "topoSetDict";
    vof.mesh_steps.push_back({"topoSet", {"-dict", "system/topoSetDict.sections"}});
  }
}

}  // namespace hydrojump::reference::detail
