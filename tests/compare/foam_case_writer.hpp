// Writes a tiny 2D OpenFOAM case by hand (ASCII polyMesh and fields), so the OpenFOAM reader can be
// tested without running OpenFOAM. Cartesian nx x nz cells, one cell thick; OpenFOAM y is vertical.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace hydrojump::compare::testing {

struct FoamBox {
  double length = 0.6, height = 0.3, thickness = 0.01;
  int nx = 30, nz = 20;
  double x0 = 0.0, z0 = 0.0;   // lower-left corner
};

inline void foam_header(std::ostream& o, const std::string& cls, const std::string& location,
                        const std::string& object) {
  o << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " << cls
    << ";\n    location    \"" << location << "\";\n    object      " << object << ";\n}\n\n";
}

// Mesh and system files. Faces: internal faces in upper-triangular order, then the "walls" patch
// (left, right, bottom, top) and the "frontAndBack" empty patch.
inline void write_foam_mesh(const std::filesystem::path& dir, const FoamBox& b) {
  namespace fs = std::filesystem;
  fs::create_directories(dir / "system");
  fs::create_directories(dir / "constant" / "polyMesh");
  {
    std::ofstream o(dir / "system" / "controlDict");
    foam_header(o, "dictionary", "system", "controlDict");
    o << "application interFoam;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\nendTime 2;\n"
         "deltaT 0.001;\nwriteControl adjustableRunTime;\nwriteInterval 0.5;\nwriteFormat ascii;\n"
         "writePrecision 12;\ntimeFormat general;\ntimePrecision 6;\n";
  }
  const int nx = b.nx, nz = b.nz;
  auto pid = [&](int i, int k, int l) { return (l * (nz + 1) + k) * (nx + 1) + i; };
  auto cid = [&](int i, int k) { return k * nx + i; };
  {
    std::ofstream o(dir / "constant" / "polyMesh" / "points");
    o.precision(17);
    foam_header(o, "vectorField", "constant/polyMesh", "points");
    o << 2 * (nx + 1) * (nz + 1) << "\n(\n";
    for (int l = 0; l < 2; ++l)
      for (int k = 0; k <= nz; ++k)
        for (int i = 0; i <= nx; ++i)
          o << "(" << b.x0 + b.length * i / nx << " " << b.z0 + b.height * k / nz << " " << b.thickness * l << ")\n";
    o << ")\n";
  }
  std::vector<std::vector<int>> faces;
  std::vector<int> owner, neighbour;
  auto xface = [&](int i, int k) { return std::vector<int>{pid(i, k, 0), pid(i, k + 1, 0), pid(i, k + 1, 1), pid(i, k, 1)}; };
  auto yface = [&](int i, int k) { return std::vector<int>{pid(i, k, 0), pid(i, k, 1), pid(i + 1, k, 1), pid(i + 1, k, 0)}; };
  auto rev = [](std::vector<int> f) { std::reverse(f.begin(), f.end()); return f; };
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) { faces.push_back(xface(i + 1, k)); owner.push_back(cid(i, k)); neighbour.push_back(cid(i + 1, k)); }
      if (k + 1 < nz) { faces.push_back(yface(i, k + 1)); owner.push_back(cid(i, k)); neighbour.push_back(cid(i, k + 1)); }
    }
  const int n_internal = static_cast<int>(faces.size());
  for (int k = 0; k < nz; ++k) { faces.push_back(rev(xface(0, k))); owner.push_back(cid(0, k)); }
  for (int k = 0; k < nz; ++k) { faces.push_back(xface(nx, k)); owner.push_back(cid(nx - 1, k)); }
  for (int i = 0; i < nx; ++i) { faces.push_back(rev(yface(i, 0))); owner.push_back(cid(i, 0)); }
  for (int i = 0; i < nx; ++i) { faces.push_back(yface(i, nz)); owner.push_back(cid(i, nz - 1)); }
  const int n_walls = static_cast<int>(faces.size()) - n_internal;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      faces.push_back({pid(i, k, 0), pid(i, k + 1, 0), pid(i + 1, k + 1, 0), pid(i + 1, k, 0)});
      owner.push_back(cid(i, k));
      faces.push_back({pid(i, k, 1), pid(i + 1, k, 1), pid(i + 1, k + 1, 1), pid(i, k + 1, 1)});
      owner.push_back(cid(i, k));
    }
  auto write_labels = [&](const char* name, const std::vector<int>& v) {
    std::ofstream o(dir / "constant" / "polyMesh" / name);
    foam_header(o, "labelList", "constant/polyMesh", name);
    o << v.size() << "\n(\n";
    for (int x : v) o << x << "\n";
    o << ")\n";
  };
  {
    std::ofstream o(dir / "constant" / "polyMesh" / "faces");
    foam_header(o, "faceList", "constant/polyMesh", "faces");
    o << faces.size() << "\n(\n";
    for (const auto& f : faces) o << "4(" << f[0] << " " << f[1] << " " << f[2] << " " << f[3] << ")\n";
    o << ")\n";
  }
  write_labels("owner", owner);
  write_labels("neighbour", neighbour);
  {
    std::ofstream o(dir / "constant" / "polyMesh" / "boundary");
    foam_header(o, "polyBoundaryMesh", "constant/polyMesh", "boundary");
    o << "2\n(\n    walls\n    {\n        type wall;\n        nFaces " << n_walls << ";\n        startFace "
      << n_internal << ";\n    }\n    frontAndBack\n    {\n        type empty;\n        nFaces "
      << 2 * nx * nz << ";\n        startFace " << n_internal + n_walls << ";\n    }\n)\n";
  }
}

