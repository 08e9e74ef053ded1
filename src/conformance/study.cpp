#include "conformance/study.h"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <numbers>
#include <numeric>
#include <ostream>
#include <string>

#include "conformance/float32_backend.h"
#include "conformance/scene_objects.h"
#include "core/format.h"
#include "core/math.h"
#include "core/parallel.h"
#include "shading/ocean_lighting.h"
#include "waves/direct_sum.h"

namespace oceanref {

namespace {
// FFTW's 1-D plans of one benchmark run: one FFTW_MEASURE plan per size, made on the calling
// thread before a transform's threads run, destroyed with the set. FFTW's planner is global and
// not thread-safe (fftw_execute_dft is), so making and destroying plans is serialised.
class FftwPlans {
 public:
  FftwPlans() = default;
  FftwPlans(const FftwPlans&) = delete;
  FftwPlans& operator=(const FftwPlans&) = delete;
  ~FftwPlans() {
    const std::lock_guard lock(planner_mutex());
    for (const auto& [n, plan] : plans_) fftw_destroy_plan(plan);
  }

  fftw_plan row_plan(int n) {
    const std::lock_guard lock(planner_mutex());
    auto it = plans_.find(n);
    if (it == plans_.end()) {
      fftw_complex* a = fftw_alloc_complex(static_cast<std::size_t>(n));
      fftw_complex* b = fftw_alloc_complex(static_cast<std::size_t>(n));
      it = plans_.emplace(n, fftw_plan_dft_1d(n, a, b, FFTW_BACKWARD, FFTW_MEASURE)).first;
      fftw_free(a);
      fftw_free(b);
    }
    return it->second;
  }

