// Camera, projected grid and rasterizer: hand-computed coverage, watertightness, perspective.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "raster/camera.h"
#include "raster/projected_grid.h"
#include "raster/rasterizer.h"

using namespace oceanref;

namespace {
std::vector<int> coverage(const std::vector<ScreenVertex>& v,
                          const std::vector<std::array<std::uint32_t, 3>>& triangles,
                          const SampleGrid& grid) {
  // Rasterize each triangle alone and count the hits per sample.
  std::vector<int> hits(static_cast<std::size_t>(grid.columns() * grid.rows()), 0);
  for (const auto& t : triangles) {
    std::vector<Fragment> f(hits.size());
    rasterize(v, {t}, grid, 0, grid.rows(), 1e-9, f);
    for (std::size_t i = 0; i < f.size(); ++i) hits[i] += f[i].triangle >= 0 ? 1 : 0;
  }
  return hits;
}
}  // namespace

TEST_CASE("rasterizer: coverage of a known triangle equals the hand-computed sample set") {
  // 1 sample per pixel at pixel centres; the triangle (0,0), (4,0), (0,4) covers the centres
  // (x + ½, y + ½) with x + y + 1 < 4, and those on the hypotenuse x + y + 1 = 4 only if it is a
  // top or left edge — it is neither (interior to its left, going down-left): excluded.
  const SampleGrid grid{6, 6, 1};
  const std::vector<ScreenVertex> v{{0, 0, 1}, {4, 0, 1}, {0, 4, 1}};
  const auto hits = coverage(v, {{0, 1, 2}}, grid);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 6; ++x) {
      CAPTURE(x);
      CAPTURE(y);
      CHECK(hits[static_cast<std::size_t>(y * 6 + x)] == (x + y + 1 < 4 ? 1 : 0));
    }
  }
}

TEST_CASE("rasterizer: vertices far off screen cover what they should, and never overflow") {
  // Such vertices come from grid points near the horizon; the row and column ranges must be
  // clamped before they become ints (UndefinedBehaviorSanitizer checks the casts).
  const SampleGrid grid{8, 6, 2};
  for (const double far : {1e10, 1e100, 1e300}) {
    CAPTURE(far);
    // A triangle around the whole image: every sample, once — unless its area overflows (at
    // 1e300), which skips it as degenerate.
    const std::vector<ScreenVertex> around{{-far, -far, 1}, {far, -far, 1}, {0, far, 1}};
    for (const int h : coverage(around, {{0, 1, 2}}, grid)) CHECK(h == (far < 1e150 ? 1 : 0));
    // Triangles entirely beyond each side of the image: no sample.
    for (const auto& v :
         std::vector<std::vector<ScreenVertex>>{{{-far, 0, 1}, {-far / 2, 0, 1}, {-far, 5, 1}},
                                                {{far / 2, 0, 1}, {far, 0, 1}, {far, 5, 1}},
                                                {{0, -far, 1}, {5, -far, 1}, {0, -far / 2, 1}},
                                                {{0, far / 2, 1}, {5, far, 1}, {0, far, 1}}}) {
      for (const int h : coverage(v, {{0, 1, 2}}, grid)) CHECK(h == 0);
    }
  }
}

