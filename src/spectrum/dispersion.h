// Dispersion relations ω(k): deep water, finite depth, gravity-capillary.
// Units: k in rad/m, ω in rad/s, speeds in m/s, depth in m (+∞ for deep water).
#pragma once

#include <array>
#include <limits>

#include "core/choice.h"

namespace oceanref {

enum class DispersionKind { deep, finite_depth, capillary };
inline constexpr std::array<Choice<DispersionKind>, 3> kDispersionKinds{{
    {DispersionKind::deep, "deep"},
    {DispersionKind::finite_depth, "finite-depth"},
    {DispersionKind::capillary, "capillary"},
}};

// One dispersion relation and its physical constants.
struct Dispersion {
  DispersionKind kind = DispersionKind::deep;
  double gravity = 9.81;                                   // g [m/s²]
  double depth = std::numeric_limits<double>::infinity();  // h [m], +∞ = deep water
  double capillary_wavenumber = 370.0;                     // k_m [rad/m] (Gamper §3.4, Unified)
};

// ω(k) [rad/s] for k ≥ 0; ω(0) = 0.
double angular_frequency(const Dispersion& d, double k);
// dω/dk [m/s], the group velocity, for k ≥ 0 (finite at k = 0 except in deep water: +∞).
double group_velocity(const Dispersion& d, double k);
// ω/k [m/s], the phase speed, for k ≥ 0 (the k → 0 limit at k = 0).
double phase_speed(const Dispersion& d, double k);
// The inverse k(ω) [rad/m] for ω ≥ 0, exact to a few ulp (ω(k) is strictly increasing).
double wavenumber_from_frequency(const Dispersion& d, double omega);

// tanh(kh) and sech²(kh), written so that kh = ∞ and kh → 0 stay exact and finite.
double depth_factor(double kh);
double depth_factor_derivative(double kh);

}  // namespace oceanref
