#include "compare/case_comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "cases/jump_toe.hpp"
#include "util/number_text.hpp"
#include "cases/output_times.hpp"
#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "compare/readers.hpp"
#include "compare/report.hpp"
#include "reference/runner.hpp"
#include "sph/kernel.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

cases::Study load_run_case(const fs::path& run_dir) {
  for (const fs::path& p : {run_dir / "sph" / "case.toml", run_dir / "vof" / "case.toml"}) {
    if (!fs::exists(p)) continue;
    // Both methods' results are reported under this case: each must have been made with it.
    for (const char* method : {"sph", "vof"}) cases::require_results_of(run_dir / method, p);
    return cases::load_study(p, cases::SpecPurpose::read_results);
  }
  throw std::runtime_error(run_dir.string() + ": no case.toml in " + (run_dir / "sph").string() + " or " +
                           (run_dir / "vof").string() + " (is this a directory written by `hydrojump generate`?)");
}

namespace {

// The numbers behind a run note's verdict into the method's metrics: the imbalance, and steady by the
// window means as 1 (yes), 0 (no) or NaN (not judged).
void set_run_balance(JumpMetrics& m, const RunBalance& b) {
  m.window_imbalance = b.imbalance;
  m.steady_by_means = b.steady ? (*b.steady ? 1.0 : 0.0) : not_a_number;
}

// Progress lines "sph: frame 3/40 at t = 5.15 s (elapsed 12 s, ETA 2 min)".
class Progress {
 public:
  Progress(std::ostream& log, std::string what, std::size_t total)
      : log_(log), what_(std::move(what)), total_(total), t0_(std::chrono::steady_clock::now()) {}
  void step(std::size_t done, double time_s) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    if (done < total_ && el - last_ < 5.0 && done != 1) return;
    last_ = el;
    const double eta = done > 0 ? el / static_cast<double>(done) * static_cast<double>(total_ - done) : 0.0;
    log_ << what_ << ": frame " << done << "/" << total_ << " at t = " << std::setprecision(4) << time_s
         << " s (elapsed " << std::lround(el) << " s, ETA " << std::lround(eta) << " s)" << std::endl;
  }

 private:
  std::ostream& log_;
  std::string what_;
  std::size_t total_;
  std::chrono::steady_clock::time_point t0_;
  double last_ = -1e9;
};

std::string window_text(double t0, double t1) {
  std::ostringstream s;
  s << "[" << t0 << ", " << t1 << "] s";
  return s.str();
}

// "ok", or "ok; N unreadable frame(s) skipped, the first: ..."
std::string skipped_status(const std::vector<std::string>& skipped) {
  if (skipped.empty()) return "ok";
  return "ok; " + std::to_string(skipped.size()) + " unreadable frame(s) skipped, the first: " + skipped.front();
}

// When the results end before the window does (a run stopped early, or still running): the clause
// saying that the averages cover only part of the window; empty otherwise. `last_output_s` is the
// last output of the whole series (a window may end between two outputs).
std::string window_coverage_clause(double last_output_s, double first_in_window_s, double last_in_window_s, double t1,
                                   double tolerance_s) {
  if (last_output_s >= t1 - tolerance_s) return {};
  return "; PART OF THE WINDOW ONLY: the results end at t = " + util::number_text(last_output_s) +
         " s, before the window's end " + util::number_text(t1) + " s, so the averages are over the outputs of " +
         window_text(first_in_window_s, last_in_window_s) + " (run on, or give --window)";
}

// The one case of a resolved study, checked to be a stilling basin with exactly one resolution.
const cases::Case& resolved_case(const cases::Study& study) {
  if (study.cases.size() != 1)
    throw std::runtime_error(study.source_file.string() + ": expected exactly one [[case]] (a resolved case), found " +
                             std::to_string(study.cases.size()));
  const cases::Case& c = study.cases.front();
  if (!c.stilling_basin())
    throw std::runtime_error("case \"" + c.id + "\" is of kind \"" + c.kind +
                             "\": `hydrojump compare` handles kind \"stilling_basin\" only");
  if (c.resolutions.size() != 1)
    throw std::runtime_error(study.source_file.string() + ": a resolved case has exactly one [resolution.*] table, found " +
                             std::to_string(c.resolutions.size()));
  return c;
}

