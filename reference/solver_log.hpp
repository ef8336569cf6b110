// Reading an interFoam log as it is written: simulated time, time step, Courant numbers, and the signs
// of a run going wrong (divergence, a crash), for progress lines with an ETA and for stopping a run
// that has blown up with a diagnosis.
//
// Lines recognised (OpenFOAM v1912 interFoam):
//   Courant Number mean: 0.0108 max: 0.0959
//   Interface Courant Number mean: 0.0127 max: 0.436
//   deltaT = 0.000123
//   Time = 1.461
//   ExecutionTime = 39.7 s  ClockTime = 40 s
//   --> FOAM FATAL ERROR / FOAM FATAL IO ERROR / Floating point exception / nan in any number
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <string_view>

namespace hydrojump::reference {

// Thresholds of the divergence checks.
struct DivergenceLimits {
  double max_courant = 0.8;        // the run's maxCo (the solver keeps Co near it when healthy)
  double courant_factor = 25.0;    // Co above max(courant_factor * max_courant, 5) is a blow-up
  double min_time_step_s = 1e-9;   // a time step collapsing below this is a blow-up
};

class SolverLog {
 public:
  explicit SolverLog(DivergenceLimits limits = {}, std::size_t kept_lines = 40);

  // Feeds one line (without the newline).
  void add_line(std::string_view line);
  // Feeds a chunk of text; incomplete last lines are kept until the rest arrives.
  void add_text(std::string_view text);

  std::optional<double> time_s() const { return time_s_; }          // latest "Time ="
  std::optional<double> time_step_s() const { return time_step_s_; }  // latest "deltaT ="
  std::optional<double> courant_max() const { return courant_max_; }
  std::optional<double> interface_courant_max() const { return interface_courant_max_; }
  std::optional<double> execution_time_s() const { return execution_time_s_; }
  long steps() const { return steps_; }                              // "Time =" lines seen

  // Non-empty once the log shows divergence or a crash: a one-line diagnosis.
  const std::string& failure() const { return failure_; }
  bool failed() const { return !failure_.empty(); }
  // The last lines (for error reports).
  std::string tail() const;
  // The last lines up to the line that showed the failure (empty while not failed).
  const std::string& failure_context() const { return failure_context_; }

 private:
  void parse_line(std::string_view line);
  void check_number(std::string_view what, double value);
  DivergenceLimits limits_;
  std::size_t kept_lines_;
  std::deque<std::string> last_lines_;
  std::string partial_;
  std::optional<double> time_s_, time_step_s_, courant_max_, interface_courant_max_, execution_time_s_;
  long steps_ = 0;
  bool saw_delta_t_ = false;
  std::string failure_;
  std::string failure_context_;
};

// Formats a duration for progress lines: "42 s", "3 min 05 s", "1 h 02 min".
std::string format_duration(double seconds);

}  // namespace hydrojump::reference
