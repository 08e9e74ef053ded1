#include "waves/tiling.h"

#include <cmath>

#include "core/math.h"
#include "waves/random.h"

namespace oceanref {

namespace {
constexpr double kSqrt3 = 1.7320508075688772;
// The tag that keeps the tiles' offsets apart from the wave components' draws ("ti").
constexpr std::uint64_t kTileOffsetTag = 0x7469;
}  // namespace

// Heitz & Neyret 2018 (Lutz §3.2): x = s·e1 + t·e2 with e1 = a(1, 0), e2 = a(1/2, √3/2); the
// unit rhombus at floor(s, t) splits into two triangles along s + t = 1.
GridTriangle grid_triangle(double edge, double x, double z) {
  const double t = z * (2.0 / kSqrt3) / edge;
  const double s = x / edge - 0.5 * t;
  const double i = std::floor(s), j = std::floor(t);
  const double fs = s - i, ft = t - j;
  const auto vi = static_cast<std::int64_t>(i);
  const auto vj = static_cast<std::int64_t>(j);
  // ∇s = (1/a, −1/(√3 a)), ∇t = (0, 2/(√3 a)).
  const std::array<double, 2> ds{1.0 / edge, -1.0 / (kSqrt3 * edge)};
  const std::array<double, 2> dt{0.0, 2.0 / (kSqrt3 * edge)};
  const auto minus = [](const std::array<double, 2>& v) { return std::array{-v[0], -v[1]}; };
  const std::array<double, 2> ds_dt{ds[0] + dt[0], ds[1] + dt[1]};
  GridTriangle out;
  if (fs + ft < 1.0) {
    out.vertices = {{{vi, vj}, {vi + 1, vj}, {vi, vj + 1}}};
    out.barycentric = {1.0 - fs - ft, fs, ft};
    out.gradient = {minus(ds_dt), ds, dt};
  } else {
    out.vertices = {{{vi + 1, vj + 1}, {vi, vj + 1}, {vi + 1, vj}}};
    out.barycentric = {fs + ft - 1.0, 1.0 - fs, 1.0 - ft};
    out.gradient = {ds_dt, minus(ds), minus(dt)};
  }
  return out;
}

std::array<double, 2> tile_centre(double edge, const std::array<std::int64_t, 2>& vertex) {
  const auto i = static_cast<double>(vertex[0]);
  const auto j = static_cast<double>(vertex[1]);
  return {edge * (i + 0.5 * j), edge * (0.5 * kSqrt3 * j)};
}

// Lutz eq. 4: Σ w² = 1.
BlendWeights variance_preserving_weights(const GridTriangle& t) {
  const std::array<double, 3>& b = t.barycentric;
  const double r = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  std::array<double, 2> dr{};  // Σ_j b_j ∇b_j (= r∇r)
  for (std::size_t v = 0; v < 3; ++v) {
    for (std::size_t c = 0; c < 2; ++c) dr[c] += b[v] * t.gradient[v][c];
  }
  BlendWeights w;
  for (std::size_t v = 0; v < 3; ++v) {
    w.weight[v] = b[v] / r;
    for (std::size_t c = 0; c < 2; ++c) {
      w.gradient[v][c] = t.gradient[v][c] / r - b[v] * dr[c] / (r * r * r);
    }
  }
  return w;
}

// Lutz eq. 5: h(k_v), uniform over [0, L)².
std::array<double, 2> tile_offset(std::uint64_t seed, const std::array<std::int64_t, 2>& vertex,
                                  double period) {
  const std::uint64_t key =
      mix64(mix64(mix64(mix64(seed) ^ kTileOffsetTag) ^ static_cast<std::uint64_t>(vertex[0])) ^
            static_cast<std::uint64_t>(vertex[1]));
  return {uniform_open(random_word(key, 0)) * period, uniform_open(random_word(key, 1)) * period};
}

// Lutz eq. 7: θ = atan2(F) − atan2(w).
double flow_angle(const FlowMap& flow, double wind_angle, double x, double z) {
  double fx = 0.0, fz = 0.0;  // F(x), not normalized (atan2 needs only its direction)
  switch (flow.kind) {
    case FlowKind::none:
      return 0.0;
    case FlowKind::uniform:
      return flow.direction - wind_angle;
    case FlowKind::circular:  // (x, z) − c turned by +90°
      fx = -(z - flow.center_z);
      fz = x - flow.center_x;
      break;
    case FlowKind::converging:
      fx = flow.center_x - x;
      fz = flow.center_z - z;
      break;
  }
  if (fx == 0.0 && fz == 0.0) return 0.0;
  return math::atan2(fz, fx) - wind_angle;
}

// R(−θ)(x + h) (Lutz eq. 8, whose row vectors times R(θ) are R(θ)ᵀ = R(−θ) on columns).
std::array<double, 2> tile_exemplar_position(const TileReading& r, double x, double z) {
  const double px = x + r.offset_x, pz = z + r.offset_z;
  if (!r.rotated) return {px, pz};
  return {r.cos * px + r.sin * pz, -r.sin * px + r.cos * pz};
}

std::array<TileReading, 3> tile_readings(const Tiling& tiling, double x, double z) {
  const GridTriangle triangle = grid_triangle(tiling.edge, x, z);
  const BlendWeights w = variance_preserving_weights(triangle);
  std::array<TileReading, 3> out;
  for (std::size_t v = 0; v < 3; ++v) {
    TileReading& r = out[v];
    const std::array<double, 2> h = tile_offset(tiling.seed, triangle.vertices[v], tiling.period);
    r.offset_x = h[0];
    r.offset_z = h[1];
    if (tiling.flow.kind != FlowKind::none) {
      const std::array<double, 2> c = tile_centre(tiling.edge, triangle.vertices[v]);
      const double theta = flow_angle(tiling.flow, tiling.wind_angle, c[0], c[1]);
      if (theta != 0.0) {
        r.rotated = true;
        r.cos = math::cos(theta);
        r.sin = math::sin(theta);
      }
    }
    const std::array<double, 2> e = tile_exemplar_position(r, x, z);
    r.x = e[0];
    r.z = e[1];
    r.weight = w.weight[v];
    r.dw_dx = w.gradient[v][0];
    r.dw_dz = w.gradient[v][1];
  }
  return out;
}

// Lutz eq. 8 (rotation) and eq. 6 (blend), differentiated.
void add_tile(PointFields& sum, const PointFields& tile, const TileReading& r) {
  const auto at = [](Field f) { return static_cast<std::size_t>(f); };
  const auto& in = tile.raw;
  double eta_x = in[at(Field::slope_x)], eta_z = in[at(Field::slope_z)];
  double dx = in[at(Field::displacement_x)], dz = in[at(Field::displacement_z)];
  double j_xx = in[at(Field::ddx_dx)], j_xz = in[at(Field::ddx_dz)];
  double j_zx = tile.ddz_dx, j_zz = in[at(Field::ddz_dz)];
  turn_by_tile(r, eta_x, eta_z);
  turn_by_tile(r, dx, dz);
  if (r.rotated) {
    const double c = r.cos, s = r.sin;
    // R·J, then (R·J)·Rᵀ.
    const double rxx = c * j_xx - s * j_zx, rxz = c * j_xz - s * j_zz;
    const double rzx = s * j_xx + c * j_zx, rzz = s * j_xz + c * j_zz;
    j_xx = rxx * c - rxz * s;
    j_xz = rxx * s + rxz * c;
    j_zx = rzx * c - rzz * s;
    j_zz = rzx * s + rzz * c;
  }
  const double w = r.weight, wx = r.dw_dx, wz = r.dw_dz;
  const double eta = in[at(Field::height)];
  auto& out = sum.raw;
  out[at(Field::height)] += w * eta;
  out[at(Field::slope_x)] += w * eta_x + eta * wx;
  out[at(Field::slope_z)] += w * eta_z + eta * wz;
  out[at(Field::displacement_x)] += w * dx;
  out[at(Field::displacement_z)] += w * dz;
  out[at(Field::ddx_dx)] += w * j_xx + dx * wx;
  out[at(Field::ddx_dz)] += w * j_xz + dx * wz;
  sum.ddz_dx += w * j_zx + dz * wx;
  out[at(Field::ddz_dz)] += w * j_zz + dz * wz;
}

// Σ_v |∇w_v| ≤ Σ_v (|∇b_v|/r + b_v|Σ_j b_j∇b_j|/r³) ≤ 3/(hr) + 1/(hr³) with |∇b_v| = 1/h (h the
// triangle's altitude √3a/2), Σ b = 1 and r ≥ 1/√3: 6√3/h = 12/a.
double blend_weight_gradient_bound(const Tiling& tiling) {
  return 12.0 / tiling.edge;
}

}  // namespace oceanref