// What the comparison reads of the resolved case: the study (fluid, source file), its one case, the
// basin, the one resolution, the geometry and gravity.
struct CaseContext {
  const cases::Study& study;
  const cases::Case& c;
  const cases::StillingBasinCase& basin;
  const cases::Resolution& res;
  const cases::CaseGeometry& geo;
  double g;
};

// The comparison's inputs from the case: inflow y1, U1, tailwater, floor level (the bed at the inflow),
// basin extent, bed wavelength, the averaging window (the case's, or --window), the resolution and the
// laboratory values.
CaseComparison case_inputs(const CaseContext& ctx, const CompareOptions& options) {
  const cases::Case& c = ctx.c;
  const cases::StillingBasinCase& basin = ctx.basin;
  const cases::CaseGeometry& geo = ctx.geo;
  CaseComparison r;
  r.case_id = c.id;
  r.description = c.description;
  r.tailwater_control = std::string(cases::option_name(basin.control.mode));
  r.resolution = ctx.res.name;
  r.inflow_depth_m = basin.inflow_depth_m;
  r.inflow_velocity_m_s = basin.inflow_velocity_m_s;
  r.tailwater_depth_m = basin.tailwater_depth_m;
  r.gravity_m_s2 = ctx.g;
  r.floor_z_m = geo.bed.elevation(geo.inflows.empty() ? geo.x_min_m : geo.inflows.front().x_m);
  r.basin_start_m = basin.upstream_length_m;
  r.basin_end_m = basin.upstream_length_m + basin.basin_length_m;
  r.bed_wavelength_m = geo.bed.corrugated() ? geo.bed.wavelength_m() : 0.0;
  r.window_start_s = options.window_start_s.value_or(c.run.average_start_s);
  r.window_end_s = options.window_end_s.value_or(c.run.average_end_s > 0.0 ? c.run.average_end_s : c.run.end_time_s);
  r.particle_spacing_m = ctx.res.particle_spacing_m;
  r.vof_cell_size_m = ctx.res.vof_cell_size_bed_m;
  r.interpolation = to_string(options.scheme);
  r.measured_source = basin.measured.source;
  r.measured_note = basin.measured.note;
  r.lab.sequent_depth_m = basin.measured.sequent_depth_m;
  r.lab.jump_length_m = basin.measured.jump_length_m;
  r.lab.roller_length_m = basin.measured.roller_length_m;
  r.lab.eta_percent = basin.measured.eta_percent;
  r.lab.eta_smooth_percent = basin.measured.eta_smooth_percent;
  r.lab.published_sph_eta_percent = basin.measured.published_sph_eta_percent;
  return r;
}

// Throws unless the averaging window [t0, t1] is one a run of case `c` can fill: t1 >= t0, t1 within
// the latest end time a run can reach, and at least 2 output times in it (a time mean, its standard
// deviation and trend need two outputs at least).
void check_window(const cases::Case& c, double t0, double t1) {
  if (!(t1 >= t0))
    throw std::runtime_error("case \"" + c.id + "\": averaging window " + window_text(t0, t1) +
                             " is empty (end before start)");
  // No run of the case reaches beyond its latest end time (sph and vof --end-time are bounded by it).
  if (t1 > c.run.latest_end_time_s())
    throw std::runtime_error("case \"" + c.id + "\": the averaging window " + window_text(t0, t1) +
                             " ends after " + util::number_text(c.run.latest_end_time_s()) +
                             " s, the latest time a run of this case can reach (at most " +
                             util::number_text(cases::max_outputs_per_run) + " outputs, one every " +
                             util::number_text(c.run.output_interval_s) + " s): give --window within it");
  if (const long n = cases::outputs_in_window(t0, t1, c.run.output_interval_s); n < 2)
    throw std::runtime_error("case \"" + c.id + "\": the averaging window " + window_text(t0, t1) +
                             " holds " + std::to_string(n) + " output time(s) (one every " +
                             util::number_text(c.run.output_interval_s) + " s): give a window with at least 2");
}

