// docs/validation.md, generated from the validation records (compare/record.hpp) by
// `hydrojump validation-doc`: per case, method and resolution the predicted numbers against the
// laboratory and the inputs-only values (Belanger), SPH against VOF, and the record and command behind
// every row. The same records give the same text, byte for byte (a test checks the committed file).
#pragma once

#include <string>
#include <vector>

#include "cases/spec.hpp"
#include "compare/record.hpp"

namespace hydrojump::compare {

// `records_root` is printed as the folder the records live in (e.g. "validation/records").
std::string validation_markdown(const std::vector<ValidationRecord>& records, const std::string& records_root);

// The headline table of README.md: one row per case and resolution with SPH and VOF side by side, each
// prediction against the laboratory (or Belanger on a smooth bed), SPH against VOF, and the targets met
// or missed.
std::string headline_markdown(const std::vector<ValidationRecord>& records);

// `text` with the lines between "<!-- validation-table:start -->" and "<!-- validation-table:end -->"
// replaced by `block`; throws RecordError naming `file_name` when the markers are missing.
std::string with_headline(const std::string& text, const std::string& block, const std::string& file_name);

// The stilling basins of `study` that have no record of a method at `resolution`, as a Markdown table
// with the size of each missing run (water area / dx^2 particles, cells from the VOF sizes, simulated time)
// and its wall time estimated from a timed record of the same method: one at `resolution` if there is one,
// else one at another resolution of the study (the scaling includes the resolution's sizes). Either way
// it ends with the whole study's time (measured plus estimated, and scheduled on two cores as
// `hydrojump study` runs it); when every basin has a current timed record of both methods it gives that
// time alone, measured, under "Every case run at"; empty when there is nothing to say.
std::string not_run_markdown(const cases::Study& study, const std::vector<ValidationRecord>& records,
                             const std::string& resolution);

}  // namespace hydrojump::compare
