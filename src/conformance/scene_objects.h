// The scene's objects (`objects`, scene/scene.h ObjectSettings) read from their OBJ files
// (io/obj_mesh.h) and placed in the world, for both renderers (RenderJob::objects).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "trace/scene_objects.h"

namespace oceanref {

// The most triangles of all the scene's objects together.
inline constexpr std::size_t kMaxSceneObjectTriangles = 2'000'000;

// A point of the object's mesh in the world: position + R_z R_y R_x (scale·local), the rotations
// right-handed about the world axes by rotation_deg (x first).
glm::dvec3 object_to_world(const ObjectSettings& object, const glm::dvec3& local);

// The path an object's OBJ file is read from: `obj` as written when absolute, else relative to
// the scene's folder (Scene::directory).
std::string object_path(const Scene& scene, const ObjectSettings& object);

// Every object loaded and placed, in scene order (triangles in file order). Throws SceneError
// naming objects[i].obj with the file's error (ObjError: "FILE:LINE: reason"), or when all the
// objects together exceed kMaxSceneObjectTriangles.
SceneObjects load_scene_objects(const Scene& scene);

}  // namespace oceanref
