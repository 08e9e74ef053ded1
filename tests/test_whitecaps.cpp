// Whitecaps as Dupuy & Bruneton 2012 define them (waves/whitecaps.h): the moments of the
// displacement gradient against the slope variances they must add up to, the mean and variance
// of det J against Monte Carlo draws of the Gaussian residual, the coverage against the closed
// form on a synthetic Gaussian sea, and the renderer's coverage converging as spp grows.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "shading/ocean_lighting.h"
#include "spectrum/moments.h"
#include "waves/random.h"
#include "waves/whitecaps.h"

using namespace oceanref;

namespace {

// The displacement-gradient residual of a set of waves in the wind frame, each ξ_n √P_n times
// [[k_a²/k, k_a k_c/k], [k_a k_c/k, k_c²/k]] with ξ_n standard normal: its moments, the sum of
// jacobian_moments_of_mode over the waves (checked against the definition below).
struct WhitecapWave {
  double kx, kz, power;
};
JacobianMoments whitecap_moments_of(const std::vector<WhitecapWave>& waves, double c, double s) {
  JacobianMoments m;
  for (const WhitecapWave& w : waves) {
    m = m + jacobian_moments_of_mode(c * w.kx + s * w.kz, -s * w.kx + c * w.kz, w.power);
  }
  return m;
}

}  // namespace

TEST_CASE("whitecaps: one wave's moments are P k_a^i k_c^j / k^2, i + j = 4") {
  // (k_a, k_c) = (3, 4), k² = 25, P = 25: the moments are 3^i 4^j, exact in doubles.
  const JacobianMoments m = jacobian_moments_of_mode(3.0, 4.0, 25.0);
  CHECK(m.aaaa == 81.0);
  CHECK(m.aaac == 108.0);
  CHECK(m.aacc == 144.0);
  CHECK(m.accc == 192.0);
  CHECK(m.cccc == 256.0);
  // Across the wind the odd moments change sign, the even ones do not.
  const JacobianMoments mirrored = jacobian_moments_of_mode(3.0, -4.0, 25.0);
  CHECK(mirrored.aaac == -108.0);
  CHECK(mirrored.accc == -192.0);
  CHECK(mirrored.aacc == 144.0);
}

TEST_CASE("whitecaps: the displacement-gradient moments of a band add up to its slope variances") {
  // aaaa + aacc = ∫k²Ψ∫cos²D and aacc + cccc = ∫k²Ψ∫sin²D (cos⁴ + cos²sin² = cos²); the
  // spreading is symmetric about the wind, so the odd moments vanish. Both sides are adaptive
  // quadratures to the default relative tolerance (1e-8 per integral): 1e-6 leaves room.
  SpectrumSettings settings;
  settings.wind_speed = 12.0;
  settings.wind_direction = 0.7;
  const Spectrum spectrum = make_spectrum(settings);
  const double lo = 2.0, hi = 40.0;
  const JacobianMoments m = band_jacobian_moments(spectrum, lo, hi);
  const SlopeVariance v = band_slope_variance(spectrum, lo, hi);
  CHECK(m.aaaa + m.aacc == doctest::Approx(v.upwind).epsilon(1e-6));
  CHECK(m.aacc + m.cccc == doctest::Approx(v.crosswind).epsilon(1e-6));
  CHECK(std::abs(m.aaac) < 1e-9 * m.aaaa);
  CHECK(std::abs(m.accc) < 1e-9 * m.aaaa);
  // An empty band has none.
  const JacobianMoments none = band_jacobian_moments(spectrum, hi, lo);
  CHECK(none.aaaa == 0.0);
  CHECK(none.cccc == 0.0);
}