 private:
  static std::mutex& planner_mutex() {
    static std::mutex mutex;
    return mutex;
  }
  std::map<int, fftw_plan> plans_;
};

// FFTW double with the same structure as inverse_fft_2d: 1-D transforms of the rows, then of
// the columns, split among threads.
void inverse_fft_2d_fftw(FftwPlans& plans, std::vector<Complex>& data, int n, int threads) {
  const fftw_plan plan = plans.row_plan(n);
  const auto stride = static_cast<std::size_t>(n);
  parallel_for(n, threads, [&](int row) {
    fftw_complex* line = fftw_alloc_complex(stride);
    fftw_complex* out = fftw_alloc_complex(stride);
    Complex* values = &data[static_cast<std::size_t>(row) * stride];
    for (std::size_t j = 0; j < stride; ++j) {
      line[j][0] = values[j].re;
      line[j][1] = values[j].im;
    }
    fftw_execute_dft(plan, line, out);
    for (std::size_t j = 0; j < stride; ++j) values[j] = Complex(out[j][0], out[j][1]);
    fftw_free(line);
    fftw_free(out);
  });
  constexpr int kBlock = 8;  // the column blocks of inverse_fft_2d
  parallel_for((n + kBlock - 1) / kBlock, threads, [&](int block) {
    const int first = block * kBlock;
    const auto count = static_cast<std::size_t>(std::min(kBlock, n - first));
    fftw_complex* in = fftw_alloc_complex(count * stride);
    fftw_complex* out = fftw_alloc_complex(count * stride);
    for (std::size_t r = 0; r < stride; ++r) {
      for (std::size_t c = 0; c < count; ++c) {
        const Complex v = data[r * stride + static_cast<std::size_t>(first) + c];
        in[c * stride + r][0] = v.re;
        in[c * stride + r][1] = v.im;
      }
    }
    for (std::size_t c = 0; c < count; ++c)
      fftw_execute_dft(plan, in + c * stride, out + c * stride);
    for (std::size_t r = 0; r < stride; ++r) {
      for (std::size_t c = 0; c < count; ++c) {
        data[r * stride + static_cast<std::size_t>(first) + c] =
            Complex(out[c * stride + r][0], out[c * stride + r][1]);
      }
    }
    fftw_free(in);
    fftw_free(out);
  });
}

using Flags = SynthesisBenchOptions;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Run {
  std::vector<double> frame_ms;
  SynthesisTimes stages;
};

Run time_pipeline(const Ocean& ocean, const Flags& f, const InverseFft2d& fft) {
  Run run;
  // Storage is allocated once for the sequence, as a renderer would; frame −1 warms up (FFTW
  // plans, first touch of the buffers).
  std::vector<CascadeFields> fields(ocean.cascades.size());
  std::vector<SynthesisWorkspace> work(ocean.cascades.size());
  for (int frame = -1; frame < f.frames; ++frame) {
    SynthesisTimes times;
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < ocean.cascades.size(); ++i) {
      const CascadeSpectra& c = ocean.cascades[i];
      synthesize_cascade(c.low, c.high, 0.1 * frame, f.threads, fields[i], work[i], fft, &times);
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (frame < 0) continue;
    run.frame_ms.push_back(ms);
    run.stages.evolve += times.evolve * 1e3 / f.frames;
    run.stages.pack += times.pack * 1e3 / f.frames;
    run.stages.transform += times.transform * 1e3 / f.frames;
    run.stages.unpack += times.unpack * 1e3 / f.frames;
  }
  return run;
}

void bench_synthesis_impl(std::ostream& out, const Flags& f) {
  WaveSettings w;
  w.seed = f.seed;
  w.sizes = golden_ratio_sizes(1000.0, f.cascades, GoldenFactor::small);
  w.resolution = f.resolution;
  w.low_resolution = f.low_resolution > 0 ? f.low_resolution : f.resolution;
  w.choppiness.assign(w.sizes.size(), -1.0);
  const Ocean ocean = realize_ocean(w, f.threads);
  FftwPlans plans;
  const InverseFft2d by_fftw_plans = [&plans](std::vector<Complex>& data, int n, int threads) {
    inverse_fft_2d_fftw(plans, data, n, threads);
  };
  const Run kiss = time_pipeline(ocean, f, inverse_fft_2d);
  const Run fftw = time_pipeline(ocean, f, by_fftw_plans);
  // The two FFTs must give the same fields (to rounding), or the timing comparison is moot.
  double worst = 0.0;
  const CascadeSpectra& c0 = ocean.cascades[0];
  const CascadeFields by_kiss = synthesize_cascade(c0.low, c0.high, 1.0, f.threads);
  const CascadeFields by_fftw = synthesize_cascade(c0.low, c0.high, 1.0, f.threads, by_fftw_plans);
  for (std::size_t q = 0; q < by_kiss.values.size(); ++q) {
    for (std::size_t i = 0; i < by_kiss.values[q].size(); ++i) {
      worst = std::max(worst, std::fabs(by_kiss.values[q][i] - by_fftw.values[q][i]));
    }
  }
  out << "# oceanref bench synthesis: " << f.cascades << " cascades, N_h = " << w.resolution
      << ", N_l = " << w.low_resolution << ", " << f.threads << " threads, " << f.frames
      << " frames (JONSWAP 10 m/s, sizes 1000·(1-1/phi)^i m); stage times are means over the "
         "frames\n"
      << "fft,frame_ms_median,frame_ms_mean,evolve_ms,pack_ms,transform_ms,unpack_ms\n";
  for (const auto& [name, run] : {std::pair{"kissfft", &kiss}, std::pair{"fftw", &fftw}}) {
    const double mean = std::accumulate(run->frame_ms.begin(), run->frame_ms.end(), 0.0) /
                        static_cast<double>(run->frame_ms.size());
    out << name << ',' << format_number(median(run->frame_ms)) << ',' << format_number(mean) << ','
        << format_number(run->stages.evolve) << ',' << format_number(run->stages.pack) << ','
        << format_number(run->stages.transform) << ',' << format_number(run->stages.unpack) << '\n';
  }
  out << "# kissfft/fftw frame time ratio: "
      << format_number(median(kiss.frame_ms) / median(fftw.frame_ms))
      << ", transform-stage ratio: " << format_number(kiss.stages.transform / fftw.stages.transform)
      << "; largest field difference kissfft vs fftw: " << format_number(worst) << "\n";
  // The renderer's lookup: summed fields sampled bilinearly from the grids vs direct summation
  // at 64 points of a fixed quasi-random (R2) sequence over the largest tile.
  {
    const double t = 10.0;
    const std::vector<CascadeFields> grids = synthesize_ocean(ocean, t, f.threads);
    const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, t);
    double e_height = 0.0, e_slope = 0.0, e_jacobian = 0.0;
    double m_height = 0.0, m_slope = 0.0, m_jacobian = 0.0;
    for (const auto& [x, z] : r2_points(64, w.sizes[0])) {
      const PointFields a = combine_from_grids(ocean, grids, x, z);
      const PointFields d = combine_direct(ocean, evolved, x, z);
      e_height = std::max(e_height, std::fabs(a.height - d.height));
      e_slope = std::max(
          e_slope, std::max(std::fabs(a.slope_x - d.slope_x), std::fabs(a.slope_z - d.slope_z)));
      e_jacobian = std::max(e_jacobian, std::fabs(a.jacobian - d.jacobian));
      m_height = std::max(m_height, std::fabs(d.height));
      m_slope = std::max(m_slope, std::max(std::fabs(d.slope_x), std::fabs(d.slope_z)));
      m_jacobian = std::max(m_jacobian, std::fabs(d.jacobian - 1.0));
    }
    out << "lookup,field,max_abs_direct,max_abs_bilinear_minus_direct (64 points, t = 10 s)\n"
        << "bilinear,height," << format_number(m_height) << ',' << format_number(e_height) << '\n'
        << "bilinear,slope," << format_number(m_slope) << ',' << format_number(e_slope) << '\n'
        << "bilinear,jacobian-1," << format_number(m_jacobian) << ',' << format_number(e_jacobian)
        << '\n';
  }
  // Float vs double: every field of cascade 0 (the largest amplitudes) at two times.
  out << "time_s,field,max_abs_double,max_abs_float_minus_double,relative\n";
  for (const double t : {10.0, 1000.0}) {
    const CascadeFields d = synthesize_cascade(c0.low, c0.high, t, f.threads);
    for (int q = 0; q < kFieldCount; ++q) {
      const Field field = Field(q);
      const PatternSpectrum& s = is_low_resolution_field(field) ? c0.low : c0.high;
      const std::vector<float> single = float32_field(s, t, field);
      const std::vector<double>& exact = d.values[static_cast<std::size_t>(q)];
      double peak = 0.0;
      double error = 0.0;
      for (std::size_t i = 0; i < exact.size(); ++i) {
        peak = std::max(peak, std::fabs(exact[i]));
        error = std::max(error, std::fabs(static_cast<double>(single[i]) - exact[i]));
      }
      out << format_number(t) << ',' << kFieldNames[static_cast<std::size_t>(q)] << ','
          << format_number(peak) << ',' << format_number(error) << ','
          << format_number(error / peak) << '\n';
    }
  }
}
// Relative errors of the shader approximations against the exact forms.
struct ErrorStats {
  double max = 0.0;
  double sum = 0.0;
  int count = 0;
  void add(double approximate, double exact) {
    if (!(std::fabs(exact) > 0.0)) return;
    const double e = std::fabs(approximate - exact) / std::fabs(exact);
    max = std::max(max, e);
    sum += e;
    ++count;
  }
};

void bench_lighting_impl(std::ostream& out, int order) {
  constexpr double deg = std::numbers::pi / 180.0;
  ErrorStats schlick, erfc_rational, lambda_rational, fit, mirror, filtered, sun_shader;
  for (double c = 0.0; c <= 1.0 + 1e-12; c += 0.001) {
    schlick.add(fresnel_reflectance(c, FresnelForm::schlick), fresnel_reflectance(c));
  }
  for (double x = 0.001; x <= 10.0; x += 0.001) erfc_rational.add(rational_erfc(x), math::erfc(x));
  const Sky sky = make_sky(2.5, 40.0 * deg, 0.0);
  const Vec3 sun = sky.sun_direction;
  const SurfaceFrame frame = wind_frame({0.0, 1.0, 0.0}, 0.0);
  BrdfOptions shader;
  shader.fresnel = FresnelForm::schlick;
  shader.erfc = ErfcForm::rational;
  int grid = 0;
  for (const double s2 : {1e-3, 5e-3, 0.01, 0.02, 0.05, 0.1}) {
    const SlopeVariance s{s2, 0.6 * s2};
    for (double vz = 0.0; vz <= 85.0; vz += 5.0) {
      for (double va = 0.0; va <= 180.0; va += 30.0) {
        ++grid;
        const Vec3 v = direction_from_angles(vz * deg, (180.0 + va) * deg);
        // Compare the masking G₁ = 1/(1 + Λ): Λ itself → 0 where errors are irrelevant.
        lambda_rational.add(1.0 / (1.0 + smith_lambda(v[1], s2, ErfcForm::rational)),
                            1.0 / (1.0 + smith_lambda(v[1], s2)));
        fit.add(mean_fresnel_fit(v, frame, s), mean_fresnel(v, frame, s, order));
        const double sky_exact = reflected_sky(v, frame, s, sky, order)[1];
        mirror.add(reflected_sky_mirror(v, frame, s, sky, order)[1], sky_exact);
        filtered.add(reflected_sky_filtered(v, frame, s, sky, order)[1], sky_exact);
        const double exact = ocean_brdf(sun, v, frame, s).brdf_cos;
        if (exact > 1e-6 * ocean_brdf(sun, {-sun[0], sun[1], -sun[2]}, frame, s).brdf_cos) {
          sun_shader.add(ocean_brdf(sun, v, frame, s, shader).brdf_cos, exact);
        }
      }
    }
  }
  out << "# oceanref bench lighting: view zenith 0-85 deg x 7 azimuths x sigma^2 in {1e-3 .. 0.1}"
         " (crosswind 0.6x), sun at 40 deg, T = 2.5, Gauss-Hermite order "
      << order << " (" << grid << " configurations)\n"
      << "approximation,max_relative_error,mean_relative_error,samples\n";
  const auto line = [&](const char* name, const ErrorStats& e) {
    out << name << ',' << format_number(e.max) << ','
        << format_number(e.count > 0 ? e.sum / e.count : 0.0) << ',' << e.count << '\n';
  };
  line("fresnel_schlick_vs_exact (cos 0..1)", schlick);
  line("erfc_rational_vs_exact (x 0.001..10)", erfc_rational);
  line("masking_1/(1+lambda)_rational_vs_exact", lambda_rational);
  line("mean_fresnel_fit_vs_gauss_hermite", fit);
  line("sky_mirror_lookup_vs_integral (G)", mirror);
  line("sky_filtered_lookup_vs_integral (G)", filtered);
  line("sun_brdf_schlick_rational_vs_exact", sun_shader);
  // Printed vs physical transmittance (Preetham appendix A.5) over the sun's zenith angle.
  out << "sun_zenith_deg,Y_physical,Y_printed,ratio\n";
  for (const double z : {0.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 88.0}) {
    const Sky at = make_sky(2.5, z * deg, 0.0);
    const double physical = sun_radiance_xyz(at, TransmittanceForm::physical)[1];
    const double printed = sun_radiance_xyz(at, TransmittanceForm::printed)[1];
    out << format_number(z) << ',' << format_number(physical) << ',' << format_number(printed)
        << ',' << format_number(printed / physical) << '\n';
  }
  // Convergence of the sky integral with the Gauss–Hermite order (one grazing configuration).
  out << "order,L_sky_Y (view zenith 80 deg, sigma^2 0.02/0.012)\n";
  const Vec3 v = direction_from_angles(80.0 * deg, 200.0 * deg);
  for (const int n : {4, 8, 16, 32, 64, 128}) {
    out << n << ',' << format_number(reflected_sky(v, frame, {0.02, 0.012}, sky, n)[1]) << '\n';
  }
}
void bench_render_impl(std::ostream& out, const std::string& path, int threads, int width,
                       int height, int spp) {
  Scene scene = load_scene(path);
  scene.image.width = width;
  scene.image.height = height;
  scene.image.samples_per_axis = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
  const auto t0 = std::chrono::steady_clock::now();
  const Ocean ocean = realize_ocean(scene.waves, threads);
  const SceneObjects objects = load_scene_objects(scene);
  RenderJob job = scene_render_job(scene, ocean, threads);
  job.objects = &objects;
  const SlopeVariance unresolved = unresolved_slope_variance(job, scene.waves);
  const double prepare =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  RenderTimes times;
  const auto t1 = std::chrono::steady_clock::now();
  const RenderedImage image = render(job, unresolved, &times);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  double covered = 0.0;
  for (const double c : image.coverage) covered += c;
  const double samples =
      static_cast<double>(width) * height * job.samples_per_axis * job.samples_per_axis;
  out << "# oceanref bench render: " << path << " at " << width << "x" << height << ", " << spp
      << " spp, " << threads << " threads; sea covers "
      << format_number(covered / static_cast<double>(image.coverage.size())) << " of the image\n"
      << "stage,seconds\n"
      << "spectrum_realization_and_unresolved_variance," << format_number(prepare) << '\n'
      << "synthesis," << format_number(times.synthesis) << '\n'
      << "grid," << format_number(times.grid) << '\n'
      << "raster," << format_number(times.raster) << '\n'
      << "shading," << format_number(times.shading) << '\n'
      << "render_total," << format_number(total) << '\n'
      << "samples_per_second," << format_number(samples / total) << '\n';
}

// Where the spectrum's slope variance goes (waves/slope_budget.h) for every shading.normals and
// interpolation, per wind axis: resolved + sigma2 = moment.
void bench_slope_budget_impl(std::ostream& out, const std::string& path, int threads) {
  Scene scene = load_scene(path);
  const Ocean ocean = realize_ocean(scene.waves, threads);
  out << "normals,interpolation,axis,moment,resolved,above_cutoff,interpolation_loss,sampling,"
         "sigma2,interpolation_loss_share_of_bands,identity_error\n";
  for (const auto& [normals, normals_name] : kShadingNormals) {
    for (const auto& [mode, name] : kInterpolations) {
      scene.shading.normals = normals;
      scene.shading.interpolation = mode;
      const RenderJob job = scene_render_job(scene, ocean, threads);
      const SlopeVarianceBudget b = slope_budget(job, scene.waves);
      for (const bool upwind : {true, false}) {
        const auto v = [&](const SlopeVariance& w) { return upwind ? w.upwind : w.crosswind; };
        out << normals_name << ',' << name << ',' << (upwind ? "upwind" : "crosswind") << ','
            << format_number(v(b.moment)) << ',' << format_number(v(b.resolved)) << ','
            << format_number(v(b.above_cutoff)) << ',' << format_number(v(b.interpolation_loss))
            << ',' << format_number(v(b.sampling)) << ',' << format_number(v(b.unresolved)) << ','
            << format_number(v(b.interpolation_loss) / v(b.discrete)) << ','
            << format_number((v(b.resolved) + v(b.unresolved)) / v(b.moment) - 1.0) << '\n';
      }
    }
  }
}

// The speed/accuracy study: every knob timed and compared with its most exact setting in the
// same run (reference/ACCURACY.md, "Study").
double seconds_of(const std::function<void()>& body) {
  const auto t0 = std::chrono::steady_clock::now();
  body();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double relative_rmse(const std::vector<Vec3>& a, const std::vector<Vec3>& reference) {
  double err = 0.0, ref = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = a[i][c] - reference[i][c];
      err += d * d;
      ref += reference[i][c] * reference[i][c];
    }
  }
  return std::sqrt(err / std::max(ref, 1e-300));
}

