#include "raster/renderer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "core/check.h"
#include "core/format.h"
#include "core/fp_environment.h"
#include "core/math.h"
#include "core/memory.h"
#include "core/parallel.h"
#include "raster/footprint.h"
#include "raster/pixel_pattern.h"
#include "shading/ocean_brdf.h"
#include "shading/ocean_lighting.h"
#include "spectrum/moments.h"
#include "waves/fft.h"

namespace oceanref {

namespace {
Vec3 to_vec3(const glm::dvec3& v) {
  return {v.x, v.y, v.z};
}

using Geometry = FrameGeometry;

FrameFields frame_fields(const RenderJob& job, const FieldMask& wanted = kAllFields) {
  FrameFields f;
  if (job.shading.interpolation == Interpolation::direct) {
    f.evolved = evolve_ocean(*job.ocean, job.time);
  } else {
    f.grids = synthesize_ocean(*job.ocean, job.time, job.threads, wanted);
  }
  return f;
}

// The tracer's view of the frame's mesh.
TraceGrid trace_view(const Geometry& g) {
  return {g.grid.columns, g.grid.rows, &g.world, &g.triangles, &g.untraced};
}

// The footprint filter of the job's frame, or none (render.footprint_filtering off).
std::optional<FootprintFilter> frame_filter(const RenderJob& job) {
  if (!job.footprint_filtering) return std::nullopt;
  return make_footprint_filter(*job.ocean, job.time, job.shading.interpolation, job.shading.normals,
                               job.shading.whitecaps, job.threads);
}

// The objects' view for the tracer: the frame's vertices, their triangles.
TraceGrid object_view(const Geometry& g) {
  return {0, 0, &g.world, &g.object_triangles, &g.object_untraced};
}

// Appends the job's objects to the frame's vertices and triangles (FrameGeometry).
void add_objects(const RenderJob& job, Geometry& g) {
  g.sea_triangles = g.triangles.size();
  if (job.objects == nullptr || job.objects->triangles.empty()) return;
  const auto offset = static_cast<std::uint32_t>(g.world.size());
  for (const glm::dvec3& p : job.objects->positions) {
    g.world.push_back(p);
    const glm::dvec3 s = project(job.camera, p);
    g.screen.push_back({s.x, s.y, s.z});
  }
  for (const auto& t : job.objects->triangles) {
    g.object_triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    g.triangles.push_back(g.object_triangles.back());
  }
}

// The geometry's continuous surface (Renderer::raytrace_surface) without its evaluation: the
// grid's x0, p at them and the proven bounds.
TracedSurface surface_view(const Geometry& g) {
  TracedSurface s;
  s.columns = g.grid.columns;
  s.rows = g.grid.rows;
  s.base = &g.grid.base;
  s.corners = &g.surface_corners;
  const DisplacedSurfaceBounds& b = g.surface_bounds;
  s.lipschitz = glm::make_vec3(b.lipschitz.data());  // (x, y, z) in order
  s.offset = glm::make_vec3(b.offset.data());
  return s;
}

// The vertices read the waves filtered to their grid cell when filtering.
Geometry build_geometry(const RenderJob& job, const FrameFields& fields, double bound,
                        const std::optional<FootprintFilter>& filter) {
  Geometry g;
  ProjectedGridSettings settings = job.grid;
  settings.displacement_bound = bound;
  g.grid = project_grid(job.camera, settings);
  if (g.grid.visible) {
    const std::size_t count = g.grid.base.size();
    g.world = allocate_buffer<glm::dvec3>(count, "the displaced projected-grid vertices");
    g.screen = allocate_buffer<ScreenVertex>(count, "the projected-grid vertices on screen");
    parallel_for(g.grid.rows, job.threads, [&](int j) {
      for (int i = 0; i < g.grid.columns; ++i) {
        const std::size_t k =
            static_cast<std::size_t>(j) * static_cast<std::size_t>(g.grid.columns) +
            static_cast<std::size_t>(i);
        const glm::dvec2 x0 = g.grid.base[k];
        const DisplacedPoint p =
            filter ? filtered_displaced_point(*job.ocean, fields.grids, fields.evolved, *filter,
                                              x0.x, x0.y, grid_vertex_footprint(g.grid, i, j),
                                              job.shading.interpolation, job.shading.normals)
                   : displaced_point(*job.ocean, fields.grids, fields.evolved, x0.x, x0.y,
                                     job.shading.interpolation, job.shading.normals);
        g.world[k] = {p.x, p.height, p.z};
        const glm::dvec3 s = project(job.camera, g.world[k]);
        g.screen[k] = {s.x, s.y, s.z};
      }
    });
    g.triangles = grid_triangles(g.grid);
  }
  add_objects(job, g);
  if (is_ray_traced(job.renderer)) {
    // The rasterizer skips a triangle with a vertex at or behind the near plane (or not finite).
    const auto behind = [&](const std::array<std::uint32_t, 3>& t) {
      for (const std::uint32_t v : t) {
        if (!(g.screen[v].z > job.grid.near)) return true;
      }
      return false;
    };
    if (job.renderer == Renderer::raytrace) {  // the sea's triangles (else its surface, below)
      g.untraced.resize(g.sea_triangles);
      for (std::size_t t = 0; t < g.sea_triangles; ++t) g.untraced[t] = behind(g.triangles[t]);
      if (g.grid.visible) g.bounds = build_bounds_tree(trace_view(g));
    }
    g.object_untraced.resize(g.object_triangles.size());
    for (std::size_t t = 0; t < g.object_triangles.size(); ++t) {
      g.object_untraced[t] = behind(g.object_triangles[t]);
    }
    g.object_bounds = build_triangle_tree(object_view(g));
  }
  if (g.grid.visible && job.renderer == Renderer::raytrace_surface) {
    g.surface_corners = g.world;
    g.surface_corners.resize(g.grid.base.size());  // without the objects' vertices
    if (filter) {  // the vertices read filtered waves; the traced surface is the unfiltered one
      parallel_for(g.grid.rows, job.threads, [&](int j) {
        for (int i = 0; i < g.grid.columns; ++i) {
          const std::size_t k =
              static_cast<std::size_t>(j) * static_cast<std::size_t>(g.grid.columns) +
              static_cast<std::size_t>(i);
          const DisplacedPoint p =
              displaced_point(*job.ocean, fields.grids, fields.evolved, g.grid.base[k].x,
                              g.grid.base[k].y, job.shading.interpolation, job.shading.normals);
          g.surface_corners[k] = {p.x, p.height, p.z};
        }
      });
    }
    g.surface_bounds = displaced_surface_bounds(*job.ocean, fields.grids, fields.evolved,
                                                job.shading.interpolation);
    g.surface_tree = build_surface_tree(surface_view(g));
  }
  return g;
}

// The continuous surface of the frame (Renderer::raytrace_surface) for the surface tracer — the
// geometry's corners, bounds and the unfiltered p(x0) of waves/surface.h — and the tracer's
// settings from the camera and render.surface_tolerance: once per pass, not per ray.
struct SurfaceTrace {
  TracedSurface surface;
  SurfaceTraceSettings settings;
};
SurfaceTrace surface_trace(const RenderFrame& frame) {
  const RenderJob& job = frame.job;
  SurfaceTrace trace{surface_view(frame.geometry), {}};
  trace.settings.angular_tolerance =
      job.surface_tolerance * job.camera.vertical_fov / job.camera.height;
  trace.settings.forward = job.camera.forward;
  trace.settings.near = job.grid.near;
  TracedSurface& s = trace.surface;
  s.point = [&frame, &job](const glm::dvec2& x0) {
    const DisplacedPoint p =
        displaced_point(*job.ocean, frame.fields.grids, frame.fields.evolved, x0.x, x0.y,
                        job.shading.interpolation, job.shading.normals);
    return glm::dvec3(p.x, p.height, p.z);
  };
  s.point_derivatives = [&frame, &job](const glm::dvec2& x0) {
    const DisplacedPointDerivatives d =
        displaced_point_derivatives(*job.ocean, frame.fields.grids, frame.fields.evolved, x0.x,
                                    x0.y, job.shading.interpolation);
    return SurfacePoint{glm::dvec3(d.point.x, d.point.height, d.point.z),
                        glm::dvec3(d.d_dx0[0], d.d_dx0[1], d.d_dx0[2]),
                        glm::dvec3(d.d_dz0[0], d.d_dz0[1], d.d_dz0[2])};
  };
  return trace;
}

// A hit on the continuous surface as a fragment of the grid's triangles: the triangle of the
// hit's cell whose base (x0) holds the hit's x0, and its barycentric weights there, so that
// shade_sample's Σ w·x0 is the hit's x0 (to rounding).
RayHit surface_fragment_hit(const Geometry& g, const SurfaceHit& hit) {
  RayHit out;
  out.t = hit.t;
  const auto cross = [](const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; };
  double best_minimum = -std::numeric_limits<double>::infinity();
  for (const std::int64_t triangle : {2 * hit.cell, 2 * hit.cell + 1}) {
    const auto& t = g.triangles[static_cast<std::size_t>(triangle)];
    const glm::dvec2 a = g.grid.base[t[0]], b = g.grid.base[t[1]], c = g.grid.base[t[2]];
    const double area = cross(b - a, c - a);
    const double u = cross(hit.x0 - a, c - a) / area, v = cross(b - a, hit.x0 - a) / area;
    const std::array<double, 3> w{1.0 - u - v, u, v};
    const double minimum = std::min({w[0], w[1], w[2]});
    if (!(minimum > best_minimum)) continue;
    best_minimum = minimum;
    out.triangle = triangle;
    // Outside by rounding only: clamped and renormalized.
    const double sum = std::max(w[0], 0.0) + std::max(w[1], 0.0) + std::max(w[2], 0.0);
    for (std::size_t k = 0; k < 3; ++k) out.weights[k] = std::max(w[k], 0.0) / sum;
  }
  return out;
}

// The nearest hit of a ray from the camera: the sea's or an object's (objects numbered from
// sea_triangles on); equal distances to the sea, as the rasterizer's depth ties.
RayHit trace_scene(const RenderFrame& frame, const SurfaceTrace* surface, const glm::dvec3& origin,
                   const glm::dvec3& direction) {
  const Geometry& g = frame.geometry;
  RayHit sea;
  if (surface != nullptr) {
    const SurfaceHit hit =
        trace_surface(surface->surface, g.surface_tree, surface->settings, origin, direction);
    if (hit.hit) sea = surface_fragment_hit(g, hit);
  } else {
    sea = trace_ray(trace_view(g), g.bounds, origin, direction);
  }
  if (g.object_triangles.empty()) return sea;
  RayHit object = trace_ray(object_view(g), g.object_bounds, origin, direction);
  if (object.triangle < 0 || (sea.triangle >= 0 && !(object.t < sea.t))) return sea;
  object.triangle += static_cast<std::int64_t>(g.sea_triangles);
  return object;
}

// The fragments of sample rows [first_row, last_row), columns `window`, of `grid` by ray tracing
// (Renderer::raytrace, raytrace_surface) into `out`, which holds rows from fragment_row on (as
// rasterize): each sample's ray against the displaced grid (or the continuous surface), its
// nearest hit with the world-space weights (the perspective-correct ones; on the surface, the
// weights of the hit's x0) and the view depth of the hit point.
void trace_fragments(const RenderFrame& frame, const SampleGrid& grid, int first_row, int last_row,
                     std::vector<Fragment>& out, int fragment_row, FragmentColumns window,
                     int threads) {
  const RenderJob& job = frame.job;
  if (frame.geometry.triangles.empty()) return;
  const std::optional<SurfaceTrace> surface = job.renderer == Renderer::raytrace_surface
                                                  ? std::optional(surface_trace(frame))
                                                  : std::nullopt;
  const int count = window.count < 0 ? grid.columns() - window.first : window.count;
  parallel_for(last_row - first_row, threads, [&](int r) {
    const int row = first_row + r;
    for (int a = 0; a < count; ++a) {
      const int column = window.first + a;
      const glm::dvec3 d = ray_direction(job.camera, grid.sample_x(column), grid.sample_y(row));
      const RayHit hit = trace_scene(frame, surface ? &*surface : nullptr, job.camera.position, d);
      if (hit.triangle < 0) continue;
      Fragment& f =
          out[static_cast<std::size_t>(row - fragment_row) * static_cast<std::size_t>(count) +
              static_cast<std::size_t>(a)];
      f.triangle = hit.triangle;
      f.weights = hit.weights;
      f.depth = project(job.camera, job.camera.position + hit.t * d).z;
    }
  });
}

// The fragments of arbitrary image positions [pixels] by ray tracing, as trace_fragments.
void trace_points(const RenderFrame& frame, std::span<const std::array<double, 2>> points,
                  std::span<Fragment> out) {
  const RenderJob& job = frame.job;
  if (frame.geometry.triangles.empty()) return;
  const std::optional<SurfaceTrace> surface = job.renderer == Renderer::raytrace_surface
                                                  ? std::optional(surface_trace(frame))
                                                  : std::nullopt;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 d = ray_direction(job.camera, points[i][0], points[i][1]);
    const RayHit hit = trace_scene(frame, surface ? &*surface : nullptr, job.camera.position, d);
    if (hit.triangle < 0) continue;
    out[i] = {project(job.camera, job.camera.position + hit.t * d).z, hit.triangle, hit.weights};
  }
}

// The unit normal of an object triangle, facing against `ray` (two-sided).
Vec3 object_normal(const Geometry& g, std::size_t triangle, const glm::dvec3& ray) {
  const auto& t = g.triangles[triangle];
  glm::dvec3 n = glm::cross(g.world[t[1]] - g.world[t[0]], g.world[t[2]] - g.world[t[0]]);
  if (glm::dot(n, ray) > 0.0) n = -n;
  return normalize(to_vec3(n));
}

// The radiance an object triangle sends back along `ray`.
Vec3 object_radiance(const RenderFrame& frame, std::size_t triangle, const glm::dvec3& ray,
                     Vec3* normal = nullptr) {
  const Geometry& g = frame.geometry;
  const Vec3 n = object_normal(g, triangle, ray);
  if (normal != nullptr) *normal = n;
  const SceneObjects& objects = *frame.job.objects;
  const ObjectMaterial& m = objects.materials[objects.material[triangle - g.sea_triangles]];
  const FrameLighting& light = frame.light;
  return diffuse_object_radiance(m.albedo, n, light.sun_direction,
                                 scaled(light.sun_radiance, light.sun_solid_angle),
                                 light.sky_irradiance);
}

// A = I + u∂D̄ of read fields (their raw sums are scaled by u).
Deformation read_deformation(const PointFields& f) {
  return {1.0 + f.raw[static_cast<std::size_t>(Field::ddx_dx)],
          f.raw[static_cast<std::size_t>(Field::ddx_dz)], f.ddz_dx,
          1.0 + f.raw[static_cast<std::size_t>(Field::ddz_dz)]};
}

// One sample, its cell `cell` pixels wide (1/S of a grid's; footprint filtering reads the waves
// filtered to it), its lighting integrals by `lighting`'s accuracy (frame.sample_shading, or
// job.shading for a two-level correction).
SampleProbe shade_sample(const RenderFrame& frame, const Fragment& f, const glm::dvec3& ray,
                         double cell, const ShadingSettings& lighting) {
  const RenderJob& job = frame.job;
  const Geometry& g = frame.geometry;
  const FrameLighting& light = frame.light;
  SampleProbe p;
  if (f.triangle < 0) {
    // The sky (and the sun disk) behind the sea.
    const Vec3 d = to_vec3(ray);
    p.radiance = sky_radiance_rgb(job.sky, d);
    if (dot(d, light.sun_direction) >= light.cos_sun_radius) {
      for (std::size_t c = 0; c < 3; ++c) p.radiance[c] += light.sun_radiance[c];
    }
    return p;
  }
  p.depth = f.depth;
  p.triangle = f.triangle;
  const auto& t = g.triangles[static_cast<std::size_t>(f.triangle)];
  if (static_cast<std::size_t>(f.triangle) >= g.sea_triangles) {
    p.object = true;
    for (std::size_t v = 0; v < 3; ++v) p.position += f.weights[v] * g.world[t[v]];
    p.radiance = object_radiance(frame, static_cast<std::size_t>(f.triangle), ray, &p.normal);
    return p;
  }
  p.hit = true;
  for (std::size_t v = 0; v < 3; ++v) {
    p.x0 += f.weights[v] * g.grid.base[t[v]];
    p.position += f.weights[v] * g.world[t[v]];
  }
  const Ocean& ocean = *job.ocean;
  const ShadingSettings& sh = job.shading;
  if (job.renderer == Renderer::raytrace_surface) {  // on the continuous surface, at x0
    const DisplacedPoint q = displaced_point(ocean, frame.fields.grids, frame.fields.evolved,
                                             p.x0.x, p.x0.y, sh.interpolation, sh.normals);
    p.position = {q.x, q.height, q.z};
  }
  p.roughness = frame.unresolved;
  if (frame.filter) {
    // The sample's cell (1/S pixel) on the sea plane: the waves read filtered to it, and the
    // slope variance under it that the read normal lacks added to σ² (footprint_filter.h).
    std::array<ScreenVertex, 3> screen{};
    std::array<glm::dvec2, 3> base{};
    for (std::size_t v = 0; v < 3; ++v) {
      screen[v] = g.screen[t[v]];
      base[v] = g.grid.base[t[v]];
    }
    p.footprint = sample_footprint(base_derivatives(screen, base, f.weights), cell);
    p.fields = filtered_fields_at(ocean, frame.fields.grids, frame.fields.evolved, *frame.filter,
                                  p.x0.x, p.x0.y, p.footprint, sh.interpolation, sh.normals);
    const SlopeVariance v = footprint_slope_variance(*frame.filter, p.footprint);
    p.roughness.upwind += v.upwind;
    p.roughness.crosswind += v.crosswind;
  } else {
    p.fields = combine_shading_at(ocean, frame.fields.grids, frame.fields.evolved, p.x0.x, p.x0.y,
                                  sh.interpolation, sh.normals);
  }
  p.normal = p.fields.normal;  // shading.normals (waves/surface.h)
  p.view = to_vec3(glm::normalize(job.camera.position - p.position));
  // The geometry faces the camera but the shading normal (from waves finer than the grid) may
  // not: bend it towards the viewer until V·N = 0.001 (documented in README, "render").
  constexpr double kMinimumCosView = 1e-3;
  const double vn = dot(p.view, p.normal);
  if (vn < kMinimumCosView) {
    Vec3 n{};
    for (std::size_t c = 0; c < 3; ++c) n[c] = p.normal[c] + (kMinimumCosView - vn) * p.view[c];
    p.normal = normalize(n);
  }
  if (sh.model == ShadingModel::four_term) {
    p.lighting = four_term_lighting(sh, job.sky, light, p.view, p.normal, p.position.y);
  } else {
    const SurfaceFrame surface = wind_frame(p.normal, job.ocean->spectrum.wind_direction);
    // The two-level estimate's lighting error is its correction's bound, not the fast rules'.
    p.lighting = lighting_terms(lighting, job.sky, light, p.view, surface, p.roughness,
                                job.estimate_fast_error && !job.lighting_correction);
  }
  if (is_ray_traced(job.renderer) && job.object_reflections && !g.object_triangles.empty()) {
    // The mirror ray about the shading normal: an object there replaces the reflected sky.
    const double vn_shading = dot(p.view, p.normal);
    const Vec3 mirror = combine(2.0 * vn_shading, p.normal, -1.0, p.view);
    const glm::dvec3 r(mirror[0], mirror[1], mirror[2]);
    const RayHit hit = trace_ray(object_view(g), g.object_bounds, p.position, r);
    if (hit.triangle >= 0) {
      p.reflects_object = true;
      const Vec3 seen =
          object_radiance(frame, g.sea_triangles + static_cast<std::size_t>(hit.triangle), r);
      const double fresnel = fresnel_reflectance(vn_shading, sh.brdf.fresnel);
      p.lighting.sky = scaled(seen, fresnel);
      p.lighting.sky_error = Vec3{};
    }
  }
  const LightingTerms& l = p.lighting;
  for (std::size_t c = 0; c < 3; ++c) {
    p.radiance[c] = l.sun[c] + l.sky[c] + l.sea[c];
    p.lighting_error[c] = l.sun_error[c] + l.sky_error[c] + l.sea_error[c];
  }
  if (sh.whitecaps) {
    // Dupuy & Bruneton: det J under the sample's footprint is normal with the read fields' det J
    // as mean and the variance of the waves they lack (waves/whitecaps.h): the unresolved ones
    // and, with footprint filtering, those the filter removed under the footprint.
    const JacobianMoments residual =
        frame.filter
            ? job.unresolved_jacobian + footprint_jacobian_moments(*frame.filter, p.footprint)
            : job.unresolved_jacobian;
    p.jacobian_mean = p.fields.jacobian;
    p.jacobian_variance =
        jacobian_variance(read_deformation(p.fields), residual, frame.wind_cos, frame.wind_sin);
    p.whitecap_coverage = foam_coverage_at(frame, p.fields, p.x0.x, p.x0.y, residual);
    const double cos_sun = std::fmax(0.0, dot(p.normal, light.sun_direction));
    Vec3 e_sun{};
    for (std::size_t c = 0; c < 3; ++c) {
      e_sun[c] = light.sun_radiance[c] * light.sun_solid_angle * cos_sun;
    }
    p.foam = foam_radiance(sh.foam_albedo, e_sun, light.sky_irradiance);
    p.radiance = mix_whitecaps(p.radiance, p.foam, p.whitecap_coverage);
    for (double& e : p.lighting_error) e *= 1.0 - p.whitecap_coverage;
  }
  return p;
}

// The fragments of the sample rows [first_row, last_row).
std::vector<Fragment> raster_pass(const RenderFrame& frame, const SampleGrid& grid, int first_row,
                                  int last_row) {
  const RenderJob& job = frame.job;
  const Geometry& g = frame.geometry;
  const int rows = last_row - first_row;
  std::vector<Fragment> fragments = allocate_buffer<Fragment>(
      static_cast<std::size_t>(grid.columns()) * static_cast<std::size_t>(rows),
      "the sample fragments (one per sample of the image)");
  if (g.triangles.empty() || rows == 0) return fragments;
  if (is_ray_traced(job.renderer)) {
    trace_fragments(frame, grid, first_row, last_row, fragments, first_row, {}, job.threads);
    return fragments;
  }
  // Bands of sample rows handed out one at a time (parallel_for): the sea's triangles crowd
  // near the horizon, so equal shares per thread would not be equal work; about 8 per thread.
  // Each band rasterizes the triangles that reach it, in triangle order (binned first).
  const int bands = std::min(rows, 8 * std::max(1, job.threads));
  std::vector<int> starts(static_cast<std::size_t>(bands) + 1);
  for (int b = 0; b <= bands; ++b) {
    starts[static_cast<std::size_t>(b)] =
        first_row + static_cast<int>(static_cast<long>(rows) * b / bands);
  }
  // The band holding a sample row in [first_row, last_row).
  const auto band_of = [&](double row) {
    return static_cast<std::size_t>(
        std::upper_bound(starts.begin(), starts.end() - 1, static_cast<int>(row)) - starts.begin() -
        1);
  };
  std::vector<std::vector<std::uint32_t>> binned(static_cast<std::size_t>(bands));
  for (std::size_t t = 0; t < g.triangles.size(); ++t) {
    const auto& v = g.triangles[t];
    const auto [lo, hi] =
        sample_rows_of(g.screen[v[0]], g.screen[v[1]], g.screen[v[2]], grid, job.grid.near);
    if (!(lo < last_row && hi > first_row)) continue;
    // The bands from the one holding row max(lo, first_row) to the one holding hi − 1.
    const std::size_t b0 = band_of(std::fmax(lo, first_row));
    const std::size_t b1 = band_of(std::fmin(hi, last_row) - 1.0);
    for (std::size_t b = b0; b <= b1; ++b) binned[b].push_back(static_cast<std::uint32_t>(t));
  }
  parallel_for(bands, job.threads, [&](int band) {
    const auto b = static_cast<std::size_t>(band);
    rasterize(g.screen, g.triangles, binned[b], grid, starts[b], starts[b + 1], job.grid.near,
              fragments, first_row);
  });
  return fragments;
}

// What the resolve of a pixel keeps of one sample.
struct SampleValue {
  Vec3 radiance{}, lighting_error{}, sun{}, sky{}, sea{}, foam{};
  double whitecap_coverage = 0.0;
  Vec3 normal{};
  glm::dvec2 x0{0.0};
  double depth = 0.0;
  bool hit = false;
};
static_assert(sizeof(SampleValue) == kResolvedSampleBytes, "refinement_bytes counts these");

SampleValue sample_value(const SampleProbe& p) {
  return {p.radiance, p.lighting_error,    p.lighting.sun, p.lighting.sky, p.lighting.sea,
          p.foam,     p.whitecap_coverage, p.normal,       p.x0,           p.depth,
          p.hit};
}

// A pixel's mean radiance and its estimated error as the pixel integral.
struct PixelEstimate {
  Vec3 mean{};
  Vec3 error{};
};

// What the reference changes of one sample lit by the fast rules (RenderJob::lighting_correction):
// reference − fast of the radiance and the terms, and the reference's estimated error of the
// radiance. 0 for a sample that does not see the sea (no lighting integral).
struct SampleCorrection {
  Vec3 radiance{}, sun{}, sky{}, sea{};
  Vec3 estimate{};
};
static_assert(sizeof(SampleCorrection) == kCorrectionSampleBytes, "refinement_bytes counts these");

// The two-level estimate's correction of one pixel: the mean of its samples' corrections at one
// level of the nested grid, and the lighting part of the pixel's bound.
struct PixelCorrection {
  Vec3 radiance{}, sun{}, sky{}, sea{};  // the means of reference − fast
  // kPixelErrorStandardErrors standard errors of the mean radiance correction + the mean of the
  // reference's estimates; +∞ where nothing estimates it (one sample of the sea, or none of the
  // level's samples on the sea while others of the pixel are).
  Vec3 error{};
};

// The mean of `field` over the values: Σ (1/n)·value in order from 0 (the resolve's sum).
template <class Value>
Vec3 mean_of(std::span<const Value> values, Vec3 Value::*field) {
  const double per_sample = 1.0 / static_cast<double>(values.size());
  Vec3 mean{};
  for (const Value& v : values) {
    for (std::size_t c = 0; c < 3; ++c) mean[c] += per_sample * (v.*field)[c];
  }
  return mean;
}

// The mean of `field` over the values of an S×S grid (with Mastin's anti-aliasing, and its 16
// more) and its bound: kPixelErrorStandardErrors standard errors of the mean with the samples
// taken as independent (0 for one sample).
template <class Value>
PixelEstimate fixed_grid_estimate(std::span<const Value> values, Vec3 Value::*field) {
  PixelEstimate e;
  e.mean = mean_of(values, field);
  std::array<Vec3, kMaxSamplesPerAxis * kMaxSamplesPerAxis +
                       kMastinExtraSamplesPerAxis * kMastinExtraSamplesPerAxis>
      x;
  OCEANREF_EXPECTS(values.size() <= x.size(), "at most 32 x 32 + 16 samples of a fixed grid");
  for (std::size_t i = 0; i < values.size(); ++i) x[i] = values[i].*field;
  const Vec3 se = pixel_standard_error(std::span(x.data(), values.size()), e.mean);
  for (std::size_t c = 0; c < 3; ++c) e.error[c] = kPixelErrorStandardErrors * se[c];
  return e;
}

// The same for the n×n values of a refined grid (n a multiple of 3): the standard error from the
// spread of the nine interleaved (n/3)×(n/3) grids' means (every third value from offset
// (i, j)), each a stratified estimate of the pixel.
template <class Value>
PixelEstimate nested_grid_estimate(std::span<const Value> values, int n, Vec3 Value::*field) {
  PixelEstimate e;
  e.mean = mean_of(values, field);
  std::array<Vec3, 9> sub{};
  const int m = n / 3;
  const double per_sample = 1.0 / (static_cast<double>(m) * m);
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const Vec3& v = values[static_cast<std::size_t>(b) * static_cast<std::size_t>(n) +
                             static_cast<std::size_t>(a)].*
                      field;
      Vec3& g = sub[static_cast<std::size_t>(3 * (b % 3) + a % 3)];
      for (std::size_t c = 0; c < 3; ++c) g[c] += per_sample * v[c];
    }
  }
  const Vec3 spread = pixel_standard_error(sub, e.mean);
  for (std::size_t c = 0; c < 3; ++c) e.error[c] = kPixelErrorStandardErrors * spread[c];
  return e;
}

