// Image and field comparison for backend authors (`oceanref compare`): per channel the largest
// absolute and relative error, RMSE, PSNR, the largest ULP distance of the float32 values, the
// share of failing pixels and the worst pixel.
#pragma once

#include <string>
#include <vector>

#include "io/exr.h"

namespace oceanref {

struct CompareThresholds {
  double absolute = 0.0;  // a value fails if |a − b| > absolute + relative·|a| …
  double relative = 0.0;
  long long ulp = 0;           // … and its ULP distance exceeds ulp
  double allowed_share = 0.0;  // the images pass if at most this share of pixels fail
};

struct ChannelMetrics {
  std::string name;
  double max_absolute = 0.0;
  double max_relative = 0.0;  // |a − b|/|a| where a ≠ 0
  double rmse = 0.0;
  double psnr = 0.0;  // 20 log10(peak |a| / RMSE) [dB]; +inf when identical
  long long max_ulp = 0;
  double failing_share = 0.0;
  int worst_x = 0, worst_y = 0;  // in the channel's own (possibly subsampled) grid
};

struct Comparison {
  std::vector<ChannelMetrics> channels;
  double failing_share = 0.0;  // pixels failing in any channel (full-resolution channels)
  bool pass = true;
  std::vector<float> difference;  // per pixel the largest |a − b| over the RGB-sized channels
};

// Distance in units in the last place between two float32 values (ordered integer mapping);
// NaNs are infinitely far from everything but themselves.
long long ulp_distance(float a, float b);

// Throws std::invalid_argument when the images' sizes or channel sets differ.
Comparison compare_images(const ExrImage& golden, const ExrImage& candidate,
                          const CompareThresholds& thresholds);

}  // namespace oceanref
