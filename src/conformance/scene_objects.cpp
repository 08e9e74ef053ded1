#include "conformance/scene_objects.h"

#include <filesystem>
#include <numbers>

#include "core/math.h"
#include "io/obj_mesh.h"

namespace oceanref {

namespace {
// v rotated by `angle` [rad] about one world axis (0: x, 1: y, 2: z), right-handed.
glm::dvec3 rotate_about(const glm::dvec3& v, int axis, double angle) {
  const double c = math::cos(angle), s = math::sin(angle);
  switch (axis) {
    case 0:
      return {v.x, c * v.y - s * v.z, s * v.y + c * v.z};
    case 1:
      return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
    default:
      return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
  }
}
}  // namespace

glm::dvec3 object_to_world(const ObjectSettings& object, const glm::dvec3& local) {
  glm::dvec3 p = object.scale * local;
  for (int axis = 0; axis < 3; ++axis) {
    p = rotate_about(p, axis, object.rotation_deg[axis] * (std::numbers::pi / 180.0));
  }
  return object.position + p;
}

std::string object_path(const Scene& scene, const ObjectSettings& object) {
  const std::filesystem::path obj(object.obj);
  if (obj.is_absolute() || scene.directory.empty()) return obj.string();
  return (std::filesystem::path(scene.directory) / obj).string();
}

SceneObjects load_scene_objects(const Scene& scene) {
  SceneObjects out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectSettings& object = scene.objects[i];
    const std::string key = "objects[" + std::to_string(i) + "].obj";
    ObjLimits limits;
    limits.max_triangles = kMaxSceneObjectTriangles - out.triangles.size();
    TriangleMesh mesh;
    try {
      mesh = load_obj(object_path(scene, object), limits);
    } catch (const ObjError& e) {
      throw SceneError(key, std::string(e.what()) +
                                (limits.max_triangles < kMaxObjTriangles
                                     ? " (all objects together: at most " +
                                           std::to_string(kMaxSceneObjectTriangles) + " triangles)"
                                     : ""));
    }
    const auto offset = static_cast<std::uint32_t>(out.positions.size());
    for (const glm::dvec3& p : mesh.positions) out.positions.push_back(object_to_world(object, p));
    for (const auto& t : mesh.triangles) {
      out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
      out.material.push_back(static_cast<std::uint32_t>(out.materials.size()));
    }
    out.materials.push_back(object.material);
  }
  return out;
}

}  // namespace oceanref
