#include "conformance/sequence.h"

#include <cmath>
#include <stdexcept>

#include "shading/tone_mapping.h"

namespace oceanref {

Scene frame_scene(const Scene& scene, int frame, double fps) {
  Scene s = scene;
  s.time = scene.time + frame / fps;
  return s;
}

double metered_luminance(const Scene& frame_scene, int threads) {
  Scene m = frame_scene;
  m.image.width = std::max(1, (m.image.width + kMeteringDivisor - 1) / kMeteringDivisor);
  m.image.height = std::max(1, (m.image.height + kMeteringDivisor - 1) / kMeteringDivisor);
  m.image.samples_per_axis = 1;
  m.image.pixel_tolerance = 0.0;
  m.image.max_refinements = 0;
  m.image.mastin_antialiasing = 0.0;
  m.shading.accuracy = LightingAccuracy::fast;
  RenderOutputOptions options;
  options.threads = threads;
  return log_average_luminance(render_scene(m, options).image.radiance);
}

std::vector<SequenceFrame> adaptation_through(const Scene& scene, int last, double fps, int threads,
                                              const std::function<void(const std::string&)>& log) {
  std::vector<SequenceFrame> frames;
  for (int k = 0; k <= last; ++k) {
    if (log) {
      log("metering frame " + std::to_string(k) + " of 0.." + std::to_string(last) +
          " (temporal adaptation)");
    }
    SequenceFrame f;
    f.index = k;
    f.fps = fps;
    const Scene s = frame_scene(scene, k, fps);
    f.time = s.time;
    f.metered_luminance = metered_luminance(s, threads);
    f.adapted_luminance =
        k == 0 ? f.metered_luminance
               : adapt_luminance(frames.back().adapted_luminance, f.metered_luminance, 1.0 / fps);
    f.key = automatic_key(f.adapted_luminance);
    frames.push_back(f);
  }
  return frames;
}

namespace {
// The last run of '#' in a pattern: [first, end).
std::pair<std::size_t, std::size_t> hash_run(const std::string& pattern) {
  const std::size_t end = pattern.find_last_of('#');
  if (end == std::string::npos) {
    throw std::invalid_argument(
        "expected a '#' run for the frame number (e.g. ocean_####.exr), got '" + pattern + "'");
  }
  std::size_t first = end;
  while (first > 0 && pattern[first - 1] == '#') --first;
  return {first, end + 1};
}
}  // namespace

std::string frame_path(const std::string& pattern, int frame) {
  const auto [first, end] = hash_run(pattern);
  std::string number = std::to_string(frame);
  if (number.size() < end - first) number.insert(0, end - first - number.size(), '0');
  return pattern.substr(0, first) + number + pattern.substr(end);
}

std::string ffmpeg_pattern(const std::string& pattern) {
  const auto [first, end] = hash_run(pattern);
  // A literal '%' is "%%" to ffmpeg.
  const auto escaped = [](const std::string& text) {
    std::string out;
    for (const char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
  };
  return escaped(pattern.substr(0, first)) + "%0" + std::to_string(end - first) + "d" +
         escaped(pattern.substr(end));
}

}  // namespace oceanref
