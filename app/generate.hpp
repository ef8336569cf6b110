// `hydrojump check` and `hydrojump generate`: validate a study, print derived quantities, and write the
// case directories of both solvers.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cases/spec.hpp"

namespace hydrojump::app {

// The study named on a command line: a file, or "default" / "embedded" for the built-in study.
cases::Study load_spec_argument(const std::string& spec);

// Prints every case of `study` with its derived quantities (q, Fr1, y2*, E1, eta, ...).
void print_study_summary(const cases::Study& study, std::ostream& out);

// The cases called `ids` (all cases when empty). Throws cases::SpecError naming unknown ids.
std::vector<const cases::Case*> select_cases(const cases::Study& study,
                                             const std::vector<std::string>& ids);

// Validates the selected cases at `resolution` as `generate` does before it writes anything: the
// spec's rules, then what only the solvers' derivations find (particle generation, gates, the
// OpenFOAM mesh plan; each case is written once into a scratch directory that is removed again).
// Throws cases::SpecError naming the spec file, the case and the resolution.
void check_cases(const cases::Study& study, const std::vector<const cases::Case*>& selected,
                 const std::string& resolution);

// Writes DIR/<case>/sph/ and DIR/<case>/vof/ for each selected case at `resolution`, after
// validating every selected case at that resolution first (nothing is written if one fails).
void generate_cases(const cases::Study& study, const std::vector<const cases::Case*>& selected,
                    const std::string& resolution, const std::filesystem::path& out_dir,
                    std::ostream& log);

// Adds `check` and `generate` to `app`.
void register_case_commands(CLI::App& app);

}  // namespace hydrojump::app
