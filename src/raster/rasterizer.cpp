#include "raster/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/check.h"

namespace oceanref {

namespace {
struct Point {
  double x, y;
};

// The edge function of the directed edge a → b at p, evaluated with the endpoints in a canonical
// (lexicographic) order and negated for the other direction: the two triangles sharing an edge
// get exactly opposite values.
double edge_function(Point a, Point b, Point p) {
  const bool swapped = (b.x < a.x) || (b.x == a.x && b.y < a.y);
  const Point u = swapped ? b : a;
  const Point v = swapped ? a : b;
  const double e = (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x);
  return swapped ? -e : e;
}

// Top-left rule for a triangle wound so that inside is e > 0 (image y down): the interior of the
// directed edge d = b − a lies along (−d_y, d_x). A sample exactly on an edge belongs to the
// triangle if the edge is a "top" edge (horizontal, the interior below: d_x > 0) or a "left" edge
// (the interior to its right: d_y < 0).
bool owns_boundary(Point a, Point b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  return (dy == 0.0 && dx > 0.0) || dy < 0.0;
}

// A screen triangle wound so that its interior has positive edge functions (vertex k of the
// winding is the triangle's vertex order[k]), with its edges' ownership by the top-left rule.
struct CoverageTriangle {
  Point a, b, c;
  double za, zb, zc;  // view depths
  double area;        // twice the screen area, > 0
  std::array<int, 3> order;
  bool own_ab, own_bc, own_ca;
};

// The triangle ready for coverage tests; none when its screen area is 0 or not finite.
std::optional<CoverageTriangle> coverage_triangle(const ScreenVertex& v0, const ScreenVertex& v1,
                                                  const ScreenVertex& v2) {
  const Point p[3] = {{v0.x, v0.y}, {v1.x, v1.y}, {v2.x, v2.y}};
  const double z[3] = {v0.z, v1.z, v2.z};
  std::array<int, 3> order = {0, 1, 2};
  const double area = edge_function(p[0], p[1], p[2]);
  if (area == 0.0 || !std::isfinite(area)) return std::nullopt;
  if (area < 0.0) std::swap(order[1], order[2]);
  CoverageTriangle t{p[order[0]], p[order[1]],     p[order[2]], z[order[0]], z[order[1]],
                     z[order[2]], std::fabs(area), order,       false,       false,
                     false};
  t.own_ab = owns_boundary(t.a, t.b);
  t.own_bc = owns_boundary(t.b, t.c);
  t.own_ca = owns_boundary(t.c, t.a);
  return t;
}

// Triangle `index` into fragment f when it covers q (edge functions, the top-left rule on its
// edges) nearer than f's triangle (a tie keeps f's): perspective-correct weights, the screen
// barycentrics divided by depth and renormalized.
void cover(const CoverageTriangle& t, std::size_t index, Point q, Fragment& f) {
  const double e0 = edge_function(t.b, t.c, q);  // weight of a
  const double e1 = edge_function(t.c, t.a, q);  // weight of b
  const double e2 = edge_function(t.a, t.b, q);  // weight of c
  if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) return;
  if ((e0 == 0.0 && !t.own_bc) || (e1 == 0.0 && !t.own_ca) || (e2 == 0.0 && !t.own_ab)) return;
  const double la = e0 / t.area / t.za;
  const double lb = e1 / t.area / t.zb;
  const double lc = e2 / t.area / t.zc;
  const double sum = la + lb + lc;
  const double depth = 1.0 / sum;
  if (f.triangle >= 0 && !(depth < f.depth)) return;
  f.depth = depth;
  f.triangle = static_cast<std::int64_t>(index);
  std::array<double, 3> w{};
  w[static_cast<std::size_t>(t.order[0])] = la / sum;
  w[static_cast<std::size_t>(t.order[1])] = lb / sum;
  w[static_cast<std::size_t>(t.order[2])] = lc / sum;
  f.weights = w;
}
}  // namespace

