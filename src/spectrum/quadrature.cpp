#include "spectrum/quadrature.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

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

}  // namespace oceanref