// The smooth-bed theory from the inputs alone (cases::jump_hydraulics): Bélanger's sequent depth
//   y2* = y1/2 (sqrt(1 + 8 Fr1^2) - 1),   Fr1 = U1/sqrt(g y1),
// and eta* = (E1 - E2*)/E1 in %, E = y + q^2/(2 g y^2).
void set_smooth_bed_theory(CaseComparison& r) {
  const cases::JumpHydraulics jh =
      cases::jump_hydraulics(r.inflow_depth_m, r.inflow_velocity_m_s, r.tailwater_depth_m, r.gravity_m_s2);
  r.belanger_y2_m = jh.belanger_y2_m;
  r.eta_smooth_theory_percent = 100.0 * jh.eta_smooth;
}

// The case's sections as columns, each with `points` profile points.
std::vector<ColumnSpec> case_sections(const cases::CaseGeometry& geo, int points) {
  std::vector<ColumnSpec> sections;
  for (const auto& s : geo.sections) sections.push_back({s.name, std::string(cases::option_name(s.role)), s.x_m, geo.bed.elevation(s.x_m), points});
  return sections;
}

// The spacing ds of the stations along the channel, L = x_max - x_min long: --station-spacing, else the
// finer of the SPH particle spacing and the VOF bed cell (L/500 without either); at least L/3000 (at
// most 3,000 stations: a finer spacing costs time and adds nothing at the kernel's or the cells' scale;
// a finer --station-spacing is said in `log`, not silently coarsened). The toe, the lengths and the
// surface are found on the stations: a --station-spacing coarser than y1 throws.
double station_spacing(const CaseContext& ctx, double y1, const CompareOptions& options, std::ostream& log) {
  const cases::Resolution& res = ctx.res;
  const double length = ctx.geo.x_max_m - ctx.geo.x_min_m;
  double ds = options.station_spacing_m;
  if (ds > y1)
    throw std::runtime_error("--station-spacing " + util::number_text(ds) + " m is coarser than the inflow depth y1 = " +
                             util::number_text(y1) + " m of case \"" + ctx.c.id +
                             "\": the toe and the jump's lengths need stations finer than y1 (default: the finer of the "
                             "SPH particle spacing and the VOF bed cell)");
  if (!(ds > 0.0)) {
    ds = std::min(res.particle_spacing_m > 0 ? res.particle_spacing_m : 1e9,
                  res.vof_cell_size_bed_m > 0 ? res.vof_cell_size_bed_m : 1e9);
    if (ds > 1e8) ds = length / 500.0;
  }
  if (options.station_spacing_m > 0.0 && ds < length / 3000.0)
    log << "compare: --station-spacing " << util::number_text(ds) << " m is finer than the limit of 3000 stations over "
        << util::number_text(length) << " m: using " << std::setprecision(4) << length / 3000.0 << std::setprecision(6)
        << " m" << std::endl;
  return std::max(ds, length / 3000.0);
}

// The columns along the channel, where the jump's toe, lengths and surface are found, and the grid of
// the velocity-field snapshot.
struct SamplingLayout {
  std::vector<ColumnSpec> stations;
  SnapshotGrid grid;
  std::vector<double> grid_bed;  // z_b at each grid column
};

// The stations, n = max(3, floor(L/ds)) of them at the centres of n equal parts of the channel,
//   x_i = x_min + (i + 1/2) L/n,
// and the snapshot grid, nx = L/ds within [50, 800] columns and nz = nx (z_max - z_min)/L within
// [10, 400] rows, with the bed under each grid column.
SamplingLayout sampling_layout(const CaseContext& ctx, double y1, const CompareOptions& options, std::ostream& log) {
  const cases::CaseGeometry& geo = ctx.geo;
  const double length = geo.x_max_m - geo.x_min_m;
  const double ds = station_spacing(ctx, y1, options, log);
  SamplingLayout l;
  const int n_stations = std::max(3, static_cast<int>(std::floor(length / ds)));
  for (int i = 0; i < n_stations; ++i) {
    const double x = geo.x_min_m + (i + 0.5) * length / n_stations;
    l.stations.push_back({"", "station", x, geo.bed.elevation(x), options.station_points});
  }
  SnapshotGrid& grid = l.grid;
  grid.x_min = geo.x_min_m; grid.x_max = geo.x_max_m;
  grid.z_min = geo.z_min_m; grid.z_max = geo.z_max_m;
  grid.nx = std::min(800, std::max(50, static_cast<int>(length / ds)));
  grid.nz = std::clamp(static_cast<int>(std::lround(grid.nx * (geo.z_max_m - geo.z_min_m) / length)), 10, 400);
  l.grid_bed.resize(static_cast<std::size_t>(grid.nx));
  for (int i = 0; i < grid.nx; ++i)
    l.grid_bed[static_cast<std::size_t>(i)] = geo.bed.elevation(grid.x_min + i * length / (grid.nx - 1));
  return l;
}