TEST_CASE("whitecaps: mean and variance of det J against Monte Carlo draws of the residual") {
  // μ = det A and σ² from the closed form (waves/whitecaps.h) against 400 000 draws of
  // det(A + M′) with M′ = Σ ξ_n √P_n G_n. The sample mean's standard error is σ/√N ≈ 0.0016σ and
  // the sample variance's about σ²√(2/N)·(kurtosis factor < 2) ≈ 0.5%: 5 standard errors.
  const std::vector<WhitecapWave> waves{{0.8, 0.1, 0.2},  {0.3, -0.9, 0.15}, {-0.5, 0.6, 0.1},
                                        {1.4, 0.7, 0.06}, {0.2, 1.1, 0.08},  {-1.0, -0.2, 0.12}};
  const Deformation a{0.7, 0.2, -0.1, 1.3};
  const double phi = 0.6;
  const double c = math::cos(phi), s = math::sin(phi);
  const JacobianMoments m = whitecap_moments_of(waves, c, s);
  const double det_a = a.xx * a.zz - a.xz * a.zx;
  const double variance = jacobian_variance(a, m, c, s);
  const int draws = 400000;
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < draws; ++i) {
    double xx = a.xx, xz = a.xz, zx = a.zx, zz = a.zz;
    for (std::size_t n = 0; n < waves.size(); ++n) {
      const WhitecapWave& w = waves[n];
      const double k = std::hypot(w.kx, w.kz);
      const double xi =
          standard_normal_pair(component_key(7u, 0, i, static_cast<std::int32_t>(n))).real *
          std::sqrt(w.power);
      xx += xi * w.kx * w.kx / k;
      xz += xi * w.kx * w.kz / k;
      zx += xi * w.kx * w.kz / k;
      zz += xi * w.kz * w.kz / k;
    }
    const double j = xx * zz - xz * zx;
    sum += j;
    squares += j * j;
  }
  const double mean = sum / draws;
  const double sample_variance = squares / draws - mean * mean;
  CHECK(std::abs(mean - det_a) < 5.0 * std::sqrt(variance / draws));
  CHECK(sample_variance == doctest::Approx(variance).epsilon(5.0 * 2.0 * std::sqrt(2.0 / draws)));
  // The quadratic term matters here: without it the variance is off by more than the tolerance.
  const double quadratic = m.aaaa * m.cccc + 3.0 * m.aacc * m.aacc - 4.0 * m.aaac * m.accc;
  MESSAGE("quadratic term / variance = ", quadratic / variance);
  CHECK(quadratic > 0.02 * variance);
  // The variance does not depend on the frame the moments are written in: the same waves in a
  // frame turned by 1 rad give the same σ².
  const double c2 = math::cos(phi + 1.0), s2 = math::sin(phi + 1.0);
  CHECK(jacobian_variance(a, whitecap_moments_of(waves, c2, s2), c2, s2) ==
        doctest::Approx(variance).epsilon(1e-12));
}

TEST_CASE("whitecaps: the coverage matches the closed form on a synthetic Gaussian sea") {
  // Waves along x only: D_z = 0, so det J = 1 + u ∂D_x/∂x exactly — a sum of 400 independent
  // random-phase waves, Gaussian to the central limit. The share of 100 000 positions with
  // det J < ε against W = ½ erfc((μ − ε)/√(2σ²)) with μ = 1 and σ² = jacobian_variance of the
  // waves' moments (× u²). Tolerance 0.01 absolute: the positions' sampling error of a share
  // near 0.1–0.3 (≈ 0.0015), the finite wave count's departure from Gaussian (measured below
  // 0.004).
  const int count = 400;
  std::vector<double> k(count), amplitude(count), phase(count);
  std::vector<WhitecapWave> waves;
  for (int n = 0; n < count; ++n) {
    const std::uint64_t key = component_key(11u, 1, n, 0);
    k[static_cast<std::size_t>(n)] = 0.05 + 2.0 * uniform_open(random_word(key, 0));
    amplitude[static_cast<std::size_t>(n)] =
        0.04 / k[static_cast<std::size_t>(n)] * (0.5 + uniform_open(random_word(key, 1)));
    phase[static_cast<std::size_t>(n)] = 2.0 * std::numbers::pi * uniform_open(random_word(key, 2));
    // ∂D_x/∂x = Σ A k cos(kx + φ): variance Σ ½A²k² = Σ P k²·k²/k² with P = ½A².
    const double a = amplitude[static_cast<std::size_t>(n)];
    waves.push_back({k[static_cast<std::size_t>(n)], 0.0, 0.5 * a * a});
  }
  for (const double u : {-1.0, -1.6}) {
    for (const double threshold : {0.0, 0.3}) {
      CAPTURE(u);
      CAPTURE(threshold);
      const JacobianMoments m = scaled(whitecap_moments_of(waves, 1.0, 0.0), u * u);
      const double expected = whitecap_coverage(1.0, jacobian_variance({}, m, 1.0, 0.0), threshold);
      int below = 0;
      const int positions = 100000;
      for (int i = 0; i < positions; ++i) {
        const double x = 3000.0 * uniform_open(random_word(component_key(12u, 2, i, 0), 0));
        double derivative = 0.0;
        for (std::size_t n = 0; n < waves.size(); ++n) {
          derivative += amplitude[n] * k[n] * math::cos(k[n] * x + phase[n]);
        }
        if (1.0 + u * derivative < threshold) ++below;
      }
      const double share = static_cast<double>(below) / positions;
      CHECK(expected > 0.02);
      CHECK(std::abs(share - expected) < 0.01);
    }
  }
}

