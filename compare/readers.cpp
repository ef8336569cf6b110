#include "compare/readers.hpp"

#include "util/number_text.hpp"
#include "cases/output_times.hpp"
#include "util/time_directories.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCompositeDataIterator.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkLogger.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOpenFOAMReader.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringOutputWindow.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>

namespace fs = std::filesystem;

namespace hydrojump::compare {

namespace {

std::string attribute(const std::string& tag, const std::string& name) {
  const std::regex re("\\b" + name + "\\s*=\\s*(\"([^\"]*)\"|'([^']*)')");
  std::smatch m;
  if (!std::regex_search(tag, m, re)) return {};
  return m[2].matched ? m[2].str() : m[3].str();
}

}  // namespace

std::vector<PvdEntry> read_pvd(const fs::path& pvd_file) {
  std::ifstream in(pvd_file);
  if (!in) throw std::runtime_error(pvd_file.string() + ": cannot open the .pvd file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  if (text.find("Collection") == std::string::npos)
    throw std::runtime_error(pvd_file.string() + ": not a ParaView collection (no <Collection>)");
  // A file cut short would list only its first frames (hydrojump sph replaces it whole at every output).
  if (text.find("</Collection>") == std::string::npos)
    throw std::runtime_error(pvd_file.string() + ": ends before </Collection>: the file is damaged (cut short)");
  std::vector<PvdEntry> out;
  std::vector<std::string> parts;  // each data set's part attribute ("" when it has none)
  const std::regex tag_re("<DataSet\\b[^>]*>");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tag_re); it != std::sregex_iterator(); ++it) {
    const std::string tag = it->str();
    const std::string t = attribute(tag, "timestep");
    const std::string f = attribute(tag, "file");
    if (f.empty())
      throw std::runtime_error(pvd_file.string() + ": a <DataSet> has no file attribute: " + tag);
    if (t.empty())
      throw std::runtime_error(pvd_file.string() + ": a <DataSet> has no timestep attribute: " + tag);
    PvdEntry e;
    try {
      std::size_t used = 0;
      e.time_s = std::stod(t, &used);
      if (used != t.size() || !std::isfinite(e.time_s)) throw std::invalid_argument(t);
    } catch (const std::exception&) {
      throw std::runtime_error(pvd_file.string() + ": timestep=\"" + t + "\" is not a finite number in " + tag);
    }
    e.file = fs::path(f).is_absolute() ? fs::path(f) : pvd_file.parent_path() / f;
    out.push_back(e);
    parts.push_back(attribute(tag, "part"));
  }
  if (out.empty()) throw std::runtime_error(pvd_file.string() + ": the collection lists no <DataSet>");
  // One data set per time (and part): a time listed twice would count its frame twice in every mean,
  // or mix two runs' frames (an edited or merged file).
  std::vector<std::size_t> order(out.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return out[a].time_s != out[b].time_s ? out[a].time_s < out[b].time_s : parts[a] < parts[b];
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::size_t i = order[k - 1], j = order[k];
    if (out[i].time_s == out[j].time_s && parts[i] == parts[j])
      throw std::runtime_error(pvd_file.string() + ": the time " + util::number_text(out[i].time_s) +
                               " s is listed twice (" + out[i].file.filename().string() + " and " +
                               out[j].file.filename().string() + "): the collection is damaged or merged");
  }
  std::stable_sort(out.begin(), out.end(), [](const PvdEntry& a, const PvdEntry& b) { return a.time_s < b.time_s; });
  return out;
}

std::vector<PvdEntry> entries_in_window(const std::vector<PvdEntry>& entries, double t0, double t1, double tolerance_s) {
  std::vector<PvdEntry> out;
  for (const auto& e : entries)
    if (cases::in_output_window(e.time_s, t0, t1, tolerance_s)) out.push_back(e);
  return out;
}

static std::string array_names(vtkFieldData* fd) {
  std::string s;
  for (int i = 0; i < fd->GetNumberOfArrays(); ++i) {
    if (!s.empty()) s += ", ";
    s += fd->GetArrayName(i) ? fd->GetArrayName(i) : "(unnamed)";
  }
  return s.empty() ? "none" : s;
}