TEST_CASE("rasterizer: row bands give the fragments of one full pass, whatever their number") {
  // A fan of triangles crossing many rows; bands of 1, 3 and 7 sample rows.
  const SampleGrid grid{9, 7, 2};
  std::vector<ScreenVertex> v{{4.5, 3.5, 2}};
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t i = 0; i < 12; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 12.0;
    v.push_back({4.5 + 6.0 * std::cos(a), 3.5 + 5.0 * std::sin(a), 2.0 + 0.1 * i});
    triangles.push_back({0, i + 1, i == 11 ? 1 : i + 2});
  }
  std::vector<Fragment> whole(static_cast<std::size_t>(grid.columns() * grid.rows()));
  rasterize(v, triangles, grid, 0, grid.rows(), 1e-9, whole);
  const auto columns = static_cast<std::size_t>(grid.columns());
  for (const int band : {1, 3, 7}) {
    // Into one buffer of the whole grid, and into a buffer of the band alone (as a tile).
    std::vector<Fragment> banded(whole.size());
    for (int first = 0; first < grid.rows(); first += band) {
      const int last = std::min(first + band, grid.rows());
      rasterize(v, triangles, grid, first, last, 1e-9, banded);
      std::vector<Fragment> alone(static_cast<std::size_t>(last - first) * columns);
      rasterize(v, triangles, grid, first, last, 1e-9, alone, first);
      // Only the triangles whose sample rows reach the band (as the renderer bins them).
      std::vector<std::uint32_t> reach;
      for (std::uint32_t t = 0; t < triangles.size(); ++t) {
        const auto& i = triangles[t];
        const auto [lo, hi] = sample_rows_of(v[i[0]], v[i[1]], v[i[2]], grid, 1e-9);
        if (lo < last && hi > first) reach.push_back(t);
      }
      if (band == 1) CHECK(reach.size() < triangles.size());  // a row misses some triangles
      std::vector<Fragment> binned(alone.size());
      rasterize(v, triangles, reach, grid, first, last, 1e-9, binned, first);
      for (std::size_t i = 0; i < alone.size(); ++i) {
        const Fragment& w = whole[static_cast<std::size_t>(first) * columns + i];
        CHECK(alone[i].triangle == w.triangle);
        CHECK(binned[i].triangle == w.triangle);
        CHECK(binned[i].weights == w.weights);
        CHECK(alone[i].depth == w.depth);
        CHECK(alone[i].weights == w.weights);
      }
    }
    for (std::size_t i = 0; i < whole.size(); ++i) {
      CHECK(banded[i].triangle == whole[i].triangle);
      CHECK(banded[i].depth == whole[i].depth);
      CHECK(banded[i].weights == whole[i].weights);
    }
  }
}

TEST_CASE("rasterizer: arbitrary points get the fragments a grid pass gives its samples") {
  // The fan above with vertices on sample positions (ties) and overlapping depths: the points at
  // every sample position of a 2×2 grid, in a scrambled order, against rasterize's fragments;
  // a triangle behind the near plane covers no point.
  const SampleGrid grid{9, 7, 2};
  std::vector<ScreenVertex> v{{4.5, 3.5, 2}};
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> all;
  for (std::uint32_t i = 0; i < 12; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 12.0;
    v.push_back({4.5 + 6.0 * std::cos(a), 3.5 + 5.0 * std::sin(a), 2.0 + 0.1 * i});
    triangles.push_back({0, i + 1, i == 11 ? 1 : i + 2});
    all.push_back(i);
  }
  v.push_back({0.25, 0.25, 0.5});  // a triangle nearer than all, one vertex behind the plane
  v.push_back({8.75, 0.25, 0.5});
  v.push_back({4.25, 6.75, 1e-12});
  triangles.push_back({13, 14, 15});
  all.push_back(12);
  std::vector<Fragment> whole(static_cast<std::size_t>(grid.columns() * grid.rows()));
  rasterize(v, triangles, grid, 0, grid.rows(), 1e-9, whole);
  std::vector<std::array<double, 2>> points;
  std::vector<std::size_t> sample;
  for (std::size_t k = 0; k < whole.size(); ++k) {
    const std::size_t i = (k * 37) % whole.size();  // 37 is prime to 14 × 18 = 252
    sample.push_back(i);
    points.push_back(
        {grid.sample_x(static_cast<int>(i % 18)), grid.sample_y(static_cast<int>(i / 18))});
  }
  std::vector<Fragment> at_points(points.size());
  rasterize_points(v, triangles, all, points, 1e-9, at_points);
  int covered = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Fragment& w = whole[sample[k]];
    CHECK(at_points[k].triangle == w.triangle);
    CHECK(at_points[k].depth == w.depth);
    CHECK(at_points[k].weights == w.weights);
    covered += w.triangle >= 0 ? 1 : 0;
    CHECK(at_points[k].triangle != 12);
  }
  CHECK(covered > 100);
}