// The estimate of the n×n values of a pixel grid (n = S: the fixed grid; else refined).
template <class Value>
PixelEstimate grid_estimate(std::span<const Value> values, int n, int samples_per_axis,
                            Vec3 Value::*field) {
  return n == samples_per_axis ? fixed_grid_estimate(values, field)
                               : nested_grid_estimate(values, n, field);
}

// The Sobol' pattern's estimate from values stored point-major (point i of replicate r at
// i·kPixelReplicates + r): the mean of the first `points` points of the first `replicates`
// replicates (a prefix of the values: replicates < kPixelReplicates only with one point) and
// its bound, kPixelErrorStandardErrors standard errors from the spread of the replicates' means.
template <class Value>
PixelEstimate replicate_estimate(std::span<const Value> values, int replicates, int points,
                                 Vec3 Value::*field) {
  OCEANREF_EXPECTS(replicates == kPixelReplicates || (replicates < kPixelReplicates && points == 1),
                   "a prefix of the point-major values");
  const std::size_t count = static_cast<std::size_t>(replicates) * static_cast<std::size_t>(points);
  PixelEstimate e;
  e.mean = mean_of(values.first(count), field);
  std::array<Vec3, kPixelReplicates> means{};
  const double per_point = 1.0 / points;
  for (std::size_t i = 0; i < count; ++i) {
    Vec3& m = means[i % kPixelReplicates];
    for (std::size_t c = 0; c < 3; ++c) m[c] += per_point * (values[i].*field)[c];
  }
  const Vec3 se =
      pixel_standard_error(std::span(means.data(), static_cast<std::size_t>(replicates)), e.mean);
  for (std::size_t c = 0; c < 3; ++c) e.error[c] = kPixelErrorStandardErrors * se[c];
  return e;
}

