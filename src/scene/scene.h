// Scene files (DESIGN.md, "Scene files"): JSON validated strictly — unknown keys, wrong types,
// non-finite numbers, out-of-range values and sizes over the memory cap are rejected with the
// JSON path of the key. Sections: seed, time, waves, camera, grid, atmosphere, shading, render
// (objects is rejected as not supported yet). A valid key that does nothing for the scene is
// reported (Scene::unused, warnings of load_scene); tests/test_settings_reach.cpp checks that
// every other key changes the output.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "raster/renderer.h"
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

struct CameraSettings {
  glm::dvec3 position{0.0, 4.0, 0.0};
  glm::dvec3 look_at{0.0, 0.0, 200.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double vertical_fov_deg = 50.0;
};

struct AtmosphereSettings {
  double sun_zenith_deg = 75.0;
  double sun_azimuth_deg = 90.0;
  double turbidity = 2.5;
};

struct ImageSettings {
  int width = 640;
  int height = 360;
  int samples_per_axis = 2;  // samples_per_pixel = S²
  // Adaptive sampling (RenderJob::pixel_tolerance, max_refinements); 0: the fixed S×S grid.
  double pixel_tolerance = 0.0;
  int max_refinements = 0;
  PixelPattern pixel_pattern = PixelPattern::sobol;  // RenderJob::pixel_pattern
  bool footprint_filtering = false;                  // RenderJob::footprint_filtering
  double mastin_antialiasing = 0.0;                  // RenderJob::antialiasing_contrast (0: off)
  Renderer renderer = Renderer::raster;  // RenderJob::renderer (`render --renderer` overrides)
  double surface_tolerance = kDefaultSurfaceTolerance;  // RenderJob::surface_tolerance [pixels]
  double tone_key = 0.18;                               // Reinhard key a for the PNG preview
  double tone_white = 0.0;  // L_white for the preview; 0: the largest scaled luminance
};

// A key present in a scene file that does nothing for this scene (pbrt-v4's ReportUnused): e.g.
// a setting of a spectrum or mode the scene does not select. Keys of the other lighting mode,
// and spectrum parameters of another model, are errors instead (see parse_scene).
struct UnusedKey {
  std::string path;    // JSON path, e.g. "waves.spectrum.fetch"
  std::string reason;  // why it has no effect, e.g. "the phillips spectrum has no fetch"
};

// An object of the scene (`objects`): an OBJ mesh (its path as written in the scene; relative
// paths are relative to the scene file's folder, see Scene::directory), scaled, rotated about
// the x, then y, then z axis (right-handed, degrees) and moved to `position`.
struct ObjectSettings {
  std::string obj;
  glm::dvec3 position{0.0};
  glm::dvec3 rotation_deg{0.0};
  double scale = 1.0;
  ObjectMaterial material;
};
inline constexpr std::size_t kMaxSceneObjects = 64;

struct Scene {
  std::uint64_t seed = 1;
  double time = 0.0;  // s
  WaveSettings waves;
  FoamSequence foam;
  CameraSettings camera;
  ProjectedGridSettings grid;
  AtmosphereSettings atmosphere;
  ShadingSettings shading;
  ImageSettings image;
  std::vector<ObjectSettings> objects;
  // The folder relative object paths start from: the scene file's (load_scene), else empty (the
  // working directory).
  std::string directory;
  std::string canonical;          // the parsed document, dumped canonically (sorted keys): hashed
  std::vector<UnusedKey> unused;  // present keys without effect here, in scene_key_paths order
};

// The JSON path of every setting a scene file accepts (leaves, e.g. "waves.spectrum.fetch"), in
// document order: the parser's accepted keys of each object are derived from this list (the top
// level also holds `objects`, an array whose elements have their own keys: ObjectSettings).
const std::vector<std::string>& scene_key_paths();

// The camera and sky of a scene (the validated settings resolved).
Camera scene_camera(const Scene& scene);
Sky scene_sky(const Scene& scene);
// Whether the scene's render is the two-level estimate (RenderJob::lighting_correction): adaptive
// sampling (render.pixel_tolerance) of Bruneton's BRDF at reference accuracy.
bool two_level_lighting(const Scene& scene);
// Everything `render` needs from a scene and its realized ocean (which must outlive the job).
RenderJob scene_render_job(const Scene& scene, const Ocean& ocean, int threads);

// Parses scene text strictly (DESIGN.md, "Scene files"): one JSON value and nothing after it but
// whitespace; no NUL byte anywhere; no key twice in one object; every number finite as a double.
// Errors are SceneErrors naming the JSON path (e.g. "waves.cascades.sizes[1]") or, for syntax
// errors, `source` with the line and column; quoted input is escaped (core/format.h escape_value).
nlohmann::json parse_scene_json(std::string_view text, const std::string& source);

Scene parse_scene(const nlohmann::json& document);
// Reads and parses a scene file; errors name the file (parse errors) or the JSON path. Each key
// without effect (Scene::unused) is reported as one warning line on `warnings` (nullptr: none);
// the one-argument form reports on std::cerr.
Scene load_scene(const std::string& path, std::ostream* warnings);
Scene load_scene(const std::string& path);

// One override of a scene file's key on the command line (`render --set KEY=VALUE`): KEY the
// key's JSON path with dots (e.g. "shading.accuracy"; the objects on the way are created),
// VALUE a JSON value (a number, true, false, "text", [..], {..}) or else a bare word taken as a
// string; `null` removes the key (its default applies). Applied to the document before
// parse_scene, so the override is validated exactly as in a file and is part of the scene the
// outputs record (Scene::canonical). Errors are SceneErrors naming KEY.
void apply_scene_override(nlohmann::json& document, const std::string& assignment);
// load_scene with the overrides applied in order.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides,
                 std::ostream* warnings);

}  // namespace oceanref
