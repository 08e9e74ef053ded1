// Dispersion relations: closed forms, limits, derivatives and the inverse.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "spectrum/dispersion.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::relative;
const Dispersion kDeep{DispersionKind::deep, 9.81, HUGE_VAL, 370.0};
Dispersion finite_depth(double h) {
  return {DispersionKind::finite_depth, 9.81, h, 370.0};
}
Dispersion capillary(double h = HUGE_VAL) {
  return {DispersionKind::capillary, 9.81, h, 370.0};
}
}  // namespace

TEST_CASE("deep water: omega = sqrt(gk), c = omega/k, group velocity = c/2") {
  for (const double k : {1e-6, 0.01, 1.0, 100.0, 1e5}) {
    const double w = std::sqrt(9.81 * k);
    CHECK(angular_frequency(kDeep, k) == w);
    CHECK(relative(phase_speed(kDeep, k), w / k) < 1e-15);
    CHECK(relative(group_velocity(kDeep, k), 0.5 * w / k) < 1e-15);
  }
  CHECK(angular_frequency(kDeep, 0.0) == 0.0);
  CHECK(std::isinf(group_velocity(kDeep, 0.0)));
}

TEST_CASE("finite depth tends to deep water as kh grows and to sqrt(gh) k as kh -> 0") {
  // kh ≥ 20: tanh(kh) = 1 − 2e^{−40} = 1 in double, so the relations agree to rounding.
  for (const double k : {0.02, 0.5, 7.0}) {
    CHECK(relative(angular_frequency(finite_depth(1000.0 / k), k), angular_frequency(kDeep, k)) <
          1e-15);
    CHECK(relative(group_velocity(finite_depth(1000.0 / k), k), group_velocity(kDeep, k)) < 1e-15);
  }
  // Shallow: ω = k√(gh)·(1 − (kh)²/6 + …); at kh = 1e−4 the relative gap is 1.7e−9.
  const double h = 2.0;
  const double k = 5e-5;
  CHECK(relative(angular_frequency(finite_depth(h), k), k * std::sqrt(9.81 * h)) < 2e-9);
  CHECK(relative(group_velocity(finite_depth(h), k), std::sqrt(9.81 * h)) < 1e-8);
  CHECK(group_velocity(finite_depth(h), 0.0) == std::sqrt(9.81 * h));
  CHECK(phase_speed(finite_depth(h), 0.0) == std::sqrt(9.81 * h));
}

TEST_CASE("gravity-capillary: deep-water limit and Lamb's minimum phase speed c_m = 0.23 m/s") {
  // ω_cap/ω_deep = √(1 + (k/k_m)²) ≈ 1 + (k/k_m)²/2: 3.7e−9 at k = 0.01 rad/m.
  CHECK(relative(angular_frequency(capillary(), 0.01), angular_frequency(kDeep, 0.01)) < 4e-10);
  // With depth, the tanh(kh) factor of Alimardanov eq. 2.9 applies as well.
  CHECK(relative(angular_frequency(capillary(3.0), 0.4),
                 std::sqrt(9.81 * 0.4 * (1.0 + 0.4 * 0.4 / (370.0 * 370.0)) *
                           std::tanh(0.4 * 3.0))) < 1e-15);
  // The minimum of c(k) = √(g(1 + (k/k_m)²)/k) lies at k = k_m with c = √(2g/k_m) = 0.2303 m/s;
  // published c_m = 0.23 m/s (Gamper §3.4, Lamb 1945): agreement to the 2 digits printed.
  const double c_min = phase_speed(capillary(), 370.0);
  CHECK(c_min < phase_speed(capillary(), 369.0));
  CHECK(c_min < phase_speed(capillary(), 371.0));
  CHECK(std::fabs(c_min - 0.23) < 0.005);
}

TEST_CASE("group velocity is the derivative of omega(k)") {
  // Central differences with step 1e−5·k: truncation ~1e−10, rounding ~1e−11 relative.
  for (const Dispersion& d :
       {kDeep, finite_depth(0.3), finite_depth(20.0), capillary(), capillary(0.05)}) {
    for (const double k : {0.003, 0.1, 2.0, 50.0, 400.0, 3000.0}) {
      const double step = 1e-5 * k;
      const double numeric =
          (angular_frequency(d, k + step) - angular_frequency(d, k - step)) / (2.0 * step);
      CHECK(relative(group_velocity(d, k), numeric) < 1e-8);
    }
  }
}

TEST_CASE("k(omega) inverts omega(k) for every relation, depth and wavenumber") {
  for (const Dispersion& d : {kDeep, finite_depth(0.01), finite_depth(0.5), finite_depth(40.0),
                              capillary(), capillary(0.2)}) {
    for (double k = 1e-5; k < 1e5; k *= 3.7) {
      const double w = angular_frequency(d, k);
      CHECK(relative(wavenumber_from_frequency(d, w), k) < 1e-14);
    }
  }
  CHECK(wavenumber_from_frequency(finite_depth(1.0), 0.0) == 0.0);
}

TEST_CASE("k(omega): a first bracket end that is already the root is returned as it is") {
  // Capillary waves in deep water at small ω: (k/k_m)² vanishes beside 1 at k = ω²/g, so
  // ω(ω²/g) rounds to ω itself for many ω; there the inverse's bracket [0, ω²/g] ends at the
  // root and it must return ω²/g unchanged (a search that widened the bracket first would land
  // within 2 ulp of it, not on it).
  const Dispersion d = capillary();
  int exact = 0;
  for (double w = 1e-6; w < 1e-2; w *= 1.01) {
    const double k = w * w / 9.81;
    if (angular_frequency(d, k) != w) continue;
    ++exact;
    CAPTURE(w);
    CHECK(wavenumber_from_frequency(d, w) == k);
  }
  CHECK(exact > 100);
}

TEST_CASE("tiny frequencies: the shallow-water limit k = omega/sqrt(gh) holds down to subnormals") {
  // ω(k) = k·c(k) keeps ω > 0 where g·k·tanh(kh) would underflow; the inverse must terminate
  // and return the shallow limit (relative error of the limit ~ (kh)²/6, far below 1e-14 here).
  for (const Dispersion& d : {finite_depth(0.01), finite_depth(1.0), capillary(3.0)}) {
    for (const double w : {1e-300, 1e-200, 1e-100, 1e-20}) {
      CHECK(relative(wavenumber_from_frequency(d, w), w / std::sqrt(9.81 * d.depth)) < 1e-14);
      CHECK(relative(angular_frequency(d, w / std::sqrt(9.81 * d.depth)), w) < 1e-14);
    }
    CHECK(wavenumber_from_frequency(d, std::numeric_limits<double>::denorm_min()) >= 0.0);
  }
  CHECK(wavenumber_from_frequency(kDeep, 1e-300) == 0.0);  // ω²/g underflows
}
