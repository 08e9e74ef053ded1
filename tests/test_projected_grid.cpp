// The projected grid (raster/projected_grid.h, Johanson 2004) checked geometrically, not for
// finiteness: its vertices are the displaced surface sampled at their undisplaced points, its
// mesh covers every pixel whose ray can meet the sea and none whose ray cannot, and the horizon
// and the viewing extremes (level, grazing, inside the wave volume, straight down, looking up)
// keep both promises.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster/projected_grid.h"
#include "raster/rasterizer.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::kDeg;
using testing::kInfinity;

// The view depth at which the ray through image point (x, y) reaches the plane y = level, +∞ if
// it never does in front of the camera.
double depth_to_level(const Camera& c, double x, double y, double level) {
  const glm::dvec3 d = ray_direction(c, x, y);
  const double t = (level - c.position.y) / d.y;
  if (!(t > 0.0) || std::isinf(t)) return kInfinity;
  return t * glm::dot(d, c.forward);
}

struct Viewpoint {
  const char* name;
  glm::dvec3 position, look_at, up;
  double fov_deg;
};

// Above the sea (y > 1.5 m), inside the ±1.5 m volume and below the mean plane; level, grazing,
// down, straight down, up with the frustum's lower edge below the horizon.
const std::vector<Viewpoint> kViewpoints{
    {"high, looking down", {0, 40, 0}, {10, 0, 60}, {0, 1, 0}, 50},
    {"level at the horizon", {0, 3, 0}, {0, 3, 100}, {0, 1, 0}, 50},
    {"rolled, at the horizon", {0, 3, 0}, {30, 3, 100}, {0.3, 1, 0}, 40},
    {"close to the surface", {0, 0.2, 0}, {0, 0, 10}, {0, 1, 0}, 70},
    {"inside the volume", {0, 0.05, 0}, {0, 0.05, 30}, {0, 1, 0}, 60},
    {"below the mean plane", {0, -0.5, 0}, {0, -0.5, 10}, {0, 1, 0}, 60},
    {"straight down", {3, 20, -4}, {3, 0, -4}, {0, 0, 1}, 60},
    {"looking up, horizon in view", {0, 5, 0}, {0, 9, 30}, {0, 1, 0}, 60},
};
}  // namespace

TEST_CASE("projected grid, flat sea: the mesh covers exactly the rays that meet the plane") {
  // The grid's vertices lie on y = 0 (step 4 of the header); between them the mesh is the plane
  // itself. So a sample is covered iff its ray meets y = 0 in front of the camera within the far
  // range, and the fragment's depth is that intersection's. The image is sampled at every pixel
  // centre of a 64 × 36 image, edges included. Tolerance of the depth: 1e-9 relative — the
  // rasterizer's perspective-correct interpolation of a plane is exact up to rounding of sums of
  // a few dozen terms (~1e-14), far below any geometric error (a wrong triangle is off by > 1%).
  for (const double bound : {0.0, 1.5}) {
    for (const Viewpoint& v : kViewpoints) {
      const std::string view_name = v.name;
      CAPTURE(view_name);
      CAPTURE(bound);
      const Camera camera = make_camera(v.position, v.look_at, v.up, v.fov_deg * kDeg, 64, 36);
      ProjectedGridSettings s;
      s.columns = 65;
      s.rows = 65;
      s.displacement_bound = bound;
      const ProjectedGrid g = project_grid(camera, s);
      REQUIRE(g.visible);
      REQUIRE(g.base.size() == 65u * 65u);
      std::vector<ScreenVertex> screen;
      for (const glm::dvec2& b : g.base) {
        const glm::dvec3 p = project(camera, {b.x, 0.0, b.y});
        screen.push_back({p.x, p.y, p.z});
      }
      const SampleGrid samples{camera.width, camera.height, 1};
      std::vector<Fragment> fragments(static_cast<std::size_t>(camera.width * camera.height));
      rasterize(screen, grid_triangles(g), samples, 0, samples.rows(), s.near, fragments);
      int covered = 0, expected = 0;
      for (int r = 0; r < samples.rows(); ++r) {
        for (int c = 0; c < samples.columns(); ++c) {
          CAPTURE(c);
          CAPTURE(r);
          const Fragment& f = fragments[static_cast<std::size_t>(r * samples.columns() + c)];
          const double depth = depth_to_level(camera, samples.sample_x(c), samples.sample_y(r), 0);
          const bool meets = depth > s.near && depth < s.far;
          expected += meets ? 1 : 0;
          covered += f.triangle >= 0 ? 1 : 0;
          CHECK((f.triangle >= 0) == meets);
          if (f.triangle >= 0 && meets) CHECK(f.depth == doctest::Approx(depth).epsilon(1e-9));
        }
      }
      // Each viewpoint sees both sea and sky except straight down (all sea).
      CHECK(expected > 64 * 36 / 5);
      if (std::string(v.name) == "straight down") CHECK(covered == 64 * 36);
    }
  }
}

