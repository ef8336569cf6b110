// Writes a ParticleFrame as the SPH solver's .vtp (point arrays velocity, density, pressure, type, id)
// and a .pvd collection, for the reader tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>

#include "compare/sampling.hpp"

namespace hydrojump::compare::testing {

// `vertical_axis` 2 writes points (x, 0, z) as the SPH solver does; 1 writes (x, z, 0).
inline void write_vtp(const std::filesystem::path& file, const ParticleFrame& f, bool with_density = true,
                      int vertical_axis = 2) {
  auto pts = vtkSmartPointer<vtkPoints>::New();
  auto vel = vtkSmartPointer<vtkDoubleArray>::New();
  vel->SetName("velocity");
  vel->SetNumberOfComponents(3);
  auto rho = vtkSmartPointer<vtkDoubleArray>::New();
  rho->SetName("density");
  auto p = vtkSmartPointer<vtkDoubleArray>::New();
  p->SetName("pressure");
  auto type = vtkSmartPointer<vtkIntArray>::New();
  type->SetName("type");
  auto id = vtkSmartPointer<vtkIntArray>::New();
  id->SetName("id");
  for (std::size_t j = 0; j < f.x.size(); ++j) {
    if (vertical_axis == 2) {
      pts->InsertNextPoint(f.x[j], 0.0, f.z[j]);
      vel->InsertNextTuple3(f.u[j], 0.0, f.w[j]);
    } else {
      pts->InsertNextPoint(f.x[j], f.z[j], 0.0);
      vel->InsertNextTuple3(f.u[j], f.w[j], 0.0);
    }
    rho->InsertNextValue(f.density[j]);
    p->InsertNextValue(f.pressure.empty() ? 0.0 : f.pressure[j]);
    type->InsertNextValue(f.type[j]);
    id->InsertNextValue(static_cast<int>(j));
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->GetPointData()->AddArray(vel);
  if (with_density) pd->GetPointData()->AddArray(rho);
  pd->GetPointData()->AddArray(p);
  pd->GetPointData()->AddArray(type);
  pd->GetPointData()->AddArray(id);
  auto w = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  w->SetFileName(file.string().c_str());
  w->SetInputData(pd);
  w->SetDataModeToBinary();
  w->Write();
}

// entries: (time, file name relative to the .pvd)
inline void write_pvd(const std::filesystem::path& file, const std::vector<std::pair<double, std::string>>& entries) {
  std::ofstream o(file);
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  bool flip = false;
  for (const auto& [t, name] : entries) {
    // alternate the attribute order: the parser must not depend on it
    if (flip) o << "    <DataSet file='" << name << "' part=\"0\" timestep=\"" << t << "\"/>\n";
    else o << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << name << "\"/>\n";
    flip = !flip;
  }
  o << "  </Collection>\n</VTKFile>\n";
}

}  // namespace hydrojump::compare::testing