void bench_study_impl(std::ostream& out, const std::string& path, int threads, bool quick) {
  const Scene base = load_scene(path);
  const StudySweeps sweeps = study_sweeps(quick, threads);
  // 1. FFT grid vs direct summation at the grid nodes of cascade 0.
  {
    const FftVsDirect r = study_fft_vs_direct(base, threads);
    out << "# 1. FFT grids vs direct summation (the synthesis of all cascades; cascade 0's "
           "fields at 8 nodes along x)\n"
        << "fft_seconds_per_frame," << format_number(r.fft_seconds_per_frame)
        << "\nfft_seconds_per_node_of_cascade0," << format_number(r.fft_seconds_per_node)
        << "\ndirect_seconds_per_point," << format_number(r.direct_seconds_per_point)
        << "\nmax_abs_difference_at_nodes," << format_number(r.max_abs_difference) << '\n';
  }
  // 2. FFT resolution and cascade count: Hs and mss of the sampled spectrum vs the continuous.
  {
    const Spectrum s = make_spectrum(base.waves.spectrum);
    const SpectralMoments exact = spectral_moments(s, 2.0 * std::numbers::pi / kMinimumWavelength);
    out << "# 2. FFT resolution N and cascade count: sampled sum of Theta dk^2 vs the continuous "
           "spectrum to lambda_min (Hs "
        << format_number(exact.significant_wave_height) << " m, mss " << format_number(exact.mss)
        << ")\nN,cascades,Hs_relative_error,mss_relative_error,synthesis_seconds\n";
    for (const int n : sweeps.fft_resolutions) {
      for (const int count : sweeps.cascade_counts) {
        WaveSettings w = base.waves;
        w.resolution = w.low_resolution = n;
        w.sizes = golden_ratio_sizes(800.0, count, GoldenFactor::small);
        w.choppiness.assign(w.sizes.size(), 0.0);
        const Ocean ocean = realize_ocean(w, threads);
        double m0 = 0.0, mss = 0.0;
        for (const CascadeSpectra& c : ocean.cascades) {
          const int res = c.high.pattern.resolution;
          const double dk = wavenumber_spacing(c.high.pattern.size);
          for (int b = 0; b < res; ++b) {
            for (int a = 0; a < res; ++a) {
              const double kx = wave_index(a, res) * dk, kz = wave_index(b, res) * dk;
              const double k = math::hypot(kx, kz);
              if (!(k > 0.0) || !c.high.pattern.band.contains(k)) continue;
              const double e = wavevector_spectrum(s, kx, kz) * dk * dk;
              m0 += e;
              mss += k * k * e;
            }
          }
        }
        const double seconds = seconds_of([&] { (void)synthesize_ocean(ocean, 0.0, threads); });
        out << n << ',' << count << ','
            << format_number(4.0 * std::sqrt(m0) / exact.significant_wave_height - 1.0) << ','
            << format_number(mss / exact.mss - 1.0) << ',' << format_number(seconds) << '\n';
      }
    }
  }
  // 3–4. Projected-grid resolution and samples per pixel: images vs the finest setting.
  const auto render_with = [&](int columns, int axis, int width, int height, double* seconds) {
    Scene scene = base;
    scene.grid.columns = scene.grid.rows = columns;
    scene.image.width = width;
    scene.image.height = height;
    scene.image.samples_per_axis = axis;
    const Ocean ocean = realize_ocean(scene.waves, threads);
    const SceneObjects objects = load_scene_objects(scene);
    RenderJob job = scene_render_job(scene, ocean, threads);
    job.objects = &objects;
    const SlopeVariance u = unresolved_slope_variance(job, scene.waves);
    RenderedImage image;
    *seconds = seconds_of([&] { image = render(job, u); });
    return image;
  };
  {
    double t = 0.0;
    const int w = sweeps.grid_width, h = sweeps.grid_height;
    const RenderedImage finest = render_with(sweeps.finest_grid, 1, w, h, &t);
    out << "# 3. projected-grid resolution (" << w << 'x' << h << ", 1 spp) vs "
        << sweeps.finest_grid << "^2 (" << format_number(t) << " s)\ngrid,relative_rmse,seconds\n";
    for (const int columns : sweeps.grid_columns) {
      const RenderedImage image = render_with(columns, 1, w, h, &t);
      out << columns << ',' << format_number(relative_rmse(image.radiance, finest.radiance)) << ','
          << format_number(t) << '\n';
    }
  }
  {
    double t = 0.0;
    const int w = sweeps.spp_width, h = sweeps.spp_height, grid = sweeps.spp_grid;
    const RenderedImage finest = render_with(grid, sweeps.finest_axis, w, h, &t);
    out << "# 4. samples per pixel (" << w << 'x' << h << ", grid " << grid << ") vs "
        << sweeps.finest_axis * sweeps.finest_axis << " spp (" << format_number(t)
        << " s)\nspp,relative_rmse,seconds\n";
    for (const int axis : sweeps.axes) {
      const RenderedImage image = render_with(grid, axis, w, h, &t);
      out << axis * axis << ',' << format_number(relative_rmse(image.radiance, finest.radiance))
          << ',' << format_number(t) << '\n';
    }
  }
  // 5. Whitecap footprint statistics (study_whitecap_footprints).
  {
    const WhitecapFootprints w = study_whitecap_footprints(base, threads);
    out << "# 5. whitecap coverage over 4x4-node footprints of cascade 0's tile (16 m/s, u = "
           "-2.5): Gaussian "
           "statistics vs the share of nodes with det J < threshold\n"
        << "mean_coverage," << format_number(w.mean_coverage) << "\nmean_abs_difference,"
        << format_number(w.mean_abs_difference) << "\nmax_abs_difference,"
        << format_number(w.max_abs_difference) << '\n';
  }
  out << "# 6. interpolation modes vs direct summation\n";
  bench_interpolation(out, path, threads);
  out << "# 7. synthesis: KissFFT vs FFTW, float vs double fields\n";
  bench_synthesis_impl(out, sweeps.synthesis);
  out << "# 8. BRDF options vs the exact terms\n";
  bench_lighting_impl(out, sweeps.lighting_order);
}
}  // namespace

