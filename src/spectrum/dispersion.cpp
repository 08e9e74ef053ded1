#include "spectrum/dispersion.h"

#include <cmath>
#include <limits>

#include "core/math.h"

namespace oceanref {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

bool has_depth(const Dispersion& d) {
  return d.kind != DispersionKind::deep && std::isfinite(d.depth);
}
// 1 + (k/k_m)² — the surface-tension factor of the gravity-capillary relation (Gamper §3.4).
double capillary_factor(const Dispersion& d, double k) {
  if (d.kind != DispersionKind::capillary) return 1.0;
  const double r = k / d.capillary_wavenumber;
  return 1.0 + r * r;
}
// d/dk of k·(1 + (k/k_m)²) = 1 + 3(k/k_m)².
double capillary_factor_derivative(const Dispersion& d, double k) {
  if (d.kind != DispersionKind::capillary) return 1.0;
  const double r = k / d.capillary_wavenumber;
  return 1.0 + 3.0 * r * r;
}
}  // namespace

// tanh(x) for x ≥ 0; tanh(∞) = 1.
double depth_factor(double kh) {
  return std::isinf(kh) ? 1.0 : math::tanh(kh);
}

// sech²(x) = 4e^{−2x}/(1 + e^{−2x})² for x ≥ 0: no overflow of cosh for large x.
double depth_factor_derivative(double kh) {
  const double e = math::exp(-2.0 * kh);
  return 4.0 * e / ((1.0 + e) * (1.0 + e));
}

namespace {
// tanh(kh)/k = h·tanh(kh)/kh [m], exact as kh → 0 (no underflow of k·h for tiny k).
double depth_factor_over_k(const Dispersion& d, double k) {
  const double kh = k * d.depth;
  return kh < 1e-8 ? d.depth : depth_factor(kh) / k;
}
}  // namespace

// c = ω/k = √(g·(1 + (k/k_m)²)·tanh(kh)/k); the k → 0 limits: √(gh) with depth, +∞ without;
// k → ∞: 0, or +∞ with capillarity.
double phase_speed(const Dispersion& d, double k) {
  if (k <= 0.0) return has_depth(d) ? std::sqrt(d.gravity * d.depth) : kInf;
  if (std::isinf(k)) return d.kind == DispersionKind::capillary ? kInf : 0.0;
  if (!has_depth(d)) return std::sqrt(d.gravity * capillary_factor(d, k) / k);
  return std::sqrt(d.gravity * capillary_factor(d, k) * depth_factor_over_k(d, k));
}

// ω² = g·k·(1 + (k/k_m)²)·tanh(kh)  (Alimardanov eq. 2.7–2.9; Gamper §3.4 with k_m = 370 rad/m).
// Deep: tanh → 1 and no capillary term; finite depth: no capillary term. With a depth,
// ω = k·c(k), so that ω stays > 0 for every k > 0 (g·k·tanh(kh) would underflow).
double angular_frequency(const Dispersion& d, double k) {
  if (k <= 0.0) return 0.0;
  if (std::isinf(k)) return kInf;
  if (has_depth(d)) return k * phase_speed(d, k);
  return std::sqrt(d.gravity * k * capillary_factor(d, k));
}

// dω/dk = g·[c'(k)·tanh(kh) + k·c(k)·h·sech²(kh)] / (2ω), with c the capillary factor
// (derivative of the relation above), evaluated as g·[c'·tanh(kh)/k + c·h·sech²(kh)] / (2ω/k).
// The k → 0 limits: √(gh) with depth, +∞ without.
double group_velocity(const Dispersion& d, double k) {
  if (k <= 0.0) return has_depth(d) ? std::sqrt(d.gravity * d.depth) : kInf;
  if (std::isinf(k)) return phase_speed(d, k);  // the k → ∞ limits: 0, or ∞ with capillarity
  if (!has_depth(d)) {
    return d.gravity * capillary_factor_derivative(d, k) / (2.0 * angular_frequency(d, k));
  }
  const double dw2_over_k =
      d.gravity * (capillary_factor_derivative(d, k) * depth_factor_over_k(d, k) +
                   capillary_factor(d, k) * d.depth * depth_factor_derivative(k * d.depth));
  return dw2_over_k / (2.0 * phase_speed(d, k));
}

// Inverse of ω(k): Newton's method kept inside a shrinking bracket [lo, hi] (ω is strictly
// increasing in k), falling back to bisection; a fixed stopping rule makes it deterministic.
double wavenumber_from_frequency(const Dispersion& d, double omega) {
  if (!(omega > 0.0)) return 0.0;
  if (std::isinf(omega)) return kInf;
  const double k_deep = omega * omega / d.gravity;
  if (d.kind == DispersionKind::deep || std::isinf(k_deep)) return k_deep;
  double lo = 0.0;
  double hi = k_deep;
  if (has_depth(d)) hi = std::fmax(hi, omega / std::sqrt(d.gravity * d.depth));
  if (hi == 0.0) return 0.0;  // ω so small that k ≈ ω/√(gh) or ω²/g underflows to 0
  while (angular_frequency(d, hi) < omega) {
    lo = hi;
    hi *= 2.0;
    if (std::isinf(hi)) return kInf;
  }
  double k = hi;
  for (int iteration = 0; iteration < 300; ++iteration) {
    const double f = angular_frequency(d, k) - omega;
    if (f == 0.0) return k;
    if (f > 0.0) {
      hi = k;
    } else {
      lo = k;
    }
    double next = k - f / group_velocity(d, k);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - k) <= 2.0 * std::numeric_limits<double>::epsilon() * next) return next;
    k = next;
  }
  return k;
}

}  // namespace oceanref
