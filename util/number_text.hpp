// The text of a number in messages and in the resolved case text: the shortest decimal (%g with
// 6 to 17 significant digits) that reads back to the same double, so a range or a value quoted in an
// error is exactly the one checked ("0.1", not "0.10000000000000001"; "1e-06"; "nan", "inf").
// Example:
//   throw std::runtime_error("--station-spacing " + util::number_text(ds) + " m is coarser than y1");
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace hydrojump::util {

inline std::string number_text(double v) {
  char buffer[64];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, v);
    if (std::strtod(buffer, nullptr) == v) break;
  }
  return buffer;
}

}  // namespace hydrojump::util
