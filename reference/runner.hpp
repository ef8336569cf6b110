// Running a generated OpenFOAM case: `hydrojump vof DIR [--np N] [--resume]`.
//
//   1. OpenFOAM present and usable (the binaries on PATH, WM_PROJECT_DIR set or /usr/share/openfoam);
//   2. mesh_strategy "body_fitted" only after a self-test shows interFoam handles faces that are not
//      aligned with the axes (the Debian v1912 build does not: see self_test_non_orthogonal);
//   3. mesh steps (blockMesh [topoSet subsetMesh] [topoSet sections]), checkMesh (a failed check stops
//      with its report), 0.orig -> 0, setFields;
//   4. interFoam, serial or `--np N` (decomposePar, mpirun -np N ... -parallel, reconstructPar), with a
//      progress line (simulated time, time step, Courant number, ETA) and divergence detection
//      (Courant blow-up, time-step collapse, NaN, crash) that stops the solver and prints the last
//      lines of the log;
//   5. `--resume` continues from the latest complete time directory (an incomplete one, left by a
//      killed run, is moved aside to <time>.incomplete); the run is split into legs that keep every
//      output on the case's output times and write the end time (plan_solver_legs below);
//   6. `--map-from SRC` (a fresh start only) replaces the setFields state by the latest complete time
//      of another run of the same case, interpolated onto this mesh with OpenFOAM's `mapFields
//      -consistent` (mesh sequencing: a finer run started from a settled coarser one; only the
//      fields the case starts with are mapped, and cells the source's domain does not cover, as
//      when the air layer was raised, keep setFields' state). The run still starts at t = 0;
//   7. with `[case.tailwater] control = "hold_toe"` the legs are split every
//      `[vof] tailwater_control_interval_s`
//      and, after each, the outlet's Umean in the latest time directory is reset by the control law of
//      tailwater_control.hpp (a tailgate holding the toe at the basin start; log: tailwater_control.csv).
// Every step logs to DIR/log.<application>.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hydrojump::reference {

// A failed OpenFOAM step or run, with a message meant for the user (what failed, why, what to do).
class OpenFoamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  int np = 1;                          // MPI ranks; 1 = serial
  bool resume = false;                 // continue from the latest time directory
  double progress_interval_s = 30.0;   // wall seconds between progress lines when not on a terminal
  bool force_body_fitted = false;      // run a body_fitted mesh even if the self-test fails (experts)
  std::optional<double> end_time_s;    // run to this time: written into system/controlDict's endTime
                                       // (extends a finished run with --resume); else that endTime
  std::optional<std::filesystem::path> map_from;  // another run of the same case (its vof directory)
                                                  // whose latest time becomes this run's initial state
};

// What the runner needs from the machine. Throws OpenFoamError naming what is missing.
struct OpenFoamInstallation {
  std::filesystem::path project_dir;   // WM_PROJECT_DIR
  std::string version;                 // from interFoam's banner, e.g. "1912"
};
OpenFoamInstallation check_openfoam(bool need_mpi);

// Result of the non-orthogonal-face self-test: still water (16 x 16 cells, half full) run for 100
// fixed steps of 1 ms in an axis-aligned box and in the same box sheared by 2 degrees. A healthy
// interFoam keeps the flow at rest in both (Courant number ~1e-5); the defective build blows up in
// the sheared box.
struct SelfTestResult {
  double axis_aligned_courant = 0.0;   // largest Courant number seen (inf if the run crashed)
  double sheared_courant = 0.0;
  bool axis_aligned_ok = false;
  bool sheared_ok = false;
  std::string summary() const;
};
// Runs the self-test in a fresh directory under `work_dir` (removed afterwards).
SelfTestResult self_test_non_orthogonal(const std::filesystem::path& work_dir);

// Why OpenFOAM cannot run a case in `dir`, or nothing: v1912 strips blanks and quotes from file
// names (fileName::stripInvalid), so a case whose absolute path holds one fails in blockMesh.
std::optional<std::string> openfoam_path_problem(const std::filesystem::path& dir);

// The latest time directory of `case_dir` (> 0), or nothing.
std::optional<double> latest_time(const std::filesystem::path& case_dir);

// interFoam counts its write times from the time it starts at and writes no time that is not a write
// time, not even its endTime. To keep every output of a run on the grid k dt_out (the SPH solver's output
// times) and to write its end time, the runner splits a run into legs, each one interFoam run with its own
// endTime (and write interval, when set):
//   an aligning leg to the first grid time when the start lies off the grid (a run stopped by Ctrl-C and
//   resumed), written once at its end; the grid times; a closing leg written once at an end time off the
//   grid. Times within 1e-6 dt_out of the grid count as on it.
//
//   g_first = ceil(t_start / dt_out) dt_out,   g_last = floor(t_end / dt_out) dt_out
//
// Usually this is one leg (start and end on the grid); none when the start is not before the end.
// Without a known interval (writeControl not counting simulated time) it is one leg at the case's
// settings.
struct SolverLeg {
  double end_s = 0.0;
  std::optional<double> write_interval_s;  // this leg's writeInterval; nothing: the case's
};
std::vector<SolverLeg> plan_solver_legs(double start_s, double end_s, std::optional<double> output_interval_s);

// The legs of a run with the tailwater control (tailwater_control.hpp): each leg on the output grid
// (one without its own write interval) split at every `interval_s` from its start, so that the control
// acts after each piece; aligning and closing legs are kept whole. `interval_s` <= 0: the legs unchanged.
std::vector<SolverLeg> split_legs_for_control(const std::vector<SolverLeg>& legs, double start_s, double interval_s);

// The controlDict text `text` (read from `file`, named in errors) for one leg: endTime = leg.end_s and,
// when the leg has its own write interval, each writeInterval equal to the case's that counts simulated
// time (its block's writeControl adjustable, adjustableRunTime or runTime) set to it.
std::string leg_control_dict(const std::string& text, const std::filesystem::path& file, const SolverLeg& leg);

// What goes back into system/controlDict after a leg: the case's text `original` when the file still
// holds the leg's `leg_text`; when it was edited by hand during the leg (`current`: OpenFOAM rereads it,
// runTimeModifiable), the edit with the case's endTime value back, unless the leg also set its own
// write interval (nullopt: the edit cannot be told from the leg's changes; the caller keeps it aside).
std::optional<std::string> control_dict_after_leg(const std::string& original, const std::string& leg_text,
                                                  const std::string& current, const std::filesystem::path& file,
                                                  const SolverLeg& leg);

// Meshes and runs the case in `dir` (written by `hydrojump generate`, holding case.toml).
// Throws OpenFoamError (or cases::SpecError for a bad case.toml).
void run_vof_case(const std::filesystem::path& dir, const RunOptions& options, std::ostream& out);

}  // namespace hydrojump::reference