TEST_CASE("whitecaps: the unresolved moments carry the unresolved slope variance times u²") {
  const auto scene = parse_scene(nlohmann::json::parse(R"({"seed": 3,
      "waves": {"spectrum": {"wind_speed": 14}, "cascades": {"sizes": [90, 21]}, "resolution": 32,
                "choppiness": [-0.6, -1.1]},
      "shading": {"whitecaps": true, "accuracy": "fast"},
      "render": {"width": 16, "height": 9}})"));
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const SlopeVarianceBudget b =
      slope_variance_budget(ocean, scene.waves.minimum_wavelength, 0.0, scene.shading.interpolation,
                            scene.shading.normals);
  const JacobianMoments m = unresolved_jacobian_moments(ocean, b);
  // The finest cascade (21 m) has u = −1.1.
  CHECK(m.aaaa + 2.0 * m.aacc + m.cccc ==
        doctest::Approx(1.21 * (b.unresolved.upwind + b.unresolved.crosswind)).epsilon(1e-12));
  // Its shape is the spectrum's above the cut-off.
  const JacobianMoments above =
      band_jacobian_moments(ocean.spectrum, b.cutoff_wavenumber, b.floor_wavenumber);
  CHECK(m.aaaa / m.cccc == doctest::Approx(above.aaaa / above.cccc).epsilon(1e-12));
  CHECK(m.aacc / m.cccc == doctest::Approx(above.aacc / above.cccc).epsilon(1e-12));
  const RenderJob job = scene_render_job(scene, ocean, 1);
  CHECK(job.unresolved_jacobian.aaaa == m.aaaa);
  // An empty band above the cut-off (it reaches the floor): the isotropic shape 3/8, 1/8, 3/8
  // of the slope variance left (a budget's unresolved part may be clamped, not 0), finite.
  SlopeVarianceBudget empty = b;
  empty.cutoff_wavenumber = b.floor_wavenumber;
  const JacobianMoments iso = unresolved_jacobian_moments(ocean, empty);
  const double left = 1.21 * (b.unresolved.upwind + b.unresolved.crosswind);
  CHECK(iso.aaaa == doctest::Approx(0.375 * left).epsilon(1e-15));
  CHECK(iso.aaac == 0.0);
  CHECK(iso.aacc == doctest::Approx(0.125 * left).epsilon(1e-15));
  CHECK(iso.accc == 0.0);
  CHECK(iso.cccc == doctest::Approx(0.375 * left).epsilon(1e-15));
}

