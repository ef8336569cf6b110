// The `record` and `validation-doc` commands: keep a study's finished comparisons as validation
// records (compare/record.hpp) and write docs/validation.md from them (compare/validation_doc.hpp).
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

namespace hydrojump::app {

void register_record_commands(CLI::App& app);

// The study file a resolved case came from, as a record's `hydrojump study` command names it:
// "default" for the embedded study; a file under `working_dir` relative to it (a record made from the
// repository root names cases/ead2002.toml, wherever the clone lies); any other path as the study was
// given it. The resolved case's first line reads "# Resolved by hydrojump from FILE: case ...";
// "SPEC" when it does not.
std::string study_command_argument(const std::filesystem::path& resolved_case, const std::filesystem::path& working_dir);

}  // namespace hydrojump::app