namespace {

// Collects VTK's own messages while a file is read, instead of letting VTK print them (in colour,
// with object dumps) on the terminal: a damaged file then gives one line naming it, with VTK's first
// message. Not for concurrent use (VTK's output window is one per process); frames are read one by one.
class VtkMessagesCollected {
 public:
  // VTK 9 also logs errors to stderr through vtkLogger: that is off meanwhile (the verbosity cutoff
  // in force, that of stderr when nothing else logs, comes back after).
  VtkMessagesCollected()
      : previous_(vtkOutputWindow::GetInstance()), previous_stderr_(vtkLogger::GetCurrentVerbosityCutoff()) {
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~VtkMessagesCollected() {
    vtkLogger::SetStderrVerbosity(previous_stderr_);
    vtkOutputWindow::SetInstance(previous_);
  }
  VtkMessagesCollected(const VtkMessagesCollected&) = delete;
  VtkMessagesCollected& operator=(const VtkMessagesCollected&) = delete;

  // VTK's first message, shortened to its text (without the source location VTK puts first).
  std::string first_message() const {
    std::string text = window_->GetOutput();
    std::istringstream lines(text);
    // VTK writes "ERROR: In <file>, line <n>" and then "<class> (<address>): <message>".
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("ERROR:", 0) == 0 || line.rfind("Warning:", 0) == 0 || line.rfind("Generic Warning:", 0) == 0)
        continue;
      const auto object = line.find("): ");
      std::string message = object == std::string::npos ? line : line.substr(object + 3);
      while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
      if (!message.empty()) return message.substr(0, 200);
    }
    return {};
  }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity previous_stderr_;
  vtkNew<vtkStringOutputWindow> window_;
};

// The largest speed a particle of a readable frame may have (m/s): a hydraulic flow in a flume moves
// at a few m/s, and the SPH solver stops a run as unstable long before 1 km/s; beyond it the frame is
// damaged (or its run diverged), not data.
constexpr double max_particle_speed_m_s = 1e3;
// The largest coordinate (m) of a particle of a readable frame, for the same reason.
constexpr double max_particle_coordinate_m = 1e6;

// Refuses a frame whose values cannot be a particle state: a non-finite or absurd position or velocity,
// a non-positive density, an unknown particle type, or no fluid particle at all. Such a frame (a
// damaged file) would otherwise enter the averages as if it were data.
void check_particle_values(const ParticleFrame& f, const fs::path& vtp_file) {
  const auto bad = [&](std::size_t k, const std::string& what, double value) {
    std::ostringstream o;
    o << vtp_file.string() << ": particle " << k << " has " << what << " " << value
      << ", which no particle state has (a damaged file, or a diverged run): frame refused";
    throw std::runtime_error(o.str());
  };
  std::size_t fluid = 0;
  for (std::size_t k = 0; k < f.x.size(); ++k) {
    if (!std::isfinite(f.x[k]) || std::abs(f.x[k]) > max_particle_coordinate_m) bad(k, "the x coordinate", f.x[k]);
    if (!std::isfinite(f.z[k]) || std::abs(f.z[k]) > max_particle_coordinate_m) bad(k, "the vertical coordinate", f.z[k]);
    if (!(std::abs(f.u[k]) <= max_particle_speed_m_s)) bad(k, "the horizontal velocity (m/s)", f.u[k]);
    if (!(std::abs(f.w[k]) <= max_particle_speed_m_s)) bad(k, "the vertical velocity (m/s)", f.w[k]);
    if (!(f.density[k] > 0.0) || !std::isfinite(f.density[k])) bad(k, "the density (kg/m^3)", f.density[k]);
    if (f.type[k] < 0 || f.type[k] > static_cast<int>(sph::ParticleType::moving_wall)) bad(k, "the type", f.type[k]);
    if (!f.mass.empty() && !(f.mass[k] > 0.0 && std::isfinite(f.mass[k]))) bad(k, "the mass (kg/m)", f.mass[k]);
    if (f.type[k] == static_cast<int>(sph::ParticleType::fluid)) ++fluid;
  }
  if (fluid == 0 && !f.x.empty())
    throw std::runtime_error(vtp_file.string() + ": no fluid particle (type 0) among its " + std::to_string(f.x.size()) +
                             " particles: frame refused");
}

}  // namespace

