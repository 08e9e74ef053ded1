// A pinhole camera in double precision (+Y up). Pixel coordinates: x to the right from the left
// image edge, y downwards from the top edge, so pixel (i, j) covers [i, i+1) × [j, j+1).
#pragma once

#include <glm/glm.hpp>

namespace oceanref {

struct Camera {
  glm::dvec3 position;
  glm::dvec3 forward;   // unit, the viewing direction
  glm::dvec3 right;     // unit
  glm::dvec3 up;        // unit, right × … completing the basis
  double vertical_fov;  // [rad]
  int width;
  int height;
};

// Throws std::invalid_argument for a degenerate setup (look_at = position, up ∥ forward,
// fov outside (0, π), sizes < 1).
Camera make_camera(const glm::dvec3& position, const glm::dvec3& look_at, const glm::dvec3& up,
                   double vertical_fov, int width, int height);

// The unit ray direction through image point (x, y) [pixels].
glm::dvec3 ray_direction(const Camera& c, double x, double y);

// A world point in image coordinates: (x, y) [pixels] and the view depth z = (p − eye)·forward
// [m]; z ≤ 0 means behind the camera.
glm::dvec3 project(const Camera& c, const glm::dvec3& world);

}  // namespace oceanref
