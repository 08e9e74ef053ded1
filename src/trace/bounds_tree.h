// A tree of axis-aligned bounding boxes and its nearest-first traversal, shared by the ray
// tracers against the triangulated grid and objects (height_field_tracer.h) and against the
// continuous surface (surface_tracer.h), and the ray–triangle test at their leaves.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace oceanref {

// Over the grid's cells (the quadtree), or over the triangles of any mesh (objects).
struct BoundsTree {
  struct Node {
    glm::dvec3 lower{0.0}, upper{0.0};    // bounding box of the block
    std::array<int, 2> children{-1, -1};  // −1: a leaf
    // A leaf's items [first, first + count): a grid cell's two triangles (2c, 2c + 1 for the
    // cell c = j·(columns − 1) + i), one triangle of a mesh, or one cell (surface_tracer.h).
    int first = -1, count = 0;
  };
  std::vector<Node> nodes;  // nodes[0] is the root
};

// The slab test: the ray's parameter interval inside the box, [near, far] (near > far: misses);
// `inverse` is 1/direction per axis.
inline std::pair<double, double> box_interval(const glm::dvec3& origin, const glm::dvec3& inverse,
                                              const glm::dvec3& lower, const glm::dvec3& upper) {
  double near = 0.0, far = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    double t0 = (lower[axis] - origin[axis]) * inverse[axis];
    double t1 = (upper[axis] - origin[axis]) * inverse[axis];
    if (std::isnan(t0) || std::isnan(t1)) {  // parallel to the slab, on its plane: inside
      if (origin[axis] < lower[axis] || origin[axis] > upper[axis]) return {1.0, 0.0};
      continue;
    }
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return {near, far};
}

// Calls leaf(node) for every leaf whose box the ray origin + t·direction (t ≥ 0) enters, the
// nearer child first (depth-first), skipping a box entered beyond limit() (the best hit so far,
// or +∞): the order, and so the result, depends only on the tree and the ray.
template <class Limit, class Leaf>
void visit_leaves_nearest_first(const BoundsTree& tree, const glm::dvec3& origin,
                                const glm::dvec3& direction, const Limit& limit, const Leaf& leaf) {
  if (tree.nodes.empty()) return;
  const glm::dvec3 inverse = 1.0 / direction;
  const auto enter = [&](int node) {
    const BoundsTree::Node& n = tree.nodes[static_cast<std::size_t>(node)];
    return box_interval(origin, inverse, n.lower, n.upper);
  };
  const auto [root_near, root_far] = enter(0);
  if (root_near > root_far) return;
  std::vector<std::pair<int, double>> stack{{0, root_near}};
  while (!stack.empty()) {
    const auto [index, near] = stack.back();
    stack.pop_back();
    if (near > limit()) continue;
    const BoundsTree::Node& n = tree.nodes[static_cast<std::size_t>(index)];
    if (n.children[0] < 0) {
      leaf(n);
      continue;
    }
    const auto [a, b] = n.children;
    const auto [a_near, a_far] = enter(a);
    const auto [b_near, b_far] = enter(b);
    const bool a_hit = a_near <= a_far, b_hit = b_near <= b_far;
    // Pushed farther first, so the nearer is popped next.
    if (a_hit && b_hit && a_near <= b_near) {
      stack.emplace_back(b, b_near);
      stack.emplace_back(a, a_near);
    } else {
      if (a_hit) stack.emplace_back(a, a_near);
      if (b_hit) stack.emplace_back(b, b_near);
    }
  }
}

// Möller & Trumbore 1997: t and the weights (u, v) of (b, c) of the hit of a ray with triangle
// abc, the edges included with a slack of 1e-12 (u, v ≥ −1e-12, u + v ≤ 1 + 1e-12) so that a
// ray through a shared edge hits one of the two triangles; false if it misses or hits at t ≤ 0.
inline bool intersect_triangle(const glm::dvec3& origin, const glm::dvec3& direction,
                               const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                               double& t, double& u, double& v) {
  constexpr double kEdgeSlack = 1e-12;
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(direction, e2);
  const double det = glm::dot(e1, p);
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double inverse = 1.0 / det;
  const glm::dvec3 s = origin - a;
  u = glm::dot(s, p) * inverse;
  if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack) return false;
  const glm::dvec3 q = glm::cross(s, e1);
  v = glm::dot(direction, q) * inverse;
  if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack) return false;
  t = glm::dot(e2, q) * inverse;
  return t > 0.0;
}

// Pads a box so that rounding in what it bounds (and a hit on an edge's slack) stays inside it.
inline void pad_box(BoundsTree::Node& node) {
  const glm::dvec3 pad(1e-9 * (1.0 + std::max({glm::length(node.lower), glm::length(node.upper)})));
  node.lower -= pad;
  node.upper += pad;
}

}  // namespace oceanref
