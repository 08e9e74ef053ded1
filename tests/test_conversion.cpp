// The change of variables S(ω) → Ψ(k) → Θ(k) (Gamper eq. 3.58–3.61, generalized to every
// dispersion relation) conserves energy: ∫S dω = ∫Ψ dk = ∬Θ dk_x dk_z = m0.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "spectrum/model.h"
#include "spectrum/moments.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::kPi;
const QuadratureTolerance kConversionTolerance{1e-11, 0.0, 4000};

double frequency_integral(const Spectrum& s) {
  std::vector<double> b{0.0};
  for (int j = -6; j <= 12; ++j) b.push_back(std::ldexp(s.peak_frequency, j));
  b.push_back(HUGE_VAL);
  return integrate([&](double w) { return frequency_spectrum(s, w); }, b, kConversionTolerance)
      .value;
}

double wavenumber_integral(const Spectrum& s) {
  return integrate([&](double k) { return wavenumber_spectrum(s, k); },
                   wavenumber_breakpoints(s, HUGE_VAL), kConversionTolerance)
      .value;
}

// ∬Θ(k_x, k_z) dk_x dk_z in polar coordinates: ∫ k [∫ Θ(k cos θ, k sin θ) dθ] dk, calling the
// Cartesian Θ itself, so the 1/k of eq. 3.60 and dω/dk of eq. 3.58 are both exercised.
double wavevector_integral(const Spectrum& s) {
  const QuadratureTolerance inner{1e-12, 0.0, 4000};
  return integrate(
             [&](double k) {
               const double phi = s.wind_direction;
               return k * integrate(
                              [&](double t) {
                                return wavevector_spectrum(s, k * std::cos(t + phi),
                                                           k * std::sin(t + phi));
                              },
                              {-kPi, -0.5 * kPi, 0.0, 0.5 * kPi, kPi}, inner)
                              .value;
             },
             wavenumber_breakpoints(s, HUGE_VAL), kConversionTolerance)
      .value;
}
}  // namespace

TEST_CASE(
    "energy is conserved between S(omega), Psi(k) and Theta(k) for every model and "
    "dispersion") {
  // Quadrature tolerance 1e−11 (relative) on each side; a mismatch above 1e−7 would be a
  // missing or wrong Jacobian (the error Gamper §5.2 describes), which is O(1).
  for (const SpectrumModel m :
       {SpectrumModel::phillips, SpectrumModel::pierson_moskowitz, SpectrumModel::jonswap,
        SpectrumModel::tma, SpectrumModel::donelan, SpectrumModel::unified}) {
    for (const DispersionKind d :
         {DispersionKind::deep, DispersionKind::finite_depth, DispersionKind::capillary}) {
      SpectrumSettings in;
      in.model = m;
      in.dispersion = d;
      in.depth = 4.0;
      in.wind_direction = 0.3;
      in.fetch = 3.0e4;
      const Spectrum s = make_spectrum(in);
      CAPTURE(to_string(m));
      CAPTURE(to_string(d));
      const double by_k = wavenumber_integral(s);
      CHECK(by_k > 0.0);
      CHECK(std::fabs(frequency_integral(s) - by_k) < 1e-7 * by_k);
      CHECK(std::fabs(wavevector_integral(s) - by_k) < 1e-7 * by_k);
    }
  }
}

TEST_CASE("Theta(k) has the units and symmetry the conversion implies") {
  // Deep water, wind along +x: Θ at k along the wind equals Ψ(k)·D(0)/k (eq. 3.61).
  SpectrumSettings in;
  in.model = SpectrumModel::pierson_moskowitz;
  const Spectrum s = make_spectrum(in);
  const double k = 0.2;
  CHECK(wavevector_spectrum(s, k, 0.0) ==
        doctest::Approx(wavenumber_spectrum(s, k) * spreading_at_wavenumber(s, k, 0.0) / k)
            .epsilon(1e-15));
  // Ψ(k) = S(√(gk))·½√(g/k) in deep water (eq. 3.58, verbatim).
  CHECK(wavenumber_spectrum(s, k) ==
        doctest::Approx(frequency_spectrum(s, std::sqrt(9.81 * k)) * 0.5 * std::sqrt(9.81 / k))
            .epsilon(1e-15));
  CHECK(wavevector_spectrum(s, 0.0, 0.0) == 0.0);
}
