// Grid interpolation (waves/interpolation.h) against exact polynomials and measured convergence
// orders.
//
// What the schemes promise, per axis, for x = (m + t)Δ inside a cell:
//   * bilinear: weights (1 − t, t): reproduces polynomials of degree ≤ 1 in each axis (1, x, z,
//     xz) exactly; for smooth fields the value error is O(Δ²) and the gradient error O(Δ).
//   * Catmull–Rom: Σw_j = 1, Σw_j·j = t, Σw_j·j² = t², but Σw_j·j³ = t − 3t² + 3t³: it
//     reproduces degree ≤ 2 in each axis (the 9 monomials x^a z^b, a, b ≤ 2, and every
//     combination) exactly, value and gradient, and its error for x³ is exactly
//     Δ³·t(1 − t)(1 − 2t) (derivative Δ²·(1 − 6t + 6t²)). For smooth fields: value O(Δ³),
//     gradient O(Δ²).
// A polynomial is not periodic, so the exact checks use points whose 4 × 4 stencil does not wrap
// except where the grid holds the polynomial of the signed index across the seam.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

#include "test_support.h"
#include "waves/interpolation.h"
#include "waves/realization.h"

using namespace oceanref;

namespace {
using testing::kPi;

struct Poly {  // Σ c_ab x^a z^b, a, b ≤ 3
  double c[4][4] = {};
  double operator()(double x, double z) const {
    double s = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) s += c[a][b] * std::pow(x, a) * std::pow(z, b);
    }
    return s;
  }
  double dx(double x, double z) const {
    double s = 0.0;
    for (int a = 1; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) s += a * c[a][b] * std::pow(x, a - 1) * std::pow(z, b);
    }
    return s;
  }
  double dz(double x, double z) const {
    double s = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int b = 1; b < 4; ++b) s += b * c[a][b] * std::pow(x, a) * std::pow(z, b - 1);
    }
    return s;
  }
};

// The grid of f at the nodes (m, n)·Δ: f(x_m, z_n) with x_m = signed(m)·Δ when `signed_index`
// (the node index α ∈ [−N/2, N/2), so the values are continuous across the seam at 0), else
// m·Δ.
template <class F>
std::vector<double> sample_grid(const F& f, int n, double size, bool signed_index) {
  std::vector<double> g(grid_cells(n));
  const double spacing = size / n;
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < n; ++a) {
      const int i = signed_index ? wave_index(a, n) : a;
      const int j = signed_index ? wave_index(b, n) : b;
      g[grid_offset(a, b, n)] = f(i * spacing, j * spacing);
    }
  }
  return g;
}

// Deterministic pseudo-random fractions in (0, 1), away from the nodes.
double fraction(int i) {
  return 0.03 + 0.94 * std::fmod(0.6180339887498949 * (i + 1), 1.0);
}
}  // namespace

TEST_CASE("bicubic: every polynomial of degree <= 2 per axis is reproduced, value and gradient") {
  // 9 monomials with coefficients of both signs; points with cells 1 … N − 3 so the stencil
  // (m − 1 … m + 2) stays inside. Tolerance: 1e-12 of the field's magnitude — 16 products of
  // weights (|w| ≤ 1.2) with values, plus the position's rounding through the fmod (t exact to
  // ~N·ε), is < 1e-13 relative.
  const int n = 16;
  const double size = 40.0;
  const double spacing = size / n;
  Poly p;
  const double coefficients[3][3] = {{0.7, -1.3, 0.25}, {2.1, 0.4, -0.11}, {-0.6, 0.09, 0.017}};
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) p.c[a][b] = coefficients[a][b];
  }
  const std::vector<double> g = sample_grid(p, n, size, false);
  double scale = 0.0;
  for (const double v : g) scale = std::fmax(scale, std::fabs(v));
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const double x = (1 + (i % (n - 3))) * spacing + fraction(i) * spacing;
    const double z = (1 + ((7 * i) % (n - 3))) * spacing + fraction(i + 1000) * spacing;
    CAPTURE(x);
    CAPTURE(z);
    const GridSample s = sample_periodic_gradient(g, n, size, x, z, Interpolation::bicubic);
    CHECK(std::fabs(s.value - p(x, z)) <= 1e-12 * scale);
    CHECK(std::fabs(s.d_dx - p.dx(x, z)) <= 1e-12 * scale / spacing);
    CHECK(std::fabs(s.d_dz - p.dz(x, z)) <= 1e-12 * scale / spacing);
    // The value-only form is the same function, bit for bit (header promise).
    CHECK(sample_periodic_bicubic(g, n, size, x, z) == s.value);
    ++checked;
  }
  CHECK(checked == 200);
}