TEST_CASE("rasterizer: a triangle's sample rows, none unless strictly in front of the near plane") {
  // Rows [⌈min y·S − ½⌉, ⌊max y·S − ½⌋ + 1): the samples whose centres (r + ½)/S lie in [min y,
  // max y]. A corner on the near plane or behind it (or a NaN depth), or an x or y not finite:
  // no rows, and rasterize culls such a triangle.
  const SampleGrid grid{8, 6, 2};
  const double near = 0.5;
  const ScreenVertex a{1.0, 1.25, 2.0}, b{6.0, 3.0, 2.0}, c{2.0, 4.75, 2.0};
  CHECK(sample_rows_of(a, b, c, grid, near) == std::pair{2.0, 10.0});  // 1.25·2 − ½ → 2; 9 + 1
  const ScreenVertex on_plane{c.x, c.y, near};
  const ScreenVertex just_in_front{c.x, c.y, std::nextafter(near, 1.0)};
  for (const auto& rows :
       {sample_rows_of(a, b, on_plane, grid, near), sample_rows_of(on_plane, a, b, grid, near),
        sample_rows_of(a, on_plane, b, grid, near)}) {
    CHECK(rows.first >= rows.second);
  }
  CHECK(sample_rows_of(a, b, just_in_front, grid, near) == std::pair{2.0, 10.0});
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const ScreenVertex& bad :
       {ScreenVertex{1.0, kNaN, 2.0}, ScreenVertex{kNaN, 1.0, 2.0}, ScreenVertex{1.0, 1.0, kNaN},
        ScreenVertex{1.0, kInf, 2.0}, ScreenVertex{-kInf, 1.0, 2.0}}) {
    const auto none = sample_rows_of(a, b, bad, grid, near);
    CHECK_FALSE(none.first < none.second);
  }
  // And rasterize agrees: the triangle with a corner on the plane writes no fragment.
  std::vector<Fragment> fragments(static_cast<std::size_t>(grid.columns() * grid.rows()));
  rasterize({a, b, on_plane}, {{0, 1, 2}}, grid, 0, grid.rows(), near, fragments);
  CHECK(std::all_of(fragments.begin(), fragments.end(),
                    [](const Fragment& f) { return f.triangle < 0; }));
  rasterize({a, b, just_in_front}, {{0, 1, 2}}, grid, 0, grid.rows(), near, fragments);
  CHECK(std::any_of(fragments.begin(), fragments.end(),
                    [](const Fragment& f) { return f.triangle == 0; }));
}

TEST_CASE("rasterizer: watertight fan and grid, every sample exactly once") {
  // A fan of 12 triangles around (8, 8) with vertices on sample positions (worst case for ties),
  // and a 2×2-supersampled grid of quads: each covered sample is hit exactly once.
  const SampleGrid grid{16, 16, 2};
  std::vector<ScreenVertex> v{{8.25, 8.25, 1}};
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    v.push_back({8.25 + 6.0 * std::cos(a), 8.25 + 6.0 * std::sin(a), 1.0});
  }
  std::vector<std::array<std::uint32_t, 3>> fan;
  for (int i = 0; i < n; ++i) {
    fan.push_back(
        {0u, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % n)});
  }
  const auto hits = coverage(v, fan, grid);
  int covered = 0;
  for (const int h : hits) {
    CHECK(h <= 1);
    covered += h;
  }
  // Inside the polygon (radius ≥ 6 cos(π/12) = 5.8): every sample within 5.7 of the centre hit.
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.columns(); ++c) {
      const double dx = grid.sample_x(c) - 8.25, dy = grid.sample_y(r) - 8.25;
      if (dx * dx + dy * dy < 5.7 * 5.7)
        CHECK(hits[static_cast<std::size_t>(r * grid.columns() + c)] == 1);
    }
  }
  CHECK(covered > 0);
  // A regular grid of quads with vertices on half-sample positions.
  std::vector<ScreenVertex> g;
  std::vector<std::array<std::uint32_t, 3>> quads;
  const int m = 9;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) g.push_back({1.0 + 1.75 * i, 1.0 + 1.75 * j + 0.1 * i, 1.0});
  }
  for (int j = 0; j + 1 < m; ++j) {
    for (int i = 0; i + 1 < m; ++i) {
      const auto k = static_cast<std::uint32_t>(j * m + i);
      quads.push_back({k, k + 1, k + static_cast<std::uint32_t>(m)});
      quads.push_back(
          {k + 1, k + static_cast<std::uint32_t>(m) + 1, k + static_cast<std::uint32_t>(m)});
    }
  }
  for (const int h : coverage(g, quads, grid)) CHECK(h <= 1);
}

