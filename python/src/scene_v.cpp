// Scenes, their wave fields and the reference image (scene/scene.h, waves/ocean.h,
// raster/renderer.h), and reading EXR files (io/exr.h). The fields are assembled here from the
// library's pieces the way `oceanref fields` lays them out (docs/FILES.md): one array per channel
// name, the doubles behind the EXR's float32 channels.
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "common.h"
#include "conformance/render_output.h"
#include "conformance/scene_objects.h"
#include "io/exr.h"
#include "io/sha256.h"
#include "scene/scene.h"
#include "waves/ocean.h"

namespace oceanref::python {

namespace {

struct PyScene {
  Scene scene;
};

PyScene scene_from_file(const std::string& path) {
  py::gil_scoped_release release;
  return {load_scene(path)};
}

PyScene scene_from_json(const std::string& text) {
  return {parse_scene(parse_scene_json(text, "(scene JSON)"))};
}

double scene_time(const Scene& scene, const std::optional<double>& time) {
  if (!time) return scene.time;
  if (!(std::fabs(*time) <= 1e7)) {
    throw ArgumentError("time", "must be in [-1e7, 1e7] s, got " + format_number(*time));
  }
  return *time;
}

// Every channel of `oceanref fields -o` (stage fields) as doubles, by channel name.
std::map<std::string, std::vector<double>> scene_fields(const Scene& scene, double time,
                                                        int threads,
                                                        std::map<std::string, int>& sizes) {
  const Ocean ocean = realize_ocean(scene.waves, threads);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, time, threads);
  std::map<std::string, std::vector<double>> out;
  const auto put = [&](const std::string& name, int n, std::vector<double> values) {
    sizes[name] = n;
    out[name] = std::move(values);
  };
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string name = "c" + std::to_string(i) + ".";
    for (int q = 0; q < kFieldCount; ++q) {
      const int n =
          is_low_resolution_field(Field(q)) ? fields[i].low_resolution : fields[i].high_resolution;
      put(name + std::string(kFieldNames[static_cast<std::size_t>(q)]), n,
          fields[i].values[static_cast<std::size_t>(q)]);
    }
    const std::vector<double> jacobian = cascade_jacobian(fields[i], ocean.cascades[i].choppiness);
    std::vector<double> foam(jacobian.size());
    for (std::size_t k = 0; k < foam.size(); ++k) foam[k] = jacobian[k] < 0.0 ? 1.0 : 0.0;
    put(name + "jacobian", fields[i].high_resolution, jacobian);
    put(name + "foam", fields[i].high_resolution, foam);
  }
  std::vector<PointFields> sum =
      combine_on_footprint(ocean, evolve_ocean(ocean, time), scene.shading.normals, threads);
  if (scene.foam.steps > 0) {  // foam of a sequence: accumulated over the earlier frames
    const AccumulatedFoam foam =
        accumulate_foam(ocean, time, scene.foam, scene.shading.normals, threads);
    for (std::size_t i = 0; i < fields.size(); ++i) {
      out["c" + std::to_string(i) + ".foam"] = foam.cascades[i];
    }
    for (std::size_t c = 0; c < sum.size(); ++c) sum[c].foam = foam.combined[c];
  }
  const int n = scene.waves.resolution;
  const auto sum_channel = [&](const char* name, double PointFields::*member) {
    std::vector<double> v(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) v[i] = sum[i].*member;
    put(std::string("sum.") + name, n, std::move(v));
  };
  sum_channel("height", &PointFields::height);
  sum_channel("slope_x", &PointFields::slope_x);
  sum_channel("slope_z", &PointFields::slope_z);
  sum_channel("jacobian", &PointFields::jacobian);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    std::vector<double> v(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) v[i] = sum[i].normal[axis];
    put(std::string("sum.normal_") + "xyz"[axis], n, std::move(v));
  }
  sum_channel("foam", &PointFields::foam);
  return out;
}

