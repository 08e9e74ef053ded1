// Double-double kernels shared between the portable elementary functions (core/math.h) — e.g.
// erfc needs e^{−x²} and lgamma needs ln x and sin(πx) to more than double precision. Internal
// to core/; the rest of the project calls core/math.h.
#pragma once

#include "core/double_double.h"

namespace oceanref::math {

// e^(x.hi + x.lo) as a double-double, relative error < 2^−100, for x.hi in [−745.2, 709.8]
// (a result below DBL_MIN may lose relative accuracy gradually, as a subnormal does).
// Defined in core/math_exp_log.cpp.
dd::DD exp_dd(dd::DD x);

// ln x as a double-double, absolute error < 2^−100·max(1, |ln x|), for finite x > 0 (subnormals
// included). Defined in core/math_exp_log.cpp.
dd::DD log_dd(double x);

// sin(πx) as a double-double, relative error < 2^−100, for every finite x with |x| ≥ 2^−967
// (below, the low part is subnormal and the relative accuracy degrades gradually; the high part
// stays correctly rounded). Exact reduction of x modulo 2; exact zeros at the integers with the
// sign of C's sinpi. Defined in core/math_trig.cpp.
dd::DD sinpi_dd(double x);

}  // namespace oceanref::math
