// The height-field ray tracer (issue 17, point 1; trace/height_field_tracer.h): hits against
// analytic values on a flat grid, the quadtree against testing every triangle on a wavy grid,
// and in a render: the ray tracer sees what the rasterizer sees on the same displaced grid.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <nlohmann/json.hpp>

#include "conformance/render_output.h"
#include "raster/projected_grid.h"
#include "scene/scene.h"
#include "trace/height_field_tracer.h"

#include "glitter_scene.h"

using namespace oceanref;

namespace {
// A columns × rows grid over [0, columns − 1] × [0, rows − 1] in x, z with height h(x, z).
struct TestGrid {
  int columns, rows;
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<bool> skipped;
  TraceGrid view() const { return {columns, rows, &vertices, &triangles, &skipped}; }
};

template <class Height>
TestGrid make_grid(int columns, int rows, const Height& h) {
  TestGrid g{columns, rows, {}, {}, {}};
  ProjectedGrid p;
  p.visible = true;
  p.columns = columns;
  p.rows = rows;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) g.vertices.push_back({i, h(i, j), j});
  }
  g.triangles = grid_triangles(p);
  g.skipped.assign(g.triangles.size(), false);
  return g;
}
}  // namespace

TEST_CASE("tracer: a flat grid, hit points and weights by hand") {
  const TestGrid g = make_grid(5, 4, [](double, double) { return 0.0; });
  const BoundsTree tree = build_bounds_tree(g.view());
  REQUIRE(!tree.nodes.empty());
  // Straight down onto (1.25, 0, 2.5): cell (1, 2), its first triangle (k, k + 1, k + columns)
  // holds the points with fractional x + z ≤ 1 (0.25 + 0.5).
  const RayHit hit = trace_ray(g.view(), tree, {1.25, 10.0, 2.5}, {0.0, -1.0, 0.0});
  REQUIRE(hit.triangle == 2 * (2 * 4 + 1));
  CHECK(hit.t == doctest::Approx(10.0));
  CHECK(hit.weights[0] == doctest::Approx(0.25));  // 1 − u − v
  CHECK(hit.weights[1] == doctest::Approx(0.25));  // towards +x
  CHECK(hit.weights[2] == doctest::Approx(0.5));   // towards +z
  // Missing the grid, pointing away, and a skipped triangle.
  CHECK(trace_ray(g.view(), tree, {10.0, 10.0, 2.5}, {0.0, -1.0, 0.0}).triangle < 0);
  CHECK(trace_ray(g.view(), tree, {1.25, 10.0, 2.5}, {0.0, 1.0, 0.0}).triangle < 0);
  TestGrid holed = g;
  holed.skipped[2 * (2 * 4 + 1)] = true;
  const BoundsTree holed_tree = build_bounds_tree(holed.view());
  CHECK(trace_ray(holed.view(), holed_tree, {1.25, 10.0, 2.5}, {0.0, -1.0, 0.0}).triangle < 0);
}

TEST_CASE("tracer: a hit on an edge or vertex shared by triangles goes to the lowest index") {
  // On a flat 9 × 9 grid, rays from every side land exactly on cell edges, cell diagonals and
  // vertices, where several triangles are hit at the same t. The hit belongs to the lowest
  // triangle index among them whatever order the quadtree visits them in (a ray from +x reaches
  // the higher cells' boxes first). Every point below lies on an edge, a diagonal or a vertex
  // shared by two to six triangles. The candidates by hand: cell (i, j)'s first triangle
  // 2 (8 j + i) holds fx + fz <= 1, its second fx + fz >= 1.
  const TestGrid g = make_grid(9, 9, [](double, double) { return 0.0; });
  const BoundsTree tree = build_bounds_tree(g.view());
  const auto lowest_triangle = [](double x, double z) {
    int best = -1;
    for (int j = 0; j < 8; ++j) {
      for (int i = 0; i < 8; ++i) {
        const double fx = x - i, fz = z - j;
        if (fx < 0.0 || fx > 1.0 || fz < 0.0 || fz > 1.0) continue;
        const int first = 2 * (8 * j + i);
        const int id = fx + fz <= 1.0 ? first : first + 1;
        if (best < 0 || id < best) best = id;
      }
    }
    return best;
  };
  for (const glm::dvec3 d :
       {glm::dvec3{-1, -1, 0}, glm::dvec3{1, -1, 0}, glm::dvec3{0, -1, -1}, glm::dvec3{0, -1, 1},
        glm::dvec3{-1, -1, -1}, glm::dvec3{1, -1, 1}, glm::dvec3{0, -1, 0}}) {
    for (const auto& [x, z] : {std::pair{4.0, 2.5}, std::pair{2.5, 4.0}, std::pair{4.0, 4.0},
                               std::pair{3.25, 5.75}, std::pair{6.0, 1.0}, std::pair{1.5, 6.5}}) {
      const glm::dvec3 direction = d;
      const double px = x, pz = z;
      CAPTURE(direction.x);
      CAPTURE(direction.z);
      CAPTURE(px);
      CAPTURE(pz);
      const glm::dvec3 origin = glm::dvec3{px, 0.0, pz} - 3.0 * direction;
      const RayHit hit = trace_ray(g.view(), tree, origin, direction);
      CHECK(hit.t == 3.0);
      CHECK(hit.triangle == lowest_triangle(px, pz));
      CHECK(trace_ray_brute_force(g.view(), origin, direction).triangle == hit.triangle);
    }
  }
}

