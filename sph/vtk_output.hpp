// ParaView-ready output of the particles: one VTK XML PolyData file (.vtp) per output time and a
// .pvd collection listing them with their times. Points are (x, 0, z) (the x-z plane, as in
// DualSPHysics 2D output). Point data: "velocity" (3 components, y = 0), "density", "pressure",
// "type" (sph::ParticleType: 0 fluid, 1 boundary, 2 inflow buffer, 3 outflow buffer, 4 moving wall) and "id". Every file is written atomically (temporary file, rename).
//
// Usage:
//   ParticleSeries series(dir, "particles");
//   series.write(particles, time);   // writes dir/particles_0000.vtp and rewrites dir/particles.pvd
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sph/particles.hpp"

namespace hydrojump::sph {

// Writes one .vtp file (atomically).
void write_particles_vtp(const ParticleSet& ps, const std::filesystem::path& file);

// Reads a .vtp written by write_particles_vtp (positions, velocity, density, pressure, type, id);
// the other arrays are left zero. Throws std::runtime_error if the file cannot be read.
ParticleSet read_particles_vtp(const std::filesystem::path& file);

// A time series of .vtp files and its .pvd index.
class ParticleSeries {
 public:
  ParticleSeries(std::filesystem::path dir, std::string stem);
  // Writes the next file and the updated .pvd; returns the .vtp path.
  std::filesystem::path write(const ParticleSet& ps, double time);
  // The entries written so far (time, file name relative to the directory); restored on resume.
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  void restore(std::vector<std::pair<double, std::string>> entries) { entries_ = std::move(entries); }
  // Writes the .pvd of the entries as they are (after a restore that left one out).
  void rewrite_pvd() const { write_pvd(); }
  std::filesystem::path pvd_path() const { return dir_ / (stem_ + ".pvd"); }

 private:
  void write_pvd() const;
  std::filesystem::path dir_;
  std::string stem_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace hydrojump::sph