ParticleFrame read_vtp_particles(const fs::path& vtp_file, double time_s) {
  if (!fs::exists(vtp_file)) throw std::runtime_error(vtp_file.string() + ": particle file does not exist");
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  if (!reader->CanReadFile(vtp_file.string().c_str()))  // checked quietly, before VTK logs parse errors
    throw std::runtime_error(vtp_file.string() + ": not a VTK XML PolyData (.vtp) file");
  reader->SetFileName(vtp_file.string().c_str());
  vtkPolyData* pd = nullptr;
  {
    const VtkMessagesCollected messages;
    reader->Update();
    pd = reader->GetOutput();
    // (A read that succeeds with warnings goes on: the values are checked below.)
    if (reader->GetErrorCode() != 0 || pd == nullptr || pd->GetPoints() == nullptr) {
      const std::string vtk = messages.first_message();
      throw std::runtime_error(vtp_file.string() + ": not a readable VTK XML PolyData (.vtp) file" +
                               (vtk.empty() ? std::string() : " (VTK: " + vtk + ")"));
    }
  }
  vtkPointData* pt = pd->GetPointData();
  auto require = [&](const char* name, int comps) -> vtkDataArray* {
    vtkDataArray* a = pt->GetArray(name);
    if (a == nullptr)
      throw std::runtime_error(vtp_file.string() + ": point array \"" + name + "\" is missing (present: " +
                               array_names(pt) + ")");
    if (a->GetNumberOfComponents() < comps)
      throw std::runtime_error(vtp_file.string() + ": point array \"" + name + "\" has " +
                               std::to_string(a->GetNumberOfComponents()) + " components, expected " +
                               std::to_string(comps));
    return a;
  };
  vtkDataArray* vel = require("velocity", 2);
  vtkDataArray* rho = require("density", 1);
  vtkDataArray* type = require("type", 1);
  vtkDataArray* p = pt->GetArray("pressure");
  vtkDataArray* mass = pt->GetArray("mass");
  const vtkIdType n = pd->GetNumberOfPoints();
  // The vertical axis: the SPH solver writes points (x, 0, z) as DualSPHysics does; data in the x-y
  // plane, (x, z, 0), are accepted too. The axis that is constant is the spanwise one.
  double bounds[6];
  pd->GetBounds(bounds);
  const double span_y = n > 0 ? bounds[3] - bounds[2] : 0.0;
  const double span_z = n > 0 ? bounds[5] - bounds[4] : 0.0;
  if (span_y > 0.0 && span_z > 0.0)
    throw std::runtime_error(vtp_file.string() + ": particles are not 2D (they spread in both y and z); expected "
                             "points (x, 0, z) or (x, z, 0)");
  const int vertical = span_z > 0.0 ? 2 : 1;
  ParticleFrame f;
  f.time_s = time_s;
  f.x.resize(static_cast<std::size_t>(n)); f.z.resize(f.x.size()); f.u.resize(f.x.size());
  f.w.resize(f.x.size()); f.density.resize(f.x.size()); f.type.resize(f.x.size());
  if (p) f.pressure.resize(f.x.size());
  if (mass) f.mass.resize(f.x.size());
  if (vel->GetNumberOfComponents() <= vertical)
    throw std::runtime_error(vtp_file.string() + ": point array \"velocity\" has no component along the vertical axis");
  for (vtkIdType i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    double xyz[3];
    pd->GetPoint(i, xyz);
    f.x[k] = xyz[0];
    f.z[k] = xyz[vertical];
    f.u[k] = vel->GetComponent(i, 0);
    f.w[k] = vel->GetComponent(i, vertical);
    f.density[k] = rho->GetComponent(i, 0);
    f.type[k] = static_cast<int>(std::lround(type->GetComponent(i, 0)));
    if (p) f.pressure[k] = p->GetComponent(i, 0);
    if (mass) f.mass[k] = mass->GetComponent(i, 0);
  }
  check_particle_values(f, vtp_file);
  return f;
}

// ---------------------------------------------------------------------------------------- OpenFOAM --
struct OpenFoamResults::Impl {
  vtkSmartPointer<vtkOpenFOAMReader> reader = vtkSmartPointer<vtkOpenFOAMReader>::New();
};

OpenFoamResults::OpenFoamResults(const fs::path& case_dir) : impl_(std::make_unique<Impl>()), case_dir_(case_dir) {
  const fs::path control = case_dir / "system" / "controlDict";
  if (!fs::exists(control))
    throw std::runtime_error(case_dir.string() + ": not an OpenFOAM case (no system/controlDict)");
  if (!fs::exists(case_dir / "constant" / "polyMesh" / "owner") &&
      !fs::exists(case_dir / "constant" / "polyMesh" / "owner.gz"))
    throw std::runtime_error(case_dir.string() + ": the OpenFOAM case has no mesh (constant/polyMesh/owner)");
  auto& r = *impl_->reader;
  r.SetFileName(control.string().c_str());
  r.SkipZeroTimeOff();
  r.CreateCellToPointOff();
  r.DecomposePolyhedraOff();
  r.ReadZonesOff();
  r.CacheMeshOn();
  r.UpdateInformation();
  vtkDoubleArray* tv = r.GetTimeValues();
  if (tv)
    for (vtkIdType i = 0; i < tv->GetNumberOfTuples(); ++i) times_.push_back(tv->GetValue(i));
  std::sort(times_.begin(), times_.end());
  r.SetPatchArrayStatus("internalMesh", 1);
  for (int i = 0; i < r.GetNumberOfPatchArrays(); ++i) {
    const std::string name = r.GetPatchArrayName(i);
    if (name != "internalMesh") r.SetPatchArrayStatus(name.c_str(), 0);
  }
}