WhitecapFootprints study_whitecap_footprints(const Scene& base, int threads) {
  WaveSettings stormy = base.waves;  // a sea that folds: 16 m/s, u = −2.5
  stormy.spectrum.wind_speed = 16.0;
  stormy.choppiness.assign(stormy.sizes.size(), -2.5);
  const Ocean ocean = realize_ocean(stormy, threads);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, base.time, threads);
  const CascadeFields& f0 = fields[0];
  const double eps = base.shading.whitecap_threshold;
  double difference = 0.0, covered = 0.0;
  WhitecapFootprints w;
  const int n = f0.high_resolution;
  for (int by = 0; by + 4 <= n; by += 4) {
    for (int bx = 0; bx + 4 <= n; bx += 4) {
      double mean = 0.0, square = 0.0, indicator = 0.0;
      for (int y = by; y < by + 4; ++y) {
        for (int x = bx; x < bx + 4; ++x) {
          const double j =
              combine_from_grids(ocean, fields, x * f0.size / n, y * f0.size / n).jacobian;
          mean += j / 16.0;
          square += j * j / 16.0;
          indicator += (j < eps ? 1.0 : 0.0) / 16.0;
        }
      }
      const double gauss = whitecap_coverage(mean, std::max(0.0, square - mean * mean), eps);
      difference += std::fabs(gauss - indicator);
      w.max_abs_difference = std::max(w.max_abs_difference, std::fabs(gauss - indicator));
      covered += indicator;
      ++w.footprints;
    }
  }
  w.mean_coverage = covered / w.footprints;
  w.mean_abs_difference = difference / w.footprints;
  return w;
}

