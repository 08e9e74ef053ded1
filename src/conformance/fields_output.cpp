#include "conformance/fields_output.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "conformance/channel_name.h"
#include "conformance/provenance.h"
#include "core/format.h"
#include "io/sha256.h"
#include "raster/renderer.h"
#include "waves/direct_sum.h"
#include "waves/ocean.h"

namespace oceanref {

namespace {
std::vector<float> to_float(const std::vector<double>& v) {
  return std::vector<float>(v.begin(), v.end());
}

std::string join_numbers(const std::vector<double>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + format_number(v[i]);
  return s;
}

// The attributes every part of a fields or stage file carries: provenance and scene parameters.
std::map<std::string, std::string> common_attributes(const Scene& scene, Stage stage) {
  return {{"oceanref.version", oceanref_version()},
          {"oceanref.commit", oceanref_commit()},
          {"oceanref.scene_sha256", sha256_hex(scene.canonical)},
          {"oceanref.scene", scene.canonical},
          {"oceanref.seed", std::to_string(scene.seed)},
          {"oceanref.time_s", format_number(scene.time)},
          {"oceanref.stage", kStageNames[static_cast<std::size_t>(stage)]},
          {"oceanref.cascade_sizes_m", join_numbers(scene.waves.sizes)},
          {"oceanref.choppiness", join_numbers(scene.waves.choppiness)},
          {"oceanref.resolution", std::to_string(scene.waves.resolution)},
          {"oceanref.low_resolution", std::to_string(scene.waves.low_resolution)}};
}

// The attributes of the part holding cascade `cascade` on the grid of `p`.
void add_pattern_attributes(ExrImage& image, const Pattern& p, double choppiness) {
  image.attributes["oceanref.cascade"] = std::to_string(p.cascade);
  image.attributes["oceanref.L_m"] = format_number(p.size);
  image.attributes["oceanref.N"] = std::to_string(p.resolution);
  image.attributes["oceanref.cascade_choppiness"] = format_number(choppiness);
  image.attributes["oceanref.band_rad_per_m"] =
      format_number(p.band.lower) + "," + format_number(p.band.upper);
}

constexpr const char* kFieldGrid =
    "pixel (column m, row n) is the sample at x = m L/N, z = n L/N [m] of this part's cascade "
    "(L = oceanref.L_m, N = oceanref.N); each field is the unnormalized inverse DFT "
    "f(m, n) = sum_{a,b} M_f(k_ab) h(k_ab, t) exp(+2 pi i (a m + b n)/N) (no 1/N^2) of h(k, t) "
    "on the grid of the hkt stage (docs/BACKENDS.md)";

constexpr const char* kSpectralGrid =
    "pixel (column a, row b) holds the integer wavevector (alpha, beta) = (a < N/2 ? a : a - N, "
    "b < N/2 ? b : b - N), k = (alpha, beta) 2 pi/L [rad/m]: FFT order, k = 0 at pixel (0, 0), "
    "not centred; the conjugate partner of (a, b) (wavevector -k) is ((N - a) mod N, (N - b) "
    "mod N); on a Nyquist line (alpha or beta = -N/2) the index -N/2 is its own partner; h0 is "
    "drawn only where in_band = 1 (k != 0 inside the band oceanref.band_rad_per_m, lower <= |k| "
    "< upper: band partitioning and the shortest wavelength), elsewhere h0 = 0 "
    "(docs/BACKENDS.md)";

// The unit of each field channel (the part after "c<i>." or "sum.").
std::string field_unit(const std::string& field) {
  return field == "height" || field == "disp_x" || field == "disp_z" ? "m" : "1";
}

// Adds field `name` (e.g. "c0.height") as channel exr_channel_name(name) ("c0.height.V"); its
// unit attribute and its entry in `exact` (the hash input) keep the field name.
void add_channel(ExrImage& image, std::map<std::string, std::vector<double>>& exact,
                 const std::string& name, const std::string& unit,
                 const std::vector<double>& values) {
  // A non-finite value (or one beyond float's range) is never written: the first one, by pixel.
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(static_cast<float>(values[i]))) {
      const std::size_t w = static_cast<std::size_t>(std::max(image.width, 1));
      throw NonFiniteOutputError(name + " at pixel (" + std::to_string(i % w) + ", " +
                                 std::to_string(i / w) + ") is " + format_number(values[i]) +
                                 (std::isfinite(values[i]) ? " (beyond float32's range)" : ""));
    }
  }
  image.channels.push_back({exr_channel_name(name), 1, to_float(values)});
  image.attributes["oceanref.units." + name] = unit;
  exact[name] = values;
}
}  // namespace

// `fields` writes the FFT cascades' grids (and points read from them): a Gerstner ocean has none.
void require_cascades(const Scene& scene) {
  if (scene.waves.model == WaveModel::gerstner) {
    throw SceneError("waves.model",
                     "fields writes the FFT cascades' grids and reads points from them; a gerstner "
                     "scene has none (render and probe sum its waves)");
  }
}

