// Command-line front end of the SPH solver: the `sph` and `bench` subcommands of `hydrojump`, and
// the writer of the SPH half of a generated case directory.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "cases/spec.hpp"

namespace hydrojump::sph {

// What `hydrojump sph DIR` was asked to do.
struct SphOptions {
  std::string dir;            // holds case.toml (written by `generate` / write_sph_input)
  bool resume = false;        // continue from DIR/checkpoint.bin
  bool restart = false;       // start over although DIR holds a run
  int threads = 0;            // 0: OpenMP default
  double end_time = 0.0;      // > 0: stop at this time instead of the case's end_time_s
  bool quiet = false;         // no progress line
};

// Runs the case in opt.dir. Returns 0 when finished, 128 + signal number when stopped by
// SIGINT/SIGTERM (after writing a checkpoint). Throws SimulationFailure (sph/run.hpp) when the run goes
// unstable, std::runtime_error / cases::SpecError on bad input.
int run_sph_directory(const SphOptions& opt);

// The fingerprint stored in a run's checkpoints: of the case text (case.toml) and the solver code (solver_fingerprint),
// ignoring sph.max_density_variation and sph.checkpoint_interval_wall_s (run control, not physics),
// so that --resume accepts a relaxed stability limit.
std::string run_fingerprint(const std::string& case_text);

// Adds `hydrojump sph DIR` (run a generated case) and `hydrojump bench` to `app`.
void register_commands(CLI::App& app);

// Writes what `hydrojump sph` reads into `dir` (DIR/<case>/sph/): the resolved case spec and the
// initial particle set for inspection. `dir` is created.
void write_sph_input(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                     const std::filesystem::path& dir);

}  // namespace hydrojump::sph