TEST_CASE("tracer: the quadtree finds what testing every triangle finds") {
  // A wavy grid seen at grazing angles, where a ray passes over crests before it hits.
  const TestGrid g = make_grid(33, 29, [](double x, double z) {
    return 1.5 * std::sin(0.7 * x) * std::cos(0.45 * z) + 0.3 * std::sin(2.1 * x + 1.3 * z);
  });
  const BoundsTree tree = build_bounds_tree(g.view());
  int hits = 0;
  for (int n = 0; n < 400; ++n) {
    const glm::dvec3 origin{-5.0 + 0.11 * n, 3.0 + 0.01 * (n % 17), -4.0};
    const glm::dvec3 direction =
        glm::normalize(glm::dvec3{0.3 + 0.002 * (n % 23), -0.08 - 0.003 * (n % 31), 1.0});
    const RayHit fast = trace_ray(g.view(), tree, origin, direction);
    const RayHit slow = trace_ray_brute_force(g.view(), origin, direction);
    CHECK(fast.triangle == slow.triangle);
    CHECK(fast.t == slow.t);
    if (fast.triangle >= 0) ++hits;
  }
  CHECK(hits > 200);
}

TEST_CASE("tracer: each quadtree box is its block's box, padded by 1e-9 of its size") {
  // The boxes decide only what is tested, so a box too large passes every hit test above and
  // costs time alone: check the boxes themselves.
  const TestGrid g = make_grid(9, 7, [](double x, double z) { return std::sin(x) * (z - 3.0); });
  const BoundsTree tree = build_bounds_tree(g.view());
  const auto padding = [](const glm::dvec3& lower, const glm::dvec3& upper) {
    return 1e-9 * (1.0 + std::max(glm::length(lower), glm::length(upper)));
  };
  std::size_t leaves = 0;
  for (const BoundsTree::Node& n : tree.nodes) {
    glm::dvec3 lower(HUGE_VAL), upper(-HUGE_VAL);
    if (n.children[0] < 0) {
      ++leaves;
      const int cell = n.first / 2, i = cell % (g.columns - 1), j = cell / (g.columns - 1);
      for (const int dj : {0, 1}) {
        for (const int di : {0, 1}) {
          const glm::dvec3& v = g.vertices[static_cast<std::size_t>((j + dj) * g.columns + i + di)];
          lower = glm::min(lower, v);
          upper = glm::max(upper, v);
        }
      }
    } else {
      for (const int c : n.children) {
        lower = glm::min(lower, tree.nodes[static_cast<std::size_t>(c)].lower);
        upper = glm::max(upper, tree.nodes[static_cast<std::size_t>(c)].upper);
      }
    }
    // A leaf: its vertices' box, padded. A parent's box is its block's vertices' box, padded,
    // so it lies within twice its padding of the union of its (padded) children.
    const double pad = padding(lower, upper);
    const double slack = n.children[0] < 0 ? 1e-15 * (1.0 + glm::length(upper)) : 2.0 * pad;
    for (int axis = 0; axis < 3; ++axis) {
      CHECK(std::fabs(n.lower[axis] - (lower[axis] - pad)) <= slack);
      CHECK(std::fabs(n.upper[axis] - (upper[axis] + pad)) <= slack);
    }
  }
  CHECK(leaves == static_cast<std::size_t>((g.columns - 1) * (g.rows - 1)));
}