TEST_CASE("whitecaps: the coverage of the pixels converges as the samples per pixel grow") {
  // Only the whitecaps lit (sun, sky and sea off): the foam layer is Σ W·L_foam over the
  // samples. Its RMS difference from 16 × 16 samples per pixel must fall as S grows; measured
  // 4.74, 1.55, 0.74 and 0.42 times the reference's mean at S = 1, 2, 4, 8 (the foam is sparse:
  // a few pixels hold it).
  const auto scene = parse_scene(nlohmann::json::parse(R"({"seed": 5, "time": 1.5,
      "waves": {"spectrum": {"wind_speed": 20}, "cascades": {"sizes": [60, 17]},
                "resolution": 64, "choppiness": -1.4},
      "camera": {"position": [0, 14, 0], "look_at": [0, 0, 40]},
      "grid": {"columns": 128, "rows": 128},
      "shading": {"whitecaps": true, "sun": false, "sky": false, "sea": false, "accuracy": "fast"},
      "render": {"width": 32, "height": 18, "samples_per_pixel": 1}})"));
  const Ocean ocean = realize_ocean(scene.waves, 1);
  RenderJob job = scene_render_job(scene, ocean, 2);
  job.layers = true;
  const SlopeVariance unresolved = unresolved_slope_variance(job, scene.waves);
  const auto foam_of = [&](int s) {
    job.samples_per_axis = s;
    return render(job, unresolved).foam;
  };
  const std::vector<Vec3> reference = foam_of(16);
  double mean = 0.0;
  for (const Vec3& v : reference) mean += v[1] / static_cast<double>(reference.size());
  REQUIRE(mean > 0.0);
  // The RMS difference of the foam layer from the reference, relative to its mean, at S = 1 … 8.
  const auto errors_of = [&](const char* what) {
    std::vector<double> errors;
    for (const int s : {1, 2, 4, 8}) {
      const std::vector<Vec3> foam = foam_of(s);
      double squares = 0.0;
      for (std::size_t i = 0; i < foam.size(); ++i) {
        squares += (foam[i][1] - reference[i][1]) * (foam[i][1] - reference[i][1]);
      }
      errors.push_back(std::sqrt(squares / static_cast<double>(foam.size())) / mean);
      MESSAGE(what, "S = ", s, ": RMS error of the foam layer / its mean = ", errors.back());
    }
    return errors;
  };
  const std::vector<double> errors = errors_of("");
  for (std::size_t i = 1; i < errors.size(); ++i) CHECK(errors[i] < 0.75 * errors[i - 1]);
  CHECK(errors.back() < 0.2 * errors.front());
  // Footprint filtering: each sample's coverage is that of its cell — the read det J and the
  // variance the filter removed, taken as Gaussian (Dupuy & Bruneton's model). Where a cell holds
  // resolved waves whose det J has lighter tails than a Gaussian (two cascades of few large waves;
  // towards the horizon the cells are long), the coverage is biased high: measured 13.2, 11.1, 8.7
  // and 7.2 times the reference's mean at S = 1, 2, 4, 8 (this test prints them). The cells
  // shrink as S grows, so the error must fall with S towards the same limit.
  job.footprint_filtering = true;
  const std::vector<double> filtered = errors_of("footprint filtering, ");
  for (std::size_t i = 1; i < filtered.size(); ++i) CHECK(filtered[i] < 0.9 * filtered[i - 1]);
}

namespace {
// A small choppy sea that folds, with foam that decays in 7 steps of 0.05 s.
Scene whitecap_foam_scene(const char* steps) {
  auto j = nlohmann::json::parse(R"({"seed": 9, "time": 2.0,
      "waves": {"spectrum": {"wind_speed": 20}, "cascades": {"sizes": [60, 17]}, "resolution": 64,
                "choppiness": -4.0, "foam": {"decay": 4, "time_step": 0.05}},
      "camera": {"position": [0, 10, 0], "look_at": [0, 0, 30]},
      "grid": {"columns": 64, "rows": 64},
      "shading": {"whitecaps": true, "sun": false, "sky": false, "sea": false,
                  "accuracy": "fast", "interpolation": "direct"},
      "render": {"width": 24, "height": 14, "samples_per_pixel": 1}})");
  j["waves"]["foam"]["steps"] = nlohmann::json::parse(steps);
  return parse_scene(j);
}
}  // namespace