TEST_CASE("projected grid: a frustum that cannot see the sea gives no grid") {
  ProjectedGridSettings s;
  s.columns = 17;
  s.rows = 17;
  s.displacement_bound = 1.5;
  // Well above the volume, the whole frustum above the horizon: nothing to draw.
  const Camera up = make_camera({0, 10, 0}, {0, 40, 10}, {0, 1, 0}, 30 * kDeg, 64, 36);
  const ProjectedGrid g = project_grid(up, s);
  CHECK_FALSE(g.visible);
  CHECK(g.base.empty());
  CHECK(grid_triangles(g).empty());
  // The same view from inside the volume can see waves: visible.
  const Camera inside = make_camera({0, 1.0, 0}, {0, 31, 10}, {0, 1, 0}, 30 * kDeg, 64, 36);
  CHECK(project_grid(inside, s).visible);
}

TEST_CASE("projected grid: a mirror-symmetric view gives a mirror-symmetric grid, edge to edge") {
  // Vertex (i, j) sits at u = i/(columns − 1), v = j/(rows − 1) of the projector's widened
  // range (header, step 4), so the first and last columns are its two edges. A view whose
  // visible sea is mirror-symmetric has a range symmetric about the mirror: level and unrolled,
  // vertex i mirrors vertex columns − 1 − i about the camera's vertical plane; straight down,
  // (i, j) mirrors (columns − 1 − i, rows − 1 − j) about the point below the camera. Each (x0,
  // z0) is a few dozen rounded operations from the same matrices: 1e-9 of the grid's extent.
  for (const double bound : {0.0, 1.5}) {
    for (const int columns : {17, 12}) {
      CAPTURE(bound);
      CAPTURE(columns);
      ProjectedGridSettings s;
      s.columns = columns;
      s.rows = 9;
      s.displacement_bound = bound;
      const auto at = [&](const ProjectedGrid& g, int i, int j) {
        return g.base[static_cast<std::size_t>(j * columns + i)];
      };
      const Camera level = make_camera({0, 3, 0}, {0, 3, 100}, {0, 1, 0}, 50 * kDeg, 64, 36);
      const ProjectedGrid g = project_grid(level, s);
      REQUIRE(g.visible);
      const double width = std::fabs(at(g, columns - 1, 0).x - at(g, 0, 0).x);
      REQUIRE(width > 1.0);
      for (int j = 0; j < s.rows; ++j) {
        for (int i = 0; i < columns; ++i) {
          const glm::dvec2 a = at(g, i, j), b = at(g, columns - 1 - i, j);
          CHECK(std::fabs(a.x + b.x) <= 1e-9 * width);
          CHECK(std::fabs(a.y - b.y) <= 1e-9 * std::fabs(a.y));
        }
      }
      // (The projector may turn the grid's axes looking straight down; the point symmetry holds.)
      const Camera down = make_camera({3, 20, -4}, {3, 0, -4}, {0, 0, 1}, 60 * kDeg, 64, 36);
      const ProjectedGrid d = project_grid(down, s);
      REQUIRE(d.visible);
      const double extent = glm::length(at(d, columns - 1, s.rows - 1) - at(d, 0, 0));
      REQUIRE(extent > 1.0);
      for (int j = 0; j < s.rows; ++j) {
        for (int i = 0; i < columns; ++i) {
          const glm::dvec2 sum = at(d, i, j) + at(d, columns - 1 - i, s.rows - 1 - j);
          CHECK(glm::length(sum - glm::dvec2(6.0, -8.0)) <= 1e-9 * extent);
        }
      }
    }
  }
}

TEST_CASE("projected grid: the triangles tile the grid cells, two per cell, row by row") {
  ProjectedGrid g;
  g.visible = true;
  g.columns = 4;
  g.rows = 3;
  const auto t = grid_triangles(g);
  REQUIRE(t.size() == 2u * 3u * 2u);
  CHECK(t[0] == std::array<std::uint32_t, 3>{0, 1, 4});
  CHECK(t[1] == std::array<std::uint32_t, 3>{1, 5, 4});
  CHECK(t[2] == std::array<std::uint32_t, 3>{1, 2, 5});
  CHECK(t[6] == std::array<std::uint32_t, 3>{4, 5, 8});
  CHECK(t[11] == std::array<std::uint32_t, 3>{7, 11, 10});
}

