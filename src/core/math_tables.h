// The generated polynomial tables of the special functions (core/math_special.cpp, written by
// tools/math_tables/special.py), exposed so that a test can evaluate each stored piece against
// an independent multiple-precision library (tests/math_tables_check.cpp, MPFR). Not for use
// outside core/math_special.cpp and that test.
#pragma once

#include <span>

#include "core/double_double.h"

namespace oceanref::math::tables {

// A polynomial piece: f(centre + t) ≈ Σ c_i t^i for x in [x_min, x_max]; the first n_dd
// coefficients are double-doubles (hi, lo), the others doubles; centre = hi + lo + lo2.
struct Piece {
  double x_min, x_max;
  double centre_hi, centre_lo, centre_lo2;
  int n_dd, degree, offset;
};

// One table: its name (the function it approximates, as tools/math_tables/special.py fits it),
// its pieces and their coefficients.
struct PieceTable {
  const char* name;
  std::span<const Piece> pieces;
  const double* coefs;
};

// erf_small: g(u) = erf(√u)/√u; erf; erfcx: e^{x²} erfc x; lgamma: ln Γ(x); stirling:
// W(z) = x [ln Γ(x) − (x − ½) ln x + x − ½ ln 2π] with x = 1/√z; lgamma_neg_zero: ln|Γ(x)|.
std::span<const PieceTable> special_piece_tables();
// 2^{j/128} = hi + lo, j = 0..127 (Tang's table).
std::span<const dd::DD> exp2_table();

}  // namespace oceanref::math::tables