TEST_CASE("foam: \"steady\" steps make the accumulation independent of where it started") {
  // δ = 4 · 0.05 = 0.2: ⌊1/δ⌋ + 2 = 7 steps.
  const Scene scene = whitecap_foam_scene(R"("steady")");
  CHECK(scene.foam.steps == 7);
  const Ocean ocean = realize_ocean(scene.waves, 1);
  const AccumulatedFoam steady =
      accumulate_foam(ocean, 2.0, scene.foam, ShadingNormals::surface, 2);
  FoamSequence longer = scene.foam;
  longer.steps += 5;
  const AccumulatedFoam from_earlier =
      accumulate_foam(ocean, 2.0, longer, ShadingNormals::surface, 2);
  CHECK(steady.combined == from_earlier.combined);  // the same bits
  CHECK(steady.cascades == from_earlier.cascades);
  // ... and the accumulation matters: fewer steps give less foam somewhere.
  FoamSequence shorter = scene.foam;
  shorter.steps = 1;
  const AccumulatedFoam recent = accumulate_foam(ocean, 2.0, shorter, ShadingNormals::surface, 2);
  double more = 0.0;
  for (std::size_t i = 0; i < recent.combined.size(); ++i) {
    CHECK(recent.combined[i] <= steady.combined[i]);
    more += steady.combined[i] - recent.combined[i];
  }
  CHECK(more > 0.0);
  // The scene's errors name the key.
  CHECK_THROWS_WITH_AS(whitecap_foam_scene(R"("forever")"), doctest::Contains("waves.foam.steps"),
                       SceneError);
  auto j = nlohmann::json::parse(R"({"waves": {"foam": {"decay": 0, "steps": "steady"}}})");
  CHECK_THROWS_WITH_AS(parse_scene(j), doctest::Contains("decay > 0"), SceneError);
  // ⌊1/(decay·Δt)⌋ + 2 steps, at most kMaxFoamSteps: 1/(decay·Δt) = 9998.5 gives exactly the
  // limit (accepted), 9999.5 one step more (refused, naming the count).
  j["waves"]["foam"]["decay"] = 1.0;
  j["waves"]["foam"]["time_step"] = 1.0 / 9998.5;
  CHECK(parse_scene(j).foam.steps == kMaxFoamSteps);
  j["waves"]["foam"]["time_step"] = 1.0 / 9999.5;
  CHECK_THROWS_WITH_AS(parse_scene(j), doctest::Contains("would take 10001 steps"), SceneError);
  // Accumulated whitecaps are read at a sample's point, not filtered to its footprint: steps
  // with whitecaps and footprint filtering are refused; any two of the three are accepted.
  nlohmann::json filtered = nlohmann::json::parse(
      R"({"waves": {"foam": {"steps": 4}}, "shading": {"whitecaps": true},
          "render": {"footprint_filtering": true}})");
  CHECK_THROWS_WITH_AS(parse_scene(filtered), doctest::Contains("waves.foam.steps: accumulated"),
                       SceneError);
  for (const auto& setting : {std::pair{"/waves/foam/steps", nlohmann::json(0)},
                              std::pair{"/shading/whitecaps", nlohmann::json(false)},
                              std::pair{"/render/footprint_filtering", nlohmann::json(false)}}) {
    const std::string key = setting.first;
    CAPTURE(key);
    nlohmann::json accepted = filtered;
    accepted[nlohmann::json::json_pointer(key)] = setting.second;
    CHECK_NOTHROW(parse_scene(accepted));
  }
}

TEST_CASE("foam: the renderer's accumulated whitecaps equal what `fields` accumulates") {
  // With the variance taken away (no unresolved waves) and the threshold 0, W is the indicator
  // of det J < 0 and its accumulation the one accumulate_foam folds on cascade 0's footprint
  // lattice — there from direct sums on the lattice, here from the renderer's reading at a point.
  // The two sums differ by rounding: a node may differ only where |det J| < 1e-9.
  const Scene scene = whitecap_foam_scene("5");
  const Ocean ocean = realize_ocean(scene.waves, 1);
  RenderJob job = scene_render_job(scene, ocean, 2);
  job.unresolved_jacobian = {};
  const RenderFrame frame = prepare_frame(job, {1e-10, 1e-10});
  REQUIRE(frame.foam_history.size() == 5);
  const AccumulatedFoam fields =
      accumulate_foam(ocean, scene.time, scene.foam, scene.shading.normals, 2);
  const int n = ocean.cascades.front().high.pattern.resolution;
  REQUIRE(fields.combined.size() == static_cast<std::size_t>(n * n));
  const double spacing = ocean.cascades.front().high.pattern.size / n;
  int foamy = 0, differ = 0;
  for (int b = 0; b < n; b += 2) {  // every fourth node (the test's time)
    for (int a = 0; a < n; a += 2) {
      const double x = a * spacing, z = b * spacing;
      const PointFields f =
          combine_shading_at(ocean, frame.fields.grids, frame.fields.evolved, x, z,
                             scene.shading.interpolation, scene.shading.normals);
      const double render = foam_coverage_at(frame, f, x, z, {});
      const double expected = fields.combined[static_cast<std::size_t>(b * n + a)];
      if (expected > 0.0) ++foamy;
      if (render != expected && std::abs(f.jacobian) > 1e-9) ++differ;
    }
  }
  CHECK(foamy > 20);
  CHECK(differ == 0);
  // The accumulation never lowers the coverage below the instant's.
  const PointFields f = combine_shading_at(ocean, frame.fields.grids, frame.fields.evolved, 3.0,
                                           4.0, scene.shading.interpolation, scene.shading.normals);
  RenderFrame instant = frame;
  instant.foam_history.clear();
  CHECK(foam_coverage_at(frame, f, 3.0, 4.0, job.unresolved_jacobian) >=
        foam_coverage_at(instant, f, 3.0, 4.0, job.unresolved_jacobian));
}

