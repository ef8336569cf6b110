#include "sph/vtk_output.hpp"

#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "util/atomic_file.hpp"

namespace hydrojump::sph {

void write_particles_vtp(const ParticleSet& ps, const std::filesystem::path& file) {
  const vtkIdType n = ps.size();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkDoubleArray> velocity, density, pressure;
  velocity->SetName("velocity");
  velocity->SetNumberOfComponents(3);
  velocity->SetNumberOfTuples(n);
  density->SetName("density");
  density->SetNumberOfTuples(n);
  pressure->SetName("pressure");
  pressure->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> type;
  type->SetName("type");
  type->SetNumberOfTuples(n);
  vtkNew<vtkTypeInt64Array> id;
  id->SetName("id");
  id->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    points->SetPoint(i, ps.x[i], 0.0, ps.z[i]);
    vertices->InsertNextCell(1, &i);
    velocity->SetTuple3(i, ps.u[i], 0.0, ps.w[i]);
    density->SetValue(i, ps.rho[i]);
    pressure->SetValue(i, ps.p[i]);
    type->SetValue(i, ps.type[i]);
    id->SetValue(i, ps.id[i]);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetVerts(vertices);
  poly->GetPointData()->AddArray(velocity);
  poly->GetPointData()->AddArray(density);
  poly->GetPointData()->AddArray(pressure);
  poly->GetPointData()->AddArray(type);
  poly->GetPointData()->AddArray(id);
  util::write_via_temporary(file, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(tmp.string().c_str());
    writer->SetInputData(poly);
    writer->SetDataModeToBinary();
    if (writer->Write() != 1) throw std::runtime_error("VTK could not write '" + file.string() + "'");
  });
}

ParticleSet read_particles_vtp(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw std::runtime_error("no such file: '" + file.string() + "'");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  if (poly == nullptr || poly->GetPoints() == nullptr) throw std::runtime_error("'" + file.string() + "' holds no particles");
  const vtkIdType n = poly->GetNumberOfPoints();
  auto* pd = poly->GetPointData();
  auto* velocity = pd->GetArray("velocity");
  auto* density = pd->GetArray("density");
  auto* pressure = pd->GetArray("pressure");
  auto* type = pd->GetArray("type");
  auto* id = pd->GetArray("id");
  if (!velocity || !density || !pressure || !type || !id)
    throw std::runtime_error("'" + file.string() + "' lacks one of the arrays velocity, density, pressure, type, id");
  ParticleSet ps;
  ps.resize(n);
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    poly->GetPoint(i, p);
    ps.x[i] = p[0];
    ps.z[i] = p[2];
    ps.u[i] = velocity->GetComponent(i, 0);
    ps.w[i] = velocity->GetComponent(i, 2);
    ps.rho[i] = density->GetComponent(i, 0);
    ps.p[i] = pressure->GetComponent(i, 0);
    ps.type[i] = static_cast<std::uint8_t>(type->GetComponent(i, 0));
    ps.id[i] = static_cast<std::int64_t>(id->GetComponent(i, 0));
  }
  return ps;
}

ParticleSeries::ParticleSeries(std::filesystem::path dir, std::string stem) : dir_(std::move(dir)), stem_(std::move(stem)) {}

std::filesystem::path ParticleSeries::write(const ParticleSet& ps, double time) {
  char name[64];
  std::snprintf(name, sizeof name, "_%04zu.vtp", entries_.size());
  const std::string file = stem_ + name;
  write_particles_vtp(ps, dir_ / file);
  entries_.emplace_back(time, file);
  write_pvd();
  return dir_ / file;
}

void ParticleSeries::write_pvd() const {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n";
  s << std::setprecision(10);
  for (const auto& [t, file] : entries_)
    s << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  util::write_file_atomically(pvd_path(), s.str());
}

}  // namespace hydrojump::sph
