#include "shading/tone_mapping.h"

#include <cmath>

#include "core/math.h"

namespace oceanref {

double relative_luminance(const Vec3& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

double log_average_luminance(const std::vector<Vec3>& image, double delta) {
  if (image.empty()) return 0.0;
  double sum = 0.0;
  for (const Vec3& c : image) sum += log_luminance_term(c, delta);
  return math::exp(sum / static_cast<double>(image.size()));
}

double log_luminance_term(const Vec3& rgb, double delta) {
  return math::log(delta + std::fmax(relative_luminance(rgb), 0.0));
}

Vec3 reinhard(const Vec3& rgb, double log_average, double key, double white) {
  const double lw = relative_luminance(rgb);
  if (!(lw > 0.0) || !(log_average > 0.0)) return {0.0, 0.0, 0.0};
  const double l = key / log_average * lw;
  const double ld = l * (1.0 + l / (white * white)) / (1.0 + l);
  const double scale = ld / lw;
  return {rgb[0] * scale, rgb[1] * scale, rgb[2] * scale};
}

double automatic_key(double adaptation_luminance) {
  return 1.03 - 2.0 / (2.0 + math::log10(adaptation_luminance + 1.0));
}

double adaptation_time_constant(double luminance) {
  const double rod = 0.04 / (0.04 + luminance);
  return rod * 0.4 + (1.0 - rod) * 0.1;
}

double adapt_luminance(double adapted, double scene, double time_step) {
  return adapted +
         (scene - adapted) * (1.0 - math::exp(-time_step / adaptation_time_constant(adapted)));
}

double srgb_encode(double linear) {
  const double c = std::fmin(std::fmax(linear, 0.0), 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * math::pow(c, 1.0 / 2.4) - 0.055;
}

}  // namespace oceanref