py::array_t<double> image_array(const std::vector<Vec3>& v, int width, int height) {
  py::array_t<double> out({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width),
                           static_cast<py::ssize_t>(3)});
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) o[3 * i + c] = v[i][c];
  }
  return out;
}

py::array_t<double> scalar_image(const std::vector<double>& v, int width, int height) {
  return to_array(v, {static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)});
}

py::dict render_scene(const PyScene& s, int threads_arg, std::optional<int> spp, bool aov,
                      bool lighting_error, bool samples, const std::string& renderer,
                      double max_memory) {
  const int threads = resolve_threads(threads_arg);
  Scene scene = s.scene;
  if (spp) {
    const int axis = static_cast<int>(std::lround(std::sqrt(static_cast<double>(*spp))));
    if (*spp < 1 || *spp > kMaxSamplesPerAxis * kMaxSamplesPerAxis || axis * axis != *spp) {
      throw ArgumentError("spp", "must be a square number in [1, " +
                                     std::to_string(kMaxSamplesPerAxis * kMaxSamplesPerAxis) +
                                     "], got " + std::to_string(*spp));
    }
    scene.image.samples_per_axis = axis;
  }
  if (!(max_memory >= kMinMaxMemory && max_memory <= kMaxMaxMemory)) {
    throw ArgumentError("max_memory", "must be in [" + shortest_number(kMinMaxMemory) + ", " +
                                          shortest_number(kMaxMaxMemory) + "] bytes, got " +
                                          shortest_number(max_memory));
  }
  if (samples && scene.image.pixel_tolerance > 0.0) {
    throw ArgumentError("samples",
                        "the fixed grid's samples only: not with render.pixel_tolerance "
                        "(adaptive sampling)");
  }
  if (samples && scene.image.mastin_antialiasing > 0.0) {
    throw ArgumentError("samples",
                        "the fixed grid's samples only: not with render.mastin_antialiasing");
  }
  if (!renderer.empty()) {
    scene.image.renderer = parse_choice<ArgumentError>(kRenderers, "renderer", renderer);
  }
  RenderOutputOptions options;
  options.aov = aov;
  options.keep_samples = samples;
  require_within(render_memory_estimate(scene, options), max_memory, "max_memory=");
  RenderedImage image;
  {
    py::gil_scoped_release release;
    const Ocean ocean = realize_ocean(scene.waves, threads);
    const SceneObjects objects = load_scene_objects(scene);
    RenderJob job = scene_render_job(scene, ocean, threads);
    job.objects = &objects;
    job.estimate_fast_error = lighting_error;  // as `oceanref render --lighting-error`
    job.layers = aov;
    job.keep_samples = samples;  // as `oceanref render --samples`
    const SlopeVariance unresolved = unresolved_slope_variance(job, scene.waves);
    image = render(job, unresolved);
  }
  const int w = image.width;
  const int h = image.height;
  py::dict d;
  d["radiance"] = image_array(image.radiance, w, h);
  d["unconverged_samples"] = image.unconverged_samples;
  d["integrand_evaluations"] = image.integrand_evaluations;
  if (!image.pixel_samples.empty()) {
    d["pixel_samples"] = scalar_image(image.pixel_samples, w, h);
    d["capped_pixels"] = image.capped_pixels;
  }
  if (samples) {
    const int axis = scene.image.samples_per_axis;
    d["samples"] = image_array(image.sample_radiance, w * axis, h * axis);
  }
  d["unresolved_slope_variance"] =
      py::make_tuple(image.unresolved.upwind, image.unresolved.crosswind);
  if (aov) {
    d["sun"] = image_array(image.sun, w, h);
    d["sky"] = image_array(image.sky, w, h);
    d["sea"] = image_array(image.sea, w, h);
    d["foam"] = image_array(image.foam, w, h);
    d["normal"] = image_array(image.normal, w, h);
    d["x0"] = image_array(image.x0, w, h);
    d["lighting_error"] = image_array(image.lighting_error, w, h);
    d["pixel_error"] = image_array(image.pixel_error, w, h);
    d["depth"] = scalar_image(image.depth, w, h);
    d["coverage"] = scalar_image(image.coverage, w, h);
  }
  return d;
}