namespace {
// The rasterizer over the triangles triangles[index(i)], i < count, in that order.
template <class Index>
void rasterize_indexed(const std::vector<ScreenVertex>& vertices,
                       const std::vector<std::array<std::uint32_t, 3>>& triangles,
                       std::size_t count, const Index& index, const SampleGrid& grid, int first_row,
                       int last_row, double near, std::vector<Fragment>& fragments,
                       int fragment_row, FragmentColumns window) {
  const int columns = grid.columns();
  const int first_column = window.first;
  const int end_column = window.count < 0 ? columns : first_column + window.count;
  OCEANREF_EXPECTS(grid.samples_per_axis >= 1 && 0 <= first_column && first_column < end_column &&
                       end_column <= columns,
                   "sample columns [" + std::to_string(first_column) + ", " +
                       std::to_string(end_column) + ") inside the grid's " +
                       std::to_string(columns));
  const std::size_t width = static_cast<std::size_t>(end_column - first_column);
  OCEANREF_EXPECTS(fragments.size() % width == 0,
                   "whole sample rows of fragments: " + std::to_string(fragments.size()) +
                       " for rows of " + std::to_string(width));
  const int fragment_end = fragment_row + static_cast<int>(fragments.size() / width);
  OCEANREF_EXPECTS(0 <= fragment_row && fragment_row <= first_row && first_row <= last_row &&
                       last_row <= fragment_end && fragment_end <= grid.rows(),
                   "sample rows [" + std::to_string(first_row) + ", " + std::to_string(last_row) +
                       ") inside the fragments' rows [" + std::to_string(fragment_row) + ", " +
                       std::to_string(fragment_end) + ") inside [0, " +
                       std::to_string(grid.rows()) + ")");
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t t = index(i);
    OCEANREF_EXPECTS(t < triangles.size(), "triangle index " + std::to_string(t) + " of " +
                                               std::to_string(triangles.size()));
    OCEANREF_EXPECTS(triangles[t][0] < vertices.size() && triangles[t][1] < vertices.size() &&
                         triangles[t][2] < vertices.size(),
                     "triangle " + std::to_string(t) + " indexes a vertex beyond the " +
                         std::to_string(vertices.size()) + " given");
    const ScreenVertex& v0 = vertices[triangles[t][0]];
    const ScreenVertex& v1 = vertices[triangles[t][1]];
    const ScreenVertex& v2 = vertices[triangles[t][2]];
    // Sample rows the triangle can touch, within [first_row, last_row) (clamped as doubles, so
    // that a vertex far off screen never overflows an int; a NaN fails the test).
    const int s = grid.samples_per_axis;
    const auto [lowest, highest] = sample_rows_of(v0, v1, v2, grid, near);
    if (!(lowest < last_row && highest > first_row)) continue;
    const int row_begin = std::max(static_cast<int>(std::fmax(lowest, first_row)), first_row);
    const int row_end = std::min(static_cast<int>(std::fmin(highest, last_row)), last_row);
    if (row_begin >= row_end) continue;
    const std::optional<CoverageTriangle> tri = coverage_triangle(v0, v1, v2);
    if (!tri) continue;
    const Point a = tri->a, b = tri->b, c = tri->c;
    const Point edges[3][2] = {{a, b}, {b, c}, {c, a}};
    for (int row = row_begin; row < row_end; ++row) {
      const double sy = grid.sample_y(row);
      // The span from the edges crossing this scanline (edge walking).
      double x_lo = std::numeric_limits<double>::infinity();
      double x_hi = -x_lo;
      for (const auto& e : edges) {
        const Point u = e[0], v = e[1];
        if ((u.y <= sy && sy <= v.y) || (v.y <= sy && sy <= u.y)) {
          const double x =
              u.y == v.y ? std::min(u.x, v.x) : u.x + (sy - u.y) * (v.x - u.x) / (v.y - u.y);
          const double x2 = u.y == v.y ? std::max(u.x, v.x) : x;
          x_lo = std::min(x_lo, x);
          x_hi = std::max(x_hi, x2);
        }
      }
      if (!(x_hi >= x_lo)) continue;
      // One sample of slack on each side; the edge functions decide exactly.
      // Clamped as doubles: a vertex far off screen never overflows an int.
      const double lowest_column = first_column;
      const double last_column = end_column;
      const int col_begin = static_cast<int>(
          std::fmin(std::fmax(lowest_column, std::floor(x_lo * s - 0.5)), last_column));
      const int col_end = static_cast<int>(
          std::fmax(std::fmin(last_column, std::ceil(x_hi * s - 0.5) + 1.0), lowest_column));
      for (int col = col_begin; col < col_end; ++col) {
        cover(*tri, t, Point{grid.sample_x(col), sy},
              fragments[static_cast<std::size_t>(row - fragment_row) * width +
                        static_cast<std::size_t>(col - first_column)]);
      }
    }
  }
}

}  // namespace

