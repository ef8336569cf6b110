// Loading and validating a study spec (TOML, read with toml++).
//
// Every rejection is a SpecError whose message names the file, the line, the full key, the value and
// the allowed range, e.g.
//   cases/ead2002.toml:42: case "A": inflow.depth_m = -0.01 is out of range: must be > 0 and <= 10 (m)
// Unknown keys, wrong types, missing required keys and non-physical values are all rejected; nothing
// is written by any command while a spec fails validation.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "cases/spec.hpp"

namespace hydrojump::cases {

class SpecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a spec is read for. "run": every check. "read_results": a resolved case.toml of a finished run
// read back to compare its results; the rules that only guard how a new run is set up (the SPH inflow
// buffer's whole rows) are skipped, so run directories made before them still
// compare.
enum class SpecPurpose { run, read_results };

// Reads and validates a study file. Throws SpecError.
Study load_study(const std::filesystem::path& file, SpecPurpose purpose = SpecPurpose::run);

// Same, from text; `source_name` stands for the file in messages, and relative data paths
// (dam-break measurements) are resolved against `base_dir`.
Study parse_study(std::string_view toml_text, const std::string& source_name,
                  const std::filesystem::path& base_dir, SpecPurpose purpose = SpecPurpose::run);

// The default study compiled into the program (cases/ead2002.toml), for `hydrojump study` without a
// file, and its text.
std::string_view embedded_default_study_text();
Study load_embedded_default_study();

// Validation that depends on the chosen resolution (e.g. the corrugation wavelength must span at
// least 4 particle spacings, y1 at least 5). Throws SpecError naming the case and resolution.
void validate_for_resolution(const Study& study, const Case& c, const std::string& resolution);

inline constexpr const char* kResolvedFrontFileName = "measured_front.csv";

// Writes a single-case study file that reproduces `c` exactly at resolution `resolution` (all
// defaults made explicit), so a run directory carries its resolved spec. Written atomically. A dam
// break's measured front (case.measured.front_file) is copied beside it as kResolvedFrontFileName
// and named relatively, so the directory can be moved.
void write_resolved_case(const Study& study, const Case& c, const std::string& resolution,
                         const std::filesystem::path& out_file);

// The text write_resolved_case writes (used to detect whether a case changed between runs).
std::string resolved_case_text(const Study& study, const Case& c, const std::string& resolution);

}  // namespace hydrojump::cases
