// The ray tracer against the continuous displaced surface (issue 17: ground-truth visibility).
//
// The surface is p(x0) = (x0 + Σu_iD_i(x0), Σ η_i(x0)) over the part of the base plane the
// projected grid covers (Gamper eq. 4.20; waves/surface.h), not its triangulation: where the
// grid under-samples a crest at a grazing view, the rasterizer and the grid ray tracer cut it,
// this tracer does not. Rays meet it through three levels of bounds, each proven, none sampled:
//   1. a tree over the grid's cells in x0 (bounds_tree.h), each cell's box that of
//      p = (x0, 0, z0) + q: the box of the cell's x0 plus the range of the offset q at its four
//      corners widened by L_j·ρ per component, L_j a Lipschitz bound of q_j
//      (displaced_surface_bounds) and ρ the farthest any point of the cell's quad is from its
//      nearest corner (≤ its longest edge or diagonal / √3), that range cut to the plane-wide
//      bound |q_j| ≤ offset_j;
//   2. inside a cell, the refinement Mastin, Watterberg & Mareda 1987 describe for their height
//      field ("a series of bounding boxes ... that are successively finer approximations to the
//      surface", the nearer first, a stack): the cell's bilinear parameter square is halved
//      across its longer side in x0 (their quarters, taken as two halvings; along the length
//      of a long thin cell near the horizon only), p evaluated at the new corners, each half
//      bounded the same way, until a patch's box is smaller than the tolerance —
//      `angular_tolerance` × its distance from the ray's origin (or `absolute_tolerance`);
//   3. on such a patch, the ray meets the two triangles of its corners, and Newton's method on
//      p(x0(s, t)) = origin + λ·direction from there gives the exact hit (converged to 1e-12 in
//      the cell's parameters, and inside the cell).
// So a ray that passes the surface by more than the tolerance is decided exactly, and a hit is a
// point of the continuous surface to rounding; only rays that graze the surface within the
// tolerance (a silhouette, seen at sub-tolerance width) may be decided either way. When Newton
// fails (a fold, a tangent ray), the triangle's hit is kept: `refined` false.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "trace/bounds_tree.h"

namespace oceanref {

// p(x0) and its partial derivatives ∂p/∂x0, ∂p/∂z0.
struct SurfacePoint {
  glm::dvec3 position{0.0}, d_dx0{0.0}, d_dz0{0.0};
};

// The surface over the grid's cells, with its bounds and its evaluation.
struct TracedSurface {
  int columns = 0, rows = 0;
  const std::vector<glm::dvec2>* base = nullptr;     // x0 of the vertices [j·columns + i]
  const std::vector<glm::dvec3>* corners = nullptr;  // p(x0) at them (the same function as
                                                     // `point`)
  // The offset q(x0) = p(x0) − (x0, 0, z0): |q_j(a) − q_j(b)| ≤ lipschitz_j·|a − b| and
  // |q_j| ≤ offset_j (per component).
  glm::dvec3 lipschitz{0.0};
  glm::dvec3 offset{0.0};
  std::function<glm::dvec3(const glm::dvec2&)> point;                // p(x0)
  std::function<SurfacePoint(const glm::dvec2&)> point_derivatives;  // p and ∂p
};

struct SurfaceTraceSettings {
  double angular_tolerance = 1e-4;   // [rad] a patch is small enough when its box is at most this
  double absolute_tolerance = 1e-6;  // [m] × its distance, or this
  // A hit counts only in front of the near plane: (hit − origin)·forward > near.
  glm::dvec3 forward{0.0, 0.0, -1.0};
  double near = 0.0;
};

struct SurfaceHit {
  bool hit = false;
  double t = 0.0;          // along the ray (its direction unit: the distance)
  glm::dvec2 x0{0.0};      // where on the base plane the hit point comes from
  std::int64_t cell = -1;  // j·(columns − 1) + i
  bool refined = false;    // Newton's method converged (else the small patch's triangle hit)
};

// The leaves are the cells (first = the cell's index, count = 1).
BoundsTree build_surface_tree(const TracedSurface& surface);

// The nearest hit with t > 0 of origin + t·direction (direction unit).
SurfaceHit trace_surface(const TracedSurface& surface, const BoundsTree& tree,
                         const SurfaceTraceSettings& settings, const glm::dvec3& origin,
                         const glm::dvec3& direction);

}  // namespace oceanref
