// Scene files (DESIGN.md, "Scene files"): JSON validated strictly — unknown keys, wrong types,
// non-finite numbers, out-of-range values and sizes over the memory cap are rejected with the
// JSON path of the key. This version reads the sections `seed`, `time` and `waves`; the other
// sections of the contract (camera, grid, atmosphere, shading, render, objects) are rejected as
// not yet supported rather than silently ignored.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "waves/ocean.h"

namespace oceanref {

// A scene value that is invalid: `path` is the JSON path (e.g. "waves.spectrum.wind_speed").
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string path, const std::string& message)
      : std::runtime_error(path + ": " + message), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

struct Scene {
  std::uint64_t seed = 1;
  double time = 0.0;  // s
  WaveSettings waves;
  FoamSequence foam;
};

// The memory cap for wave grids (bytes): scenes whose grids would need more are rejected.
inline constexpr double kWaveMemoryCap = 8.0 * 1024 * 1024 * 1024;

Scene parse_scene(const nlohmann::json& document);
// Reads and parses a scene file; errors name the file (parse errors) or the JSON path.
Scene load_scene(const std::string& path);

}  // namespace oceanref