namespace {
Scene wave_scene(const Viewpoint& v, const char* interpolation, const char* normals) {
  auto j = nlohmann::json::parse(R"({"seed": 4, "time": 2.0,
      "waves": {"spectrum": {"wind_speed": 5, "fetch": 20000}, "cascades": {"sizes": [120, 35]},
                "resolution": 32, "low_resolution": 16,
                "choppiness": -0.9},
      "grid": {"columns": 96, "rows": 96},
      "atmosphere": {"sun_zenith_deg": 60, "sun_azimuth_deg": 80, "turbidity": 3},
      "shading": {"accuracy": "fast", "sky_order": 2, "sun_order": 0},
      "render": {"width": 64, "height": 36, "samples_per_pixel": 1}})");
  j["camera"] = {{"position", {v.position.x, v.position.y, v.position.z}},
                 {"look_at", {v.look_at.x, v.look_at.y, v.look_at.z}},
                 {"up", {v.up.x, v.up.y, v.up.z}},
                 {"vertical_fov_deg", v.fov_deg}};
  j["shading"]["interpolation"] = interpolation;
  j["shading"]["normals"] = normals;
  return parse_scene(j);
}
}  // namespace

TEST_CASE("projected grid: every vertex is the displaced surface at its undisplaced point") {
  // The mesh render draws (surface_mesh) against the surface evaluated independently here:
  // p(x0) = (x0 + Σu_iD_i(x0), Σ η_i(x0), z0 + Σu_iD_i(x0)) (Gamper eq. 4.20, 4.24). From the
  // grids (bilinear, bicubic) the same function of the same fields: bit for bit. By direct
  // summation against combine_direct, which evaluates h(k, t) and sums on its own path: to
  // 1e-12 m (a few hundred components of |h| ≤ 0.5 m summed in a different grouping; the
  // rounding is ~1e-15 m per term).
  const Viewpoint v = kViewpoints[0];
  for (const char* interpolation : {"bilinear", "bicubic", "direct"}) {
    for (const char* normals : {"surface", "high_resolution"}) {
      CAPTURE(interpolation);
      CAPTURE(normals);
      const Scene scene = wave_scene(v, interpolation, normals);
      const Ocean ocean = realize_ocean(scene.waves, 1);
      const RenderJob job = scene_render_job(scene, ocean, 2);
      const SurfaceMesh mesh = surface_mesh(job);
      REQUIRE(mesh.grid.visible);
      REQUIRE(mesh.world.size() == mesh.grid.base.size());
      CHECK(mesh.triangles == grid_triangles(mesh.grid));
      const std::vector<CascadeFields> grids = synthesize_ocean(ocean, scene.time, 1);
      const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, scene.time);
      double largest_displacement = 0.0;
      for (std::size_t k = 0; k < mesh.world.size(); k += 7) {
        const glm::dvec2 x0 = mesh.grid.base[k];
        const glm::dvec3& p = mesh.world[k];
        CAPTURE(k);
        if (job.shading.interpolation == Interpolation::direct) {
          const PointFields f = combine_direct(ocean, x0.x, x0.y, scene.time);
          CHECK(std::fabs(p.x - (x0.x + f.raw[3])) < 1e-12 * (1.0 + std::fabs(x0.x)));
          CHECK(std::fabs(p.y - f.height) < 1e-12);
          CHECK(std::fabs(p.z - (x0.y + f.raw[4])) < 1e-12 * (1.0 + std::fabs(x0.y)));
        } else {
          const PointFields f = combine_shading_at(ocean, grids, evolved, x0.x, x0.y,
                                                   job.shading.interpolation, job.shading.normals);
          CHECK(p.x == x0.x + f.raw[static_cast<std::size_t>(Field::displacement_x)]);
          CHECK(p.y == f.height);
          CHECK(p.z == x0.y + f.raw[static_cast<std::size_t>(Field::displacement_z)]);
        }
        largest_displacement = std::fmax(largest_displacement, std::fabs(p.x - x0.x));
      }
      // The waves and the choppy displacement are really there (the check is not of a flat sea).
      CHECK(largest_displacement > 0.05);
    }
  }
}

