// Command-line front end of the comparator: `hydrojump compare RUN_DIR` (see case_comparison.hpp for
// the function a study runner calls per case). `hydrojump study` is registered by study.hpp.
#pragma once

#include <CLI/CLI.hpp>

namespace hydrojump::compare {

// Adds `hydrojump compare RUN_DIR` to `app`.
void register_commands(CLI::App& app);

}  // namespace hydrojump::compare
