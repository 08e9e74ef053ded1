// The projected grid of Johanson 2004 ("Real-time water rendering: introducing the projected
// grid concept", §2.4–2.5; Gamper §4.5, Fig. 4.13): a regular grid in the post-perspective space
// of a projector camera, projected onto the base plane y = 0, covering exactly the part of the
// plane whose displaced surface can be visible.
//
// 1. The render camera's frustum (near to far) is intersected with the planes y = ±h that bound
//    the displaced surface (h = the largest possible |η|); the intersection points and the
//    frustum corners between the planes span the visible volume. None: no ocean in view.
// 2. The points are projected onto y = 0.
// 3. The projector is the render camera moved to at least h + 1 m above the plane (mirrored when
//    below it), aimed at the point where the view direction meets the plane (or, looking up or
//    level, at the point ahead at 10× its height), so it always looks down.
// 4. The range of the points in the projector's normalized device coordinates, widened by a
//    margin for horizontal displacement, defines M_range; grid vertex (u, v) ∈ [0, 1]² maps to
//    the projector NDC point, unprojected to a line and intersected with y = 0.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "raster/camera.h"

namespace oceanref {

struct ProjectedGridSettings {
  int columns = 256;
  int rows = 256;
  double displacement_bound = 0.0;  // h [m]: the largest |η|
  double margin = 0.1;              // widening of the projected range, relative to its size
  double near = 0.05;               // render frustum [m]
  double far = 1.0e5;
};

struct ProjectedGrid {
  bool visible = false;  // false: no part of the sea can be seen
  int columns = 0;
  int rows = 0;
  std::vector<glm::dvec2> base;  // (x0, z0) of vertex (i, j) at [j·columns + i]
  glm::dvec3 projector_position{0.0};
  glm::dvec3 projector_target{0.0};
};

ProjectedGrid project_grid(const Camera& camera, const ProjectedGridSettings& settings);

// The triangles of the grid's mesh (vertex indices j·columns + i), two per cell (i, j):
// (k, k + 1, k + columns) and (k + 1, k + columns + 1, k + columns), cells row by row. Empty for
// an invisible grid.
std::vector<std::array<std::uint32_t, 3>> grid_triangles(const ProjectedGrid& grid);

}  // namespace oceanref
