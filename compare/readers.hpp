// Readers of both methods' results, frame by frame:
//   SPH  a ParaView .pvd collection (parsed here: plain VTK has no PVD reader) of .vtp particle files
//        read with vtkXMLPolyDataReader. Points (x, 0, z) as the SPH solver writes them (sph/vtk_output,
//        DualSPHysics style) or (x, z, 0): the constant coordinate is taken as spanwise. Point arrays
//        "velocity" (3 components), "density", "pressure", "type" (sph/particles.hpp: 0 fluid,
//        1 boundary, 2 inflow buffer, 3 outflow buffer, 4 moving wall); optional "mass".
//   VOF  an OpenFOAM case directory read directly with vtkOpenFOAMReader (no foamToVTK): the internal
//        mesh's cell data "alpha.water", "U" and "p_rgh" (or "p"). 2D, one cell thick: OpenFOAM y is
//        vertical, z spanwise.
// Every error names the file (and array or time) concerned.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "compare/sampling.hpp"

namespace hydrojump::compare {

struct PvdEntry {
  double time_s = 0.0;
  std::filesystem::path file;   // absolute or relative to the current directory
};

// The data sets of a .pvd collection, sorted by time (relative file names are resolved against the
// .pvd's directory). Throws std::runtime_error naming the file when it is unreadable or malformed.
std::vector<PvdEntry> read_pvd(const std::filesystem::path& pvd_file);

// The entries in the window [t0, t1] within `tolerance_s` (cases/output_times.hpp: outputs come late).
std::vector<PvdEntry> entries_in_window(const std::vector<PvdEntry>& entries, double t0, double t1, double tolerance_s);

// One particle file. Throws std::runtime_error naming the file and the missing array, or the particle
// and the value when a value cannot be a particle state (non-finite, |x| or |z| > 1e6 m, a speed
// component > 1e3 m/s, density <= 0, an unknown type) or the frame has no fluid particle. VTK's own
// messages about a damaged file are collected into that error, not printed.
ParticleFrame read_vtp_particles(const std::filesystem::path& vtp_file, double time_s);

// An OpenFOAM case read through vtkOpenFOAMReader. Keeps the reader (and its mesh cache) alive.
class OpenFoamResults {
 public:
  // `case_dir` must contain system/controlDict. Throws std::runtime_error naming what is missing.
  explicit OpenFoamResults(const std::filesystem::path& case_dir);
  ~OpenFoamResults();
  OpenFoamResults(const OpenFoamResults&) = delete;
  OpenFoamResults& operator=(const OpenFoamResults&) = delete;

  // Times of the written time directories (the 0 directory included).
  const std::vector<double>& times() const { return times_; }
  // The times in the window [t0, t1] within `tolerance_s` (cases/output_times.hpp).
  std::vector<double> times_in_window(double t0, double t1, double tolerance_s) const;
  // The internal mesh's cells at `time_s` (one of times()).
  CellFrame read(double time_s);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::filesystem::path case_dir_;
  std::vector<double> times_;
};

// The .pvd file of an SPH run directory: the only one, or the one named after "particles"/"fluid"
// when there are several. Throws naming the directory when there is none.
std::filesystem::path find_pvd(const std::filesystem::path& sph_dir);

// True when `vof_dir` holds an OpenFOAM case with at least one written time after 0.
bool has_openfoam_results(const std::filesystem::path& vof_dir);
// What `vof_dir` lacks to hold such results (no controlDict, no mesh, no written time), or "".
std::string missing_openfoam_results(const std::filesystem::path& vof_dir);

}  // namespace hydrojump::compare
