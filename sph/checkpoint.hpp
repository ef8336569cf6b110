// Binary checkpoints of a run: the solver clock, every particle array, and the state of the run's
// outputs (output series, log, gauge and basin rows), so `hydrojump sph DIR --resume` continues exactly
// where the run stopped: a resumed run reproduces the uninterrupted one bit for bit on the same
// number of threads. Written atomically (temporary file, then rename), so a run killed while writing
// keeps the previous checkpoint.
//
// Format (little endian, host doubles): "HJSPHCK9", the case fingerprint, the clock (time, last dt, steps,
// inflow and outflow mass totals, the outflow target depth, the toe-holding control's volume target, the density outliers
// removed: count and mass),
// the particle count and arrays, the run state and "HJSPHCK9" again, then the FNV-1a checksum of all that as 16 hex digits. Readers reject
// other magic strings (naming another version's), truncated files, a checksum that does not match
// (a byte changed after the write), and values no run writes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sph/particles.hpp"
#include "sph/solver.hpp"

namespace hydrojump::sph {

struct Checkpoint {
  std::string fingerprint;                               // identifies the resolved case
  SolverClock clock;
  ParticleSet particles;
  double next_output_time = 0.0;
  // The last output is the end state of a run that ended between two output times (not on the
  // output grid): a run extended from here drops it, as an uninterrupted run never wrote it.
  bool last_output_is_end_state = false;
  std::vector<std::pair<double, std::string>> series;    // .pvd entries
  std::vector<std::string> log_rows;                     // run_log.csv rows (without header)
  std::vector<std::string> gauge_rows;                   // gauges.csv rows (without header)
  std::vector<std::string> basin_rows;                   // basin.csv rows (stilling basins)
};

void write_checkpoint(const Checkpoint& c, const std::filesystem::path& file);
// Throws std::runtime_error naming the file if it is missing, truncated or not a checkpoint.
Checkpoint read_checkpoint(const std::filesystem::path& file);

}  // namespace hydrojump::sph