TEST_CASE("bicubic across the periodic seam: the signed-index quadratic, and x + L reads x") {
  // The grid holds q(α·Δ) with α the signed node index, continuous across the seam; points in
  // the cells −1 and 0 (stencils wrapping to N − 2, N − 1) read q exactly, and a point shifted
  // by ±L reads the same value (the stencil and fractions are the same up to the rounding of
  // x ± L, ~ε·L in position: 1e-12 relative to the field).
  const int n = 32;
  const double size = 10.0;
  const double spacing = size / n;
  const auto q = [](double x, double z) { return 1.0 - 0.8 * x + 0.35 * x * x + 0.5 * z * z * x; };
  const std::vector<double> g = sample_grid(q, n, size, true);
  for (int i = 0; i < 50; ++i) {
    const double x = (fraction(i) - (i % 2)) * spacing;  // cells 0 and −1
    const double z = (fraction(i + 77) - ((i / 2) % 2)) * spacing;
    CAPTURE(x);
    CAPTURE(z);
    const double v = sample_periodic_bicubic(g, n, size, x, z);
    CHECK(v == doctest::Approx(q(x, z)).epsilon(1e-12));
    CHECK(sample_periodic_bicubic(g, n, size, x + size, z - size) ==
          doctest::Approx(v).epsilon(1e-12));
    CHECK(sample_periodic_bicubic(g, n, size, x - 3 * size, z + 2 * size) ==
          doctest::Approx(v).epsilon(1e-12));
  }
}

TEST_CASE(
    "bicubic: the error for x^3 is exactly h^3 t(1 - t)(1 - 2t), its slope h^2(1 - 6t + 6t^2)") {
  // Catmull–Rom is not cubic-precise: the leading error term is known in closed form. The
  // interpolant of x³ minus x³ at x = (m + t)Δ is Δ³·t(1 − t)(1 − 2t), the same in every cell;
  // z³ likewise. Tolerances 1e-10 (value) and 1e-9 (slope) absolute: the values reach 7·10²
  // and the difference cancels them, leaving rounding of ~1e-12; the errors checked are
  // ~1e-2 … 0.4.
  const int n = 16;
  const double size = 10.0;
  const double h = size / n;
  const auto cube_x = [](double x, double) { return x * x * x; };
  const auto cube_z = [](double, double z) { return z * z * z; };
  const std::vector<double> gx = sample_grid(cube_x, n, size, false);
  const std::vector<double> gz = sample_grid(cube_z, n, size, false);
  for (int m = 1; m <= n - 3; ++m) {
    for (const double t : {0.1, 0.25, 0.5, 0.8}) {
      CAPTURE(m);
      CAPTURE(t);
      const double x = (m + t) * h;
      const double z = (n - 2 - m + 0.37) * h;
      const double value_error = h * h * h * t * (1 - t) * (1 - 2 * t);
      const double slope_error = h * h * (1 - 6 * t + 6 * t * t);
      const GridSample sx = sample_periodic_gradient(gx, n, size, x, z, Interpolation::bicubic);
      CHECK(std::fabs(sx.value - x * x * x - value_error) < 1e-10);
      CHECK(std::fabs(sx.d_dx - 3 * x * x - slope_error) < 1e-9);
      CHECK(std::fabs(sx.d_dz) < 1e-9);
      const GridSample sz = sample_periodic_gradient(gz, n, size, z, x, Interpolation::bicubic);
      CHECK(std::fabs(sz.value - x * x * x - value_error) < 1e-10);
      CHECK(std::fabs(sz.d_dz - 3 * x * x - slope_error) < 1e-9);
    }
  }
}

