// Numbers as text for messages, summaries and tables.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace latfrac {

// `digits` significant digits, printf's %g (as a stream's setprecision(digits) prints).
inline std::string significant(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

// The fewest %g digits that read back as the same double.
inline std::string full_precision(double value) {
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

}  // namespace latfrac
