#include "spectrum/moments.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/check.h"
#include "core/format.h"
#include "core/math.h"

namespace oceanref {

namespace {
constexpr double kPi = std::numbers::pi;

void require_converged(const QuadratureResult& r, const char* what) {
  if (r.converged) return;
  throw std::runtime_error(std::string(what) +
                           " did not converge (the integral may diverge: spectra with a k⁻³ "
                           "tail need a finite k_max for the slope moments)");
}
}  // namespace

std::vector<double> wavenumber_breakpoints(const Spectrum& s, double k_max) {
  std::vector<double> b{0.0};
  for (int j = -6; j <= 12; ++j) {
    const double k = std::ldexp(s.peak_wavenumber, j);
    if (k < k_max) b.push_back(k);
  }
  if (s.model == SpectrumModel::unified && s.unified.capillary_wavenumber < k_max) {
    b.push_back(s.unified.capillary_wavenumber);  // the gravity-capillary peak at k_m
    std::sort(b.begin(), b.end());
  }
  b.push_back(k_max);
  return b;
}

QuadratureResult integrate_over_direction(const Spectrum& s, double k,
                                          const std::function<double(double)>& weight,
                                          const QuadratureTolerance& tolerance) {
  const double phi = s.wind_direction;
  // Integrate over θ' = θ − φ ∈ [−π, π], split at the peak and at ±π/2.
  const std::vector<double> b{-kPi, -0.5 * kPi, 0.0, 0.5 * kPi, kPi};
  const SpreadingAt d = spreading_at(s, angular_frequency(s.dispersion, k), k);
  return integrate([&](double t) { return weight(t + phi) * directional_spreading(d, t + phi); }, b,
                   tolerance);
}

QuadratureResult zeroth_moment(const Spectrum& s, double k_max,
                               const QuadratureTolerance& tolerance) {
  const QuadratureResult m0 = integrate([&](double k) { return wavenumber_spectrum(s, k); },
                                        wavenumber_breakpoints(s, k_max), tolerance);
  require_converged(m0, "m0");
  return m0;
}

SpectralMoments spectral_moments(const Spectrum& s, double k_max,
                                 const QuadratureTolerance& tolerance) {
  if (!(k_max > 0.0 && (k_max <= kMaxMomentWavenumber || k_max == HUGE_VAL))) {
    throw std::invalid_argument("spectral_moments: k_max must be in (0, 1e6] rad/m or inf, got " +
                                format_number(k_max));
  }
  SpectralMoments m;
  const std::vector<double> b = wavenumber_breakpoints(s, k_max);
  const QuadratureResult m0 = zeroth_moment(s, k_max, tolerance);
  // mss_x = ∫ k² Ψ(k) [∫ cos²θ D dθ] dk and likewise with sin²θ (eq. A.1 in polar form).
  QuadratureTolerance inner = tolerance;
  inner.relative = tolerance.relative * 0.1;
  auto slope_moment = [&](bool along_x) {
    return integrate(
        [&](double k) {
          const double psi = wavenumber_spectrum(s, k);
          if (psi == 0.0) return 0.0;
          const QuadratureResult d = integrate_over_direction(
              s, k,
              [along_x](double theta) {
                const double c = along_x ? math::cos(theta) : math::sin(theta);
                return c * c;
              },
              inner);
          return k * k * psi * d.value;
        },
        b, tolerance);
  };
  const QuadratureResult mx = slope_moment(true);
  require_converged(mx, "mss_x");
  const QuadratureResult mz = slope_moment(false);
  require_converged(mz, "mss_z");
  m.m0 = m0.value;
  m.m0_error = m0.error;
  m.significant_wave_height = 4.0 * std::sqrt(m0.value);
  m.mss_x = mx.value;
  m.mss_x_error = mx.error;
  m.mss_z = mz.value;
  m.mss_z_error = mz.error;
  m.mss = mx.value + mz.value;
  return m;
}

namespace {
// ∫_{k_lo}^{k_hi} k² Ψ(k) ∫ g(θ − φ) D(k, θ) dθ dk for a weight g of the angle to the wind.
double band_direction_moment(const Spectrum& s, double k_lo, double k_hi,
                             const std::function<double(double)>& weight, const char* name,
                             const QuadratureTolerance& tolerance, double inner_absolute = 0.0) {
  OCEANREF_EXPECTS(k_lo >= 0.0, "a band starts at a wavenumber >= 0, got " + std::to_string(k_lo));
  if (!(k_hi > k_lo)) return 0.0;
  std::vector<double> b{k_lo};
  for (const double k : wavenumber_breakpoints(s, k_hi)) {
    if (k > k_lo && k < k_hi) b.push_back(k);
  }
  b.push_back(k_hi);  // a band to ∞ keeps a finite breakpoint: k_lo > 0 or k_p·2⁻⁶
  QuadratureTolerance inner = tolerance;
  inner.relative = tolerance.relative * 0.1;
  inner.absolute = inner_absolute;
  const double phi = s.wind_direction;
  const QuadratureResult r = integrate(
      [&](double k) {
        const double psi = wavenumber_spectrum(s, k);
        if (psi == 0.0) return 0.0;
        return k * k * psi *
               integrate_over_direction(
                   s, k, [&](double theta) { return weight(theta - phi); }, inner)
                   .value;
      },
      b, tolerance);
  require_converged(r, name);
  return r.value;
}
}  // namespace

SlopeVariance band_slope_variance(const Spectrum& s, double k_lo, double k_hi,
                                  const QuadratureTolerance& tolerance) {
  const auto cos2 = [](double t) { return math::cos(t) * math::cos(t); };
  const auto sin2 = [](double t) { return math::sin(t) * math::sin(t); };
  return {band_direction_moment(s, k_lo, k_hi, cos2, "upwind slope variance", tolerance),
          band_direction_moment(s, k_lo, k_hi, sin2, "crosswind slope variance", tolerance)};
}

JacobianMoments band_jacobian_moments(const Spectrum& s, double k_lo, double k_hi,
                                      const QuadratureTolerance& tolerance) {
  // c^a s^b of the angle to the wind, a + b = 4.
  const auto term = [&](int a, const char* name, const QuadratureTolerance& tol,
                        double inner_absolute) {
    return band_direction_moment(
        s, k_lo, k_hi,
        [a](double t) {
          const math::SinCos cs = math::sincos(t);
          double v = 1.0;
          for (int i = 0; i < 4; ++i) v *= i < a ? cs.cos : cs.sin;
          return v;
        },
        name, tol, inner_absolute);
  };
  JacobianMoments m;
  m.aaaa = term(4, "Jacobian moment along^4", tolerance, 0.0);
  m.aacc = term(2, "Jacobian moment along^2 across^2", tolerance, 0.0);
  m.cccc = term(0, "Jacobian moment across^4", tolerance, 0.0);
  // The odd ones vanish for a spreading symmetric about the wind: each integral to an absolute
  // error (relative to the band's slope variance; inside, to |g| ≤ 1 times ∫D dθ = 1) instead of
  // a relative one it could not meet.
  QuadratureTolerance odd = tolerance;
  odd.absolute = std::fmax(odd.absolute, tolerance.relative * (m.aaaa + 2.0 * m.aacc + m.cccc));
  m.aaac = term(3, "Jacobian moment along^3 across", odd, 0.1 * tolerance.relative);
  m.accc = term(1, "Jacobian moment along across^3", odd, 0.1 * tolerance.relative);
  return m;
}

}  // namespace oceanref
