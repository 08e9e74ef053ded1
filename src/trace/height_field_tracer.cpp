#include "trace/height_field_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace oceanref {

namespace {
// Tests one triangle against the best hit so far.
void test_triangle(const TraceGrid& grid, std::size_t index, const glm::dvec3& origin,
                   const glm::dvec3& direction, RayHit& best) {
  if ((*grid.skipped)[index]) return;
  const auto& tri = (*grid.triangles)[index];
  const std::vector<glm::dvec3>& v = *grid.vertices;
  double t = 0.0, u = 0.0, w = 0.0;
  if (!intersect_triangle(origin, direction, v[tri[0]], v[tri[1]], v[tri[2]], t, u, w)) return;
  const auto id = static_cast<std::int64_t>(index);
  if (best.triangle >= 0 && (t > best.t || (t == best.t && id > best.triangle))) return;
  // Clamped into the triangle (a hit on the slack outside an edge is on the edge).
  u = std::clamp(u, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - u);
  best = {t, id, {1.0 - u - w, u, w}};
}

int build(const TraceGrid& grid, BoundsTree& tree, int i0, int i1, int j0, int j1) {
  const int index = static_cast<int>(tree.nodes.size());
  tree.nodes.emplace_back();
  BoundsTree::Node node;
  node.lower = glm::dvec3(std::numeric_limits<double>::infinity());
  node.upper = -node.lower;
  const std::vector<glm::dvec3>& v = *grid.vertices;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const glm::dvec3& p = v[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.columns) +
                              static_cast<std::size_t>(i)];
      node.lower = glm::min(node.lower, p);
      node.upper = glm::max(node.upper, p);
    }
  }
  pad_box(node);
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    node.first = 2 * (j0 * (grid.columns - 1) + i0);
    node.count = 2;
  } else if (i1 - i0 >= j1 - j0) {
    const int middle = (i0 + i1) / 2;
    node.children = {build(grid, tree, i0, middle, j0, j1), build(grid, tree, middle, i1, j0, j1)};
  } else {
    const int middle = (j0 + j1) / 2;
    node.children = {build(grid, tree, i0, i1, j0, middle), build(grid, tree, i0, i1, middle, j1)};
  }
  tree.nodes[static_cast<std::size_t>(index)] = node;
  return index;
}

// The box of triangles order[from, to), padded.
void bound_triangles(const TraceGrid& mesh, const std::vector<std::uint32_t>& order,
                     std::size_t from, std::size_t to, BoundsTree::Node& node) {
  node.lower = glm::dvec3(std::numeric_limits<double>::infinity());
  node.upper = -node.lower;
  for (std::size_t i = from; i < to; ++i) {
    for (const std::uint32_t v : (*mesh.triangles)[order[i]]) {
      node.lower = glm::min(node.lower, (*mesh.vertices)[v]);
      node.upper = glm::max(node.upper, (*mesh.vertices)[v]);
    }
  }
  pad_box(node);
}

glm::dvec3 centroid(const TraceGrid& mesh, std::uint32_t t) {
  const auto& tri = (*mesh.triangles)[t];
  const std::vector<glm::dvec3>& v = *mesh.vertices;
  return (v[tri[0]] + v[tri[1]] + v[tri[2]]) / 3.0;
}

int build_triangles(const TraceGrid& mesh, BoundsTree& tree, std::vector<std::uint32_t>& order,
                    std::size_t from, std::size_t to) {
  const int index = static_cast<int>(tree.nodes.size());
  tree.nodes.emplace_back();
  BoundsTree::Node node;
  bound_triangles(mesh, order, from, to, node);
  if (to - from == 1) {
    node.first = static_cast<int>(order[from]);
    node.count = 1;
  } else {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t i = from; i < to; ++i) {
      lo = glm::min(lo, centroid(mesh, order[i]));
      hi = glm::max(hi, centroid(mesh, order[i]));
    }
    const glm::dvec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    // Sorted by centroid, ties by index: the same tree on every platform.
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(from),
              order.begin() + static_cast<std::ptrdiff_t>(to),
              [&](std::uint32_t a, std::uint32_t b) {
                const double ca = centroid(mesh, a)[axis], cb = centroid(mesh, b)[axis];
                return ca < cb || (ca == cb && a < b);
              });
    const std::size_t middle = from + (to - from) / 2;
    node.children = {build_triangles(mesh, tree, order, from, middle),
                     build_triangles(mesh, tree, order, middle, to)};
  }
  tree.nodes[static_cast<std::size_t>(index)] = node;
  return index;
}
}  // namespace

BoundsTree build_triangle_tree(const TraceGrid& mesh) {
  BoundsTree tree;
  const std::size_t count = mesh.triangles->size();
  if (count == 0) return tree;
  std::vector<std::uint32_t> order(count);
  for (std::size_t i = 0; i < count; ++i) order[i] = static_cast<std::uint32_t>(i);
  tree.nodes.reserve(2 * count);
  build_triangles(mesh, tree, order, 0, count);
  return tree;
}

BoundsTree build_bounds_tree(const TraceGrid& grid) {
  BoundsTree tree;
  if (grid.columns < 2 || grid.rows < 2) return tree;
  tree.nodes.reserve(2 * static_cast<std::size_t>(grid.columns - 1) *
                     static_cast<std::size_t>(grid.rows - 1));
  build(grid, tree, 0, grid.columns - 1, 0, grid.rows - 1);
  return tree;
}

RayHit trace_ray(const TraceGrid& grid, const BoundsTree& tree, const glm::dvec3& origin,
                 const glm::dvec3& direction) {
  RayHit best;
  const auto limit = [&] {
    return best.triangle >= 0 ? best.t : std::numeric_limits<double>::infinity();
  };
  visit_leaves_nearest_first(tree, origin, direction, limit, [&](const BoundsTree::Node& n) {
    for (int t = n.first; t < n.first + n.count; ++t) {
      test_triangle(grid, static_cast<std::size_t>(t), origin, direction, best);
    }
  });
  return best;
}

RayHit trace_ray_brute_force(const TraceGrid& grid, const glm::dvec3& origin,
                             const glm::dvec3& direction) {
  RayHit best;
  for (std::size_t i = 0; i < grid.triangles->size(); ++i) {
    test_triangle(grid, i, origin, direction, best);
  }
  return best;
}

}  // namespace oceanref
