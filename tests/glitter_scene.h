// A scene for the pixel-integral tests (test_pixel_error.cpp, test_adaptive_sampling.cpp):
// waves, sun glitter, sky and the horizon in 24×12 pixels, fast lighting (the pixel integral is
// the subject, not the lighting integrals).
#pragma once

#include <nlohmann/json.hpp>

namespace oceanref::testing {

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

}  // namespace oceanref::testing