TEST_CASE("foam: the history read from the newest back gives the forward recursion's bits") {
  // accumulated_foam_of_history against accumulated_foam run forward over every instant, on
  // histories of every kind — no foam, a foam patch at a random age, coverages at ½ (where the
  // decay changes), 0 and 1, NaN, long runs — and on histories made to sit at the stopping
  // rule's edge (the older foam decayed to exactly `current` ± an ulp or two).
  const double decay = 0.1, dt = 0.25;  // the default scene's: 42 steady steps
  const int steps = steady_foam_steps(decay, dt);
  REQUIRE(steps == 42);
  const auto before_now = [&](const std::vector<double>& w) {
    double foam = 0.0;  // w[age − 1], oldest last
    for (auto it = w.rbegin(); it != w.rend(); ++it) {
      foam = accumulated_foam(foam, *it, decay, dt);
    }
    return foam;
  };
  const auto forward = [&](const std::vector<double>& w, double current) {
    return accumulated_foam(before_now(w), current, decay, dt);
  };
  const auto history = [&](const std::vector<double>& w, double current, int& reads) {
    reads = 0;
    return accumulated_foam_of_history(static_cast<int>(w.size()), current, decay, dt,
                                       [&](int age) {
                                         ++reads;
                                         return w[static_cast<std::size_t>(age - 1)];
                                       });
  };
  std::mt19937_64 draw(7);
  const auto uniform = [&] { return static_cast<double>(draw() >> 11) * 0x1p-53; };
  int reads = 0;
  // A sea without whitecaps: after the newest 19 instants (decays 19 · 0.05) an older one can
  // leave at most 1 − 0.95 = 0.05, which now's decay 0.05 takes to 0 < current; the older 23
  // are not read.
  const std::vector<double> calm(42, 1e-7);
  CHECK(history(calm, 2e-7, reads) == forward(calm, 2e-7));
  CHECK(reads == 19);
  int compared = 0, skipped = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<double> w(static_cast<std::size_t>(steps));
    const int kind = trial % 5;
    for (double& x : w) {
      x = kind == 0   ? 1e-6 * uniform()
          : kind == 1 ? uniform()
          : kind == 2 ? std::vector<double>{0.0, 0.5, 1.0, 0.25}[draw() % 4]
          : kind == 3 ? (draw() % 7 == 0 ? std::nan("") : 0.01 * uniform())
                      : 1e-3 * uniform();
    }
    // A patch of foam somewhere in most histories.
    if (kind >= 3) w[draw() % w.size()] = kind == 4 ? 1.0 : 0.5 + 0.5 * uniform();
    double current = kind == 2 ? 0.0 : 0.1 * uniform();
    if (trial % 10 == 9) {
      // At the edge: current = the foam the history leaves before now, decayed, ± 0–2 ulps.
      current = std::fmax(0.0, before_now(w) - decay * dt / 0.5);
      for (int u = 0; u < static_cast<int>(draw() % 3); ++u) {
        current = std::nextafter(current, draw() % 2 ? 1.0 : 0.0);
      }
    }
    const double expected = forward(w, current);
    const double got = history(w, current, reads);
    CHECK(std::memcmp(&got, &expected, sizeof got) == 0);
    ++compared;
    skipped += reads < steps ? 1 : 0;
  }
  MESSAGE("histories that stopped early: " << skipped << " of " << compared);
  CHECK(skipped > 4000);  // the small-coverage kinds stop early (8861 of 20000 measured)
}

