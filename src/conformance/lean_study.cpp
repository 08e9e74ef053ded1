#include "conformance/lean_study.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <ostream>
#include <stdexcept>

#include "core/format.h"
#include "core/fp_environment.h"
#include "core/math.h"
#include "core/parallel.h"
#include "raster/renderer.h"
#include "shading/lean.h"
#include "waves/ocean.h"
#include "waves/random.h"
#include "waves/surface.h"

namespace oceanref {

namespace {
constexpr std::array<const char*, 4> kMethods{"normal_mapping", "lean", "lean_corrected",
                                              "lean_exact"};
struct FootprintErrors {
  std::array<double, 4> lobe{}, glint{};
};

// The half vector's slope of the glint near the horizon (see the header).
std::array<double, 2> glint_half_slope() {
  const double deg = std::numbers::pi / 180.0;
  const std::array<double, 3> v{-math::cos(5.0 * deg), math::sin(5.0 * deg), 0.0};
  const std::array<double, 3> l{math::cos(10.0 * deg) * math::cos(3.0 * deg), math::sin(10.0 * deg),
                                math::cos(10.0 * deg) * math::sin(3.0 * deg)};
  const std::array<double, 3> h{v[0] + l[0], v[1] + l[1], v[2] + l[2]};
  return {h[0] / h[1], h[2] / h[1]};
}

struct Study {
  const Ocean* ocean = nullptr;
  Ocean exemplar;  // the same cascades, periodic
  std::vector<CascadeFields> fields;
  std::vector<EvolvedCascade> evolved;
  Interpolation mode = Interpolation::bicubic;
  double base = 0.0;  // 1/s
  LeanMoments mean;   // μ_B, μ_M of the exemplar

  LeanMoments moments_at(const Ocean& o, double x, double z) const {
    return lean_moments(combine_surface_at(o, fields, evolved, x, z, mode).normal);
  }
};

void add_moments(LeanMoments& sum, const LeanMoments& m) {
  for (std::size_t c = 0; c < 2; ++c) sum.b[c] += m.b[c];
  for (std::size_t c = 0; c < 3; ++c) sum.m[c] += m.m[c];
}
void scale_moments(LeanMoments& m, double s) {
  for (double& v : m.b) v *= s;
  for (double& v : m.m) v *= s;
}

FootprintErrors footprint_errors(const Study& st, double cx, double cz, double across, double along,
                                 int n) {
  const Ocean& ocean = *st.ocean;
  const bool tiled = ocean.synthesis == Synthesis::tiling_and_blending;
  // The tiles of the footprint's centre (one tile of weight 1 for any other synthesis).
  std::array<TileReading, 3> tiles{};
  std::size_t tile_count = 1;
  if (tiled) {
    tiles = tile_readings(ocean.tiling, cx, cz);
    tile_count = 3;
  } else {
    tiles[0].weight = 1.0;
  }
  std::vector<std::array<double, 2>> slopes;  // ñ of the rendered surface at every point
  LeanMoments exact;
  std::array<LeanMoments, 3> raw{};  // per tile, in the exemplar's frame
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = cx + ((i + 0.5) / n - 0.5) * along;
      const double z = cz + ((j + 0.5) / n - 0.5) * across;
      const LeanMoments m = st.moments_at(ocean, x, z);
      slopes.push_back(m.b);
      add_moments(exact, m);
      for (std::size_t t = 0; t < tile_count; ++t) {
        const std::array<double, 2> e = tile_exemplar_position(tiles[t], x, z);
        add_moments(raw[t], tiled ? st.moments_at(st.exemplar, e[0], e[1]) : m);
      }
    }
  }
  const double count = static_cast<double>(slopes.size());
  scale_moments(exact, 1.0 / count);
  std::array<LeanMoments, 3> corrected{}, uncorrected{};
  std::array<double, 3> weights{};
  std::array<double, 2> b{};  // Σ w_i R_i B_i
  for (std::size_t t = 0; t < tile_count; ++t) {
    scale_moments(raw[t], 1.0 / count);
    const TileReading& r = tiles[t];
    corrected[t] = turned_lean_moments(raw[t], r.cos, r.sin);
    uncorrected[t] = {corrected[t].b, raw[t].m};
    weights[t] = r.weight;
    for (std::size_t c = 0; c < 2; ++c) b[c] += r.weight * corrected[t].b[c];
  }
  const SlopeCovariance base_lobe{st.base, st.base, 0.0};
  const std::array<SlopeCovariance, 4> covariances{
      base_lobe, blended_lean_covariance(uncorrected, weights, st.mean, st.base),
      blended_lean_covariance(corrected, weights, st.mean, st.base),
      lean_covariance(exact.b, exact.m, st.base)};
  const std::array<std::array<double, 2>, 4> means{b, b, b, exact.b};
  const auto truth = [&](const std::array<double, 2>& h) {
    double sum = 0.0;
    for (const std::array<double, 2>& s : slopes) sum += beckmann_slope_density(h, s, base_lobe);
    return sum / count;
  };
  // The grid of h̃: ±4 standard deviations of the truth around its mean.
  const SlopeCovariance spread = lean_covariance(exact.b, exact.m, st.base);
  FootprintErrors e;
  std::array<double, 4> squares{};
  double truth_squares = 0.0;
  for (const std::array<double, 2>& h :
       lobe_grid(exact.b, {4.0 * std::sqrt(spread.xx), 4.0 * std::sqrt(spread.zz)})) {
    const double p = truth(h);
    truth_squares += p * p;
    for (std::size_t m = 0; m < 4; ++m) {
      const double d = beckmann_slope_density(h, means[m], covariances[m]) - p;
      squares[m] += d * d;
    }
  }
  const std::array<double, 2> g = glint_half_slope();
  const double p_glint = truth(g);
  for (std::size_t m = 0; m < 4; ++m) {
    e.lobe[m] = std::sqrt(squares[m] / truth_squares);
    e.glint[m] = std::fabs(beckmann_slope_density(g, means[m], covariances[m]) - p_glint) / p_glint;
  }
  return e;
}
}  // namespace