TEST_CASE("rasterizer: perspective-correct interpolation of a plane and nearest depth wins") {
  // A plane seen by a camera: the interpolated depth at each sample equals the ray-plane depth.
  const Camera cam =
      make_camera({0, 2, 0}, {0, 0, 10}, {0, 1, 0}, 60.0 * std::numbers::pi / 180, 32, 24);
  const glm::dvec3 corners[3] = {{-20, 0, 3}, {20, 0, 3}, {0, 0, 60}};
  std::vector<ScreenVertex> v;
  for (const auto& p : corners) {
    const glm::dvec3 s = project(cam, p);
    v.push_back({s.x, s.y, s.z});
  }
  const SampleGrid grid{32, 24, 1};
  std::vector<Fragment> f(static_cast<std::size_t>(32 * 24));
  rasterize(v, {{0, 1, 2}}, grid, 0, 24, 1e-6, f);
  int checked = 0;
  for (int r = 0; r < 24; ++r) {
    for (int c = 0; c < 32; ++c) {
      const Fragment& x = f[static_cast<std::size_t>(r * 32 + c)];
      if (x.triangle < 0) continue;
      const glm::dvec3 d = ray_direction(cam, grid.sample_x(c), grid.sample_y(r));
      const double t = cam.position.y / -d.y;  // ray–plane distance
      CHECK(x.depth == doctest::Approx(t * glm::dot(d, cam.forward)).epsilon(1e-12));
      // The interpolated world point is on the ray.
      glm::dvec3 p{0.0};
      for (int k = 0; k < 3; ++k) p += x.weights[static_cast<std::size_t>(k)] * corners[k];
      const glm::dvec3 expected = cam.position + t * d;
      CHECK(glm::length(p - expected) < 1e-9 * t);
      ++checked;
    }
  }
  CHECK(checked > 50);
}

TEST_CASE("projected grid: flat sea vertices are ray-plane hits; viewing cases") {
  const double deg = std::numbers::pi / 180.0;
  ProjectedGridSettings s;
  s.columns = 33;
  s.rows = 17;
  s.displacement_bound = 1.5;
  // Above the water looking down: every grid vertex on y = 0, in front of the camera.
  const Camera down = make_camera({0, 10, 0}, {5, 0, 30}, {0, 1, 0}, 50 * deg, 320, 180);
  const ProjectedGrid g = project_grid(down, s);
  REQUIRE(g.visible);
  // The vertices are the hits of the projector's rays through a regular grid of its image: the
  // rays of one grid row span a plane through the projector, which meets the sea plane in a
  // straight line, so each row's vertices, stored at [j·columns + i], are collinear (to
  // rounding: 1e-9 of the row's extent); a wrong layout scatters them.
  for (int j = 0; j < s.rows; ++j) {
    const auto at = [&](int i) { return g.base[static_cast<std::size_t>(j * s.columns + i)]; };
    const glm::dvec2 a = at(0), d = at(s.columns - 1) - a;
    REQUIRE(glm::length(d) > 0.0);
    for (int i = 1; i + 1 < s.columns; ++i) {
      const glm::dvec2 e = at(i) - a;
      CHECK(std::fabs(d.x * e.y - d.y * e.x) <= 1e-9 * glm::length(d) * glm::length(d));
    }
  }
  // Looking up from above the water, well above the volume: the sea may be out of view.
  const Camera sky = make_camera({0, 10, 0}, {0, 40, 10}, {0, 1, 0}, 30 * deg, 320, 180);
  CHECK_FALSE(project_grid(sky, s).visible);
  // At the horizon, very close to the surface, and inside the displaceable volume: visible.
  for (const Camera& c :
       {make_camera({0, 3, 0}, {0, 3, 100}, {0, 1, 0}, 50 * deg, 320, 180),
        make_camera({0, 0.2, 0}, {0, 0, 10}, {0, 1, 0}, 70 * deg, 320, 180),
        make_camera({0, -0.5, 0}, {0, -0.5, 10}, {0, 1, 0}, 60 * deg, 320, 180)}) {
    const ProjectedGrid p = project_grid(c, s);
    CHECK(p.visible);
    CHECK(p.projector_position.y >= s.displacement_bound + 1.0);
    for (const glm::dvec2& b : p.base) CHECK((std::isfinite(b.x) && std::isfinite(b.y)));
    // Level or looking up (the first and last): the projector aims at the point ahead on the
    // plane at 10× its height (projected_grid.h, 3.).
    if (c.forward.y >= -1e-6) {
      const glm::dvec3 ahead = glm::normalize(glm::dvec3(c.forward.x, 0.0, c.forward.z));
      const glm::dvec3 expected = p.projector_position + 10.0 * p.projector_position.y * ahead;
      CHECK(glm::length(p.projector_target - glm::dvec3(expected.x, 0.0, expected.z)) <
            1e-12 * p.projector_position.y);
    }
  }
}