// The averaging window [t0, t1] and how late after its nominal time an output may come
// (cases/output_times.hpp).
struct AveragingWindow {
  double t0 = 0.0, t1 = 0.0;
  double tolerance_s = 0.0;
};

// What sampling one method's results needs: the case, the run directory, the options, the columns and
// the window; progress and skipped frames are said in `log`.
struct SamplingJob {
  const CaseContext& ctx;
  const fs::path& run_dir;
  const CompareOptions& options;
  const std::vector<ColumnSpec>& sections;
  const SamplingLayout& layout;
  AveragingWindow window;
  std::ostream& log;
};

// A series from another directory (--sph-pvd): when a case record lies beside it, it must be this
// case's, as the one in RUN_DIR/sph is (load_run_case); throws naming the first differing setting.
// Results of other programs have none.
void check_series_case(const fs::path& pvd, const SamplingJob& job) {
  const fs::path other = pvd.parent_path();
  if (job.options.sph_pvd.empty() || !fs::exists(cases::recorded_case_file(other))) return;
  const fs::path recorded = cases::recorded_case_file(other);
  const fs::path& case_file = job.ctx.study.source_file;
  const auto d = cases::first_setting_difference(util::read_text_file(recorded), util::read_text_file(case_file));
  if (d.any()) {
    throw std::runtime_error(pvd.string() + " was made with other settings than " + case_file.string() + ": " +
                             recorded.string() + " has '" + d.a + "' where it has '" + d.b + "'");
  }
}

// How the case's particles are interpolated: its kernel, with h = smoothing_length(coef_h, dx), the
// fluid's density, the scheme, and no surface above z_max + 2 h (a particle thrown above the domain
// is no surface).
SphSamplingSettings sph_sampling_settings(const SamplingJob& job) {
  const CaseContext& ctx = job.ctx;
  SphSamplingSettings s;
  s.kernel = std::string(cases::option_name(ctx.c.sph.kernel));
  s.particle_spacing_m = ctx.res.particle_spacing_m;
  s.smoothing_length_m = sph::smoothing_length(ctx.c.sph.coef_h, ctx.res.particle_spacing_m);
  s.reference_density_kg_m3 = ctx.study.fluid.density_kg_m3;
  s.scheme = job.options.scheme;
  s.z_ceiling_m = ctx.geo.z_max_m + 2.0 * s.smoothing_length_m;
  return s;
}

// The time statistics of the SPH frames `entries` (those in the window) into out.stats; a frame that
// cannot be read is skipped (said in `log`, and returned), the others are kept. Throws when none could
// be read.
std::vector<std::string> accumulate_sph_frames(const SamplingJob& job, const std::vector<PvdEntry>& entries,
                                               MethodOutcome& out) {
  const SphSamplingSettings s = sph_sampling_settings(job);
  MethodAccumulator acc("sph", job.sections, job.layout.stations, job.layout.grid, job.ctx.g);
  Progress progress(job.log, "sph", entries.size());
  std::vector<std::string> skipped;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    try {
      const ParticleFrame f = read_vtp_particles(entries[i].file, entries[i].time_s);
      acc.add_frame(*make_sph_sampler(f, s), i + 1 == entries.size(), job.layout.grid_bed);
    } catch (const std::exception& e) {  // one unreadable frame does not lose the others
      skipped.push_back(e.what());
      job.log << "sph: frame at t = " << entries[i].time_s << " s skipped: " << e.what() << std::endl;
    }
    progress.step(i + 1, entries[i].time_s);
  }
  if (acc.frame_count() == 0) throw std::runtime_error("no readable frame: " + skipped.front());
  out.stats = acc.finish(job.options.section_points);
  return skipped;
}

