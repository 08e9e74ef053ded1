#include "sky/color.h"

namespace oceanref {

Vec3 xyY_to_XYZ(double x, double y, double Y) {
  if (!(y > 0.0) || Y == 0.0) return {0.0, 0.0, 0.0};
  return {x * Y / y, Y, (1.0 - x - y) * Y / y};
}

namespace {
Matrix3 inverse(const Matrix3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Matrix3 r{};
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}
}  // namespace

Matrix3 xyz_to_linear_srgb_matrix() {
  // Columns: XYZ of the primaries with Y = 1, scaled so that R = G = B = 1 is the white.
  const Vec3 r = xyY_to_XYZ(0.64, 0.33, 1.0);
  const Vec3 g = xyY_to_XYZ(0.30, 0.60, 1.0);
  const Vec3 b = xyY_to_XYZ(0.15, 0.06, 1.0);
  const Matrix3 primaries{{{r[0], g[0], b[0]}, {r[1], g[1], b[1]}, {r[2], g[2], b[2]}}};
  const Vec3 white = xyY_to_XYZ(0.3127, 0.3290, 1.0);
  const Matrix3 inv = inverse(primaries);
  Vec3 s{};
  for (std::size_t i = 0; i < 3; ++i) {
    s[i] = inv[i][0] * white[0] + inv[i][1] * white[1] + inv[i][2] * white[2];
  }
  Matrix3 m{};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) m[i][j] = primaries[i][j] * s[j];
  }
  return inverse(m);
}

Vec3 xyz_to_linear_srgb(const Vec3& xyz) {
  static const Matrix3 m = xyz_to_linear_srgb_matrix();  // a constant, derived once
  Vec3 rgb{};
  for (std::size_t i = 0; i < 3; ++i)
    rgb[i] = m[i][0] * xyz[0] + m[i][1] * xyz[1] + m[i][2] * xyz[2];
  return rgb;
}

}  // namespace oceanref