TEST_CASE("a point within rounding of a node reads the node's value exactly, in every mode") {
  // x = m·Δ + L (a period on) in floating point lands an ulp or so either side of the node
  // (Δ = 7.3/32 is not a binary fraction); a point within 1e−9 cell of a node is that node, so
  // every interpolation returns the stored value bit for bit, and bilinear's gradient is that of
  // the cell the node starts (not of the cell before it).
  const int n = 32;
  const double size = 7.3;
  const double spacing = size / n;
  const auto f = [](double x, double z) { return std::sin(1.3 * x + 0.2) * std::cos(0.7 * z) + x; };
  const std::vector<double> g = sample_grid(f, n, size, false);
  int off_node = 0;  // points whose scaled position is not an integer before the snap
  for (int m = 1; m < n; m += 3) {
    for (const int k : {2, 17, 30}) {
      CAPTURE(m);
      CAPTURE(k);
      const double x = m * spacing + size, z = k * spacing - 2.0 * size;
      const double stored = g[grid_offset(m, k, n)];
      off_node += std::fmod(x, size) / spacing != m ? 1 : 0;
      off_node += std::fmod(z, size) / spacing + n != k ? 1 : 0;
      CHECK(sample_periodic(g, n, size, x, z) == stored);
      CHECK(sample_periodic_bicubic(g, n, size, x, z) == stored);
      const GridSample linear = sample_periodic_gradient(g, n, size, x, z, Interpolation::bilinear);
      CHECK(linear.value == stored);
      // The cell (m, k): its x slope at the node row z_k is the forward difference.
      CHECK(linear.d_dx ==
            doctest::Approx((g[grid_offset((m + 1) % n, k, n)] - stored) / spacing).epsilon(1e-9));
      CHECK(sample_periodic_gradient(g, n, size, x, z, Interpolation::bicubic).value == stored);
    }
  }
  CHECK(off_node > 0);  // the rounding the snap exists for occurs among these points

  // The node's own value, not a sum in which its neighbours carry weight 0: a node holding −0
  // reads −0 (a sum adds +0 and loses the sign), and a NaN at the neighbouring nodes does not
  // reach it (0 · NaN is NaN).
  std::vector<double> h = g;
  const int m = 9, k = 17;
  h[grid_offset(m, k, n)] = -0.0;
  for (const auto& [i, j] : {std::pair{m + 1, k}, {m - 1, k}, {m, k + 1}, {m + 2, k + 2}}) {
    h[grid_offset(i, j, n)] = std::numeric_limits<double>::quiet_NaN();
  }
  const double x = m * spacing, z = k * spacing;
  for (const double v :
       {sample_periodic(h, n, size, x, z), sample_periodic_bicubic(h, n, size, x, z),
        sample_periodic_gradient(h, n, size, x, z, Interpolation::bilinear).value,
        sample_periodic_gradient(h, n, size, x, z, Interpolation::bicubic).value}) {
    CHECK(v == 0.0);
    CHECK(std::signbit(v));
  }
}

