#include "waves/cascades.h"

#include <cmath>
#include <numbers>

namespace oceanref {

double golden_factor(GoldenFactor f) {
  const double inverse_phi = 2.0 / (1.0 + std::sqrt(5.0));  // φ⁻¹ = 0.618…
  return f == GoldenFactor::large ? inverse_phi : 1.0 - inverse_phi;
}

std::vector<double> golden_ratio_sizes(double largest, int count, GoldenFactor f) {
  std::vector<double> sizes;
  double size = largest;
  for (int i = 0; i < count; ++i) {
    sizes.push_back(size);
    size *= golden_factor(f);
  }
  return sizes;
}

double nyquist_wavenumber(double size, int resolution) {
  return std::numbers::pi * resolution / size;
}

std::vector<Band> cascade_bands(const std::vector<double>& sizes, int resolution, bool partitioned,
                                double k_max, const std::vector<double>& edges) {
  std::vector<Band> bands;
  double lower = 0.0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    Band b;
    if (partitioned) {
      b.lower = lower;
      b.upper = i < edges.size() ? edges[i] : nyquist_wavenumber(sizes[i], resolution);
      lower = b.upper;
    }
    b.upper = std::fmin(b.upper, k_max);
    b.lower = std::fmin(b.lower, b.upper);
    bands.push_back(b);
  }
  return bands;
}

}  // namespace oceanref
