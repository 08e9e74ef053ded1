// The second renderer's visibility (issue 17, point 1): Mastin, Watterberg & Mareda 1987's
// height-field ray tracer, rays against the displaced surface through a quadtree of bounds. Here
// the surface is the rasterizer's own: the projected grid's displaced vertices, two triangles per
// cell (raster/projected_grid.h, grid_triangles), so the two renderers differ only in how they
// decide what a sample sees — edge functions and a depth test on screen, or the nearest ray
// intersection in the world — and a disagreement is a bug of one of them, not a different
// surface. Mastin's quadtree holds the maximum height per block of the height field; ours holds,
// per block of grid cells, the bounding box of its vertices (the grid is not regular in x and z),
// split along the longer side down to single cells.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "trace/bounds_tree.h"

namespace oceanref {

// What a ray hits first: the triangle (index in grid_triangles order) at ray parameter t, with
// the barycentric weights of its three vertices at the hit (world-space: the perspective-correct
// weights of a rasterizer); triangle < 0 if nothing.
struct RayHit {
  double t = 0.0;
  std::int64_t triangle = -1;
  std::array<double, 3> weights{};
};

// A view of the grid's vertices and triangles and of which triangles may be hit (a triangle the
// rasterizer skips, with a vertex at or behind the near plane, is skipped here too).
struct TraceGrid {
  int columns = 0, rows = 0;
  const std::vector<glm::dvec3>* vertices = nullptr;  // [j·columns + i], displaced, world [m]
  const std::vector<std::array<std::uint32_t, 3>>* triangles = nullptr;  // grid_triangles
  const std::vector<bool>* skipped = nullptr;                            // per triangle
};

// The quadtree over the grid's cells: per block of cells the box of its vertices, split along the
// longer side down to single cells.
BoundsTree build_bounds_tree(const TraceGrid& grid);
// The bounds of any triangles (`grid.columns`, `rows` unused): split at the median centroid along
// the longest axis of the centroids' box, down to one triangle per leaf.
BoundsTree build_triangle_tree(const TraceGrid& mesh);

// The nearest intersection with t > 0 of the ray origin + t·direction: the smallest t wins, and
// between equal t the smaller triangle index (the rasterizer's order for equal depths).
// Möller–Trumbore per triangle, with the edges included (u, v ≥ −1e-12, u + v ≤ 1 + 1e-12) so a
// ray through a shared edge hits one of the two triangles.
RayHit trace_ray(const TraceGrid& grid, const BoundsTree& tree, const glm::dvec3& origin,
                 const glm::dvec3& direction);

// The same by testing every triangle (for tests).
RayHit trace_ray_brute_force(const TraceGrid& grid, const glm::dvec3& origin,
                             const glm::dvec3& direction);

}  // namespace oceanref
