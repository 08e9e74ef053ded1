// Three-component vectors of doubles: directions, positions, and RGB or XYZ triples, with the few
// operations the stages share. Each is written out component by component in a fixed order
// (no fused multiply-add: the build forbids contraction), so every caller gets the same bits.
#pragma once

#include <array>
#include <cmath>

namespace oceanref {

using Vec3 = std::array<double, 3>;

// a·b = a₀b₀ + a₁b₁ + a₂b₂, summed left to right.
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// a × b (right-handed).
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// |v| = √(v·v) (sqrt is correctly rounded everywhere; no hypot).
inline double length(const Vec3& v) {
  return std::sqrt(dot(v, v));
}

// v/|v|, each component divided by the length (a zero vector gives NaNs: callers check).
inline Vec3 normalize(const Vec3& v) {
  const double l = length(v);
  return {v[0] / l, v[1] / l, v[2] / l};
}

// a·v, component by component.
inline Vec3 scaled(const Vec3& v, double a) {
  return {a * v[0], a * v[1], a * v[2]};
}

// a·u + b·v and a·u + b·v + c·w, each component summed left to right.
inline Vec3 combine(double a, const Vec3& u, double b, const Vec3& v) {
  return {a * u[0] + b * v[0], a * u[1] + b * v[1], a * u[2] + b * v[2]};
}
inline Vec3 combine(double a, const Vec3& u, double b, const Vec3& v, double c, const Vec3& w) {
  return {a * u[0] + b * v[0] + c * w[0], a * u[1] + b * v[1] + c * w[1],
          a * u[2] + b * v[2] + c * w[2]};
}

}  // namespace oceanref
