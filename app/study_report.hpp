// The study's results as it ran them (each case's stages, their states and wall times) and the study
// report written from them: OUT/study_report.md with the table across cases, OUT/eta_summary.csv and
// the eta bar chart (app/study.hpp runs the study).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "app/study.hpp"
#include "cases/spec.hpp"

namespace hydrojump::app {

// One stage of a case as the study ended it.
struct StageResult {
  std::string stage;
  std::string state;     // "done", "cached", "failed", "stopped", "skipped", "earlier run"
  double seconds = 0.0;
  int exit_status = 0;
  std::string message;   // why a stage failed before it could run
};

struct CaseResult {
  std::string id;
  std::vector<StageResult> stages;
  bool failed() const {
    for (const auto& s : stages) {
      if (s.state == "failed") return true;
    }
    return false;
  }
};

// "42s", "3m07s", "1h05m": a wall time for the log and the report.
std::string duration_text(double seconds);

// OUT/study_report.md (the results across `results`' cases from their comparisons, the eta bars, each
// stage's state and wall time, the study's citations) and OUT/eta_summary.csv; a plot that could not
// be made is said in the report and in `log`.
void write_study_report(const StudyOptions& options, const cases::Study& study,
                        const std::vector<CaseResult>& results, std::ostream& log);

}  // namespace hydrojump::app