// The SPH outcome: the .pvd series (--sph-pvd, else the one under RUN_DIR/sph) sampled over the window;
// "missing: ..." with the reason when there is none, it is another case's or no frame lies in the window.
void sample_sph(const SamplingJob& job, MethodOutcome& out) {
  const AveragingWindow& w = job.window;
  out.method = "sph";
  try {
    const fs::path pvd = job.options.sph_pvd.empty() ? find_pvd(job.run_dir / "sph") : job.options.sph_pvd;
    out.source = pvd.string();
    check_series_case(pvd, job);
    const auto all = read_pvd(pvd);
    const auto entries = entries_in_window(all, w.t0, w.t1, w.tolerance_s);
    if (entries.empty()) {
      out.status = "missing: no output time of " + pvd.string() + " lies in the averaging window " +
                   window_text(w.t0, w.t1) + " (the series covers " + window_text(all.front().time_s, all.back().time_s) + ")";
      return;
    }
    const std::vector<std::string> skipped = accumulate_sph_frames(job, entries, out);
    out.available = true;
    out.status = skipped_status(skipped) + window_coverage_clause(all.back().time_s, entries.front().time_s,
                                                                  entries.back().time_s, w.t1, w.tolerance_s);
  } catch (const std::exception& e) {
    out.status = std::string("missing: ") + e.what();
  }
}

// The time statistics of the OpenFOAM times `times` (those in the window) into out.stats; a time that
// cannot be read is skipped (said in `log`, and returned), the others are kept. Throws when none could
// be read.
std::vector<std::string> accumulate_vof_times(const SamplingJob& job, OpenFoamResults& foam,
                                              const std::vector<double>& times, MethodOutcome& out) {
  MethodAccumulator acc("vof", job.sections, job.layout.stations, job.layout.grid, job.ctx.g);
  Progress progress(job.log, "vof", times.size());
  std::vector<std::string> skipped;
  for (std::size_t i = 0; i < times.size(); ++i) {
    try {
      const CellFrame f = foam.read(times[i]);
      acc.add_frame(*make_vof_sampler(f, job.options.scheme), i + 1 == times.size(), job.layout.grid_bed);
    } catch (const std::exception& e) {
      skipped.push_back(e.what());
      job.log << "vof: time " << times[i] << " s skipped: " << e.what() << std::endl;
    }
    progress.step(i + 1, times[i]);
  }
  if (acc.frame_count() == 0) throw std::runtime_error("no readable time: " + skipped.front());
  out.stats = acc.finish(job.options.section_points);
  return skipped;
}

// The VOF outcome: the OpenFOAM case RUN_DIR/vof sampled over the window; "missing: ..." with the
// reason when it has no results (a decomposed run is named) or no written time lies in the window.
void sample_vof(const SamplingJob& job, MethodOutcome& out) {
  const AveragingWindow& w = job.window;
  out.method = "vof";
  const fs::path vof_dir = job.run_dir / "vof";
  out.source = vof_dir.string();
  try {
    if (const std::string lack = missing_openfoam_results(vof_dir); !lack.empty()) {
      out.status = "missing: " + vof_dir.string() + " has no OpenFOAM results (" + lack + ")";
      if (fs::exists(vof_dir / "processor0"))
        out.status += "; it holds a decomposed run: reconstruct it first (reconstructPar)";
      return;
    }
    OpenFoamResults foam(vof_dir);
    const auto times = foam.times_in_window(w.t0, w.t1, w.tolerance_s);
    if (times.empty()) {
      out.status = "missing: no written time of " + vof_dir.string() + " lies in the averaging window " +
                   window_text(w.t0, w.t1) + " (times " + window_text(foam.times().front(), foam.times().back()) + ")";
      return;
    }
    const std::vector<std::string> skipped = accumulate_vof_times(job, foam, times, out);
    out.available = true;
    out.status = skipped_status(skipped) + window_coverage_clause(foam.times().back(), times.front(), times.back(), w.t1,
                                                                  w.tolerance_s);
  } catch (const std::exception& e) {
    out.status = std::string("missing: ") + e.what();
  }
}