std::vector<std::array<double, 2>> lobe_grid(const std::array<double, 2>& centre,
                                             const std::array<double, 2>& half_width) {
  constexpr int kLobeGrid = 24;
  std::vector<std::array<double, 2>> points;
  points.reserve(kLobeGrid * kLobeGrid);
  for (int j = 0; j < kLobeGrid; ++j) {
    for (int i = 0; i < kLobeGrid; ++i) {
      points.push_back({centre[0] + half_width[0] * ((i + 0.5) / kLobeGrid * 2.0 - 1.0),
                        centre[1] + half_width[1] * ((j + 0.5) / kLobeGrid * 2.0 - 1.0)});
    }
  }
  return points;
}

LeanMoments exemplar_mean_moments(const Ocean& exemplar, const std::vector<CascadeFields>& fields,
                                  const std::vector<EvolvedCascade>& evolved, Interpolation mode,
                                  double period) {
  constexpr int kMeanGrid = 128;
  LeanMoments mean;
  for (int j = 0; j < kMeanGrid; ++j) {
    for (int i = 0; i < kMeanGrid; ++i) {
      const double x = period * (i + 0.5) / kMeanGrid, z = period * (j + 0.5) / kMeanGrid;
      add_moments(mean,
                  lean_moments(combine_surface_at(exemplar, fields, evolved, x, z, mode).normal));
    }
  }
  scale_moments(mean, 1.0 / (kMeanGrid * kMeanGrid));
  return mean;
}

std::vector<LeanStudyRow> lean_study(const Scene& scene, const LeanStudySettings& s) {
  if (s.footprints < 1 || s.samples_per_axis < 2 || !(s.elongation >= 1.0) || s.threads < 1) {
    throw std::invalid_argument(
        "lean study: footprints >= 1, samples per axis >= 2, elongation >= 1, threads >= 1");
  }
  const ReferenceFpEnvironment fp;
  const Ocean ocean = realize_ocean(scene.waves, s.threads);
  Study st;
  st.ocean = &ocean;
  st.exemplar = ocean;
  st.exemplar.synthesis = Synthesis::periodic;
  st.mode = scene.shading.interpolation;
  if (st.mode == Interpolation::direct) {
    st.evolved = evolve_ocean(ocean, scene.time);
  } else {
    st.fields = synthesize_ocean(ocean, scene.time, s.threads);
  }
  const RenderJob job = scene_render_job(scene, ocean, s.threads);
  const SlopeVariance unresolved = unresolved_slope_variance(job, scene.waves);
  st.base = 0.5 * (unresolved.upwind + unresolved.crosswind);
  double period = 0.0;
  for (const double size : scene.waves.sizes) period = std::fmax(period, size);
  // μ_B, μ_M of Lutz eq. 13 (with Σ w² = 1 their term cancels).
  st.mean = exemplar_mean_moments(st.exemplar, st.fields, st.evolved, st.mode, period);
  const std::vector<double> sizes = s.footprint_sizes.empty()
                                        ? std::vector<double>{period / 16, period / 4, period}
                                        : s.footprint_sizes;
  const std::uint64_t key = mix64(mix64(s.seed) ^ 0x6c65616eULL);  // "lean"
  std::vector<LeanStudyRow> rows;
  for (const double across : sizes) {
    if (!(across > 0.0)) throw std::invalid_argument("lean study: footprint sizes must be > 0");
    std::vector<FootprintErrors> errors(static_cast<std::size_t>(s.footprints));
    parallel_for(s.footprints, s.threads, [&](int f) {
      const auto i = static_cast<std::uint64_t>(f);
      const double cx = 64.0 * period * uniform_open(random_word(key, 2 * i));
      const double cz = 64.0 * period * uniform_open(random_word(key, 2 * i + 1));
      errors[static_cast<std::size_t>(f)] =
          footprint_errors(st, cx, cz, across, s.elongation * across, s.samples_per_axis);
    });
    for (std::size_t m = 0; m < kMethods.size(); ++m) {
      LeanStudyRow r;
      r.method = kMethods[m];
      r.footprint = across;
      for (const FootprintErrors& e : errors) {
        r.lobe_error_mean += e.lobe[m] / static_cast<double>(errors.size());
        r.lobe_error_max = std::fmax(r.lobe_error_max, e.lobe[m]);
        r.glint_error_mean += e.glint[m] / static_cast<double>(errors.size());
      }
      rows.push_back(r);
    }
  }
  return rows;
}

void bench_lean(std::ostream& out, const std::vector<LeanStudyRow>& rows) {
  out << "method,footprint_m,lobe_error_mean,lobe_error_max,glint_error_mean\n";
  for (const LeanStudyRow& r : rows) {
    out << r.method << ',' << format_number(r.footprint) << ',' << format_number(r.lobe_error_mean)
        << ',' << format_number(r.lobe_error_max) << ',' << format_number(r.glint_error_mean)
        << '\n';
  }
}

}  // namespace oceanref