OpenFoamResults::~OpenFoamResults() = default;

std::vector<double> OpenFoamResults::times_in_window(double t0, double t1, double tolerance_s) const {
  std::vector<double> out;
  for (double t : times_)
    if (cases::in_output_window(t, t0, t1, tolerance_s)) out.push_back(t);
  return out;
}

CellFrame OpenFoamResults::read(double time_s) {
  auto& r = *impl_->reader;
  const std::string where = case_dir_.string() + " at t = " + std::to_string(time_s) + " s";
  r.UpdateTimeStep(time_s);
  vtkMultiBlockDataSet* mb = r.GetOutput();
  vtkUnstructuredGrid* grid = nullptr;
  if (mb) {
    auto it = vtkSmartPointer<vtkCompositeDataIterator>::Take(mb->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
      grid = vtkUnstructuredGrid::SafeDownCast(it->GetCurrentDataObject());
      if (grid) break;
    }
  }
  if (grid == nullptr || grid->GetNumberOfCells() == 0)
    throw std::runtime_error(where + ": vtkOpenFOAMReader returned no internal mesh");
  vtkCellData* cd = grid->GetCellData();
  vtkDataArray* alpha = cd->GetArray("alpha.water");
  vtkDataArray* u = cd->GetArray("U");
  vtkDataArray* p = cd->GetArray("p_rgh");
  if (!p) p = cd->GetArray("p");
  if (!alpha || !u)
    throw std::runtime_error(where + ": cell fields \"alpha.water\" and \"U\" are required (present: " +
                             array_names(cd) + ")");
  const vtkIdType n = grid->GetNumberOfCells();
  CellFrame f;
  f.time_s = time_s;
  const std::size_t nn = static_cast<std::size_t>(n);
  for (auto* v : {&f.xc, &f.zc, &f.x_lo, &f.x_hi, &f.z_lo, &f.z_hi, &f.alpha, &f.u, &f.w, &f.pressure})
    v->resize(nn);
  for (vtkIdType i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    double b[6];
    grid->GetCellBounds(i, b);
    f.x_lo[k] = b[0]; f.x_hi[k] = b[1];
    f.z_lo[k] = b[2]; f.z_hi[k] = b[3];   // OpenFOAM y is vertical
    f.xc[k] = 0.5 * (b[0] + b[1]);
    f.zc[k] = 0.5 * (b[2] + b[3]);
    f.alpha[k] = alpha->GetComponent(i, 0);
    f.u[k] = u->GetComponent(i, 0);
    f.w[k] = u->GetComponent(i, 1);
    f.pressure[k] = p ? p->GetComponent(i, 0) : not_a_number;
  }
  return f;
}

fs::path find_pvd(const fs::path& sph_dir) {
  std::vector<fs::path> found;
  if (fs::is_directory(sph_dir))
    for (const auto& e : fs::recursive_directory_iterator(sph_dir))
      if (e.is_regular_file() && e.path().extension() == ".pvd") found.push_back(e.path());
  if (found.empty()) throw std::runtime_error(sph_dir.string() + ": no .pvd particle series found");
  if (found.size() == 1) return found.front();
  std::sort(found.begin(), found.end());
  for (const char* key : {"particles", "fluid"})
    for (const auto& f : found)
      if (f.filename().string().find(key) != std::string::npos) return f;
  std::string list;
  for (const auto& f : found) list += "\n  " + f.string();
  throw std::runtime_error(sph_dir.string() + ": several .pvd files, none named *particles* or *fluid*:" + list);
}

std::string missing_openfoam_results(const fs::path& vof_dir) {
  if (!fs::exists(vof_dir / "system" / "controlDict")) return "no system/controlDict (not an OpenFOAM case)";
  if (!fs::exists(vof_dir / "constant" / "polyMesh" / "owner") &&
      !fs::exists(vof_dir / "constant" / "polyMesh" / "owner.gz"))
    return "no mesh (constant/polyMesh/owner): it was not meshed, or its mesh was removed";
  for (const auto& [t, time_dir] : util::time_directories(vof_dir, 0.0))
    if (fs::exists(time_dir / "alpha.water") || fs::exists(time_dir / "alpha.water.gz")) return {};
  return "no time directory after 0 with alpha.water (not run yet)";
}

bool has_openfoam_results(const fs::path& vof_dir) { return missing_openfoam_results(vof_dir).empty(); }

}  // namespace hydrojump::compare
