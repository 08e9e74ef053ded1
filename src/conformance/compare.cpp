#include "conformance/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

#include "core/math.h"

namespace oceanref {

long long ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) {
    return (std::isnan(a) && std::isnan(b)) ? 0 : std::numeric_limits<long long>::max();
  }
  const auto ordered = [](float f) {
    std::int32_t i = 0;
    std::memcpy(&i, &f, sizeof i);
    return static_cast<long long>(i < 0 ? std::numeric_limits<std::int32_t>::min() - i : i);
  };
  return std::llabs(ordered(a) - ordered(b));
}

Comparison compare_images(const ExrImage& golden, const ExrImage& candidate,
                          const CompareThresholds& t) {
  if (golden.width != candidate.width || golden.height != candidate.height) {
    throw std::invalid_argument("the images differ in size: " + std::to_string(golden.width) + "x" +
                                std::to_string(golden.height) + " vs " +
                                std::to_string(candidate.width) + "x" +
                                std::to_string(candidate.height));
  }
  std::map<std::string, const ExrChannel*> other;
  for (const ExrChannel& c : candidate.channels) other[c.name] = &c;
  if (other.size() != golden.channels.size()) {
    throw std::invalid_argument("the images have different channel sets");
  }
  Comparison result;
  const auto pixels =
      static_cast<std::size_t>(golden.width) * static_cast<std::size_t>(golden.height);
  std::vector<char> failing(pixels, 0);
  result.difference.assign(pixels, 0.0f);
  for (const ExrChannel& a : golden.channels) {
    const auto it = other.find(a.name);
    if (it == other.end() || it->second->sampling != a.sampling) {
      throw std::invalid_argument("channel '" + a.name + "' is missing or sampled differently");
    }
    const ExrChannel& b = *it->second;
    ChannelMetrics m;
    m.name = a.name;
    const int width = golden.width / a.sampling;
    double sum_squares = 0.0;
    double peak = 0.0;
    std::size_t fails = 0;
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      const double x = static_cast<double>(a.values[i]);
      const double y = static_cast<double>(b.values[i]);
      const double d = std::fabs(x - y);
      const long long u = ulp_distance(a.values[i], b.values[i]);
      peak = std::max(peak, std::fabs(x));
      sum_squares += d * d;
      if (d > m.max_absolute || (std::isnan(d) && !std::isnan(m.max_absolute))) {
        m.max_absolute = d;
        m.worst_x = static_cast<int>(i % static_cast<std::size_t>(width));
        m.worst_y = static_cast<int>(i / static_cast<std::size_t>(width));
      }
      if (x != 0.0) m.max_relative = std::max(m.max_relative, d / std::fabs(x));
      m.max_ulp = std::max(m.max_ulp, u);
      const bool fail = (d > t.absolute + t.relative * std::fabs(x) || std::isnan(d)) && u > t.ulp;
      if (fail) ++fails;
      if (a.sampling == 1) {
        if (fail) failing[i] = 1;
        result.difference[i] = std::max(result.difference[i], static_cast<float>(d));
      }
    }
    m.rmse =
        std::sqrt(sum_squares / static_cast<double>(std::max<std::size_t>(1, a.values.size())));
    m.psnr =
        m.rmse > 0.0 ? 20.0 * math::log10(peak / m.rmse) : std::numeric_limits<double>::infinity();
    m.failing_share =
        static_cast<double>(fails) / static_cast<double>(std::max<std::size_t>(1, a.values.size()));
    if (m.failing_share > t.allowed_share) result.pass = false;
    result.channels.push_back(m);
  }
  std::size_t failing_pixels = 0;
  for (const char f : failing) failing_pixels += f != 0 ? 1 : 0;
  result.failing_share = static_cast<double>(failing_pixels) / static_cast<double>(pixels);
  if (result.failing_share > t.allowed_share) result.pass = false;
  return result;
}

}  // namespace oceanref
