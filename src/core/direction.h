// A direction given by any nonzero finite vector, as a unit vector — the one normalization the
// command line, the Python module and the library share, so all give the same bits.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace oceanref {

// v/|v|, or nothing for the zero vector. Where |v|² would overflow (components ~1e154 and up) or
// lose digits to underflow (|v| < 1e-150), v is first divided by its largest |component| (exact
// in direction), so 1e308,1e308,0 and 1e-300,1e-300,0 give the same unit vector as 1,1,0; any
// other v is divided by its length directly.
inline std::optional<std::array<double, 3>> unit_direction(const std::array<double, 3>& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (length > 1e-150 && length < 1e150)
    return std::array{v[0] / length, v[1] / length, v[2] / length};
  const double scale = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  if (!(scale > 0.0) || !std::isfinite(scale)) return std::nullopt;
  const std::array<double, 3> w{v[0] / scale, v[1] / scale, v[2] / scale};
  const double w_length = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  return std::array{w[0] / w_length, w[1] / w_length, w[2] / w_length};
}

}  // namespace oceanref
