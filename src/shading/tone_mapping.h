// Tone mapping for previews only (the reference output stays linear): Reinhard et al. 2002
// ("Photographic Tone Reproduction for Digital Images", eq. 1–4) and the temporal adaptation of
// Krawczyk, Myszkowski, Seidel 2005 ("Lightness Perception in Tone Reproduction for High Dynamic
// Range Images", eq. 5–7 and 12), as Gamper §4.5 combines them.
#pragma once

#include <vector>

#include "core/vec3.h"

namespace oceanref {

// Luminance of linear sRGB: Y = 0.2126 R + 0.7152 G + 0.0722 B (IEC 61966-2-1, the middle row of
// the sRGB → XYZ matrix).
double relative_luminance(const Vec3& rgb);
// L̄_w = exp((1/N) Σ ln(δ + L_w))  (Reinhard eq. 1), δ a small offset for black pixels.
double log_average_luminance(const std::vector<Vec3>& image, double delta = 1e-4);
// One pixel's term ln(δ + max(L_w, 0)) of the sum above, which runs in pixel order (so that a
// caller summing band by band gets the same bits).
double log_luminance_term(const Vec3& rgb, double delta = 1e-4);
// L_d = L(1 + L/L_white²)/(1 + L) with L = (a/L̄_w)·L_w  (Reinhard eq. 2 and 4); the colour is
// scaled by L_d/L_w.
Vec3 reinhard(const Vec3& rgb, double log_average, double key, double white);
// The key from the adaptation luminance: a = 1.03 − 2/(2 + log10(L_a + 1))  (Krawczyk eq. 12).
double automatic_key(double adaptation_luminance);
// τ(L) = σ(L) τ_rod + (1 − σ(L)) τ_cone, σ(L) = 0.04/(0.04 + L), τ_rod = 0.4 s,
// τ_cone = 0.1 s  (Krawczyk eq. 6–7).
double adaptation_time_constant(double luminance);
// L_a ← L_a + (L̄_w − L_a)(1 − e^{−Δt/τ(L_a)})  (Krawczyk eq. 5).
double adapt_luminance(double adapted, double scene, double time_step);
// sRGB transfer function for an 8-bit preview: 12.92 c below 0.0031308, else 1.055 c^{1/2.4} −
// 0.055 (IEC 61966-2-1), clamped to [0, 1].
double srgb_encode(double linear);

}  // namespace oceanref
