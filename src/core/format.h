// Exact number printing shared by the library's text outputs (CSV tables, EXR attributes) and
// the command line.
#pragma once

#include <cstdio>
#include <string>

namespace oceanref {

// 17 significant digits (round-trips every double), "inf"/"-inf"/"nan" for the rest.
inline std::string format_number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace oceanref
