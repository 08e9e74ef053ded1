// The adaptive Gauss–Kronrod integrator against closed forms.
#include <doctest/doctest.h>

#include <cmath>

#include "spectrum/quadrature.h"

using namespace oceanref;

TEST_CASE("Kronrod 15 is exact for polynomials of degree <= 22, Gauss 7 for <= 13") {
  // One interval, no subdivision: a tolerance of 1 accepts the first estimate. Exactness of the
  // rule (to rounding, 1e-15) checks every abscissa and weight of the table.
  const QuadratureTolerance one_shot{1.0, 1.0, 1};
  for (int degree = 0; degree <= 22; ++degree) {
    const QuadratureResult r = integrate(
        [degree](double x) { return (degree + 1) * std::pow(x, degree); }, {0.0, 1.0}, one_shot);
    CHECK(r.value == doctest::Approx(1.0).epsilon(1e-14));
    // |K15 − G7| vanishes while G7 is exact too (degree ≤ 13).
    if (degree <= 13) CHECK(r.error < 1e-14);
  }
}

TEST_CASE("adaptive integration reaches the requested relative accuracy") {
  // ∫0^∞ e^{−x} dx = 1 with the mapped tail from x = 1.
  const QuadratureResult e = integrate([](double x) { return std::exp(-x); }, {0.0, 1.0, HUGE_VAL});
  CHECK(e.converged);
  CHECK(std::fabs(e.value - 1.0) < 1e-12);
  // ∫1^∞ x^−3 dx = 1/2 (the tail shape of every spectrum in k).
  const QuadratureResult t = integrate([](double x) { return 1.0 / (x * x * x); }, {1.0, HUGE_VAL});
  CHECK(std::fabs(t.value - 0.5) < 1e-12);
  // A narrow peak: ∫ exp(−x²/(2·0.01²)) over [−1, 1] = 0.01·√(2π).
  const QuadratureResult g = integrate(
      [](double x) { return std::exp(-0.5 * (x / 0.01) * (x / 0.01)); }, {-1.0, 0.3, 1.0});
  CHECK(std::fabs(g.value - 0.01 * std::sqrt(2.0 * M_PI)) < 1e-12);
}

TEST_CASE("a divergent integral is reported as not converged") {
  // ∫1^∞ dx/x diverges logarithmically: the estimate must not claim convergence.
  const QuadratureResult r = integrate([](double x) { return 1.0 / x; }, {1.0, HUGE_VAL});
  CHECK_FALSE(r.converged);
}
