// Command-line front end of the comparator and the study runner: `compare` and `study`.
#pragma once

#include <CLI/CLI.hpp>

namespace hydrojump::compare {

// Adds `hydrojump compare RUN_DIR` and `hydrojump study SPEC` to `app`.
void register_commands(CLI::App& app);

}  // namespace hydrojump::compare
