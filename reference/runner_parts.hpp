// The parts of `hydrojump vof` (internal to reference/): run_vof_case (runner.cpp) runs its stages
// (check, mesh, initialise, solve, finish) with these, each group in its own file:
//   | part                                          | file                    |
//   |-----------------------------------------------|-------------------------|
//   | spawn, stop requests, run_step                | foam_process.cpp        |
//   | time directories: complete, moved aside       | foam_times.cpp          |
//   | controlDict: endTime, a leg's controlDict     | control_dict_edits.cpp  |
//   | legs on the output grid, the solver           | solver_legs.cpp         |
//   | --map-from: the source, mapFields             | map_from.cpp            |
//   | the tailgate step after a leg (hold_toe)      | tailgate_step.cpp       |
//   | OpenFOAM present, path problems               | openfoam_check.cpp      |
//   | the non-orthogonal-face self-test             | self_test.cpp           |
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cases/spec.hpp"
#include "reference/foam_process.hpp"
#include "reference/runner.hpp"
#include "reference/tailwater_control.hpp"

namespace hydrojump::reference::detail {

// ------------------------------------------------------------------ time directories (foam_times.cpp)

// processor0/, processor1/, ... of a decomposed case, up to the first missing rank.
std::vector<std::filesystem::path> processor_directories(const std::filesystem::path& dir);

// A time directory is complete when its main fields are present and every field file in it (the
// turbulence fields, phi, uniform/time too) was written to the end.
bool time_directory_complete(const std::filesystem::path& time_dir);

// Moves `dir` aside as <dir>.<suffix> (<dir>.<suffix>.2, ... when that name is left from an earlier
// kill); returns the new name. Throws naming `what` when it cannot.
std::string move_aside(const std::filesystem::path& dir, const std::string& suffix, const std::string& what);

// A half-written time directory, as <name>.incomplete.
std::string move_incomplete_aside(const std::filesystem::path& time_dir);

// Present while decomposePar runs: processor*/ are then not a decomposition to resume from.
inline constexpr const char* decomposing_marker = ".decomposing";

// Removes processor*/ left by a decomposePar that was stopped or killed (the marker is still there).
void remove_cut_short_decomposition(const std::filesystem::path& dir, std::ostream& out);

// Before a resume from `ranks` (the case directory, or processor*/ when the run continues decomposed):
// the latest times not complete on every rank moved aside, the samples of the abandoned part after the
// start moved aside, and (decomposed) a half-written reconstructed time. Returns the start: the latest
// time complete everywhere, or nothing.
std::optional<double> discard_incomplete_times(const std::filesystem::path& dir, bool continue_decomposed,
                                               std::ostream& out);

// -------------------------------------------------------------- controlDict (control_dict_edits.cpp)

// The case's controlDict kept aside while a leg's replaces it.
inline constexpr const char* control_dict_original = "system/controlDict.hydrojump-original";

// The endTime value of DIR/system/controlDict (what interFoam obeys).
double control_dict_end_time(const std::filesystem::path& dir);

// Rewrites that entry's value in the case's controlDict, atomically (the rest, hand edits included, kept).
void set_control_dict_end_time(const std::filesystem::path& dir, double end_time_s);

// The controlDict's output interval when its writeControl counts simulated time, else nothing.
std::optional<double> output_grid_interval(const std::filesystem::path& dir);

// A leg's controlDict in place of the case's for its lifetime (control_dict_edits.cpp).
class ControlDictOverride {
 public:
  ControlDictOverride(const std::filesystem::path& dir, const SolverLeg& leg);
  ~ControlDictOverride();
  ControlDictOverride(const ControlDictOverride&) = delete;
  ControlDictOverride& operator=(const ControlDictOverride&) = delete;
  // Puts the case's controlDict back, keeping an edit made by hand during the leg (runTimeModifiable:
  // a changed maxCo, say) where it can (control_dict_after_leg); says so on `out` when given.
  void restore(std::ostream* out);

 private:
  std::filesystem::path dir_;
  SolverLeg leg_;
  std::string leg_text_;
  bool restored_ = false;
};

// Puts back a case controlDict left aside by a runner killed during an aligning leg.
void restore_control_dict_left_behind(const std::filesystem::path& dir, std::ostream& out);

// ----------------------------------------------------------------------- the solver (solver_legs.cpp)

// What every leg of interFoam needs: the case, the command (interFoam, or mpirun ... -parallel).
struct SolverRun {
  std::filesystem::path dir;
  const cases::Case& c;
  double thickness_m;                // spanwise cell size: discharges per unit width
  std::vector<std::string> command;
  bool parallel;
  const RunOptions& options;
  double run_end_s;                  // the end time of the whole run (progress and ETA)
  const util::DirectoryLock& lock;  // the case directory's, which the solver holds while it runs
};

// Runs the solver from `start` (nothing: t = 0) until `end_time_s`, showing progress, and returns the
// time reached. A failure (divergence, crash, an early end) or a stop request throws OpenFoamError with
// the last lines of the log and how to resume.
double run_solver(const SolverRun& run, std::optional<double> start, double end_time_s, std::ostream& out);

// ------------------------------------------------------------------------- --map-from (map_from.cpp)

// The run whose state `--map-from` starts this one from: its directory and the name of its latest
// complete time directory (as mapFields -sourceTime wants it).
struct MapSource {
  std::filesystem::path dir;
  std::string time_name;
};

// Checks that `source` holds a finished (or interrupted) run of case `case_id`, not `target` itself.
MapSource check_map_source(const std::filesystem::path& source, const std::filesystem::path& target,
                           const std::string& case_id);

// Interpolates the source's fields at its latest time onto this mesh (into 0/) with mapFields.
void map_initial_state(const StepPlace& place, const MapSource& source);

// ------------------------------------------------------------------ the tailgate (tailgate_step.cpp)

// After a leg that ended at `leg_end_s` (started at leg_start_s): the law's step from the leg's outputs,
// logged, and the outlet's Umean rewritten in the latest time directory (each processor's when decomposed).
void tailwater_control_after_leg(const std::filesystem::path& dir, const TailwaterControlLaw& law, double thickness_m,
                                 bool parallel, double leg_start_s, double leg_end_s, std::ostream& out);

}  // namespace hydrojump::reference::detail
