#include "spectrum/quadrature.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "core/fp_environment.h"
#include "core/math.h"

namespace oceanref {

namespace {
// Kronrod 15-point abscissae and weights, Gauss 7-point weights (QUADPACK qk15 table).
constexpr std::array<double, 8> kXgk = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kWgk = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kWg = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Piece {
  double a, b;  // in the integration variable (x, or t for a mapped tail)
  bool mapped;  // x = scale / t
  double scale;
  double value, error;
};

double evaluate(const std::function<double(double)>& f, const Piece& p, double u) {
  if (!p.mapped) return f(u);
  if (u <= 0.0) return 0.0;
  const double x = p.scale / u;
  return f(x) * p.scale / (u * u);
}

void gauss_kronrod(const std::function<double(double)>& f, Piece& p, int& evaluations) {
  const double center = 0.5 * (p.a + p.b);
  const double half = 0.5 * (p.b - p.a);
  const double fc = evaluate(f, p, center);
  double kronrod = fc * kWgk[7];
  double gauss = fc * kWg[3];
  for (std::size_t j = 0; j < 7; ++j) {
    const double dx = half * kXgk[j];
    const double sum = evaluate(f, p, center - dx) + evaluate(f, p, center + dx);
    kronrod += kWgk[j] * sum;
    if (j % 2 == 1) gauss += kWg[j / 2] * sum;
  }
  evaluations += 15;
  p.value = kronrod * half;
  p.error = std::fabs((kronrod - gauss) * half);
  if (!std::isfinite(p.value)) p.error = std::numeric_limits<double>::infinity();
}
}  // namespace

QuadratureResult integrate(const std::function<double(double)>& f,
                           const std::vector<double>& breakpoints,
                           const QuadratureTolerance& tolerance) {
  const ReferenceFpEnvironment fp;
  if (breakpoints.size() < 2) throw std::invalid_argument("integrate: need two breakpoints");
  QuadratureResult result;
  std::vector<Piece> pieces;
  for (std::size_t i = 0; i + 1 < breakpoints.size(); ++i) {
    const double a = breakpoints[i];
    const double b = breakpoints[i + 1];
    if (b < a) throw std::invalid_argument("integrate: breakpoints must be ascending");
    if (!(b > a)) continue;  // repeated breakpoint
    Piece p =
        std::isinf(b) ? Piece{0.0, 1.0, true, a, 0.0, 0.0} : Piece{a, b, false, 1.0, 0.0, 0.0};
    if (p.mapped && !(a > 0.0)) throw std::invalid_argument("integrate: tail needs a > 0");
    gauss_kronrod(f, p, result.evaluations);
    pieces.push_back(p);
  }
  // Sums in the fixed order of the pieces, so the result does not depend on the refinement path.
  const auto sum_pieces = [&] {
    result.value = 0.0;
    result.error = 0.0;
    for (const Piece& p : pieces) {
      result.value += p.value;
      result.error += p.error;
    }
  };
  const auto accepted = [&] {
    return std::isfinite(result.value) && std::isfinite(result.error) &&
           result.error <=
               std::fmax(tolerance.absolute, tolerance.relative * std::fabs(result.value));
  };
  sum_pieces();
  while (!accepted()) {
    if (static_cast<int>(pieces.size()) >= tolerance.max_intervals ||
        !std::isfinite(result.error)) {
      return result;  // not converged
    }
    std::size_t worst = 0;
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      if (pieces[i].error > pieces[worst].error) worst = i;
    }
    Piece left = pieces[worst];
    Piece right = pieces[worst];
    const double mid = 0.5 * (left.a + left.b);
    if (!(mid > left.a && mid < left.b)) return result;  // cannot split: not converged
    left.b = mid;
    right.a = mid;
    gauss_kronrod(f, left, result.evaluations);
    gauss_kronrod(f, right, result.evaluations);
    pieces[worst] = left;
    pieces.insert(pieces.begin() + static_cast<std::ptrdiff_t>(worst) + 1, right);
    sum_pieces();
  }
  result.converged = true;
  return result;
}

QuadratureRule gauss_legendre(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: order must be >= 1");
  QuadratureRule r{std::vector<double>(static_cast<std::size_t>(n)),
                   std::vector<double>(static_cast<std::size_t>(n))};
  const double pi = 3.141592653589793;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = math::cos(pi * (i + 0.75) / (n + 0.5));  // Tricomi's initial guess
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;
      double p1 = 0.0;
      for (int j = 1; j <= n; ++j) {  // (j)P_j = (2j − 1)x P_{j−1} − (j − 1)P_{j−2}
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p2) / j;
      }
      derivative = n * (x * p0 - p1) / (x * x - 1.0);
      const double step = p0 / derivative;
      x -= step;
      if (std::fabs(step) <= 1e-16) break;
    }
    const auto a = static_cast<std::size_t>(i);
    const auto b = static_cast<std::size_t>(n - 1 - i);
    r.nodes[a] = -x;
    r.nodes[b] = x;
    r.weights[a] = r.weights[b] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return r;
}

QuadratureRule gauss_hermite(int n) {
  if (n < 1) throw std::invalid_argument("gauss_hermite: order must be >= 1");
  QuadratureRule r{std::vector<double>(static_cast<std::size_t>(n)),
                   std::vector<double>(static_cast<std::size_t>(n))};
  const double pi_quarter = 0.7511255444649425;  // π^{−1/4}
  double z = 0.0;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Initial guesses for the largest roots first (asymptotic forms).
    if (i == 0) {
      z = std::sqrt(2.0 * n + 1.0) - 1.85575 * math::pow(2.0 * n + 1.0, -0.16667);
    } else if (i == 1) {
      z -= 1.14 * math::pow(n, 0.426) / z;
    } else if (i == 2) {
      z = 1.86 * z - 0.86 * r.nodes[0];
    } else if (i == 3) {
      z = 1.91 * z - 0.91 * r.nodes[1];
    } else {
      z = 2.0 * z - r.nodes[static_cast<std::size_t>(i - 2)];
    }
    double derivative = 1.0;
    for (int iteration = 0; iteration < 200; ++iteration) {
      double p1 = pi_quarter;
      double p2 = 0.0;
      for (int j = 0; j < n; ++j) {  // orthonormal Hermite recurrence
        const double p3 = p2;
        p2 = p1;
        p1 = z * std::sqrt(2.0 / (j + 1.0)) * p2 - std::sqrt(j / (j + 1.0)) * p3;
      }
      derivative = std::sqrt(2.0 * n) * p2;
      const double step = p1 / derivative;
      z -= step;
      if (std::fabs(step) <= 1e-15 * std::fmax(1.0, std::fabs(z))) break;
    }
    const auto a = static_cast<std::size_t>(i);
    const auto b = static_cast<std::size_t>(n - 1 - i);
    r.nodes[a] = z;
    r.nodes[b] = -z;
    r.weights[a] = r.weights[b] = 2.0 / (derivative * derivative);
  }
  return r;
}

}  // namespace oceanref
