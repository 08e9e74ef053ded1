// Objects in the scene (issue 17; Alimardanov 2022 puts whales and dolphins in the sea): triangle
// meshes placed in the world, each with a diffuse material. Both renderers see them — the
// rasterizer as depth-tested triangles beside the sea's, the ray tracer as a second bounds tree —
// and the ray tracer also in the sea's reflection (raster/renderer.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace oceanref {

// A Lambertian surface: its reflectance per linear sRGB channel, in [0, 1].
struct ObjectMaterial {
  std::array<double, 3> albedo{0.5, 0.5, 0.5};
};

// Every object's triangles in world space (metres, +Y up), one list for all objects.
struct SceneObjects {
  std::vector<glm::dvec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // into positions
  std::vector<std::uint32_t> material;                  // per triangle, into materials
  std::vector<ObjectMaterial> materials;                // per object
};

}  // namespace oceanref
