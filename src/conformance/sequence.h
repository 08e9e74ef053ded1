// Animated sequences (`render --frames A:B --fps F`): frame k is the scene at time t_k = time +
// k/F. Every frame is reproducible alone — the same bytes whether it is rendered in a sequence or
// by itself — because the state that carries over frames is replayed from a documented start:
//   - foam (waves.foam, accumulated whitecaps) is a function of time alone: the fold of the
//     instants t_k − j·Δt, j = steps … 0 (raster/renderer.h foam_coverage_at); with "steps":
//     "steady" it is the foam of a sea that has always been there (waves/ocean.h);
//   - the eye's adaptation (Krawczyk, Myszkowski & Seidel 2005, eq. 5–7, 12; Gamper §4.5) starts
//     at frame 0 adapted to its metered luminance and follows frames 0, 1, …, k; the luminance a
//     frame adapts to is metered on a small fast render of it (metered_luminance), so replaying
//     frames 0 … k − 1 for frame k costs little. Only the preview (PNG) is tone-mapped with it;
//     the EXR stays linear and records the state (SequenceFrame attributes).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "conformance/render_output.h"

namespace oceanref {

inline constexpr int kMaxFrame = 1000000;
inline constexpr double kMaxFrameRate = 1000.0;
// The metering render: the frame's scene at 1/kMeteringDivisor of its width and height (at
// least 1 pixel each), 1 sample per pixel, fast lighting (its sky_order and sun_order).
inline constexpr int kMeteringDivisor = 8;

// The scene of frame k: time + k/fps.
Scene frame_scene(const Scene& scene, int frame, double fps);
// L̄_w = exp(mean ln(δ + L_w)) (Reinhard eq. 1) of the frame scene's metering render.
double metered_luminance(const Scene& frame_scene, int threads);
// The adaptation state of frames 0 … last (index, fps, time, metered L̄_w, L_a, key): L_a(0) =
// L̄_w(0), L_a(k) = adapt_luminance(L_a(k − 1), L̄_w(k), 1/fps) (Krawczyk eq. 5–7), a =
// automatic_key(L_a) (eq. 12). `log` (may be empty) hears of each metering.
std::vector<SequenceFrame> adaptation_through(const Scene& scene, int last, double fps, int threads,
                                              const std::function<void(const std::string&)>& log);

// A path pattern's name for frame k: the last run of '#' replaced by k, zero-padded to the run's
// length (ocean_####.exr → ocean_0007.exr). Throws std::invalid_argument without a '#'.
std::string frame_path(const std::string& pattern, int frame);
// The pattern in ffmpeg's image-sequence form (the run of n '#' as %0nd).
std::string ffmpeg_pattern(const std::string& pattern);

}  // namespace oceanref
