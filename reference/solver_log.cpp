#include "reference/solver_log.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace hydrojump::reference {

namespace {

// The number following `key` in `line` (strtod syntax, so "nan" and "inf" are read too).
std::optional<double> number_after(std::string_view line, std::string_view key) {
  const auto pos = line.find(key);
  if (pos == std::string_view::npos) return std::nullopt;
  std::string rest(line.substr(pos + key.size()));
  const char* begin = rest.c_str();
  while (*begin == ' ' || *begin == '\t') ++begin;
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) {
    // strtod does not read "-nan" on every libc; recognise it explicitly.
    std::string word;
    for (const char* p = begin; *p && !std::isspace(static_cast<unsigned char>(*p)); ++p) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(*p)));
    }
    if (word == "nan" || word == "-nan") return std::nan("");
    return std::nullopt;
  }
  return value;
}

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

}  // namespace

SolverLog::SolverLog(DivergenceLimits limits, std::size_t kept_lines)
    : limits_(limits), kept_lines_(std::max<std::size_t>(kept_lines, 1)) {}

void SolverLog::check_number(std::string_view what, double value) {
  if (!failure_.empty()) return;
  if (!std::isfinite(value)) {
    failure_ = std::string(what) + " is not a number (NaN/Inf)";
    if (time_s_) failure_ += " at t = " + std::to_string(*time_s_) + " s";
  }
}

void SolverLog::add_line(std::string_view line) {
  const bool failed_before = !failure_.empty();
  parse_line(line);
  if (!failed_before && !failure_.empty()) failure_context_ = tail();
}

void SolverLog::parse_line(std::string_view line) {
  last_lines_.emplace_back(line);
  while (last_lines_.size() > kept_lines_) last_lines_.pop_front();

  if (starts_with(line, "Time = ")) {
    if (auto t = number_after(line, "Time = ")) {
      // Without adjustable time steps there is no "deltaT =" line: use the difference of times.
      if (time_s_ && !saw_delta_t_) time_step_s_ = *t - *time_s_;
      saw_delta_t_ = false;
      time_s_ = *t;
      ++steps_;
      check_number("the simulated time", *t);
    }
  } else if (starts_with(line, "deltaT = ")) {
    if (auto dt = number_after(line, "deltaT = ")) {
      time_step_s_ = *dt;
      saw_delta_t_ = true;
      check_number("the time step", *dt);
      if (failure_.empty() && *dt < limits_.min_time_step_s) {
        failure_ = "the time step collapsed to " + std::to_string(*dt) + " s";
        if (time_s_) failure_ += " at t = " + std::to_string(*time_s_) + " s";
      }
    }
  } else if (starts_with(line, "Courant Number mean:") || starts_with(line, "Interface Courant Number mean:")) {
    const bool interface = starts_with(line, "Interface");
    if (auto co = number_after(line, "max:")) {
      (interface ? interface_courant_max_ : courant_max_) = *co;
      check_number(interface ? "the interface Courant number" : "the Courant number", *co);
      const double limit = std::max(limits_.courant_factor * limits_.max_courant, 5.0);
      if (failure_.empty() && *co > limit) {
        char buffer[200];
        std::snprintf(buffer, sizeof buffer,
                      "the %s Courant number blew up to %.3g (maxCo = %.3g)", interface ? "interface" : "flow",
                      *co, limits_.max_courant);
        failure_ = buffer;
        if (time_s_) failure_ += " at t = " + std::to_string(*time_s_) + " s";
      }
    }
  } else if (starts_with(line, "ExecutionTime = ")) {
    if (auto e = number_after(line, "ExecutionTime = ")) execution_time_s_ = *e;
  } else if (line.find("Foam::error::printStack") != std::string_view::npos) {
    if (failure_.empty()) {
      failure_ = "the solver crashed (stack trace in the log)";
      if (time_s_) failure_ += " at t = " + std::to_string(*time_s_) + " s";
    }
  } else if (line.find("FOAM FATAL") != std::string_view::npos) {
    if (failure_.empty()) failure_ = "OpenFOAM stopped with a fatal error";
  } else if (line.find("sigFpe::sigHandler") != std::string_view::npos ||
             (line.find("Floating point exception") != std::string_view::npos &&
              line.find("trapping") == std::string_view::npos)) {
    // (the banner line "trapFpe: Floating point exception trapping enabled" is not a crash)
    if (failure_.empty()) {
      failure_ = "the solver crashed with a floating-point exception";
      if (time_s_) failure_ += " at t = " + std::to_string(*time_s_) + " s";
    }
  } else if (line.find("Solving for") != std::string_view::npos) {
    if (auto r = number_after(line, "Initial residual = ")) check_number("a solver residual", *r);
  }
}

void SolverLog::add_text(std::string_view text) {
  partial_.append(text);
  std::size_t start = 0;
  while (true) {
    const auto nl = partial_.find('\n', start);
    if (nl == std::string::npos) break;
    add_line(std::string_view(partial_).substr(start, nl - start));
    start = nl + 1;
  }
  partial_.erase(0, start);
}

std::string SolverLog::tail() const {
  std::string out;
  for (const std::string& l : last_lines_) out += "    " + l + "\n";
  return out;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buffer[64];
  if (s < 60) {
    std::snprintf(buffer, sizeof buffer, "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  }
  return buffer;
}

}  // namespace hydrojump::reference