MemoryEstimate fields_memory_estimate(const Scene& scene) {
  const double cells = static_cast<double>(scene.waves.resolution) * scene.waves.resolution;
  const double cascades = static_cast<double>(scene.waves.sizes.size());
  // At most ten channels per cascade (eight fields, Jacobian, foam) and eight of the sum part,
  // each value as float, as double and in the two hash inputs (8 + 4 bytes).
  const double values = (10.0 * cascades + 8.0) * cells;
  const double foam = scene.foam.steps > 0 ? 2.0 * (cascades + 1.0) * cells * sizeof(double) : 0.0;
  const std::string grids = " (waves.resolution, waves.cascades)";
  return {{{kWaveGridsItem, wave_grid_bytes(scene.waves)},
           {"output channels" + grids, values * (sizeof(float) + sizeof(double))},
           {"hash input" + grids, values * (sizeof(double) + sizeof(float))},
           {"combined fields (waves.resolution)", cells * sizeof(PointFields)},
           {"evolved spectra" + grids, 2.0 * cascades * cells * sizeof(Complex)},
           {"temporaries (waves.resolution)", 3.0 * cells * sizeof(double)},
           {"foam accumulation (waves.foam.steps)", foam}}};
}

FieldsImage fields_image(const Scene& scene, const Ocean& ocean, int threads,
                         const std::function<void(const std::string&)>& log) {
  require_cascades(scene);
  if (log) log("synthesizing " + std::to_string(ocean.cascades.size()) + " cascades");
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, threads);
  std::map<std::string, std::vector<double>> exact;  // the doubles behind each channel
  std::vector<ExrPart> parts;
  const auto new_part = [&](const std::string& name, int size) {
    ExrPart part{name, 0, 0, {}};
    part.image.width = size;
    part.image.height = size;
    part.image.attributes = common_attributes(scene, Stage::fields);
    part.image.attributes["oceanref.index_convention"] = kFieldGrid;
    parts.push_back(std::move(part));
    return parts.size() - 1;
  };
  std::vector<std::size_t> high_parts;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string name = "c" + std::to_string(i);
    const CascadeSpectra& c = ocean.cascades[i];
    const bool multi = fields[i].low_resolution != fields[i].high_resolution;
    const std::size_t high = new_part(name, fields[i].high_resolution);
    high_parts.push_back(high);
    add_pattern_attributes(parts[high].image, c.high.pattern, c.choppiness);
    std::size_t low = high;
    if (multi) {
      low = new_part(name + ".low", fields[i].low_resolution);
      add_pattern_attributes(parts[low].image, c.low.pattern, c.choppiness);
    }
    for (int q = 0; q < kFieldCount; ++q) {
      const std::string field(kFieldNames[static_cast<std::size_t>(q)]);
      add_channel(parts[is_low_resolution_field(Field(q)) ? low : high].image, exact,
                  name + "." + field, field_unit(field),
                  fields[i].values[static_cast<std::size_t>(q)]);
    }
    const std::vector<double> jacobian = cascade_jacobian(fields[i], c.choppiness);
    std::vector<double> foam(jacobian.size());
    for (std::size_t k = 0; k < foam.size(); ++k) foam[k] = jacobian[k] < 0.0 ? 1.0 : 0.0;
    add_channel(parts[high].image, exact, name + ".jacobian", "1", jacobian);
    add_channel(parts[high].image, exact, name + ".foam", "1", foam);
  }
  std::vector<PointFields> sum =
      combine_on_footprint(ocean, evolve_ocean(ocean, scene.time), scene.shading.normals, threads);
  // Foam of a sequence: the indicator accumulated over the earlier frames (listing 2.4).
  if (scene.foam.steps > 0) {
    if (log) {
      log("accumulating foam over " + std::to_string(scene.foam.steps) + " earlier frames");
    }
    const AccumulatedFoam foam =
        accumulate_foam(ocean, scene.time, scene.foam, scene.shading.normals, threads);
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::string name = "c" + std::to_string(i) + ".foam";
      for (ExrChannel& c : parts[high_parts[i]].image.channels) {
        if (c.name == exr_channel_name(name)) c.values = to_float(foam.cascades[i]);
      }
      exact[name] = foam.cascades[i];
    }
    for (std::size_t c = 0; c < sum.size(); ++c) sum[c].foam = foam.combined[c];
  }
  const std::size_t sum_part = new_part("sum", scene.waves.resolution);
  ExrImage& sum_image = parts[sum_part].image;
  add_pattern_attributes(sum_image, ocean.cascades[0].high.pattern, ocean.cascades[0].choppiness);
  sum_image.attributes.erase("oceanref.cascade");
  sum_image.attributes.erase("oceanref.cascade_choppiness");
  sum_image.attributes.erase("oceanref.band_rad_per_m");
  sum_image.attributes["oceanref.index_convention"] =
      "pixel (column m, row n) is the point x = m L/N, z = n L/N [m] on cascade 0's footprint "
      "(L = oceanref.L_m = L_0, N = oceanref.N = N_h); every cascade is evaluated exactly there "
      "(direct summation, no interpolation) and combined as shading.normals = " +
      std::string(scene.shading.normals == ShadingNormals::surface ? "surface" : "high_resolution");
  const auto sum_channel = [&](const char* name, const char* unit, double PointFields::*member) {
    std::vector<double> v(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) v[i] = sum[i].*member;
    add_channel(sum_image, exact, std::string("sum.") + name, unit, v);
  };
  sum_channel("height", "m", &PointFields::height);
  sum_channel("slope_x", "1", &PointFields::slope_x);
  sum_channel("slope_z", "1", &PointFields::slope_z);
  sum_channel("jacobian", "1", &PointFields::jacobian);
  for (int axis = 0; axis < 3; ++axis) {  // the shading normal (shading.normals)
    std::vector<double> v(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) {
      v[i] = sum[i].normal[static_cast<std::size_t>(axis)];
    }
    add_channel(sum_image, exact, std::string("sum.normal_") + "xyz"[axis], "1", v);
  }
  sum_channel("foam", "1", &PointFields::foam);
  // The hashes: every field of every part in field-name order (names are unique across parts),
  // over the field names without the channel suffix (channel_name.h), as before the suffix.
  std::vector<std::uint8_t> bytes;
  std::vector<std::uint8_t> bytes32;
  std::size_t count = 0;
  for (const auto& [name, values] : exact) count += name.size() + 1 + values.size();
  bytes.reserve(count * sizeof(double));
  bytes32.reserve(count * sizeof(float));
  for (const auto& [name, values] : exact) {  // std::map: name order
    for (auto* b : {&bytes, &bytes32}) {
      b->insert(b->end(), name.begin(), name.end());
      b->push_back(0);
    }
    for (const double v : values) {
      append_bytes(bytes, v);
      append_bytes(bytes32, static_cast<float>(v));
    }
  }
  return {std::move(parts), sha256_hex(bytes32), sha256_hex(bytes)};
}

