// Aperiodic synthesis of the ocean from its periodic exemplar: tiling and blending (Lutz,
// Schoentgen & Gilet 2024 §3.2, §4–5, after Heitz & Neyret 2018), with an authored flow map.
//
// The exemplar is the periodic ocean of the cascades (Lutz's "initial ocean tile": one IFFT of
// the whole spectrum when there is one cascade). Three hexagonal tilings overlap so that their
// centres form a triangular grid of edge a; a point x lies in one triangle of that grid, whose
// vertices v = 0, 1, 2 are the centres of the three tiles covering it. Each tile shows the
// exemplar shifted by a random offset h(k_v) drawn from the tile's index and the scene seed, and,
// with a flow map, turned by the angle θ_v of the flow at the tile's centre (Lutz eq. 7–8). The
// tiles are blended with the barycentric coordinates b_v of x normalized so that Σ w_v² = 1
// (Lutz eq. 4): for content of zero mean whose tiles are uncorrelated this keeps the variance.
//
// Every field the renderer reads is blended as its own quantity: η, D and the exact derivatives
// of the blended η and D, which include the weights' gradients (∇(Σ w_v f_v) = Σ w_v ∇f_v +
// f_v ∇w_v). The blended surface is continuous, smooth inside each triangle of the grid, and its
// normal is the gradient of what is rasterized (src/FORMULAS.md, "Tiling and blending").
#pragma once

#include <array>
#include <cstdint>

#include "core/choice.h"
#include "waves/fields.h"

