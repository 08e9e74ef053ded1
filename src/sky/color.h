// Colour conversions: CIE xyY → XYZ → linear sRGB (D65), the output space of oceanref
// (DESIGN.md: linear radiance in cd/m² per channel of linear sRGB).
#pragma once

#include <array>

#include "core/vec3.h"

namespace oceanref {

using Matrix3 = std::array<Vec3, 3>;

// X = xY/y, Z = (1 − x − y)Y/y  (CIE 015:2018 §7.3); Y = 0 or y = 0 → black.
Vec3 xyY_to_XYZ(double x, double y, double Y);

// The XYZ → linear sRGB matrix derived from the sRGB primaries R (0.64, 0.33),
// G (0.30, 0.60), B (0.15, 0.06) and the D65 white (0.3127, 0.3290) (IEC 61966-2-1):
// the rows are ( 3.2409699, −1.5373832, −0.4986108), (−0.9692436, 1.8759675, 0.0415551),
// ( 0.0556301, −0.2039770, 1.0569715) to 7 digits; Y of D65 white → (1, 1, 1).
Matrix3 xyz_to_linear_srgb_matrix();
Vec3 xyz_to_linear_srgb(const Vec3& xyz);

}  // namespace oceanref