// Cell fields of one time directory from functions of the cell centre (x, y) (y vertical).
inline void write_foam_fields(const std::filesystem::path& dir, const std::string& time, const FoamBox& b,
                              const std::function<double(double, double)>& alpha,
                              const std::function<double(double, double)>& u,
                              const std::function<double(double, double)>& v) {
  namespace fs = std::filesystem;
  fs::create_directories(dir / time);
  const int n = b.nx * b.nz;
  auto centre = [&](int c, double& x, double& y) {
    x = b.x0 + (c % b.nx + 0.5) * b.length / b.nx;
    y = b.z0 + (c / b.nx + 0.5) * b.height / b.nz;
  };
  auto scalar = [&](const char* name, const std::function<double(double, double)>& f) {
    std::ofstream o(dir / time / name);
    o.precision(17);
    foam_header(o, "volScalarField", time, name);
    o << "dimensions [0 0 0 0 0 0 0];\n\ninternalField nonuniform List<scalar>\n" << n << "\n(\n";
    for (int c = 0; c < n; ++c) { double x, y; centre(c, x, y); o << f(x, y) << "\n"; }
    o << ")\n;\n\nboundaryField\n{\n    walls\n    {\n        type zeroGradient;\n    }\n"
         "    frontAndBack\n    {\n        type empty;\n    }\n}\n";
  };
  scalar("alpha.water", alpha);
  scalar("p_rgh", [](double, double y) { return -1000.0 * 9.81 * y; });
  std::ofstream o(dir / time / "U");
  o.precision(17);
  foam_header(o, "volVectorField", time, "U");
  o << "dimensions [0 1 -1 0 0 0 0];\n\ninternalField nonuniform List<vector>\n" << n << "\n(\n";
  for (int c = 0; c < n; ++c) { double x, y; centre(c, x, y); o << "(" << u(x, y) << " " << v(x, y) << " 0)\n"; }
  o << ")\n;\n\nboundaryField\n{\n    walls\n    {\n        type fixedValue;\n        value uniform (0 0 0);\n    }\n"
       "    frontAndBack\n    {\n        type empty;\n    }\n}\n";
}

}  // namespace hydrojump::compare::testing