TEST_CASE("tracer: the smallest grids, one cell wide or tall, are traced") {
  // A grid of 2 columns or 2 rows is one strip of cells: its tree has a leaf per cell and a ray
  // straight down hits it; a grid of one column or row has no cells and no tree.
  for (const std::pair<int, int>& size : {std::pair{2, 2}, std::pair{2, 5}, std::pair{5, 2}}) {
    const int columns = size.first, rows = size.second;
    const TestGrid g = make_grid(columns, rows, [](double, double) { return 0.0; });
    const BoundsTree tree = build_bounds_tree(g.view());
    int leaves = 0;
    for (const BoundsTree::Node& n : tree.nodes) leaves += n.children[0] < 0 ? 1 : 0;
    CHECK(leaves == (columns - 1) * (rows - 1));
    // (0.25, 0.5) lies in cell (0, 0)'s first triangle.
    const RayHit hit = trace_ray(g.view(), tree, {0.25, 3.0, 0.5}, {0.0, -1.0, 0.0});
    CHECK(hit.triangle == 0);
    CHECK(hit.t == doctest::Approx(3.0));
  }
  CHECK(
      build_bounds_tree(make_grid(1, 4, [](double, double) { return 0.0; }).view()).nodes.empty());
}

TEST_CASE("tracer: the triangle tree splits each node at the median centroid, longest axis") {
  // Every inner node of build_triangle_tree: its triangles' centroids span a box; the first
  // child holds the lower half (rounded down) of them along the box's longest axis (x, then y,
  // then z on ties), the second the rest. A grid 9 x 4 wide: x at the root, z deeper down.
  const TestGrid g =
      make_grid(9, 4, [](double x, double z) { return 1e-3 * std::sin(x + 2.0 * z); });
  const BoundsTree tree = build_triangle_tree(g.view());
  const auto& triangles = *g.view().triangles;
  const auto centroid = [&](int t) {
    const auto& v = triangles[static_cast<std::size_t>(t)];
    return (g.vertices[v[0]] + g.vertices[v[1]] + g.vertices[v[2]]) / 3.0;
  };
  std::vector<std::vector<int>> under(tree.nodes.size());
  for (std::size_t k = tree.nodes.size(); k-- > 0;) {  // children come after their parent
    const BoundsTree::Node& n = tree.nodes[k];
    if (n.children[0] < 0) {
      under[k] = {n.first};
      continue;
    }
    for (const int c : n.children) {
      const std::vector<int>& u = under[static_cast<std::size_t>(c)];
      under[k].insert(under[k].end(), u.begin(), u.end());
    }
  }
  REQUIRE(under[0].size() == triangles.size());
  int inner = 0, along_z = 0;
  for (std::size_t k = 0; k < tree.nodes.size(); ++k) {
    const BoundsTree::Node& n = tree.nodes[k];
    if (n.children[0] < 0) continue;
    ++inner;
    glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (const int t : under[k]) {
      lo = glm::min(lo, centroid(t));
      hi = glm::max(hi, centroid(t));
    }
    const glm::dvec3 e = hi - lo;
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    along_z += axis == 2 ? 1 : 0;
    const std::vector<int>& first = under[static_cast<std::size_t>(n.children[0])];
    const std::vector<int>& second = under[static_cast<std::size_t>(n.children[1])];
    CHECK(first.size() == under[k].size() / 2);
    double first_max = -HUGE_VAL, second_min = HUGE_VAL;
    for (const int t : first) first_max = std::max(first_max, centroid(t)[axis]);
    for (const int t : second) second_min = std::min(second_min, centroid(t)[axis]);
    CHECK(first_max <= second_min + 1e-12);
  }
  CHECK(inner == static_cast<int>(triangles.size()) - 1);
  CHECK(along_z > 0);
}

TEST_CASE("tracer: each triangle-tree box is its triangles' box, padded by 1e-9 of its size") {
  // The objects' tree (build_triangle_tree) over the grid's triangles as a mesh: a leaf holds one
  // triangle and its box is that triangle's, padded; a parent's lies within twice its padding of
  // the union of its children's.
  const TestGrid g = make_grid(9, 7, [](double x, double z) { return std::sin(x) * (z - 3.0); });
  const BoundsTree tree = build_triangle_tree(g.view());
  const auto& triangles = *g.view().triangles;
  std::size_t leaves = 0;
  for (const BoundsTree::Node& n : tree.nodes) {
    glm::dvec3 lower(HUGE_VAL), upper(-HUGE_VAL);
    if (n.children[0] < 0) {
      ++leaves;
      REQUIRE(n.count == 1);
      for (const std::uint32_t v : triangles[static_cast<std::size_t>(n.first)]) {
        lower = glm::min(lower, g.vertices[v]);
        upper = glm::max(upper, g.vertices[v]);
      }
    } else {
      for (const int c : n.children) {
        lower = glm::min(lower, tree.nodes[static_cast<std::size_t>(c)].lower);
        upper = glm::max(upper, tree.nodes[static_cast<std::size_t>(c)].upper);
      }
    }
    const double pad = 1e-9 * (1.0 + std::max(glm::length(lower), glm::length(upper)));
    const double slack = n.children[0] < 0 ? 1e-15 * (1.0 + glm::length(upper)) : 2.0 * pad;
    for (int axis = 0; axis < 3; ++axis) {
      CHECK(std::fabs(n.lower[axis] - (lower[axis] - pad)) <= slack);
      CHECK(std::fabs(n.upper[axis] - (upper[axis] + pad)) <= slack);
    }
  }
  CHECK(leaves == triangles.size());
}

