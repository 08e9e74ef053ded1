// Spectral data tables of the sky and sun model, each with its source (spectral_tables.cpp).
// Wavelengths in nm.
#pragma once

#include <array>
#include <vector>

namespace oceanref {

struct ColorMatchingSample {
  double wavelength;  // nm
  double x, y, z;     // x̄, ȳ, z̄
};
extern const std::array<ColorMatchingSample, 81> kCie1931Observer;

// Extraterrestrial solar spectral radiance, 380, 390, …, 750 nm. Preetham prints the unit as
// W/(cm²·µm·sr); with that unit the table integrates to a tenth of the solar constant. Times
// 100 it is W/(m²·sr·nm) and reproduces the measured extraterrestrial irradiance (tested):
// that is the unit used here.
extern const std::array<double, 38> kExtraterrestrialSolarRadiance;
inline constexpr double kSolarRadianceUnit = 100.0;  // table value → W/(m²·sr·nm)

struct SpectralPoint {
  double wavelength;  // nm
  double value;
};
extern const std::vector<SpectralPoint> kOzoneAbsorption;        // k_o [1/cm]
extern const std::vector<SpectralPoint> kMixedGasAbsorption;     // k_g [1/km]
extern const std::vector<SpectralPoint> kWaterVapourAbsorption;  // k_wa [1/cm]

// Linear interpolation in a table (wavelengths increasing); 0 outside it, NaN for a NaN
// wavelength.
double interpolate(const std::vector<SpectralPoint>& table, double wavelength);

}  // namespace oceanref
