// Command-line checks shared by the subcommands (CLI11 validators). CLI11's own PositiveNumber lets
// "nan" and "inf" through and describes its range with a 300-digit number; this one does neither.
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

namespace hydrojump::util {

// A finite number > 0 ("0.5", "1e-3"); anything else is refused with the value it got.
inline CLI::Validator positive_finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(v) || !(v > 0.0))
          return "must be a finite number > 0, got '" + text + "'";
        return {};
      },
      "NUMBER > 0");
}

// A path that is not empty (an empty --out would write into the current directory).
inline CLI::Validator non_empty_path() {
  return CLI::Validator([](std::string& text) -> std::string { return text.empty() ? "must not be empty" : ""; }, "PATH");
}

}  // namespace hydrojump::util
