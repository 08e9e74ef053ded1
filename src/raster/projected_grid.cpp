#include "raster/projected_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "core/check.h"
#include "core/math.h"
#include "core/memory.h"

namespace oceanref {

namespace {
// OpenGL's perspective projection (right-handed, clip z in [−1, 1]), as glm::perspective builds
// it but with the portable tangent (glm's calls the platform's libm).
glm::dmat4 perspective_projection(double vertical_fov, double aspect, double near, double far) {
  const double t = math::tan(0.5 * vertical_fov);
  glm::dmat4 m(0.0);
  m[0][0] = 1.0 / (aspect * t);
  m[1][1] = 1.0 / t;
  m[2][2] = -(far + near) / (far - near);
  m[2][3] = -1.0;
  m[3][2] = -(2.0 * far * near) / (far - near);
  return m;
}
std::array<glm::dvec3, 8> frustum_corners(const Camera& c, double near, double far) {
  const double t = math::tan(0.5 * c.vertical_fov);
  const double aspect = static_cast<double>(c.width) / c.height;
  std::array<glm::dvec3, 8> corners{};
  int i = 0;
  for (const double d : {near, far}) {
    for (const double sy : {-1.0, 1.0}) {
      for (const double sx : {-1.0, 1.0}) {
        corners[static_cast<std::size_t>(i++)] =
            c.position + d * c.forward + sx * d * t * aspect * c.right + sy * d * t * c.up;
      }
    }
  }
  return corners;
}
}  // namespace

ProjectedGrid project_grid(const Camera& camera, const ProjectedGridSettings& s) {
  OCEANREF_EXPECTS(s.columns >= 1 && s.rows >= 1 && s.displacement_bound >= 0.0 &&
                       s.margin >= 0.0 && s.near > 0.0 && s.far > s.near,
                   "grid settings: columns, rows >= 1, bound and margin >= 0, 0 < near < far");
  ProjectedGrid grid;
  grid.columns = s.columns;
  grid.rows = s.rows;
  const double h = s.displacement_bound;
  // 1–2. The visible part of the displaceable volume, projected onto y = 0.
  const std::array<glm::dvec3, 8> corner = frustum_corners(camera, s.near, s.far);
  static constexpr int kEdges[12][2] = {{0, 1}, {1, 3}, {3, 2}, {2, 0}, {4, 5}, {5, 7},
                                        {7, 6}, {6, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  std::vector<glm::dvec3> points;
  for (const glm::dvec3& p : corner) {
    if (std::fabs(p.y) <= h) points.push_back({p.x, 0.0, p.z});
  }
  for (const auto& edge : kEdges) {
    const glm::dvec3 a = corner[static_cast<std::size_t>(edge[0])];
    const glm::dvec3 b = corner[static_cast<std::size_t>(edge[1])];
    for (const double plane : {-h, h}) {
      if ((a.y - plane) * (b.y - plane) < 0.0) {
        const double t = (plane - a.y) / (b.y - a.y);
        const glm::dvec3 p = a + t * (b - a);
        points.push_back({p.x, 0.0, p.z});
      }
    }
  }
  if (points.empty()) return grid;
  // 3. The projector: above the volume, looking down at the plane.
  glm::dvec3 position = camera.position;
  position.y = std::max(std::fabs(position.y), h + 1.0);
  glm::dvec3 target;
  if (camera.forward.y < -1e-6 && camera.position.y > 0.0) {
    target = camera.position + camera.forward * (camera.position.y / -camera.forward.y);
  } else {
    glm::dvec3 horizontal{camera.forward.x, 0.0, camera.forward.z};
    if (!(glm::length(horizontal) > 1e-9)) horizontal = camera.up;  // looking straight up/down
    horizontal.y = 0.0;
    target = position + 10.0 * position.y * glm::normalize(horizontal);
  }
  target.y = 0.0;
  glm::dvec3 projector_up = camera.forward;  // any vector not parallel to the projector's view
  projector_up.y = 0.0;
  if (!(glm::length(projector_up) > 1e-9)) projector_up = glm::dvec3(1.0, 0.0, 0.0);
  // Up for lookAt: world Y unless the projector looks straight down.
  const glm::dvec3 view_dir = glm::normalize(target - position);
  const glm::dvec3 up =
      std::fabs(view_dir.y) > 0.999 ? glm::normalize(projector_up) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dmat4 view = glm::lookAt(position, target, up);
  const double aspect = static_cast<double>(camera.width) / camera.height;
  const glm::dmat4 projection = perspective_projection(camera.vertical_fov, aspect, s.near, s.far);
  const glm::dmat4 view_projection = projection * view;
  grid.projector_position = position;
  grid.projector_target = target;
  // 4. Range of the points in the projector's NDC.
  double x_min = std::numeric_limits<double>::infinity();
  double x_max = -x_min, y_min = x_min, y_max = -x_min;
  for (const glm::dvec3& p : points) {
    const glm::dvec4 q = view_projection * glm::dvec4(p, 1.0);
    if (!(q.w > 1e-12)) continue;  // behind the projector: cannot be reached by its rays
    x_min = std::min(x_min, q.x / q.w);
    x_max = std::max(x_max, q.x / q.w);
    y_min = std::min(y_min, q.y / q.w);
    y_max = std::max(y_max, q.y / q.w);
  }
  if (!(x_max > x_min) || !(y_max > y_min)) return grid;
  const double mx = s.margin * (x_max - x_min);
  const double my = s.margin * (y_max - y_min);
  x_min -= mx;
  x_max += mx;
  y_min -= my;
  y_max += my;
  const glm::dmat4 inverse = glm::inverse(view_projection);
  grid.base = allocate_buffer<glm::dvec2>(
      static_cast<std::size_t>(s.columns) * static_cast<std::size_t>(s.rows), "the projected grid");
  for (int j = 0; j < s.rows; ++j) {
    const double v = s.rows > 1 ? static_cast<double>(j) / (s.rows - 1) : 0.5;
    for (int i = 0; i < s.columns; ++i) {
      const double u = s.columns > 1 ? static_cast<double>(i) / (s.columns - 1) : 0.5;
      const double x = x_min + u * (x_max - x_min);
      const double y = y_min + v * (y_max - y_min);
      const glm::dvec4 a = inverse * glm::dvec4(x, y, -1.0, 1.0);
      const glm::dvec4 b = inverse * glm::dvec4(x, y, 1.0, 1.0);
      const glm::dvec3 p0 = glm::dvec3(a) / a.w;
      const glm::dvec3 p1 = glm::dvec3(b) / b.w;
      // The projector looks down, so rays inside the range cross y = 0; a ray the margin pushed
      // above the projector's horizon takes its far-plane point, dropped onto the plane.
      glm::dvec3 hit{p1.x, 0.0, p1.z};
      if (p0.y > p1.y && p1.y < 0.0) hit = p0 + (p0.y / (p0.y - p1.y)) * (p1 - p0);
      grid.base[static_cast<std::size_t>(j) * static_cast<std::size_t>(s.columns) +
                static_cast<std::size_t>(i)] = {hit.x, hit.z};
    }
  }
  grid.visible = true;
  return grid;
}

std::vector<std::array<std::uint32_t, 3>> grid_triangles(const ProjectedGrid& grid) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  if (!grid.visible) return triangles;
  const auto c = static_cast<std::uint32_t>(grid.columns);
  for (int j = 0; j + 1 < grid.rows; ++j) {
    for (int i = 0; i + 1 < grid.columns; ++i) {
      const auto k = static_cast<std::uint32_t>(j * grid.columns + i);
      triangles.push_back({k, k + 1, k + c});
      triangles.push_back({k + 1, k + c + 1, k + c});
    }
  }
  return triangles;
}

}  // namespace oceanref
