// What `hydrojump study` keeps beside a solver stage of a case (OUT/<case>/), for `hydrojump record`:
//
//   | file                 | written when                        | holds                                     |
//   |----------------------|-------------------------------------|-------------------------------------------|
//   | <stage>.legs         | a leg ended unfinished (stopped or  | "seconds legs" of those legs, until the   |
//   |                      | failed) and the stage will resume   | stage finishes or starts over             |
//   | <stage>.stage.toml   | the stage finished                  | wall_time_s (all legs), legs, threads,    |
//   |                      |                                     | machine                                   |
//   | <stage>.failed       | the stage failed (not stopped on    | run_key, failure (what stopped it), and   |
//   |                      | request)                            | the timing keys of <stage>.stage.toml     |
//
// A failed run is a result (a miss), so its record says what stopped it instead of leaving the case
// "not run". <stage>.failed goes when the stage starts again.
//
// Example:
//   add_leg(dir, "sph", 312.5);                                 // a leg failed after 312.5 s
//   write_stage_failure(dir, "sph", key, failure_text(dir, "sph", dir / "sph.log", status, leg_start), 1);
#pragma once

#include <filesystem>
#include <string>
#include <utility>

namespace hydrojump::app {

// "<CPU model>, N cores" (/proc/cpuinfo's first model name; "unknown CPU" without it): wall times are
// only comparable on one machine. Quotes and backslashes are dropped (a TOML string).
std::string machine_text();

// The wall time and count of the unfinished legs in `dir`/<stage>.legs; (0, 0) when absent or damaged.
std::pair<double, int> earlier_legs(const std::filesystem::path& dir, const std::string& stage);

// Adds a leg of `seconds` to `dir`/<stage>.legs.
void add_leg(const std::filesystem::path& dir, const std::string& stage, double seconds);

// `dir`/<stage>.stage.toml for a stage that finished with this leg of `seconds` on `threads` threads
// (SPH) or ranks (VOF); removes <stage>.legs.
void write_stage_info(const std::filesystem::path& dir, const std::string& stage, double seconds, int threads);

// When a leg started, on the file system's own clock: the time `marker` (written as the leg starts) was
// last written, else now. A file written after the marker is never older than it, whereas the clock's
// now() can run a tick ahead of the file system's coarse timestamps.
std::filesystem::file_time_type leg_start_time(const std::filesystem::path& marker);

// What stopped a solver stage whose leg started at `leg_start`: the SPH run's diagnosis (the first line
// of `dir`/sph/failure.txt, when this leg wrote it), else the last line of its log `log_file`, with the
// exit status.
std::string failure_text(const std::filesystem::path& dir, const std::string& stage, const std::filesystem::path& log_file,
                         int exit_status, std::filesystem::file_time_type leg_start);

// `dir`/<stage>.failed after a failed leg (add_leg first: its wall time counts all legs so far).
void write_stage_failure(const std::filesystem::path& dir, const std::string& stage, const std::string& run_key,
                         const std::string& failure, int threads);

}  // namespace hydrojump::app