void bench_synthesis(std::ostream& out, const SynthesisBenchOptions& options) {
  bench_synthesis_impl(out, options);
}

void bench_lighting(std::ostream& out, int order) {
  bench_lighting_impl(out, order);
}

void bench_render(std::ostream& out, const std::string& scene_path, int threads, int width,
                  int height, int spp) {
  bench_render_impl(out, scene_path, threads, width, height, spp);
}

std::vector<std::array<double, 2>> r2_points(int count, double size) {
  const double g = 1.32471795724474602596;  // the plastic number: g³ = g + 1
  std::vector<std::array<double, 2>> points;
  for (int i = 1; i <= count; ++i) {
    points.push_back({size * std::fmod(i / g, 1.0), size * std::fmod(i / (g * g), 1.0)});
  }
  return points;
}

std::vector<InterpolationError> interpolation_errors(const Scene& scene, int threads) {
  const Ocean ocean = realize_ocean(scene.waves, threads);
  const std::vector<CascadeFields> fields = synthesize_ocean(ocean, scene.time, threads);
  const std::vector<std::array<double, 2>> points = r2_points(64, 300.0);
  const std::vector<EvolvedCascade> evolved = evolve_ocean(ocean, scene.time);
  std::vector<PointFields> exact;
  for (const auto& [x, z] : points) exact.push_back(combine_direct(ocean, evolved, x, z));
  std::vector<InterpolationError> rows;
  for (const auto& [mode, name] : kInterpolations) {
    InterpolationError e;
    e.mode = std::string(name);
    e.interpolation = mode;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PointFields p = combine_at(ocean, fields, evolved, points[i][0], points[i][1], mode);
      const PointFields& d = exact[i];
      e.height = std::max(e.height, std::fabs(p.height - d.height));
      e.slope = std::max(
          e.slope, std::max(std::fabs(p.slope_x - d.slope_x), std::fabs(p.slope_z - d.slope_z)));
      e.jacobian = std::max(e.jacobian, std::fabs(p.jacobian - d.jacobian));
    }
    e.seconds_per_point =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
        static_cast<double>(points.size());
    rows.push_back(e);
  }
  return rows;
}