std::vector<ExrPart> stage_image(const Scene& scene, const Ocean& ocean, Stage stage, int threads) {
  require_cascades(scene);
  std::vector<ExrPart> parts;
  for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    const bool multi = c.low.pattern.resolution != c.high.pattern.resolution;
    for (const PatternSpectrum* s : multi ? std::vector{&c.high, &c.low} : std::vector{&c.high}) {
      const std::string name = "c" + std::to_string(i) + (s == &c.low ? ".low" : "");
      ExrPart part{name, 0, 0, {}};
      part.image.width = s->pattern.resolution;
      part.image.height = s->pattern.resolution;
      part.image.attributes = common_attributes(scene, stage);
      part.image.attributes["oceanref.index_convention"] = kSpectralGrid;
      add_pattern_attributes(part.image, s->pattern, c.choppiness);
      std::map<std::string, std::vector<double>> unused;
      for (const StageChannel& channel :
           stage_channels(ocean.spectrum, *s, stage, scene.time, threads, ocean.filter)) {
        add_channel(part.image, unused, name + "." + channel.name, channel.unit, channel.values);
      }
      parts.push_back(std::move(part));
    }
  }
  return parts;
}

std::vector<PointFieldRow> fields_at_point(const Scene& scene, const Ocean& ocean, double x,
                                           double z, int threads) {
  require_cascades(scene);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, threads);
  std::vector<PointFieldRow> rows;
  const auto row = [&](const std::string& cascade, std::string_view name, double fft,
                       double direct) {
    rows.push_back({cascade, std::string(name), fft, direct});
  };
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, scene.time);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CascadeSpectra& c = ocean.cascades[i];
    const auto grid = cascade_from_grids(fields[i], x, z);
    const auto direct = direct_sum(c.low, c.high, evolved[i], x, z);
    for (std::size_t q = 0; q < kFieldNames.size(); ++q) {
      row(std::to_string(i), kFieldNames[q], grid[q], direct[q]);
    }
  }
  // The combination as the renderer shades it (shading.normals): from the grids read
  // bilinearly, and by direct summation.
  const ShadingNormals normals = scene.shading.normals;
  const PointFields g =
      combine_shading_at(ocean, fields, evolved, x, z, Interpolation::bilinear, normals);
  const PointFields d =
      combine_shading_at(ocean, fields, evolved, x, z, Interpolation::direct, normals);
  row("sum", "height", g.height, d.height);
  row("sum", "slope_x", g.slope_x, d.slope_x);
  row("sum", "slope_z", g.slope_z, d.slope_z);
  row("sum", "jacobian", g.jacobian, d.jacobian);
  const auto& ng = g.normal;
  const auto& nd = d.normal;
  row("sum", "normal_x", ng[0], nd[0]);
  row("sum", "normal_y", ng[1], nd[1]);
  row("sum", "normal_z", ng[2], nd[2]);
  row("sum", "foam", g.foam, d.foam);
  return rows;
}

}  // namespace oceanref