// What the reference changes of a sample lit by the fast rules: reference − fast.
SampleCorrection sample_correction(const SampleValue& fast, const SampleProbe& reference) {
  SampleCorrection d;
  for (std::size_t c = 0; c < 3; ++c) {
    d.radiance[c] = reference.radiance[c] - fast.radiance[c];
    d.sun[c] = reference.lighting.sun[c] - fast.sun[c];
    d.sky[c] = reference.lighting.sky[c] - fast.sky[c];
    d.sea[c] = reference.lighting.sea[c] - fast.sea[c];
  }
  d.estimate = reference.lighting_error;
  return d;
}

// Whether any of the samples sees the sea.
bool sees_sea(std::span<const SampleValue> values) {
  return std::any_of(values.begin(), values.end(), [](const SampleValue& v) { return v.hit; });
}

// The correction of a pixel from one level's sample corrections (0 where a sample does not see
// the sea) and their estimate: unknown (+∞) where the pixel sees the sea but none of the level's
// samples does, or the level has one sample.
PixelCorrection pixel_correction(std::span<const SampleCorrection> level, bool level_sees_sea,
                                 bool pixel_sees_sea, const PixelEstimate& e) {
  PixelCorrection out;
  out.radiance = e.mean;
  out.sun = mean_of(level, &SampleCorrection::sun);
  out.sky = mean_of(level, &SampleCorrection::sky);
  out.sea = mean_of(level, &SampleCorrection::sea);
  const Vec3 estimates = mean_of(level, &SampleCorrection::estimate);
  const bool unknown = pixel_sees_sea && (!level_sees_sea || level.size() < 2);
  for (std::size_t c = 0; c < 3; ++c) {
    out.error[c] = unknown ? HUGE_VAL : e.error[c] + estimates[c];
  }
  return out;
}