py::list read_exr_file(const std::string& path) {
  std::vector<ExrPart> parts;
  {
    py::gil_scoped_release release;
    parts = read_exr_parts(path);
  }
  py::list out;
  for (const ExrPart& p : parts) {
    py::dict part;
    part["name"] = p.name;
    part["level"] = py::make_tuple(p.level_x, p.level_y);
    part["width"] = p.image.width;
    part["height"] = p.image.height;
    py::dict channels;
    for (const ExrChannel& c : p.image.channels) {
      const py::ssize_t cw = p.image.width / c.sampling;
      const py::ssize_t ch = p.image.height / c.sampling;
      py::array_t<float> a({ch, cw});
      float* o = a.mutable_data();
      for (std::size_t i = 0; i < c.values.size(); ++i) o[i] = c.values[i];
      channels[py::str(c.name)] = a;
    }
    part["channels"] = channels;
    py::dict attributes;
    for (const auto& [k, v] : p.image.attributes) attributes[py::str(k)] = v;
    part["attributes"] = attributes;
    out.append(part);
  }
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene",
                      "A validated scene (scene files: DESIGN.md, reference/scene.schema.json).")
      .def_property_readonly(
          "canonical", [](const PyScene& s) { return s.scene.canonical; },
          "the parsed document as canonical JSON (sorted keys): what is hashed")
      .def_property_readonly(
          "sha256", [](const PyScene& s) { return sha256_hex(s.scene.canonical); },
          "SHA-256 of the canonical JSON (the EXR attribute oceanref.scene_sha256)")
      .def_property_readonly("seed", [](const PyScene& s) { return s.scene.seed; })
      .def_property_readonly(
          "time", [](const PyScene& s) { return s.scene.time; }, "t [s]")
      .def_property_readonly("width", [](const PyScene& s) { return s.scene.image.width; })
      .def_property_readonly("height", [](const PyScene& s) { return s.scene.image.height; })
      .def_property_readonly("samples_per_pixel",
                             [](const PyScene& s) {
                               return s.scene.image.samples_per_axis *
                                      s.scene.image.samples_per_axis;
                             })
      .def_property_readonly(
          "cascade_sizes", [](const PyScene& s) { return s.scene.waves.sizes; }, "L_i [m]")
      .def_property_readonly("resolution",
                             [](const PyScene& s) { return s.scene.waves.resolution; })
      .def_property_readonly("low_resolution",
                             [](const PyScene& s) { return s.scene.waves.low_resolution; });
  m.def("_scene_from_file", &scene_from_file, py::arg("path"));
  m.def("_scene_from_json", &scene_from_json, py::arg("text"));
  m.def(
      "_fields",
      [](const PyScene& s, std::optional<double> time, int threads) {
        const double t = scene_time(s.scene, time);
        const int n = resolve_threads(threads);
        std::map<std::string, int> sizes;
        std::map<std::string, std::vector<double>> values;
        {
          py::gil_scoped_release release;
          values = scene_fields(s.scene, t, n, sizes);
        }
        py::dict out;
        for (const auto& [name, v] : values) {
          const py::ssize_t size = sizes.at(name);
          out[py::str(name)] = to_array(v, {size, size});
        }
        return out;
      },
      py::arg("scene"), py::arg("time") = py::none(), py::arg("threads") = 0);
  m.def("_render", &render_scene, py::arg("scene"), py::arg("threads") = 0,
        py::arg("spp") = py::none(), py::arg("aov") = false, py::arg("lighting_error") = false,
        py::arg("samples") = false, py::arg("renderer") = "",
        py::arg("max_memory") = kDefaultMaxMemory);
  m.def("_read_exr", &read_exr_file, py::arg("path"));
}

}  // namespace oceanref::python