// Says each method's status in `log` and computes the jump metrics of each method with results.
void compute_method_metrics(CaseComparison& r, const JumpMetricOptions& options, std::ostream& log) {
  for (MethodOutcome* m : {&r.sph, &r.vof}) {
    log << m->method << ": " << m->status << std::endl;
    if (!m->available) continue;
    m->metrics = compute_jump_metrics(m->stats, {r.inflow_depth_m, r.inflow_velocity_m_s, r.floor_z_m, r.gravity_m_s2, options});
  }
}

// The VOF run's notes on water through the lid and on its water balance and steadiness over the window
// (vof_top_outflow_note, vof_run_note, with the numbers behind the verdict), from its discharge samples.
// A damaged sample file costs these notes (the note says which file), not the comparison.
void add_vof_balance_notes(const SamplingJob& job, CaseComparison& r) {
  const fs::path vof_dir = job.run_dir / "vof";
  try {
    const std::string note = vof_top_outflow_note(vof_dir, r.window_start_s, r.window_end_s,
                                                  r.inflow_depth_m * r.inflow_velocity_m_s, r.vof_cell_size_m);
    if (!note.empty()) r.vof.metrics.notes.push_back(note);
    const cases::StillingBasinCase& basin = job.ctx.basin;
    VofRunNoteInputs balance_inputs{vof_dir, r.window_start_s, r.window_end_s, r.inflow_depth_m * r.inflow_velocity_m_s,
                                    r.vof_cell_size_m, r.vof.metrics.toe_trend_m_per_s,
                                    cases::toe_drift_tolerance_m(basin.bed.profile, basin.bed.wavelength_m, r.inflow_depth_m)};
    const std::vector<double>& frame_toes = r.vof.metrics.toe_frames_x_m;
    balance_inputs.frames = static_cast<int>(frame_toes.size());
    balance_inputs.frames_without_toe =
        static_cast<int>(std::count_if(frame_toes.begin(), frame_toes.end(), [](double x) { return !std::isfinite(x); }));
    // As the SPH rule: some output at or after the window's end (the window itself may end off the grid).
    const std::optional<double> latest = reference::latest_time(vof_dir);
    balance_inputs.reaches_window_end = latest && *latest >= r.window_end_s - job.window.tolerance_s;
    RunBalance numbers;
    const std::string balance = vof_run_note(balance_inputs, &numbers);
    if (!balance.empty()) r.vof.metrics.notes.push_back(balance);
    set_run_balance(r.vof.metrics, numbers);
  } catch (const std::exception& e) {
    r.vof.metrics.notes.push_back(std::string("water balance unavailable: ") + e.what());
  }
}

// The note on the tailgate's log (vof_tailwater_control_note), read only for a case run with the
// control (a file left from another run is not this run's); an unreadable log is said in the note.
void add_tailgate_note(const SamplingJob& job, CaseComparison& r) {
  if (!job.ctx.c.holds_toe()) return;
  try {
    const std::string control = vof_tailwater_control_note(job.run_dir / "vof", r.window_start_s, r.window_end_s);
    if (!control.empty()) r.vof.metrics.notes.push_back(control);
  } catch (const std::exception& e) {
    r.vof.metrics.notes.push_back(std::string("tailgate control log unreadable: ") + e.what());
  }
}

// The SPH run's own verdict (summary.json of sph/basin_monitor.hpp, sph_run_note), when it wrote one,
// with the numbers behind it.
void add_sph_run_note(const SamplingJob& job, CaseComparison& r) {
  RunBalance numbers;
  const std::string note = sph_run_note(job.run_dir / "sph" / "summary.json", r.window_start_s, r.window_end_s,
                                        job.window.tolerance_s, &numbers);
  if (!note.empty()) r.sph.metrics.notes.push_back(note);
  set_run_balance(r.sph.metrics, numbers);
}