TEST_CASE("two renderers: the ray tracer sees what the rasterizer sees, for any thread count") {
  // The glitter scene (sub-pixel glints, the horizon, choppy crests) at 4 spp, and refined
  // adaptively: both renderers shade the same displaced grid, so they differ only where a
  // sample's visibility or its interpolation weights differ in rounding. Per pixel and channel,
  // |raytrace − raster| ≤ 1e-9 relative (+1e-12 cd/m²) for ≥ 99% of the pixels, and every
  // pixel's coverage is the same.
  for (const bool adaptive : {false, true}) {
    CAPTURE(adaptive);
    nlohmann::json s = testing::glitter_scene_json(4);
    if (adaptive) s["render"]["pixel_tolerance"] = 0.05;
    const Scene scene = parse_scene(s);
    RenderOutputOptions options;
    options.threads = 2;
    options.aov = true;
    const RenderedScene raster = render_scene(scene, options);
    options.renderer = Renderer::raytrace;
    const RenderedScene traced = render_scene(scene, options);
    options.threads = 1;
    const RenderedScene traced_one = render_scene(scene, options);
    CHECK(traced.radiance_f64_sha256 == traced_one.radiance_f64_sha256);
    const std::size_t pixels = raster.image.radiance.size();
    std::size_t close = 0, covered_alike = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
      bool near = true;
      for (std::size_t c = 0; c < 3; ++c) {
        const double a = raster.image.radiance[p][c], b = traced.image.radiance[p][c];
        near = near && std::fabs(a - b) <= 1e-9 * std::fabs(a) + 1e-12;
      }
      if (near) ++close;
      if (raster.image.coverage[p] == traced.image.coverage[p]) ++covered_alike;
    }
    MESSAGE("pixels within 1e-9: " << close << " of " << pixels
                                   << "; same coverage: " << covered_alike);
    CHECK(close >= 0.99 * static_cast<double>(pixels));
    CHECK(covered_alike == pixels);
    if (adaptive) CHECK(traced.image.pixel_samples == raster.image.pixel_samples);
  }
}

TEST_CASE("tracer: a ray through a vertex or an edge gets weights in [0, 1], by the clamp") {
  // Rounding puts such a ray just outside the triangle as often as inside: u or v a few ulps
  // past 0 or 1, which intersect_triangle admits within its edge slack (1e-12) so that the ray
  // hits one of the triangles sharing the edge. test_triangle clamps the hit into the triangle:
  // its weights are then ≥ 0 and ≤ 1 exactly. Aimed at the vertices and edge midpoints of
  // random triangles; some of the raw u and v must fall outside [0, 1] for this to test the clamp.
  std::uint64_t state = 12345;
  const auto uniform = [&] {  // xorshift64*, in [−1, 1)
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return static_cast<double>((state * 0x2545F4914F6CDD1DULL) >> 11) * 0x1p-52 - 1.0;
  };
  int outside = 0, hits = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    TestGrid g{2, 2, {}, {{0, 1, 2}}, {false}};
    for (int k = 0; k < 3; ++k) g.vertices.push_back({uniform(), 0.3 * uniform(), uniform()});
    const glm::dvec3 origin{3.0 * uniform(), 5.0 + uniform(), 3.0 * uniform()};
    const std::vector<glm::dvec3>& v = g.vertices;
    for (const glm::dvec3& target :
         {v[0], v[1], v[2], 0.5 * (v[0] + v[1]), 0.5 * (v[1] + v[2]), 0.5 * (v[2] + v[0])}) {
      const glm::dvec3 direction = glm::normalize(target - origin);
      double t = 0.0, u = 0.0, w = 0.0;
      if (!intersect_triangle(origin, direction, v[0], v[1], v[2], t, u, w)) continue;
      if (u < 0.0 || u > 1.0 || w < 0.0 || u + w > 1.0) ++outside;
      const RayHit hit = trace_ray_brute_force(g.view(), origin, direction);
      REQUIRE(hit.triangle == 0);
      ++hits;
      for (const double weight : hit.weights) {
        CHECK(weight >= 0.0);
        CHECK(weight <= 1.0);
      }
      CHECK(std::fabs(hit.weights[0] + hit.weights[1] + hit.weights[2] - 1.0) <= 0x1p-52);
    }
  }
  CHECK(hits > 9000);
  CHECK(outside > 100);
  MESSAGE("hits ", hits, ", raw weights outside [0, 1]: ", outside);
}