TEST_CASE("bilinear: 1, x, z and xz reproduced exactly; x^2 is not (error h^2 t(1 - t))") {
  const int n = 16;
  const double size = 8.0;
  const double h = size / n;
  const auto bilinear = [](double x, double z) { return 0.3 - 1.7 * x + 0.6 * z + 0.45 * x * z; };
  const auto square = [](double x, double) { return x * x; };
  const std::vector<double> g = sample_grid(bilinear, n, size, false);
  const std::vector<double> gs = sample_grid(square, n, size, false);
  for (int i = 0; i < 100; ++i) {
    const double t = fraction(i);
    const double x = (i % (n - 1) + t) * h;
    const double z = ((3 * i) % (n - 1) + fraction(i + 300)) * h;
    CAPTURE(x);
    CAPTURE(z);
    const GridSample s = sample_periodic_gradient(g, n, size, x, z, Interpolation::bilinear);
    // Values up to ~60: 1e-12 relative to that.
    CHECK(std::fabs(s.value - bilinear(x, z)) <= 1e-12 * 60.0);
    CHECK(std::fabs(s.d_dx - (-1.7 + 0.45 * z)) <= 1e-12 * 60.0 / h);
    CHECK(std::fabs(s.d_dz - (0.6 + 0.45 * x)) <= 1e-12 * 60.0 / h);
    CHECK(sample_periodic(g, n, size, x, z) == s.value);
    // Linear interpolation of x² overestimates by exactly h²·t(1 − t) (the chord above the arc).
    CHECK(std::fabs(sample_periodic(gs, n, size, x, z) - x * x - h * h * t * (1 - t)) < 1e-12);
  }
}

namespace {
// A smooth periodic field of period L (three modes, the largest |θ| = 2π·√5/N per node spacing:
// resolved at every N below) and its gradient.
struct Smooth {
  double size;
  double w() const { return 2 * kPi / size; }
  double operator()(double x, double z) const {
    return std::sin(w() * (x + 0.3)) * std::cos(w() * (z - 1.1)) +
           0.4 * std::cos(w() * (2 * x - z)) + 0.2 * std::sin(w() * (x + 2 * z) + 0.7);
  }
  double dx(double x, double z) const {
    return w() * (std::cos(w() * (x + 0.3)) * std::cos(w() * (z - 1.1)) -
                  0.8 * std::sin(w() * (2 * x - z)) + 0.2 * std::cos(w() * (x + 2 * z) + 0.7));
  }
  double dz(double x, double z) const {
    return w() * (-std::sin(w() * (x + 0.3)) * std::sin(w() * (z - 1.1)) +
                  0.4 * std::sin(w() * (2 * x - z)) + 0.4 * std::cos(w() * (x + 2 * z) + 0.7));
  }
};

struct Errors {
  double value = 0.0, gradient = 0.0;  // root mean square over the points
};
// Errors over 500 fixed points (the same world points at every N, so the mean over them
// averages the error over positions within cells alike at every N; a maximum over points would
// depend on where the points happen to fall in their cells: ±0.3 in the measured order).
Errors rms_errors(const Smooth& f, int n, Interpolation mode) {
  const std::vector<double> g = sample_grid(f, n, f.size, false);
  Errors e;
  for (int i = 0; i < 500; ++i) {
    const double x = fraction(i) * f.size;
    const double z = fraction(i + 5000) * f.size;
    const GridSample s = sample_periodic_gradient(g, n, f.size, x, z, mode);
    e.value += (s.value - f(x, z)) * (s.value - f(x, z));
    e.gradient += (s.d_dx - f.dx(x, z)) * (s.d_dx - f.dx(x, z)) +
                  (s.d_dz - f.dz(x, z)) * (s.d_dz - f.dz(x, z));
  }
  e.value = std::sqrt(e.value / 500.0);
  e.gradient = std::sqrt(e.gradient / 500.0);
  return e;
}
}  // namespace

