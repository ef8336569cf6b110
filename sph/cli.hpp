// Command-line front end of the SPH solver: the `sph` and `bench` subcommands of `hydrojump`, and
// the writer of the SPH half of a generated case directory.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "cases/spec.hpp"

namespace hydrojump::sph {

// Adds `hydrojump sph DIR` (run a generated case) and `hydrojump bench` to `app`.
void register_commands(CLI::App& app);

// Writes what `hydrojump sph` reads into `dir` (DIR/<case>/sph/): the resolved case spec and the
// initial particle set for inspection. `dir` is created.
void write_sph_input(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                     const std::filesystem::path& dir);

}  // namespace hydrojump::sph