TEST_CASE("rendered waves: covered iff the ray can meet the surface; horizon; straight down") {
  // With waves the surface lies between y = −h and y = +h (h the displacement bound the render
  // reports, Σ|h0| ≥ |η|), so from a camera above it a ray that reaches y = −h within the far
  // range must have met the surface:
  // its pixel is covered (coverage 1 at 1 sample per pixel) — this includes the image edges,
  // where the horizontal displacement must be inside the grid's margin. A ray that never comes
  // down to y = +h (from a camera above the volume: every ray at or above the horizon) cannot
  // meet the sea: coverage 0 and exactly the sky's radiance. Between the two planes: either.
  // (From a camera inside the volume whether a ray must meet the water depends on the water
  // at the camera: those viewpoints are checked on the flat sea above.)
  for (const Viewpoint& v : kViewpoints) {
    const std::string view_name = v.name;
    CAPTURE(view_name);
    const Scene scene = wave_scene(v, "bicubic", "surface");
    const Ocean ocean = realize_ocean(scene.waves, 1);
    RenderJob job = scene_render_job(scene, ocean, 2);
    job.layers = true;  // the depth layer
    const RenderedImage image = render(job, {0.01, 0.005});
    REQUIRE(image.depth.size() == image.radiance.size());
    const double h = image.displacement_bound;
    CAPTURE(h);
    REQUIRE(h > 0.1);
    REQUIRE(h < 1.5);  // so the "above the volume" viewpoints (y ≥ 3 m) are above it
    const Camera& camera = job.camera;
    const FrameLighting light = frame_lighting(job.sky, job.shading);
    int must = 0, must_not = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        CAPTURE(x);
        CAPTURE(y);
        const std::size_t i = static_cast<std::size_t>(y * image.width + x);
        const double low = depth_to_level(camera, x + 0.5, y + 0.5, -h);
        const double high = depth_to_level(camera, x + 0.5, y + 0.5, h);
        if (camera.position.y > h && low < job.grid.far) {
          ++must;
          CHECK(image.coverage[i] == 1.0);
        }
        if (camera.position.y > h && std::isinf(high)) {
          ++must_not;
          CHECK(image.coverage[i] == 0.0);
          const glm::dvec3 d = ray_direction(camera, x + 0.5, y + 0.5);
          Vec3 sky = sky_radiance_rgb(job.sky, {d.x, d.y, d.z});
          if (d.x * light.sun_direction[0] + d.y * light.sun_direction[1] +
                  d.z * light.sun_direction[2] >=
              light.cos_sun_radius) {
            for (std::size_t c = 0; c < 3; ++c) sky[c] += light.sun_radiance[c];
          }
          CHECK(image.radiance[i] == sky);
        }
      }
    }
    const std::string name = v.name;
    if (name == "straight down") {
      // Every pixel sees the sea at a view depth (= height above the surface) in [20 − h, 20 + h].
      CHECK(must == image.width * image.height);
      for (const double d : image.depth) CHECK((d >= 20.0 - h && d <= 20.0 + h));
    }
    // The level, rolled and upward views show the sky above the horizon.
    if (name.find("horizon") != std::string::npos) CHECK(must_not > 0);
    if (camera.position.y > h) CHECK(must > 0);
  }
}

TEST_CASE("rendered waves at the horizon: every vertex in front projects below the horizon") {
  // Camera level at 3 m, above the wave volume (h < 1.5 m): the horizon is the image's middle
  // row (y = 18 of 36); a surface point lower than the eye projects strictly below it. The mesh
  // reaches the far range (1e5 m), where the horizon and the vertices are ~3e-5 rad apart: a
  // vertex or triangle placed above the horizon would show as a vertex with y ≤ 18.
  const Viewpoint v = kViewpoints[1];
  const Scene scene = wave_scene(v, "bicubic", "surface");
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const RenderJob job = scene_render_job(scene, ocean, 2);
  const SurfaceMesh mesh = surface_mesh(job);
  REQUIRE(mesh.grid.visible);
  const double horizon_row = 0.5 * job.camera.height;
  double farthest = 0.0;
  int in_front = 0;
  for (const glm::dvec3& p : mesh.world) {
    const glm::dvec3 s = project(job.camera, p);
    if (!(s.z > job.grid.near)) continue;
    ++in_front;
    farthest = std::fmax(farthest, s.z);
    CHECK(p.y < job.camera.position.y);
    CHECK(s.y > horizon_row);
  }
  CHECK(in_front > 96 * 48);  // most of the grid is in front of the camera
  CHECK(farthest > 1e4);      // and it reaches out towards the horizon
}
