// The `record` and `validation-doc` commands: keep a study's finished comparisons as validation
// records (compare/record.hpp) and write docs/validation.md from them (compare/validation_doc.hpp).
#pragma once

#include <CLI/CLI.hpp>

namespace hydrojump::app {

void register_record_commands(CLI::App& app);

}  // namespace hydrojump::app