// The pixel from its samples and their estimate, box-filtered: Σ (1/n)·value in sample order
// from 0 (as mean_of); depth, normal and x0 the means over the sea samples. With a correction
// (RenderJob::lighting_correction), `estimate` is the corrected pixel, the terms are corrected
// alike and the lighting error is the correction's bound.
void resolve_into(RenderedImage& image, std::size_t pixel, std::span<const SampleValue> values,
                  const PixelEstimate& estimate, bool layers,
                  const PixelCorrection* correction = nullptr) {
  const double per_sample = 1.0 / static_cast<double>(values.size());
  Vec3 lighting_error{}, sun{}, sky{}, sea{}, foam{}, normal{}, x0{};
  double depth = 0.0;
  int hits = 0;
  for (const SampleValue& v : values) {
    for (std::size_t c = 0; c < 3; ++c) {
      lighting_error[c] += per_sample * v.lighting_error[c];
      sun[c] += per_sample * v.sun[c];
      sky[c] += per_sample * v.sky[c];
      sea[c] += per_sample * v.sea[c];
      foam[c] += per_sample * v.whitecap_coverage * v.foam[c];
    }
    if (!v.hit) continue;
    ++hits;
    depth += v.depth;
    for (std::size_t c = 0; c < 3; ++c) normal[c] += v.normal[c];
    x0[0] += v.x0.x;
    x0[2] += v.x0.y;
  }
  if (correction != nullptr) {
    lighting_error = correction->error;
    for (std::size_t c = 0; c < 3; ++c) {
      sun[c] += correction->sun[c];
      sky[c] += correction->sky[c];
      sea[c] += correction->sea[c];
    }
  }
  image.radiance[pixel] = estimate.mean;
  image.pixel_error[pixel] = estimate.error;
  image.lighting_error[pixel] = lighting_error;
  image.coverage[pixel] = hits * per_sample;
  if (!layers) return;
  image.sun[pixel] = sun;
  image.sky[pixel] = sky;
  image.sea[pixel] = sea;
  image.foam[pixel] = foam;
  if (hits > 0) {
    depth /= hits;
    for (std::size_t c = 0; c < 3; ++c) {
      normal[c] /= hits;
      x0[c] /= hits;
    }
  }
  image.depth[pixel] = depth;
  image.normal[pixel] = normal;
  image.x0[pixel] = x0;
}

// The pixel's bound against the tolerance T = pixel_tolerance × the largest channel of the
// (corrected) mean, per channel: whether pixel_error + lighting_error ≤ T, whether the pixel part
// alone exceeds T/2, and whether it alone is within T (so that a finer correction can help).
struct Budget {
  bool within = true;
  bool pixel_over_half = false;
  bool pixel_within = true;
};
Budget budget(const PixelEstimate& e, const PixelCorrection* correction, double tolerance) {
  const double largest = std::max({e.mean[0], e.mean[1], e.mean[2]});
  const double allowed = tolerance * largest;
  Budget b;
  for (std::size_t c = 0; c < 3; ++c) {
    const double lighting = correction != nullptr ? correction->error[c] : 0.0;
    if (!(e.error[c] + lighting <= allowed)) b.within = false;
    if (!(e.error[c] <= 0.5 * allowed)) b.pixel_over_half = true;
    if (!(e.error[c] <= allowed)) b.pixel_within = false;
  }
  return b;
}

