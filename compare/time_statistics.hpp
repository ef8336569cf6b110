// Time statistics of column samples over the averaging window: means and standard deviations of the
// section quantities, time-mean velocity profiles, the longitudinal (along-the-basin) mean surface and
// velocities, and one velocity-field snapshot per method.
#pragma once

#include <string>
#include <vector>

#include "compare/sampling.hpp"

namespace hydrojump::compare {

// A vertical line to sample: a named section of the case, or an unnamed station along the basin.
struct ColumnSpec {
  std::string name;            // section name ("" for a station)
  std::string role;            // section role ("station" for a station)
  double x_m = 0.0;
  double z_bed_m = 0.0;
  int n_points = 41;           // odd
};

// Mean and sample standard deviation (n - 1) of the finite values; std = NaN for a single value.
struct ScalarStats {
  double mean = not_a_number;
  double std = not_a_number;
  int count = 0;
};
ScalarStats stats_of(const std::vector<double>& values);

struct ColumnStatistics {
  ColumnSpec spec;
  int n_times = 0;             // frames in the window
  int n_wet = 0;               // frames in which the column had water
  ScalarStats surface, surface_from_fraction, depth, discharge, mean_velocity, max_velocity,
      near_surface_velocity, energy_coefficient, specific_energy, momentum_coefficient, specific_force,
      void_fraction;
  // Time-mean profile on a fixed grid z_bed .. highest surface over the window; at each height only
  // the frames in which that height was under water, and not in a void below the surface (sampling.hpp),
  // count (wet_fraction = their share).
  std::vector<double> z, u_mean, u_std, w_mean, wet_fraction;
};

// Regular-grid velocity snapshot of one frame (NaN outside the water or below the bed).
struct FieldSnapshot {
  double time_s = not_a_number;
  int nx = 0, nz = 0;
  double x0 = 0.0, dx = 0.0, z0 = 0.0, dz = 0.0;
  std::vector<double> u, w, fraction;   // index iz * nx + ix
  bool empty() const { return nx == 0; }
};

struct SnapshotGrid {
  double x_min = 0.0, x_max = 0.0, z_min = 0.0, z_max = 0.0;
  int nx = 0, nz = 0;          // 0: no snapshot
};

// One section at one output time (the scalars of a ColumnSample), for time-series output.
struct SectionTimeSample {
  double time_s = 0.0;
  double surface_m = not_a_number, depth_m = not_a_number, discharge_m2_s = not_a_number,
         mean_velocity_m_s = not_a_number, max_velocity_m_s = not_a_number, specific_energy_m = not_a_number;
};

// Everything one method gives over the window.
struct MethodStatistics {
  std::string method;          // "sph" | "vof"
  std::vector<double> times;   // frames used
  std::vector<ColumnStatistics> sections;
  std::vector<std::vector<SectionTimeSample>> section_series;  // [section][frame]
  std::vector<ColumnStatistics> stations;   // longitudinal, profiles not kept
  std::vector<std::vector<double>> station_surface_series;  // [frame][station] instantaneous surface
  FieldSnapshot snapshot;      // the frame added with take_snapshot (the last one in the window)
};

// Feeds frames one by one (so a long series never has to be in memory at once) and turns them into
// MethodStatistics. `bed` gives z_b(x) for the snapshot mask.
class MethodAccumulator {
 public:
  MethodAccumulator(std::string method, std::vector<ColumnSpec> sections, std::vector<ColumnSpec> stations,
                    SnapshotGrid snapshot_grid, double gravity);
  // Samples every column of `frame` (OpenMP over columns); with `take_snapshot` (pass it for the last
  // frame) also the velocity-field snapshot on the grid. `snapshot_bed_elevation` is z_b at each
  // snapshot grid column (size snapshot_grid.nx) or empty.
  void add_frame(const FrameSampler& frame, bool take_snapshot = false,
                 const std::vector<double>& snapshot_bed_elevation = {});
  std::size_t frame_count() const { return times_.size(); }
  MethodStatistics finish(int n_profile_points = 41) const;

  // Raw samples, [column][frame]; for tests and time-series output.
  const std::vector<std::vector<ColumnSample>>& section_samples() const { return section_samples_; }

 private:
  std::string method_;
  std::vector<ColumnSpec> sections_, stations_;
  SnapshotGrid grid_;
  double gravity_;
  std::vector<double> times_;
  std::vector<std::vector<ColumnSample>> section_samples_, station_samples_;
  FieldSnapshot snapshot_;
};

// Statistics of one column's samples over time.
ColumnStatistics column_statistics(const ColumnSpec& spec, const std::vector<ColumnSample>& samples,
                                   int n_profile_points, bool with_profile);

}  // namespace hydrojump::compare
