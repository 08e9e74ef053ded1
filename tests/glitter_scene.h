// Scenes for the pixel-integral tests (test_pixel_error.cpp, test_adaptive_sampling.cpp,
// test_footprint_filter.cpp), with fast lighting (the pixel integral is the subject, not the
// lighting integrals).
#pragma once

#include <nlohmann/json.hpp>

namespace oceanref::testing {

// Waves, sun glitter, sky and the horizon in 24×12 pixels.
inline nlohmann::json glitter_scene_json(int samples_per_pixel) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "seed": 3,
    "waves": {"spectrum": {"model": "jonswap", "wind_speed": 8, "fetch": 50000},
              "cascades": {"largest": 150, "count": 2, "factor": "golden-small"},
              "resolution": 32, "choppiness": -0.8},
    "camera": {"position": [0, 3, 0], "look_at": [0, 1.2, 40], "vertical_fov_deg": 40},
    "grid": {"columns": 96, "rows": 96},
    "atmosphere": {"sun_zenith_deg": 75, "sun_azimuth_deg": 90},
    "shading": {"accuracy": "fast"},
    "render": {"width": 24, "height": 12}})");
  s["render"]["samples_per_pixel"] = samples_per_pixel;
  return s;
}

// The default scene (reference/scenes/default.json) at 48×27 with fast lighting.
inline nlohmann::json default_scene_reduced_json(int samples_per_pixel) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "seed": 1,
    "waves": {
      "spectrum": {"model": "jonswap", "wind_speed": 10, "fetch": 100000, "wind_direction_deg": 80},
      "spreading": {"model": "hasselmann"},
      "cascades": {"largest": 800, "count": 4, "factor": "golden-small"},
      "resolution": 256, "low_resolution": 128, "choppiness": -0.8},
    "camera": {"position": [0, 6, 0], "look_at": [0, 2, 100], "up": [0, 1, 0],
               "vertical_fov_deg": 50},
    "grid": {"columns": 512, "rows": 512, "margin": 0.15},
    "atmosphere": {"sun_zenith_deg": 78, "sun_azimuth_deg": 85, "turbidity": 2.5},
    "shading": {"whitecaps": true, "accuracy": "fast", "interpolation": "bicubic"},
    "render": {"width": 48, "height": 27}})");
  s["render"]["samples_per_pixel"] = samples_per_pixel;
  return s;
}

}  // namespace oceanref::testing
