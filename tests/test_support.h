// Small helpers several test files share (one definition each, so that the test files also
// compile as one translation unit: the unity build of oceanref_tests, tests/CMakeLists.txt).
#pragma once

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "io/exr.h"
#include "sky/preetham.h"

namespace oceanref::testing {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = kPi / 180.0;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kGravity = 9.81;  // m/s², the value the tests' spectra use

// |a − b| / |b|.
// tools/mutation.py runs the tests without the golden hashes (OCEANREF_TESTS_NO_GOLDENS=1): the
// comparisons with reference/golden/manifest.json are made only when this is true.
inline bool golden_hashes_checked() {
  const char* value = std::getenv("OCEANREF_TESTS_NO_GOLDENS");
  return value == nullptr || std::string(value) != "1";
}

inline double relative(double a, double b) {
  return std::fabs(a - b) / std::fabs(b);
}

// The unit direction at a zenith and azimuth given in degrees (sky/preetham.h's convention).
inline Vec3 direction_deg(double zenith_deg, double azimuth_deg) {
  return direction_from_angles(zenith_deg * kDeg, azimuth_deg * kDeg);
}

// Bitwise equality (−0 ≠ +0, a NaN equals itself when its bits do).
inline bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The channel of an image by name (throws when there is none).
inline const ExrChannel& channel(const ExrImage& image, const std::string& name) {
  for (const ExrChannel& c : image.channels) {
    if (c.name == name) return c;
  }
  throw std::runtime_error("no channel " + name);
}

}  // namespace oceanref::testing
