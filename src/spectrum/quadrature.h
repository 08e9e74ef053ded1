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
// Gauss–Legendre on [−1, 1]: ∫ f dx ≈ Σ w_i f(x_i), exact for degree ≤ 2n − 1 (Newton on the
// Legendre recurrence).
QuadratureRule gauss_legendre(int order);
// Gauss–Hermite: ∫ e^{−t²} f(t) dt ≈ Σ w_i f(t_i), exact for degree ≤ 2n − 1 (Newton on the
// orthonormal Hermite recurrence, Golub–Welsch weights 2/(H̃_n')²).
QuadratureRule gauss_hermite(int order);

}  // namespace oceanref