TEST_CASE("foam: the renderer's coverage over its history equals the old way, bit for bit") {
  // foam_coverage_at reads an earlier instant's deformation from the fields it keeps
  // (deformation_at), stopping early where older instants cannot matter. Recomputed here the
  // way it was first written: every earlier instant synthesized in full, read at the point by
  // combine_shading_at, its coverage W = ½ erfc((det J − ε)/√(2σ²)) with σ² from its
  // deformation and the unresolved moments, accumulated forward over all instants. Grid
  // interpolations, both normals, the unresolved variance kept (W strictly between 0 and 1).
  for (const char* interpolation : {"bicubic", "bilinear"}) {
    for (const ShadingNormals normals :
         {ShadingNormals::surface, ShadingNormals::high_resolution}) {
      CAPTURE(interpolation);
      CAPTURE(static_cast<int>(normals));
      Scene scene = whitecap_foam_scene(R"("steady")");
      scene.shading.interpolation = std::string(interpolation) == "bicubic"
                                        ? Interpolation::bicubic
                                        : Interpolation::bilinear;
      scene.shading.normals = normals;
      // A slower decay than the helper's (δ = 0.025/max(W, ½) per step, 42 steady steps), so
      // that earlier instants often decide the result.
      scene.foam.decay = 0.5;
      scene.foam.steps = steady_foam_steps(scene.foam.decay, scene.foam.time_step);
      REQUIRE(scene.foam.steps == 42);
      const Ocean ocean = realize_ocean(scene.waves, 1);
      const RenderJob job = scene_render_job(scene, ocean, 2);
      const RenderFrame frame = prepare_frame(job, {0.01, 0.01});
      const auto coverage = [&](const PointFields& f) {
        const Deformation a{1.0 + f.raw[static_cast<std::size_t>(Field::ddx_dx)],
                            f.raw[static_cast<std::size_t>(Field::ddx_dz)], f.ddz_dx,
                            1.0 + f.raw[static_cast<std::size_t>(Field::ddz_dz)]};
        return whitecap_coverage(
            f.jacobian,
            jacobian_variance(a, job.unresolved_jacobian, frame.wind_cos, frame.wind_sin),
            scene.shading.whitecap_threshold);
      };
      std::vector<std::vector<CascadeFields>> earlier;  // oldest first
      for (int j = scene.foam.steps; j >= 1; --j) {
        earlier.push_back(synthesize_ocean(ocean, scene.time - j * scene.foam.time_step, 2));
      }
      int partial = 0, from_history = 0, compared = 0;
      for (int b = 0; b < 24; ++b) {
        for (int a = 0; a < 24; ++a) {
          const double x = 2.55 * a + 0.3, z = 2.35 * b + 0.2;
          double expected = 0.0;
          for (const std::vector<CascadeFields>& grids : earlier) {
            const PointFields f =
                combine_shading_at(ocean, grids, {}, x, z, scene.shading.interpolation, normals);
            expected =
                accumulated_foam(expected, coverage(f), scene.foam.decay, scene.foam.time_step);
          }
          const PointFields now = combine_shading_at(ocean, frame.fields.grids, {}, x, z,
                                                     scene.shading.interpolation, normals);
          expected =
              accumulated_foam(expected, coverage(now), scene.foam.decay, scene.foam.time_step);
          const double got = foam_coverage_at(frame, now, x, z, job.unresolved_jacobian);
          CHECK(std::memcmp(&got, &expected, sizeof got) == 0);
          partial += expected > 1e-6 && expected < 1.0 - 1e-6 ? 1 : 0;
          from_history += expected != coverage(now) ? 1 : 0;
          ++compared;
        }
      }
      CHECK(partial > compared / 10);  // the variance matters at many of the points
      MESSAGE("points " << compared << ", partial coverage " << partial
                        << ", decided by an earlier instant " << from_history);
      CHECK(from_history > compared / 50);  // and so do the earlier instants
    }
  }
}