TEST_CASE("convergence orders on a smooth periodic field: bicubic h^3 / h^2, bilinear h^2 / h") {
  // Measured order p = log2(e(N)/e(2N)) of the RMS value and gradient errors, N = 16 … 256.
  // The asymptotic orders are 3 and 2 (Catmull–Rom) and 2 and 1 (bilinear); the measured ones
  // on the two finest pairs must be within ±0.2 of them (the next term of the error expansion
  // is one order higher, i.e. a relative change of ~1/N ≤ 6 % per halving, ±0.1 in p; the rest
  // is the max over a finite point set).
  const Smooth f{25.0};
  for (const auto& [mode, value_order, gradient_order] :
       {std::tuple{Interpolation::bicubic, 3.0, 2.0},
        std::tuple{Interpolation::bilinear, 2.0, 1.0}}) {
    const int mode_number = static_cast<int>(mode);  // (clang 15 cannot capture a binding)
    CAPTURE(mode_number);
    std::vector<Errors> e;
    for (const int n : {16, 32, 64, 128, 256}) e.push_back(rms_errors(f, n, mode));
    for (std::size_t i = 2; i + 1 < e.size(); ++i) {
      CAPTURE(i);
      const double p_value = std::log2(e[i].value / e[i + 1].value);
      const double p_gradient = std::log2(e[i].gradient / e[i + 1].gradient);
      CHECK(std::fabs(p_value - value_order) < 0.2);
      CHECK(std::fabs(p_gradient - gradient_order) < 0.2);
    }
    // And the bicubic reading is far better than the bilinear one at the same N.
    if (mode == Interpolation::bicubic)
      CHECK(e[2].value < 0.1 * rms_errors(f, 64, Interpolation::bilinear).value);
  }
}

TEST_CASE("variance transfer factors V, W, c equal the averages of the interpolated mode") {
  // interpolation.h: a grid mode e^{iθm} read by the interpolant is a(t) (t ∈ [0, 1) in a cell);
  // V = ⟨|a|²⟩, W = ⟨|da/dt|²⟩, c = ⟨(da/dt)·a*⟩/i. Here a(t) is read from a real grid pair
  // (cos θm, sin θm) by the library's own interpolation and averaged over t by 8-point
  // Gauss–Legendre, exact for these degree ≤ 6 polynomials in t: agreement to 1e-13.
  const int n = 32;
  const double size = static_cast<double>(n);  // Δ = 1
  const double gl_nodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                              0.9602898564975363};
  const double gl_weights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                0.1012285362903763};
  for (const Interpolation mode : {Interpolation::bilinear, Interpolation::bicubic}) {
    for (const int alpha : {1, 3, 7, 12, 16}) {
      CAPTURE(static_cast<int>(mode));
      CAPTURE(alpha);
      const double theta = 2 * kPi * alpha / n;
      const auto re = [&](double x, double) { return std::cos(theta * x); };
      const auto im = [&](double x, double) { return std::sin(theta * x); };
      const std::vector<double> gr = sample_grid(re, n, size, false);
      const std::vector<double> gi = sample_grid(im, n, size, false);
      double v = 0.0, w = 0.0, c = 0.0;
      for (int k = 0; k < 8; ++k) {
        const double t = 0.5 + (k < 4 ? -0.5 : 0.5) * gl_nodes[k % 4];
        const double weight = 0.5 * gl_weights[k % 4];
        const double x = 5.0 + t;  // cell 5, z on a node row
        const GridSample a = sample_periodic_gradient(gr, n, size, x, 9.0, mode);
        const GridSample b = sample_periodic_gradient(gi, n, size, x, 9.0, mode);
        v += weight * (a.value * a.value + b.value * b.value);
        w += weight * (a.d_dx * a.d_dx + b.d_dx * b.d_dx);
        // (a' + ib')(a − ib)/i = (a'b − ab')·… : Im((a' + ib')(a − ib)) = b'a − a'b.
        c += weight * (b.d_dx * a.value - a.d_dx * b.value);
      }
      const AxisTransfer expected = axis_transfer(alpha == 16 ? -16 : alpha, n, mode);
      CHECK(std::fabs(v - expected.value) < 1e-13 * (1.0 + std::fabs(expected.value)));
      CHECK(std::fabs(w - expected.derivative) < 1e-13 * (1.0 + std::fabs(expected.derivative)));
      CHECK(std::fabs(c - expected.cross) < 1e-13 * (1.0 + std::fabs(expected.cross)));
    }
  }
}
