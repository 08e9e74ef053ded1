// The measurements behind reference/ACCURACY.md (`oceanref bench synthesis|lighting|render|
// study`): the speed/accuracy study, synthesis timing against FFTW, the shader approximations
// against the exact terms, interpolation against direct summation, the slope-variance budget.
// The bench_* functions print the CSV blocks `oceanref bench` prints (timings vary between
// runs; every other number is deterministic); the struct-returning functions are the checkable
// parts (tests/test_study.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "waves/ocean.h"

namespace oceanref {

// `bench synthesis`: JONSWAP 10 m/s, sizes 1000·(1−1/φ)^i m.
struct SynthesisBenchOptions {
  int cascades = 4;
  int resolution = 256;
  int low_resolution = 0;  // 0: = resolution
  int threads = 2;
  int frames = 20;
  std::uint64_t seed = 1;
};
// One frame of synthesis per stage with KissFFT and FFTW double (median over the frames), their
// largest field difference, the bilinear lookup against direct summation and float32 fields
// (conformance/float32_backend.h) against double.
void bench_synthesis(std::ostream& out, const SynthesisBenchOptions& options);

// The shader approximations (Schlick Fresnel, rational erfc and Λ, mean-Fresnel fit, mirror and
// filtered sky lookups, the shader sun BRDF) against the exact forms at Gauss–Hermite `order`;
// printed vs physical sun transmittance; the sky integral's convergence with the order.
void bench_lighting(std::ostream& out, int order);

// One render of the scene file at width × height and spp samples (a square) per pixel, timed
// per stage.
void bench_render(std::ostream& out, const std::string& scene_path, int threads, int width,
                  int height, int spp);

// The first `count` points of the R2 quasi-random sequence over [0, size)²: (size·frac(i/g),
// size·frac(i/g²)), i = 1 … count, g the plastic number (the study's fixed evaluation points).
std::vector<std::array<double, 2>> r2_points(int count, double size);

// The combined fields by each interpolation mode against direct summation at 64 points of the
// R2 sequence over [0, 300 m)² (r2_points): the largest absolute error of the height
// [m], of the slopes and of the Jacobian, and the mean time per point.
struct InterpolationError {
  std::string mode;  // bilinear, bicubic, direct
  Interpolation interpolation = Interpolation::bilinear;
  double height = 0.0, slope = 0.0, jacobian = 0.0;
  double seconds_per_point = 0.0;
};
std::vector<InterpolationError> interpolation_errors(const Scene& scene, int threads);
void bench_interpolation(std::ostream& out, const std::string& scene_path, int threads);

// Where the spectrum's slope variance goes (waves/slope_budget.h) for every shading.normals and
// interpolation, per wind axis: resolved + σ² = moment.
void bench_slope_budget(std::ostream& out, const std::string& scene_path, int threads);

// Study 1: the FFT grids of cascade 0 against direct summation at 8 of its nodes (row z = 0),
// every field; the time of one frame of synthesis (all cascades), per node, and per direct
// point.
struct FftVsDirect {
  double fft_seconds_per_frame = 0.0;
  double fft_seconds_per_node = 0.0;
  double direct_seconds_per_point = 0.0;
  double max_abs_difference = 0.0;
  int points = 0;
};
FftVsDirect study_fft_vs_direct(const Scene& scene, int threads);

// Study 5: a sea that folds (the scene's waves at 16 m/s, choppiness −2.5 on every cascade), over
// the 4×4-node footprints of cascade 0's tile (n/4 × n/4 of them, J = det of the Jacobian of all
// cascades combined at the nodes): the share of nodes with J < the scene's whitecap threshold ε
// against the Gaussian model ½ erfc((μ − ε)/√(2σ²)) of Dupuy & Bruneton from the footprint's
// mean μ and variance σ² of J.
struct WhitecapFootprints {
  int footprints = 0;
  double mean_coverage = 0.0;        // the share of all nodes with J < ε
  double mean_abs_difference = 0.0;  // |Gaussian − share|, mean over the footprints
  double max_abs_difference = 0.0;   // and largest
};
WhitecapFootprints study_whitecap_footprints(const Scene& base, int threads);

// The study's sweeps: each knob's settings ascend toward its most exact setting (the finest
// grid, the most samples per pixel), against which each is measured. The full sweep takes
// minutes; `quick` is the same tables on small sizes (a test of the study, not a measurement).
struct StudySweeps {
  std::vector<int> fft_resolutions, cascade_counts;  // N and the cascade count (Hs, mss)
  std::vector<int> grid_columns;                     // projected grid, against the finest
  int finest_grid = 0, grid_width = 0, grid_height = 0;
  std::vector<int> axes;  // samples per axis, against the most, on a grid of spp_grid²
  int finest_axis = 0, spp_grid = 0, spp_width = 0, spp_height = 0;
  SynthesisBenchOptions synthesis;
  int lighting_order = 0;  // Gauss-Hermite order of the exact terms (bench lighting)
};
StudySweeps study_sweeps(bool quick, int threads);

// The whole study (reference/ACCURACY.md, "Study"): FFT vs direct, FFT resolution and cascades,
// projected-grid resolution, samples per pixel, whitecap statistics, interpolation, synthesis,
// the BRDF options; each against its most exact setting in the same run; on study_sweeps(quick).
void bench_study(std::ostream& out, const std::string& scene_path, int threads, bool quick);

}  // namespace oceanref