void bench_interpolation(std::ostream& out, const std::string& scene_path, int threads) {
  const Scene scene = load_scene(scene_path);
  out << "interpolation,max_abs_height_error_m,max_abs_slope_error,max_abs_jacobian_error,"
         "seconds_per_point\n";
  for (const InterpolationError& e : interpolation_errors(scene, threads)) {
    out << e.mode << ',' << format_number(e.height) << ',' << format_number(e.slope) << ','
        << format_number(e.jacobian) << ',' << format_number(e.seconds_per_point) << '\n';
  }
}

void bench_slope_budget(std::ostream& out, const std::string& scene_path, int threads) {
  bench_slope_budget_impl(out, scene_path, threads);
}

FftVsDirect study_fft_vs_direct(const Scene& scene, int threads) {
  const Ocean ocean = realize_ocean(scene.waves, threads);
  std::vector<CascadeFields> fields;
  const double fft = seconds_of([&] { fields = synthesize_ocean(ocean, scene.time, threads); });
  const CascadeFields& f0 = fields[0];
  const CascadeSpectra& c0 = ocean.cascades[0];
  FftVsDirect r;
  const double direct = seconds_of([&] {
    const EvolvedCascade h = evolve_cascade(c0.low, c0.high, scene.time);
    for (int m = 0; m < f0.high_resolution; m += f0.high_resolution / 8) {
      const double x = m * f0.size / f0.high_resolution;
      const auto d = direct_sum(c0.low, c0.high, h, x, 0.0);
      const auto g = cascade_from_grids(f0, x, 0.0);
      for (std::size_t q = 0; q < d.size(); ++q) {
        r.max_abs_difference = std::max(r.max_abs_difference, std::fabs(d[q] - g[q]));
      }
      ++r.points;
    }
  });
  const double cells = static_cast<double>(f0.high_resolution) * f0.high_resolution;
  r.fft_seconds_per_frame = fft;
  r.fft_seconds_per_node = fft / (cells * static_cast<double>(fields.size()));
  r.direct_seconds_per_point = direct / r.points;
  return r;
}

