// The Preetham, Shirley, Smits 1999 daylight model ("A Practical Analytic Model for Daylight"):
// the Perez sky luminance distribution with turbidity-linear coefficients (§3.1, appendix A.2)
// and the spectral sun radiance after atmospheric transmittance (§3.2, appendix A.5).
//
// Conventions: +Y up; a direction's zenith angle θ = acos(d_y); the sun at zenith angle θ_s and
// azimuth φ_s is (sin θ_s cos φ_s, cos θ_s, sin θ_s sin φ_s) (azimuth from +X towards +Z, as the
// wind direction). Luminance in cd/m²; colours as CIE xyY or linear sRGB (D65) in cd/m².
//
// Validity: turbidity T ∈ [2, 10] (the range of Preetham's fits; below ~1.7 the Perez factor
// 1 + A e^{B/cos θ} turns negative at the zenith); sun zenith angle θ_s ∈ [0°, 90°]. Below the
// horizon (θ_s > 90°) the sun radiance is 0 and the sky keeps its θ_s = 90° limit. Directions
// below the horizon (d_y ≤ 0) see the sky's horizon limit: the Perez gradation factor
// 1 + A e^{B/cos θ} is held at its value 1 at θ = 90°, γ is that of the direction itself. This
// continuation is C^∞ across the horizon (every derivative of e^{B/cos θ} vanishes there as
// B < 0), so the reflection integrals see no jump where a tilted facet mirrors V below the
// horizon; physically such a ray meets the sea, whose grazing reflection (Fresnel → 1) shows the
// horizon.
#pragma once

#include "sky/color.h"

namespace oceanref {

inline constexpr double kMinTurbidity = 2.0;
inline constexpr double kMaxTurbidity = 10.0;
// The sun's mean apparent angular radius, 16′ = 0.2667° (Astronomical Almanac) [rad].
inline constexpr double kSunAngularRadius = 0.2667 * 3.141592653589793 / 180.0;
// Luminous efficacy of 555 nm light, 683 lm/W: spectral radiance [W/(m²·sr·nm)] → cd/m².
inline constexpr double kLuminousEfficacy = 683.0;

struct PerezCoefficients {
  double a, b, c, d, e;
};

// Preetham appendix A.2: the Perez coefficients for Y, x and y, linear in T.
PerezCoefficients perez_luminance_coefficients(double turbidity);
PerezCoefficients perez_x_coefficients(double turbidity);
PerezCoefficients perez_y_coefficients(double turbidity);
// F(θ, γ) = (1 + A e^{B/cos θ})(1 + C e^{Dγ} + E cos²γ)  (Preetham eq. 3, Perez et al. 1993);
// θ < 90°. The angles enter as cos θ, γ [rad] and cos γ, computed once per direction for the
// three coefficient sets (Y, x, y).
struct PerezAngles {
  double cos_theta, gamma, cos_gamma;
};
double perez(const PerezAngles& angles, const PerezCoefficients& k);
double perez(double theta, double gamma, const PerezCoefficients& k);
// Y_z = [(4.0453T − 4.9710) tan χ − 0.2155T + 2.4192]·1000 cd/m²,
// χ = (4/9 − T/120)(π − 2θ_s)  (Preetham appendix A.2; the paper's unit is kcd/m²).
double zenith_luminance(double turbidity, double sun_zenith);
// x_z, y_z = [T² T 1]·M·[θ_s³ θ_s² θ_s 1]ᵀ  (Preetham appendix A.2).
double zenith_chromaticity_x(double turbidity, double sun_zenith);
double zenith_chromaticity_y(double turbidity, double sun_zenith);

// A sky resolved once for a turbidity and a sun direction (validated).
struct Sky {
  double turbidity;
  Vec3 sun_direction;       // unit, towards the sun
  double sun_zenith;        // θ_s [rad] as given (may exceed π/2)
  double model_sun_zenith;  // min(θ_s, π/2): what the sky formulas use
  PerezCoefficients luminance, x, y;
  double zenith_luminance, zenith_x, zenith_y;
  // Per-sky constants of eq. 3–4: the sun as the model sees it and F(0, θ_s) for Y, x, y.
  Vec3 model_sun_direction;
  double perez_at_zenith_luminance, perez_at_zenith_x, perez_at_zenith_y;
};

// Throws std::invalid_argument naming the parameter and its range.
Sky make_sky(double turbidity, double sun_zenith, double sun_azimuth);
Vec3 direction_from_angles(double zenith, double azimuth);

struct Chromaticity {
  double x, y, Y;  // CIE xyY, Y in cd/m²
};
// Y = Y_z F(θ, γ)/F(0, θ_s), likewise x and y  (Preetham eq. 3–4); θ ≤ 90° (see above).
Chromaticity sky_chromaticity(const Sky& sky, const Vec3& direction);
Vec3 sky_radiance_xyz(const Sky& sky, const Vec3& direction);
Vec3 sky_radiance_rgb(const Sky& sky, const Vec3& direction);

// How the Rayleigh and aerosol transmittances are written: the physical Beer–Lambert form
// exp(−m·0.008735 λ^−4.08), exp(−m β λ^−α), or as printed in Preetham's appendix A.5,
// exp(−0.008735 λ^(−4.08 m)), exp(−β λ^(−α m)) (widely copied).
enum class TransmittanceForm { physical, printed };

// m = 1/(cos θ_s + 0.15 (93.885 − θ_s[°])^−1.253)  (Preetham A.5, after Kasten 1966).
double relative_optical_mass(double sun_zenith);
// β = 0.04608 T − 0.04586  (Preetham A.5, Ångström turbidity coefficient).
double angstrom_beta(double turbidity);
// Transmittances at wavelength λ [nm] for optical mass m (Preetham A.5, from Iqbal 1983):
double rayleigh_transmittance(double wavelength, double mass, TransmittanceForm form);
double aerosol_transmittance(double wavelength, double mass, double beta, TransmittanceForm form);
double ozone_transmittance(double wavelength, double mass);         // l = 0.35 cm
double mixed_gas_transmittance(double wavelength, double mass);     // O₂ band at 760 nm
double water_vapour_transmittance(double wavelength, double mass);  // w = 2 cm
// L_sun(λ) = S₀(λ) τ_R τ_a τ_o τ_g τ_wa  [W/(m²·sr·nm)]; S₀ = 0 outside 380–750 nm.
double sun_spectral_radiance(double wavelength, double sun_zenith, double turbidity,
                             TransmittanceForm form);
// The sun disk's radiance as XYZ [cd/m²]: 683 lm/W · ∫ L_sun (x̄, ȳ, z̄) dλ over 380–780 nm
// (trapezoid on the 5-nm observer grid); 0 when the sun is below the horizon.
Vec3 sun_radiance_xyz(const Sky& sky, TransmittanceForm form = TransmittanceForm::physical);
Vec3 sun_radiance_rgb(const Sky& sky, TransmittanceForm form = TransmittanceForm::physical);

// Horizontal irradiance of the sky dome E = ∫ L cos θ dω over the upper hemisphere [lx for Y],
// per XYZ component, by adaptive Gauss–Kronrod quadrature in θ and φ (relative tolerance given;
// the achieved error estimate is returned). The sun disk is not included.
struct SkyIrradiance {
  Vec3 xyz;
  Vec3 rgb;
  double relative_error;  // largest estimated relative error of the three components
};
SkyIrradiance sky_irradiance(const Sky& sky, double relative_tolerance = 1e-9);

}  // namespace oceanref