// The discrepancies: SPH − VOF surface over the basin and velocity profiles per section when both
// methods have results, and the metric table of both beside the experiment and the inputs alone.
void compare_methods(CaseComparison& r, bool holds_toe) {
  if (r.sph.available && r.vof.available) {
    r.surface = surface_difference(r.sph.stats, r.vof.stats, r.basin_start_m, r.basin_end_m);
    r.profiles = profile_differences(r.sph.stats, r.vof.stats, r.inflow_velocity_m_s);
  }
  r.metrics = metric_table(r.sph.available ? &r.sph.metrics : nullptr, r.vof.available ? &r.vof.metrics : nullptr,
                           r.lab, r.inflow_depth_m, r.inflow_velocity_m_s, r.gravity_m_s2, holds_toe);
}

}  // namespace

CaseComparison compare_case(const cases::Study& study, const fs::path& run_dir, const CompareOptions& options,
                            std::ostream& log) {
  const cases::Case& c = resolved_case(study);
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  const CaseContext ctx{study, c, *c.stilling_basin(), c.resolutions.begin()->second, geo, study.fluid.gravity_m_s2};

  CaseComparison r = case_inputs(ctx, options);
  check_window(c, r.window_start_s, r.window_end_s);
  set_smooth_bed_theory(r);
  r.sections = case_sections(geo, options.section_points);
  const SamplingLayout layout = sampling_layout(ctx, r.inflow_depth_m, options, log);
  const AveragingWindow window{r.window_start_s, r.window_end_s, cases::output_time_tolerance_s(c.run.output_interval_s)};
  const SamplingJob job{ctx, run_dir, options, r.sections, layout, window, log};

  sample_sph(job, r.sph);
  sample_vof(job, r.vof);
  compute_method_metrics(r, options.metrics, log);
  if (r.vof.available) {
    add_vof_balance_notes(job, r);
    add_tailgate_note(job, r);
  }
  if (r.sph.available) add_sph_run_note(job, r);
  compare_methods(r, c.holds_toe());
  return r;
}

std::string summary_text(const CaseComparison& c) {
  std::ostringstream o;
  auto lab = [&o](const std::optional<double>& v) {
    if (v) o << " [" << *v << "]";
  };
  // What the set-up held is marked as such (the toe under the toe-holding control, else y2 and eta).
  const bool held = c.tailwater_control == "hold_toe";
  const char* toe_label = held ? " (imposed)" : " (predicted)";
  const char* y2_label = held ? " (predicted)" : " (imposed)";
  for (const MethodOutcome* m : {&c.sph, &c.vof}) {
    if (!m->available) continue;
    const JumpMetrics& r = m->metrics;
    o << std::setprecision(4) << m->method << ": toe " << r.toe_mean_of_frames_x_m << " +- " << r.toe_std_m << " m"
      << toe_label;
    if (std::isfinite(r.toe_trend_m_per_s)) o << " (trend " << std::showpos << r.toe_trend_m_per_s << std::noshowpos << " m/s)";
    o << ", y2 " << r.sequent_depth_m << " m" << y2_label;
    lab(c.lab.sequent_depth_m);
    if (c.belanger_y2_m > 0.0) o << " {y2* " << c.belanger_y2_m << ", y2/y2* " << r.sequent_depth_m / c.belanger_y2_m << "}";
    o << ", eta " << 100.0 * r.eta << " %" << y2_label;
    lab(c.lab.eta_percent);
    o << ", Lj " << r.jump_length_m << " m (predicted)";
    lab(c.lab.jump_length_m);
    o << "\n";
    for (const auto& n : r.notes) o << m->method << ": " << n << "\n";
  }
  return o.str();
}

CaseComparison compare_case_directory(const fs::path& run_dir, const CompareOptions& options, std::ostream& log) {
  if (!fs::is_directory(run_dir)) throw std::runtime_error(run_dir.string() + ": run directory does not exist");
  const cases::Study study = load_run_case(run_dir);
  CaseComparison r = compare_case(study, run_dir, options, log);
  const fs::path out = options.out_dir.empty() ? run_dir : options.out_dir;
  r.figures_problem = write_report(r, out, options.plots, log);
  log << "summary over " << window_text(r.window_start_s, r.window_end_s) << " (experiment in brackets):\n"
      << summary_text(r) << std::flush;
  return r;
}

}  // namespace hydrojump::compare