namespace oceanref {

// How the plane is covered: the periodic exemplar repeated, tiled and blended, or mixed with
// aperiodic noise (Lutz eq. 2, the paper's baseline; waves/noise.h).
enum class Synthesis { periodic, tiling_and_blending, noise_blended };
inline constexpr std::array<Choice<Synthesis>, 3> kSyntheses{{
    {Synthesis::periodic, "periodic"},
    {Synthesis::tiling_and_blending, "tiling_and_blending"},
    {Synthesis::noise_blended, "noise_blended"},
}};

// The flow map F(x) (Lutz §5): the direction the waves travel at x. none: the wind's
// everywhere; uniform: one direction; circular: counter-clockwise (from x towards z) around a
// centre; converging: towards a centre (a bay). Where F is the zero vector (a centre), the wind's.
enum class FlowKind { none, uniform, circular, converging };
inline constexpr std::array<Choice<FlowKind>, 4> kFlowKinds{{
    {FlowKind::none, "none"},
    {FlowKind::uniform, "uniform"},
    {FlowKind::circular, "circular"},
    {FlowKind::converging, "converging"},
}};

struct FlowMap {
  FlowKind kind = FlowKind::none;
  double direction = 0.0;                 // uniform: the direction [rad] from x towards z
  double center_x = 0.0, center_z = 0.0;  // circular and converging [m]
};

// The tiling of a scene (waves.tiling): the tile size in exemplar periods, measured from one
// vertex of the hexagon to the opposite one (Lutz §7, "two initial ocean tile periods": 2).
struct TilingSettings {
  double tile_size = 2.0;
  FlowMap flow;
};

// The tiling resolved for an ocean: the triangular grid's edge a = tile_size·L/2 [m] (the
// hexagon's circumradius), the exemplar's period L [m], the offsets' seed and the wind's angle.
struct Tiling {
  double edge = 0.0;
  double period = 0.0;
  std::uint64_t seed = 0;
  double wind_angle = 0.0;  // atan2(w) [rad]
  FlowMap flow;
};

// The triangle of the grid holding (x, z): the integer coordinates of its vertices in the grid's
// basis e1 = a(1, 0), e2 = a(1/2, √3/2), their barycentric coordinates at the point and the
// gradients of those [1/m] (constant over the triangle). Heitz & Neyret 2018, Lutz §3.2.
struct GridTriangle {
  std::array<std::array<std::int64_t, 2>, 3> vertices{};
  std::array<double, 3> barycentric{};
  std::array<std::array<double, 2>, 3> gradient{};  // ∂b_v/∂x, ∂b_v/∂z
};
GridTriangle grid_triangle(double edge, double x, double z);

// The centre of the tile of a vertex (i, j): i·e1 + j·e2 [m].
std::array<double, 2> tile_centre(double edge, const std::array<std::int64_t, 2>& vertex);

// w_v = b_v/√(Σ b²), so that Σ w_v² = 1 (Lutz eq. 4), and ∇w_v = ∇b_v/r − b_v(Σ_j b_j ∇b_j)/r³
// with r = √(Σ b²).
struct BlendWeights {
  std::array<double, 3> weight{};
  std::array<std::array<double, 2>, 3> gradient{};
};
BlendWeights variance_preserving_weights(const GridTriangle& t);

// h(k): the tile's offset into the exemplar, uniform over one period in each axis (Lutz eq. 5),
// a pure function of the seed and the vertex (waves/random.h): words 0 and 1 of the key
// mix(mix(mix(mix(seed) ^ 0x7469) ^ uint64(i)) ^ uint64(j)) as uniform_open·L.
std::array<double, 2> tile_offset(std::uint64_t seed, const std::array<std::int64_t, 2>& vertex,
                                  double period);

// θ = atan2(F) − atan2(w) at a point (Lutz eq. 7); 0 where the flow is the zero vector.
double flow_angle(const FlowMap& flow, double wind_angle, double x, double z);

// One tile's reading at a point: where in the exemplar (R(−θ)(x + h), Lutz eq. 8 in column
// vectors), the rotation R(θ) its vectors are turned by, and its blending weight with gradient.
struct TileReading {
  double x = 0.0, z = 0.0;                // exemplar position [m]
  double offset_x = 0.0, offset_z = 0.0;  // h(k_v) [m]
  double cos = 1.0, sin = 0.0;            // of θ
  bool rotated = false;                   // θ ≠ 0
  double weight = 0.0;
  double dw_dx = 0.0, dw_dz = 0.0;
};
std::array<TileReading, 3> tile_readings(const Tiling& tiling, double x, double z);
// Where a tile (its offset and turn) reads the exemplar for the point (x, z): R(−θ)(x + h); the
// reading's own x, z for its point (conformance/lean_study.h moves a footprint's points into it).
std::array<double, 2> tile_exemplar_position(const TileReading& reading, double x, double z);

// Adds one tile's raw sums (PointFields::raw and ddz_dx, read at the tile's exemplar position,
// before finish_combination) to the blend (Lutz eq. 6 and 8 with μ = 0, the mean of every field
// of a spectrum without its k = 0 term): the vectors ∇η and D turned by R(θ), the Jacobian of D
// by R(θ)·J·R(θ)ᵀ, then w·f for every field and the weight's gradient terms f·∇w for the
// derivatives of η and D.
void add_tile(PointFields& sum, const PointFields& tile, const TileReading& reading);

// The blend's raw sums at (x, z): add_tile of exemplar(x_v, z_v) (raw sums at an exemplar
// position) for the three tiles.
template <class ExemplarSum>
PointFields blended_sum(const Tiling& tiling, double x, double z, const ExemplarSum& exemplar) {
  PointFields sum;
  for (const TileReading& r : tile_readings(tiling, x, z)) add_tile(sum, exemplar(r.x, r.z), r);
  return sum;
}

// Turns the vector (a, b) by the tile's R(θ) (a no-op when not rotated).
inline void turn_by_tile(const TileReading& r, double& a, double& b) {
  if (!r.rotated) return;
  const double a0 = a;
  a = r.cos * a0 - r.sin * b;
  b = r.sin * a0 + r.cos * b;
}

// √3: the largest Σ_v |w_v| (Σ w_v² = 1 with three weights), and 12/a: a bound of Σ_v |∇w_v|
// (src/FORMULAS.md, "Tiling and blending"); they bound the blended surface for the ray tracer.
inline constexpr double kBlendWeightSumBound = 1.7320508075688772;
double blend_weight_gradient_bound(const Tiling& tiling);

}  // namespace oceanref