// For each pixel row of [first_row, last_row), the triangles (ascending) whose screen extent
// reaches it; triangles behind the near plane, or not finite, reach none.
std::vector<std::vector<std::uint32_t>> triangles_by_pixel_row(const RenderJob& job,
                                                               const Geometry& g, int first_row,
                                                               int last_row) {
  std::vector<std::vector<std::uint32_t>> rows(static_cast<std::size_t>(last_row - first_row));
  for (std::size_t t = 0; t < g.triangles.size(); ++t) {
    const auto& v = g.triangles[t];
    const ScreenVertex &a = g.screen[v[0]], &b = g.screen[v[1]], &c = g.screen[v[2]];
    if (!(a.z > job.grid.near && b.z > job.grid.near && c.z > job.grid.near)) continue;
    const double lo = std::fmax(std::floor(std::min({a.y, b.y, c.y})), first_row);
    const double hi = std::fmin(std::floor(std::max({a.y, b.y, c.y})), last_row - 1.0);
    if (!(lo <= hi)) continue;  // NaN too
    for (int y = static_cast<int>(lo); y <= static_cast<int>(hi); ++y) {
      rows[static_cast<std::size_t>(y - first_row)].push_back(static_cast<std::uint32_t>(t));
    }
  }
  return rows;
}

// Whether triangle t's screen extent reaches pixel column x.
bool reaches_column(const Geometry& g, std::uint32_t t, int x) {
  const auto& v = g.triangles[t];
  const double lo = std::min({g.screen[v[0]].x, g.screen[v[1]].x, g.screen[v[2]].x});
  const double hi = std::max({g.screen[v[0]].x, g.screen[v[1]].x, g.screen[v[2]].x});
  return lo <= x + 1.0 && hi >= x;
}

}  // namespace

std::vector<int> spread_order(int count) {
  int bits = 0;
  while ((1L << bits) < count) ++bits;
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(count));
  for (long i = 0; i < (1L << bits); ++i) {
    long reversed = 0;  // i with its `bits` bits in reverse order
    for (int b = 0; b < bits; ++b) reversed |= ((i >> b) & 1L) << (bits - 1 - b);
    if (reversed < count) order.push_back(static_cast<int>(reversed));
  }
  return order;
}

int refined_samples_per_axis(int samples_per_axis, int refinements) {
  int n = samples_per_axis;
  for (int r = 0; r < refinements; ++r) n *= 3;
  return n;
}

int sobol_first_points(int samples_per_axis) {
  int n = 1;
  while (kPixelReplicates * n < samples_per_axis * samples_per_axis) n *= 2;
  return n;
}

int adaptive_samples(PixelPattern pattern, int samples_per_axis, int refinements) {
  if (pattern == PixelPattern::sobol) {
    return kPixelReplicates * (sobol_first_points(samples_per_axis) << refinements);
  }
  const int n = refined_samples_per_axis(samples_per_axis, refinements);
  return n * n;
}

double refinement_bytes(int samples, bool lighting_correction) {
  const double correction = lighting_correction ? kCorrectionSampleBytes : 0.0;
  return samples * (static_cast<double>(sizeof(Fragment) + 2 * kResolvedSampleBytes +
                                        sizeof(std::array<double, 2>)) +
                    correction);
}