void rasterize(const std::vector<ScreenVertex>& vertices,
               const std::vector<std::array<std::uint32_t, 3>>& triangles, const SampleGrid& grid,
               int first_row, int last_row, double near, std::vector<Fragment>& fragments,
               int fragment_row, FragmentColumns window) {
  rasterize_indexed(
      vertices, triangles, triangles.size(), [](std::size_t i) { return i; }, grid, first_row,
      last_row, near, fragments, fragment_row, window);
}

void rasterize(const std::vector<ScreenVertex>& vertices,
               const std::vector<std::array<std::uint32_t, 3>>& triangles,
               const std::vector<std::uint32_t>& subset, const SampleGrid& grid, int first_row,
               int last_row, double near, std::vector<Fragment>& fragments, int fragment_row,
               FragmentColumns window) {
  for (std::size_t i = 1; i < subset.size(); ++i) {
    OCEANREF_EXPECTS(subset[i - 1] < subset[i], "triangle indices in ascending order");
  }
  rasterize_indexed(
      vertices, triangles, subset.size(), [&](std::size_t i) { return subset[i]; }, grid, first_row,
      last_row, near, fragments, fragment_row, window);
}

void rasterize_points(const std::vector<ScreenVertex>& vertices,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles,
                      const std::vector<std::uint32_t>& subset,
                      std::span<const std::array<double, 2>> points, double near,
                      std::span<Fragment> fragments) {
  OCEANREF_EXPECTS(points.size() == fragments.size(), "a fragment per point");
  for (std::size_t i = 0; i < subset.size(); ++i) {
    OCEANREF_EXPECTS(i == 0 || subset[i - 1] < subset[i], "triangle indices in ascending order");
    const std::size_t t = subset[i];
    OCEANREF_EXPECTS(t < triangles.size() && triangles[t][0] < vertices.size() &&
                         triangles[t][1] < vertices.size() && triangles[t][2] < vertices.size(),
                     "triangle " + std::to_string(t) + " of " + std::to_string(triangles.size()) +
                         ", its vertices among the " + std::to_string(vertices.size()) + " given");
    const ScreenVertex& v0 = vertices[triangles[t][0]];
    const ScreenVertex& v1 = vertices[triangles[t][1]];
    const ScreenVertex& v2 = vertices[triangles[t][2]];
    if (!(v0.z > near && v1.z > near && v2.z > near)) continue;  // as sample_rows_of
    const std::optional<CoverageTriangle> tri = coverage_triangle(v0, v1, v2);
    if (!tri) continue;
    for (std::size_t p = 0; p < points.size(); ++p) {
      cover(*tri, t, Point{points[p][0], points[p][1]}, fragments[p]);
    }
  }
}

std::pair<double, double> sample_rows_of(const ScreenVertex& a, const ScreenVertex& b,
                                         const ScreenVertex& c, const SampleGrid& grid,
                                         double near) {
  if (!(a.z > near && b.z > near && c.z > near)) return {0.0, 0.0};
  for (const ScreenVertex& v : {a, b, c}) {
    if (!(std::isfinite(v.x) && std::isfinite(v.y))) return {0.0, 0.0};
  }
  const int s = grid.samples_per_axis;
  const double lowest = std::ceil(std::min({a.y, b.y, c.y}) * s - 0.5);
  const double highest = std::floor(std::max({a.y, b.y, c.y}) * s - 0.5) + 1.0;
  if (!(highest > lowest)) return {0.0, 0.0};
  return {lowest, highest};
}

}  // namespace oceanref