StudySweeps study_sweeps(bool quick, int threads) {
  StudySweeps s;
  s.synthesis.threads = threads;
  if (quick) {
    s.fft_resolutions = {32, 64};
    s.cascade_counts = {1, 2};
    s.grid_columns = {32, 64, 128};
    s.finest_grid = 256;
    s.grid_width = 80;
    s.grid_height = 45;
    s.axes = {1, 2};
    s.finest_axis = 4;
    s.spp_grid = 128;
    s.spp_width = 40;
    s.spp_height = 24;
    s.synthesis.cascades = 2;
    s.synthesis.resolution = 32;
    s.synthesis.frames = 1;
    s.lighting_order = 16;
  } else {
    s.fft_resolutions = {32, 64, 128, 256};
    s.cascade_counts = {1, 2, 3, 4};
    s.grid_columns = {64, 128, 256, 512, 1024};
    s.finest_grid = 2048;
    s.grid_width = 320;
    s.grid_height = 180;
    s.axes = {1, 2, 3, 4};
    s.finest_axis = 8;
    s.spp_grid = 512;
    s.spp_width = 160;
    s.spp_height = 90;
    s.synthesis.frames = 5;
    s.lighting_order = 64;
  }
  return s;
}

void bench_study(std::ostream& out, const std::string& scene_path, int threads, bool quick) {
  bench_study_impl(out, scene_path, threads, quick);
}

}  // namespace oceanref
