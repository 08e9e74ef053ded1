#include "raster/camera.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/math.h"

namespace oceanref {

Camera make_camera(const glm::dvec3& position, const glm::dvec3& look_at, const glm::dvec3& up,
                   double vertical_fov, int width, int height) {
  const glm::dvec3 d = look_at - position;
  if (!(glm::length(d) > 0.0)) throw std::invalid_argument("camera: look_at equals position");
  if (!(vertical_fov > 0.0 && vertical_fov < std::numbers::pi)) {
    throw std::invalid_argument("camera: vertical field of view must be in (0, 180) degrees");
  }
  if (width < 1 || height < 1) throw std::invalid_argument("camera: image size must be >= 1");
  const glm::dvec3 forward = glm::normalize(d);
  const glm::dvec3 side = glm::cross(forward, up);
  if (!(glm::length(side) > 1e-12)) {
    throw std::invalid_argument("camera: up must not be parallel to the viewing direction");
  }
  const glm::dvec3 right = glm::normalize(side);
  return {position, forward, right, glm::cross(right, forward), vertical_fov, width, height};
}

glm::dvec3 ray_direction(const Camera& c, double x, double y) {
  const double t = math::tan(0.5 * c.vertical_fov);
  const double aspect = static_cast<double>(c.width) / c.height;
  const double u = (2.0 * x / c.width - 1.0) * t * aspect;
  const double v = (1.0 - 2.0 * y / c.height) * t;
  return glm::normalize(c.forward + u * c.right + v * c.up);
}

glm::dvec3 project(const Camera& c, const glm::dvec3& world) {
  const glm::dvec3 p = world - c.position;
  const double z = glm::dot(p, c.forward);
  const double t = math::tan(0.5 * c.vertical_fov);
  const double aspect = static_cast<double>(c.width) / c.height;
  const double u = glm::dot(p, c.right) / (z * t * aspect);
  const double v = glm::dot(p, c.up) / (z * t);
  return {0.5 * (u + 1.0) * c.width, 0.5 * (1.0 - v) * c.height, z};
}

}  // namespace oceanref
