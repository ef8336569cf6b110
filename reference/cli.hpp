// Command-line front end of the OpenFOAM interFoam reference: the `vof` subcommand of `hydrojump`,
// and the writer of the VOF half of a generated case directory.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "cases/spec.hpp"

namespace hydrojump::reference {

// Adds `hydrojump vof DIR` (mesh and run a generated OpenFOAM case) to `app`.
void register_commands(CLI::App& app);

// Writes the complete OpenFOAM case (0/, constant/, system/, Allrun, case.toml and its copy
// generated_case_file_name, case_writer.hpp) into `dir` (DIR/<case>/vof/). `dir` is created.
void write_vof_case(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                    const std::filesystem::path& dir);

}  // namespace hydrojump::reference