double luminance_contrast(const Vec3& a, const Vec3& b) {
  const auto y = [](const Vec3& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
  const double ya = y(a), yb = y(b);
  const double sum = std::fabs(ya) + std::fabs(yb);
  return sum > 0.0 ? std::fabs(ya - yb) / sum : 0.0;
}

Vec3 pixel_standard_error(std::span<const Vec3> samples, const Vec3& mean) {
  Vec3 error{};
  if (samples.size() < 2) return error;
  const double n = static_cast<double>(samples.size());
  for (std::size_t c = 0; c < 3; ++c) {
    double squares = 0.0;
    for (const Vec3& x : samples) squares += (x[c] - mean[c]) * (x[c] - mean[c]);
    error[c] = std::sqrt(squares / (n * (n - 1.0)));
  }
  return error;
}

SlopeVarianceBudget slope_budget(const RenderJob& job, const WaveSettings& waves) {
  const ReferenceFpEnvironment fp;
  return slope_variance_budget(*job.ocean, waves.minimum_wavelength, job.time,
                               job.shading.interpolation, job.shading.normals, job.threads);
}

SlopeVariance unresolved_slope_variance(const RenderJob& job, const WaveSettings& waves) {
  return slope_budget(job, waves).unresolved;
}

namespace {
// Adds the seconds since the last lap to a stage of `times` (when given).
class StageClock {
 public:
  explicit StageClock(RenderTimes* times) : times_(times) {}
  void lap(double RenderTimes::*stage) {
    const auto now = std::chrono::steady_clock::now();
    if (times_ != nullptr) times_->*stage += std::chrono::duration<double>(now - start_).count();
    start_ = now;
  }

 private:
  RenderTimes* times_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};
}  // namespace

double foam_coverage_at(const RenderFrame& frame, const PointFields& fields, double x, double z,
                        const JacobianMoments& residual) {
  const RenderJob& job = frame.job;
  const ShadingSettings& sh = job.shading;
  const auto coverage = [&](double jacobian, const Deformation& a) {
    return whitecap_coverage(jacobian,
                             jacobian_variance(a, residual, frame.wind_cos, frame.wind_sin),
                             sh.whitecap_threshold);
  };
  const double now = coverage(fields.jacobian, read_deformation(fields));
  if (frame.foam_history.empty()) return now;
  FrameStencils stencils;  // the earlier frames' grids share their sizes: located once
  const auto earlier_coverage = [&](int age) {
    const FrameFields& earlier =
        frame.foam_history[frame.foam_history.size() - static_cast<std::size_t>(age)];
    const SurfaceDeformation d = deformation_at(*job.ocean, earlier.grids, earlier.evolved, x, z,
                                                sh.interpolation, sh.normals, stencils);
    return coverage(d.jacobian, Deformation{1.0 + d.ddx_dx, d.ddx_dz, d.ddz_dx, 1.0 + d.ddz_dz});
  };
  return accumulated_foam_of_history(static_cast<int>(frame.foam_history.size()), now,
                                     job.foam.decay, job.foam.time_step, earlier_coverage);
}

RenderFrame prepare_frame(const RenderJob& job, const SlopeVariance& unresolved,
                          RenderTimes* times) {
  OCEANREF_EXPECTS(job.ocean != nullptr && job.samples_per_axis >= 1 &&
                       job.samples_per_axis <= kMaxSamplesPerAxis,
                   "a render job names its ocean and has 1 to " +
                       std::to_string(kMaxSamplesPerAxis) + " samples per axis");
  const ReferenceFpEnvironment fp;
  StageClock clock(times);
  RenderFrame frame;
  frame.job = job;
  frame.unresolved = unresolved;
  frame.wind_cos = math::cos(job.ocean->spectrum.wind_direction);
  frame.wind_sin = math::sin(job.ocean->spectrum.wind_direction);
  frame.fields = frame_fields(job);
  if (job.shading.whitecaps && job.foam.steps > 0) {
    OCEANREF_EXPECTS(!job.footprint_filtering,
                     "accumulated foam without footprint filtering (scene validation)");
    // Only the deformation is read from earlier frames (foam_coverage_at): only its fields are
    // synthesized and kept (a transform's partner field is released), so the history costs 2
    // of the 8 fields (surface normals).
    // The frames are synthesized side by side, each on one thread (its small transforms do not
    // gain from more; the fields do not depend on the thread count).
    const FieldMask kept = deformation_fields(job.shading.normals);
    frame.foam_history.resize(static_cast<std::size_t>(job.foam.steps));
    parallel_for(job.foam.steps, job.threads, [&](int k) {
      RenderJob earlier = job;  // the oldest first: t − steps·Δt, …, t − Δt
      earlier.time = job.time - (job.foam.steps - k) * job.foam.time_step;
      earlier.threads = 1;
      FrameFields& f = frame.foam_history[static_cast<std::size_t>(k)];
      f = frame_fields(earlier, kept);
      for (CascadeFields& c : f.grids) {
        for (std::size_t q = 0; q < kept.size(); ++q) {
          if (!kept[q]) std::vector<double>().swap(c.values[q]);
        }
      }
    });
  }
  frame.filter = frame_filter(job);
  clock.lap(&RenderTimes::synthesis);
  frame.displacement_bound = height_bound(*job.ocean);
  frame.geometry = build_geometry(job, frame.fields, frame.displacement_bound, frame.filter);
  clock.lap(&RenderTimes::grid);
  frame.light = frame_lighting(job.sky, job.shading, job.lighting_correction);
  frame.sample_shading = job.shading;
  if (job.lighting_correction) frame.sample_shading.accuracy = LightingAccuracy::fast;
  return frame;
}

RenderedImage render(const RenderJob& job, const SlopeVariance& unresolved, RenderTimes* times) {
  const int last_row = job.last_row < 0 ? job.camera.height : job.last_row;  // checked there
  return render_rows(prepare_frame(job, unresolved, times), job.first_row, last_row, job.progress,
                     times);
}

namespace {
RenderedImage render_rows_with(const RenderFrame& frame, int first_row, int last_row,
                               const std::function<void(double)>& progress, RenderTimes* times,
                               bool antialias);
}  // namespace

RenderedImage render_rows(const RenderFrame& frame, int first_row, int last_row,
                          const std::function<void(double)>& progress, RenderTimes* times) {
  return render_rows_with(frame, first_row, last_row, progress, times,
                          frame.job.antialiasing_contrast > 0.0);
}

namespace {
// Mastin's anti-aliasing of the band [first_row, last_row) of `image` (its S×S means already
// resolved from `fragments`): the pixels whose contrast with a neighbour exceeds the job's
// threshold resolved again from their S×S samples and 16 more (RenderJob::antialiasing_contrast).
// Returns how many.
long add_mastin_samples(const RenderFrame& frame, const std::vector<Fragment>& fragments,
                        const SampleGrid& grid,
                        const std::vector<std::vector<std::uint32_t>>& row_triangles, int first_row,
                        int last_row, RenderedImage& image) {
  const RenderJob& job = frame.job;
  const Geometry& g = frame.geometry;
  const int s = job.samples_per_axis;
  // The S×S means of the band and of the rows just above and below it (rendered alone, the
  // same bits as in the whole image), before any pixel gets its extra samples.
  const auto mean_row = [&](int row) -> std::vector<Vec3> {
    if (row < 0 || row >= job.camera.height) return {};
    if (row >= first_row && row < last_row) {
      const auto begin =
          image.radiance.begin() + static_cast<std::ptrdiff_t>(row - first_row) * image.width;
      return {begin, begin + image.width};
    }
    return render_rows_with(frame, row, row + 1, {}, nullptr, false).radiance;
  };
  std::vector<std::vector<Vec3>> means;  // rows first_row − 1 … last_row
  for (int row = first_row - 1; row <= last_row; ++row) means.push_back(mean_row(row));
  const auto at = [&](int row, int x) -> const Vec3* {
    const std::vector<Vec3>& r = means[static_cast<std::size_t>(row - first_row + 1)];
    if (r.empty() || x < 0 || x >= image.width) return nullptr;
    return &r[static_cast<std::size_t>(x)];
  };
  const int extra = kMastinExtraSamplesPerAxis;
  const SampleGrid fine{job.camera.width, job.camera.height, extra};
  std::atomic<long> antialiased{0};
  parallel_for(image.height, job.threads, [&](int y) {
    const int row = first_row + y;
    std::vector<SampleValue> values;
    std::vector<Fragment> window;
    std::vector<std::uint32_t> subset;
    long count = 0;
    for (int x = 0; x < image.width; ++x) {
      const Vec3& centre = *at(row, x);
      double contrast = 0.0;
      for (const Vec3* n : {at(row, x - 1), at(row, x + 1), at(row - 1, x), at(row + 1, x)}) {
        if (n != nullptr) contrast = std::fmax(contrast, luminance_contrast(centre, *n));
      }
      if (!(contrast > job.antialiasing_contrast)) continue;
      ++count;
      // The S×S samples again (the same fragments, the same bits), then the 16 extra ones.
      values.clear();
      const auto shade_at = [&](const Fragment& f, const SampleGrid& samples, int r, int c) {
        const glm::dvec3 ray = ray_direction(job.camera, samples.sample_x(c), samples.sample_y(r));
        return sample_value(
            shade_sample(frame, f, ray, 1.0 / samples.samples_per_axis, frame.sample_shading));
      };
      for (int b = 0; b < s; ++b) {
        for (int a = 0; a < s; ++a) {
          const std::size_t i =
              static_cast<std::size_t>(y * s + b) * static_cast<std::size_t>(grid.columns()) +
              static_cast<std::size_t>(x * s + a);
          values.push_back(shade_at(fragments[i], grid, row * s + b, x * s + a));
        }
      }
      window.assign(static_cast<std::size_t>(extra * extra), Fragment{});
      if (is_ray_traced(job.renderer)) {
        trace_fragments(frame, fine, row * extra, row * extra + extra, window, row * extra,
                        FragmentColumns{x * extra, extra}, 1);
      } else {
        subset.clear();
        for (const std::uint32_t t : row_triangles[static_cast<std::size_t>(y)]) {
          if (reaches_column(g, t, x)) subset.push_back(t);
        }
        rasterize(g.screen, g.triangles, subset, fine, row * extra, row * extra + extra,
                  job.grid.near, window, row * extra, FragmentColumns{x * extra, extra});
      }
      for (int b = 0; b < extra; ++b) {
        for (int a = 0; a < extra; ++a) {
          values.push_back(shade_at(window[static_cast<std::size_t>(b * extra + a)], fine,
                                    row * extra + b, x * extra + a));
        }
      }
      const std::size_t pixel =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
          static_cast<std::size_t>(x);
      resolve_into(
          image, pixel, values,
          fixed_grid_estimate(std::span<const SampleValue>(values), &SampleValue::radiance),
          job.layers);
    }
    antialiased += count;
  });
  return antialiased;
}

RenderedImage render_rows_with(const RenderFrame& frame, int first_row, int last_row,
                               const std::function<void(double)>& progress, RenderTimes* times,
                               bool antialias) {
  const RenderJob& job = frame.job;
  OCEANREF_EXPECTS(0 <= first_row && first_row < last_row && last_row <= job.camera.height,
                   "pixel rows [" + std::to_string(first_row) + ", " + std::to_string(last_row) +
                       ") of a nonempty band inside the " + std::to_string(job.camera.height) +
                       " rows of the image");
  const ReferenceFpEnvironment fp;
  StageClock clock(times);
  const Geometry& g = frame.geometry;
  const SlopeVariance& unresolved = frame.unresolved;
  RenderedImage image;
  image.width = job.camera.width;
  image.height = last_row - first_row;
  image.first_row = first_row;
  image.samples_per_axis = job.samples_per_axis;
  image.unresolved = unresolved;
  image.displacement_bound = frame.displacement_bound;
  const SampleGrid grid{job.camera.width, job.camera.height, job.samples_per_axis};
  const int s = job.samples_per_axis;
  // The band's S×S fragments (none for the Sobol' pattern: its pixels find their own).
  const bool sobol = job.pixel_tolerance > 0.0 && job.pixel_pattern == PixelPattern::sobol;
  const std::vector<Fragment> fragments =
      sobol ? std::vector<Fragment>{} : raster_pass(frame, grid, first_row * s, last_row * s);
  clock.lap(&RenderTimes::raster);
  const auto pixels =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  const auto pixel_buffer = [pixels](const char* layer) {
    return allocate_buffer<Vec3>(pixels, std::string("the per-pixel ") + layer + " buffer");
  };
  image.radiance = pixel_buffer("radiance");
  image.coverage = allocate_buffer<double>(pixels, "the per-pixel coverage buffer");
  image.lighting_error = pixel_buffer("lighting error");
  image.pixel_error = pixel_buffer("pixel error");
  const bool layers = job.layers;
  if (layers) {
    image.sun = pixel_buffer("sun");
    image.sky = pixel_buffer("sky");
    image.sea = pixel_buffer("sea");
    image.foam = pixel_buffer("foam");
    image.depth = allocate_buffer<double>(pixels, "the per-pixel depth buffer");
    image.normal = pixel_buffer("normal");
    image.x0 = pixel_buffer("x0");
  }
  const bool adaptive = job.pixel_tolerance > 0.0;
  const int sobol_first = sobol_first_points(s);
  // The two-level correction's finest level, and whether level l's samples are among a pixel's
  // after r refinements (the grid's level l is its S·3^l grid; the Sobol' pattern's, its first
  // sobol_correction_samples(l)).
  const int max_correction_level = sobol ? kMaxSobolCorrectionLevel : kMaxCorrectionRefinements;
  const auto correction_level_fits = [&](int l, int r) {
    return sobol ? sobol_correction_samples(l) <= kPixelReplicates * (sobol_first << r) : l <= r;
  };
  // The Sobol' pattern's cell of sample j [pixels]: the pixel shared by the samples of the
  // refinement that added it (footprint filtering; its correction reads the same footprint).
  const auto sobol_cell = [&](std::size_t j) {
    std::size_t samples = static_cast<std::size_t>(kPixelReplicates * sobol_first);
    while (samples <= j) samples *= 2;
    return 1.0 / std::sqrt(static_cast<double>(samples));
  };
  OCEANREF_EXPECTS(adaptive || !job.lighting_correction,
                   "the two-level lighting corrects the pixels of adaptive sampling");
  OCEANREF_EXPECTS(!(adaptive && job.keep_samples),
                   "the samples of the fixed grid are kept, not those of adaptive sampling");
  OCEANREF_EXPECTS(!(antialias && (adaptive || job.keep_samples)),
                   "Mastin's anti-aliasing adds samples to the fixed grid only, without keeping "
                   "them");
  if (job.keep_samples) {
    image.sample_radiance = allocate_buffer<Vec3>(fragments.size(), "the per-sample radiance");
  }
  if (adaptive) {
    image.pixel_samples = allocate_buffer<double>(pixels, "the per-pixel sample counts");
  }
  // The triangles binned per pixel row, for rasterizing refined pixels (the ray tracer needs none).
  const std::vector<std::vector<std::uint32_t>> row_triangles =
      (adaptive || antialias) && job.renderer == Renderer::raster
          ? triangles_by_pixel_row(job, g, first_row, last_row)
          : std::vector<std::vector<std::uint32_t>>{};
  std::atomic<long> unconverged{0};
  std::atomic<long> evaluations{0};
  std::atomic<long> capped{0};
  std::atomic<long> corrected{0};
  std::atomic<int> rows_done{0};
  // Rows in spread order (spread_order): any prefix of the rows done is a sample of the whole
  // band, so the share done is the share of the work (sky rows are cheap, sea rows are not) and
  // the time left extrapolates honestly. Each row's pixels are the same bits in any order.
  const std::vector<int> order = spread_order(image.height);
  if (progress) progress(0.0);  // the rows start (after the frame and the raster pass)
  parallel_for(image.height, job.threads, [&](int index) {
    const int y = order[static_cast<std::size_t>(index)];  // the band's row
    long row_unconverged = 0;
    long row_evaluations = 0;
    long row_capped = 0;
    long row_corrected = 0;
    // A sample at image position `at` [pixels], its cell `cell` pixels wide, lit by
    // `lighting`'s accuracy, its integrals counted.
    const auto shade_point = [&](const Fragment& f, const std::array<double, 2>& at, double cell,
                                 const ShadingSettings& lighting) {
      const glm::dvec3 ray = ray_direction(job.camera, at[0], at[1]);
      const SampleProbe p = shade_sample(frame, f, ray, cell, lighting);
      if (!p.lighting.converged) ++row_unconverged;
      row_evaluations += p.lighting.evaluations;
      return p;
    };
    // Sample (row, column) of `samples`.
    const auto shade_by = [&](const Fragment& f, const SampleGrid& samples, int row, int column,
                              const ShadingSettings& lighting) {
      return shade_point(f, {samples.sample_x(column), samples.sample_y(row)},
                         1.0 / samples.samples_per_axis, lighting);
    };
    const auto shade = [&](const Fragment& f, const SampleGrid& samples, int row, int column) {
      return sample_value(shade_by(f, samples, row, column, frame.sample_shading));
    };
    // The pixel's samples (row-major) and the next level's, which trade places at each
    // refinement; reserved at the finest level once, so that what a thread holds is what
    // refinement_bytes counts, whatever the pixels' refinements.
    std::vector<SampleValue> values;
    std::vector<SampleValue> finer;
    std::vector<Fragment> window;
    std::vector<SampleCorrection> corrections;  // lighting_correction: the level's samples
    std::vector<std::array<double, 2>> points;  // the Sobol' pattern's positions [pixels]
    if (adaptive) {
      const auto finest =
          static_cast<std::size_t>(adaptive_samples(job.pixel_pattern, s, job.max_refinements));
      values.reserve(finest);
      finer.reserve(finest);
      window.reserve(finest);
      if (sobol) points.reserve(finest);
      if (job.lighting_correction) corrections.reserve(finest);
    }
    std::vector<std::uint32_t> subset;                    // the triangles that reach the pixel
    bool subset_of_pixel = false;                         // subset holds the current pixel's
    const auto at = [](int row, int column, int width) {  // row-major index
      return static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(column);
    };
    // The fragments of pixel (x, image_row) at `samples` (m×m per pixel) into `window`: its
    // footprint rasterized from `subset` (the same fragments as a whole raster pass at that
    // grid), or its rays traced.
    const auto pixel_subset = [&](int x, int image_row) -> const std::vector<std::uint32_t>& {
      if (!subset_of_pixel) {
        subset.clear();
        for (const std::uint32_t t :
             row_triangles[static_cast<std::size_t>(image_row - first_row)]) {
          if (reaches_column(g, t, x)) subset.push_back(t);
        }
        subset_of_pixel = true;
      }
      return subset;
    };
    const auto pixel_fragments = [&](int x, int image_row, const SampleGrid& samples) {
      const int m = samples.samples_per_axis;
      window.assign(static_cast<std::size_t>(m) * static_cast<std::size_t>(m), Fragment{});
      if (is_ray_traced(job.renderer)) {
        trace_fragments(frame, samples, image_row * m, image_row * m + m, window, image_row * m,
                        FragmentColumns{x * m, m}, 1);
        return;
      }
      rasterize(g.screen, g.triangles, pixel_subset(x, image_row), samples, image_row * m,
                image_row * m + m, job.grid.near, window, image_row * m, FragmentColumns{x * m, m});
    };
    // The Sobol' pattern: points [from, to) of every replicate of pixel (x, image_row) appended
    // point-major to `points`, their fragments to `window` and their values to `values`, each
    // sample's cell the pixel shared by the pixel's samples after the addition (sobol_cell).
    const auto add_points = [&](int x, int image_row, int from, int to) {
      const std::size_t start = points.size();
      for (int i = from; i < to; ++i) {
        for (int r = 0; r < kPixelReplicates; ++r) {
          const std::array<double, 2> u = scrambled_sobol_point(
              pixel_replicate_key(x, image_row, r), static_cast<std::uint32_t>(i));
          points.push_back({x + u[0], image_row + u[1]});
        }
      }
      window.resize(points.size(), Fragment{});
      const std::span<const std::array<double, 2>> added = std::span(points).subspan(start);
      const std::span<Fragment> fragments_added = std::span(window).subspan(start);
      if (is_ray_traced(job.renderer)) {
        trace_points(frame, added, fragments_added);
      } else {
        rasterize_points(g.screen, g.triangles, pixel_subset(x, image_row), added, job.grid.near,
                         fragments_added);
      }
      for (std::size_t j = start; j < points.size(); ++j) {
        values.push_back(
            sample_value(shade_point(window[j], points[j], sobol_cell(j), frame.sample_shading)));
      }
    };
    // The n×n samples of pixel (x, image_row) refined to 3n×3n: the n×n are the centres of its
    // 3×3 cells, the others shaded from their fragments.
    const auto refine = [&](int x, int image_row, int n) {
      const int m = 3 * n;
      const SampleGrid samples{job.camera.width, job.camera.height, m};
      pixel_fragments(x, image_row, samples);
      finer.clear();
      for (int b = 0; b < m; ++b) {
        for (int a = 0; a < m; ++a) {
          finer.push_back(a % 3 == 1 && b % 3 == 1
                              ? values[at(b / 3, a / 3, n)]
                              : shade(window[at(b, a, m)], samples, image_row * m + b, x * m + a));
        }
      }
      std::swap(values, finer);
    };
    // The two-level correction of pixel (x, image_row) at level l of its nested grid (m = S·3^l
    // samples per axis; the pixel's samples are n×n, n ≥ m): each of the level's samples that
    // sees the sea lit again by the reference, reference − fast.
    const auto correct = [&](int x, int image_row, int level, int n) {
      const int m = refined_samples_per_axis(s, level);
      const int step = n / m;  // the level's samples are the centres of step×step cells
      const SampleGrid samples{job.camera.width, job.camera.height, m};
      if (level > 0) pixel_fragments(x, image_row, samples);
      corrections.clear();
      bool level_sees_sea = false;
      for (int b = 0; b < m; ++b) {
        for (int a = 0; a < m; ++a) {
          const SampleValue& fast = values[at(b * step + step / 2, a * step + step / 2, n)];
          if (!fast.hit) {
            corrections.emplace_back();
            continue;
          }
          level_sees_sea = true;
          const int row = image_row * m + b;
          const int column = x * m + a;
          const Fragment& f =
              level > 0 ? window[at(b, a, m)]
                        : fragments[at((image_row - first_row) * s + b, column, grid.columns())];
          ++row_corrected;
          corrections.push_back(
              sample_correction(fast, shade_by(f, samples, row, column, job.shading)));
        }
      }
      const std::span<const SampleCorrection> level_values(corrections);
      return pixel_correction(level_values, level_sees_sea, sees_sea(values),
                              grid_estimate(level_values, m, s, &SampleCorrection::radiance));
    };
    // The same for the Sobol' pattern: level l's samples are the first sobol_correction_samples(l)
    // of the values (point-major: the first point of as many replicates, or the first points of
    // all); the corrections of a coarser level are kept (its samples are the finer level's first).
    const auto correct_sobol = [&](int level) {
      const int samples = sobol_correction_samples(level);
      const int replicates = std::min(samples, kPixelReplicates);
      const int level_points = samples / replicates;
      const auto count = static_cast<std::size_t>(samples);
      for (std::size_t j = corrections.size(); j < count; ++j) {
        if (!values[j].hit) {
          corrections.emplace_back();
          continue;
        }
        ++row_corrected;
        corrections.push_back(sample_correction(
            values[j], shade_point(window[j], points[j], sobol_cell(j), job.shading)));
      }
      const std::span<const SampleCorrection> level_values(corrections);
      const std::span<const SampleValue> all(values);
      return pixel_correction(
          level_values.first(count), sees_sea(all.first(count)), sees_sea(all),
          replicate_estimate(level_values, replicates, level_points, &SampleCorrection::radiance));
    };
    for (int x = 0; x < image.width; ++x) {
      const std::size_t pixel =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
          static_cast<std::size_t>(x);
      values.clear();
      subset_of_pixel = false;
      const int image_row = first_row + y;
      if (sobol) {
        points.clear();
        window.clear();
        corrections.clear();
        add_points(x, image_row, 0, sobol_first);
      } else {
        for (int b = 0; b < s; ++b) {
          for (int a = 0; a < s; ++a) {
            const int band_row = y * s + b;
            const int row = first_row * s + band_row;  // of the image's sample grid
            const int column = x * s + a;
            const std::size_t i = at(band_row, column, grid.columns());
            values.push_back(shade(fragments[i], grid, row, column));
            if (job.keep_samples) image.sample_radiance[i] = values.back().radiance;
          }
        }
      }
      // The grid's samples per axis, or the Sobol' pattern's points per replicate.
      int n = sobol ? sobol_first : s;
      const auto estimate_of = [&](int level_n) {
        const std::span<const SampleValue> all(values);
        return sobol ? replicate_estimate(all, kPixelReplicates, level_n, &SampleValue::radiance)
                     : grid_estimate(all, level_n, s, &SampleValue::radiance);
      };
      PixelEstimate estimate = estimate_of(n);
      std::optional<PixelCorrection> correction;
      if (adaptive) {
        int refinements = 0;
        int level = -1;  // of the correction (lighting_correction)
        const auto corrected_estimate = [&] {
          PixelEstimate e = estimate;
          if (correction) {
            for (std::size_t c = 0; c < 3; ++c) e.mean[c] += correction->radiance[c];
          }
          return e;
        };
        const auto refine_samples = [&] {
          if (sobol) {
            add_points(x, image_row, n, 2 * n);
            n *= 2;
          } else {
            refine(x, image_row, n);
            n *= 3;
          }
          ++refinements;
          estimate = estimate_of(n);
        };
        const auto refine_correction = [&] {
          if (!correction_level_fits(level + 1, refinements)) refine_samples();
          ++level;
          correction = sobol ? correct_sobol(level) : correct(x, image_row, level, n);
        };
        if (job.lighting_correction) refine_correction();
        // Until the bound meets the tolerance (one sample estimates nothing: refined at least
        // once). A reference sample costs about a hundred fast ones, so the samples are refined
        // first, while the pixel part exceeds half the budget; the correction then, if the pixel
        // part alone is within the budget (else no correction can bring the pixel within it).
        for (;;) {
          const Budget b = budget(corrected_estimate(), correction ? &*correction : nullptr,
                                  job.pixel_tolerance);
          if (b.within && values.size() > 1) break;
          const bool can_refine = refinements < job.max_refinements;
          if (can_refine && (!correction || b.pixel_over_half || values.size() < 2)) {
            refine_samples();
          } else if (correction &&
                     ((b.pixel_within && level < max_correction_level) ||
                      !std::isfinite(correction->error[0])) &&
                     correction_level_fits(level + 1, job.max_refinements)) {
            refine_correction();
          } else if (can_refine) {
            refine_samples();
          } else {
            break;
          }
        }
        estimate = corrected_estimate();
        image.pixel_samples[pixel] = static_cast<double>(values.size());
        const bool missed =
            !budget(estimate, correction ? &*correction : nullptr, job.pixel_tolerance).within;
        if (missed) ++row_capped;
      }
      resolve_into(image, pixel, values, estimate, layers, correction ? &*correction : nullptr);
    }
    unconverged += row_unconverged;
    evaluations += row_evaluations;
    capped += row_capped;
    corrected += row_corrected;
    const int done = ++rows_done;
    // Every row: a row of converged pixels can take many seconds, and the progress off a
    // terminal is a line every ~10 s (the callback's rate limit).
    if (progress) {
      progress(static_cast<double>(done) / image.height);
    }
  });
  if (antialias) {
    image.antialiased_pixels =
        add_mastin_samples(frame, fragments, grid, row_triangles, first_row, last_row, image);
  }
  clock.lap(&RenderTimes::shading);
  image.unconverged_samples = unconverged;
  image.integrand_evaluations = evaluations;
  image.capped_pixels = capped;
  image.corrected_samples = corrected;
  require_finite(image);
  return image;
}

}  // namespace

Vec3 resolve_pixel(const std::vector<SampleProbe>& samples) {
  OCEANREF_EXPECTS(!samples.empty(), "a pixel has at least one sample");
  // As render's resolve: per_sample = 1/(S·S), accumulated from 0 in sample order.
  const double per_sample = 1.0 / static_cast<double>(samples.size());
  Vec3 pixel{};
  for (const SampleProbe& p : samples) {
    for (std::size_t c = 0; c < 3; ++c) pixel[c] += per_sample * p.radiance[c];
  }
  return pixel;
}

SurfaceMesh surface_mesh(const RenderJob& job) {
  const ReferenceFpEnvironment fp;
  const FrameFields fields = frame_fields(job);
  RenderJob sea_only = job;
  sea_only.objects = nullptr;
  Geometry g = build_geometry(sea_only, fields, height_bound(*job.ocean), frame_filter(job));
  return {std::move(g.grid), std::move(g.world), std::move(g.triangles)};
}

void require_finite(const RenderedImage& image) {
  const auto text = [](double v) { return format_number(v); };
  const auto terms = [&](std::size_t p) {
    std::string s;
    for (const auto& [name, buffer] :
         {std::pair{"sun", &image.sun}, std::pair{"sky", &image.sky}, std::pair{"sea", &image.sea},
          std::pair{"foam", &image.foam}}) {
      if (p < buffer->size()) {
        s += std::string(s.empty() ? "" : ", ") + name + " = (" + text((*buffer)[p][0]) + ", " +
             text((*buffer)[p][1]) + ", " + text((*buffer)[p][2]) + ")";
      }
    }
    return s;
  };
  const auto fail = [&](std::size_t p, const std::string& buffer, const std::string& channel,
                        double value) {
    const std::size_t w = static_cast<std::size_t>(std::max(image.width, 1));
    throw NonFiniteOutputError("pixel (" + std::to_string(p % w) + ", " +
                               std::to_string(p / w + static_cast<std::size_t>(image.first_row)) +
                               "): " + buffer + channel + " is " + text(value) + " (coverage " +
                               (p < image.coverage.size() ? text(image.coverage[p]) : "?") +
                               "; terms: " + terms(p) + ")");
  };
  const std::size_t pixels = image.radiance.size();
  for (std::size_t p = 0; p < pixels; ++p) {
    // The terms first: a non-finite radiance names the term it came from.
    for (const auto& [name, buffer] :
         {std::pair{"sun", &image.sun}, std::pair{"sky", &image.sky}, std::pair{"sea", &image.sea},
          std::pair{"foam", &image.foam}, std::pair{"radiance", &image.radiance},
          std::pair{"lighting_error", &image.lighting_error}, std::pair{"normal", &image.normal},
          std::pair{"x0", &image.x0}}) {
      if (p >= buffer->size()) continue;
      for (std::size_t c = 0; c < 3; ++c) {
        if (!std::isfinite((*buffer)[p][c]))
          fail(p, name, std::string(".") + "RGB"[c], (*buffer)[p][c]);
      }
    }
    for (const auto& [name, buffer] :
         {std::pair{"depth", &image.depth}, std::pair{"coverage", &image.coverage}}) {
      if (p < buffer->size() && !std::isfinite((*buffer)[p])) fail(p, name, "", (*buffer)[p]);
    }
  }
}

std::vector<SampleProbe> probe_pixel(const RenderJob& job, const SlopeVariance& unresolved,
                                     int pixel_x, int pixel_y) {
  OCEANREF_EXPECTS(job.ocean != nullptr && job.samples_per_axis >= 1 &&
                       job.samples_per_axis <= kMaxSamplesPerAxis,
                   "a render job names its ocean and has 1 to " +
                       std::to_string(kMaxSamplesPerAxis) + " samples per axis");
  OCEANREF_EXPECTS(
      0 <= pixel_x && pixel_x < job.camera.width && 0 <= pixel_y && pixel_y < job.camera.height,
      "pixel (" + std::to_string(pixel_x) + ", " + std::to_string(pixel_y) + ") inside the " +
          std::to_string(job.camera.width) + " x " + std::to_string(job.camera.height) + " image");
  const RenderFrame frame = prepare_frame(job, unresolved);
  const ReferenceFpEnvironment fp;
  const SampleGrid grid{job.camera.width, job.camera.height, job.samples_per_axis};
  const int s = job.samples_per_axis;
  // The pixel's sample rows only (the fragments of a full pass there, bit for bit).
  const std::vector<Fragment> fragments = raster_pass(frame, grid, pixel_y * s, pixel_y * s + s);
  std::vector<SampleProbe> out;
  for (int b = 0; b < s; ++b) {
    for (int a = 0; a < s; ++a) {
      const int row = pixel_y * s + b;
      const int column = pixel_x * s + a;
      const Fragment& f =
          fragments[static_cast<std::size_t>(b) * static_cast<std::size_t>(grid.columns()) +
                    static_cast<std::size_t>(column)];
      const glm::dvec3 ray = ray_direction(job.camera, grid.sample_x(column), grid.sample_y(row));
      SampleProbe p = shade_sample(frame, f, ray, 1.0 / s, job.shading);
      p.image_x = grid.sample_x(column);
      p.image_y = grid.sample_y(row);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace oceanref
