// Adaptive Gauss–Kronrod (7/15-point) quadrature with an error estimate. Deterministic: the
// interval with the largest error is split first, ties broken by position, and the sum is
// taken in a fixed order.
#pragma once

#include <functional>
#include <vector>

namespace oceanref {

struct QuadratureResult {
  double value = 0.0;
  double error = 0.0;  // estimated absolute error (sum of |K15 − G7| over intervals)
  int evaluations = 0;
  bool converged = false;  // error ≤ max(absolute, relative·|value|) within the interval budget
};

struct QuadratureTolerance {
  double relative = 1e-10;
  double absolute = 0.0;
  int max_intervals = 4000;
};

// ∫ f over [b0, b_last] split first at the given breakpoints (ascending). The last breakpoint
// may be +∞ when the one before it is > 0: that piece is mapped by x = a/t, t ∈ (0, 1].
QuadratureResult integrate(const std::function<double(double)>& f,
                           const std::vector<double>& breakpoints,
                           const QuadratureTolerance& tolerance = {});

// A fixed-order rule: nodes and weights.
struct QuadratureRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

// The largest order gauss_legendre and gauss_hermite accept.
inline constexpr int kMaxQuadratureOrder = 1024;

// Gauss–Legendre on [−1, 1]: ∫ f dx ≈ Σ w_i f(x_i), exact for degree ≤ 2n − 1. Nodes ascending,
// x_i = −x_{n−1−i} exactly. Golub–Welsch starting values polished by Newton's method on the
// Legendre recurrence in double-double: nodes and weights within about ½ ulp for every order
// 1 … kMaxQuadratureOrder; any other order throws std::invalid_argument.
QuadratureRule gauss_legendre(int order);
// Gauss–Hermite: ∫ e^{−t²} f(t) dt ≈ Σ w_i f(t_i), exact for degree ≤ 2n − 1. Nodes descending,
// t_i = −t_{n−1−i} exactly. Golub–Welsch starting values polished by Newton's method on the
// orthonormal Hermite recurrence in double-double, weights 2/H̃_n'(t_i)² with an exponent kept
// apart: within about ½ ulp for every order 1 … kMaxQuadratureOrder, except that weights below
// the normal range (≈ e^{−t²} < 2^−1022, the outer nodes from order 371) are subnormal or 0.
// Any other order throws std::invalid_argument.
QuadratureRule gauss_hermite(int order);

}  // namespace oceanref
