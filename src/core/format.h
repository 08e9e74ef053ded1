// Exact number printing shared by the library's text outputs (CSV tables, EXR attributes) and
// the command line; values quoted in error messages, escaped for a terminal.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace oceanref {

// 17 significant digits (round-trips every double), "inf"/"-inf"/"nan" for the rest.
inline std::string format_number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// The fewest significant digits that read back as `v` (0.1, not 0.10000000000000001); whole
// numbers below 1e15 in plain digits (1000, not 1e+03). For messages: ranges and echoed values.
inline std::string shortest_number(double v) {
  if (!std::isfinite(v)) return v > 0 ? "inf" : (v < 0 ? "-inf" : "nan");
  char buffer[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    if (std::strtod(buffer, nullptr) == v) break;
  }
  if (std::string_view(buffer).find('e') != std::string_view::npos && v == std::floor(v) &&
      std::fabs(v) < 1e15) {
    std::snprintf(buffer, sizeof buffer, "%.0f", v);
  }
  return buffer;
}

// A value quoted in an error message (scene files, the command line), safe for a terminal:
// printable ASCII as is, every other byte (control bytes, NUL, DEL, all bytes of non-ASCII text)
// as \xNN and a backslash as \\; text over `max_bytes` bytes is cut there and ends with "…".
inline std::string escape_value(std::string_view text, std::size_t max_bytes = 64) {
  static const char* const hex = "0123456789ABCDEF";
  std::string out;
  const std::size_t n = std::min(text.size(), max_bytes);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\\') {
      out += "\\\\";
    } else if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xF];
    }
  }
  if (text.size() > max_bytes) out += "\u2026";
  return out;
}

}  // namespace oceanref
