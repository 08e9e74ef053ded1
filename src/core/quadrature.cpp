#include "core/quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "core/adaptive_cubature.h"
#include "core/double_double.h"
#include "core/fp_environment.h"
#include "core/math.h"

namespace oceanref {

namespace {
// The QUADPACK qk15 table, shared with the vector integrator.
constexpr const std::array<double, 8>& kXgk = cubature_detail::kKronrodNodes;
constexpr const std::array<double, 8>& kWgk = cubature_detail::kKronrodWeights;
constexpr const std::array<double, 4>& kWg = cubature_detail::kGaussWeights;

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

// ---------------------------------------------------------------------------------------------
// Gauss rules (Golub & Welsch 1969, Math. Comp. 23, 221–230): the nodes are the eigenvalues of
// the symmetric tridiagonal Jacobi matrix of the orthogonal polynomials. The eigenvalues, found
// in double by the implicit QL method, serve as starting values; Newton's method on the
// three-term recurrence, evaluated in double-double arithmetic (core/double_double.h), then
// polishes each node to about 2^-100 and the weight follows from the recurrence at the polished
// node. Both are rounded once to double, so they are correct to about ½ ulp for every order
// 1 … kMaxQuadratureOrder. Only the nonnegative nodes are computed; the others are their
// mirror images, so the rules are exactly symmetric.
namespace {
using math::dd::DD;

// Throws std::invalid_argument unless 1 ≤ order ≤ kMaxQuadratureOrder.
void check_order(const char* rule, int order) {
  if (order >= 1 && order <= kMaxQuadratureOrder) return;
  throw std::invalid_argument(std::string(rule) + ": order " + std::to_string(order) +
                              " outside the supported range [1, " +
                              std::to_string(kMaxQuadratureOrder) + "]");
}

// The eigenvalues, ascending, of the symmetric tridiagonal matrix with zero diagonal and
// off-diagonal b[0 … n−2] (b[n−1] is ignored): the implicit QL method with Wilkinson shifts
// (Bowdler, Martin, Reinsch & Wilkinson 1968, procedure tql1; the form of Press et al.,
// Numerical Recipes §11.3, tqli).
std::vector<double> jacobi_eigenvalues(std::vector<double> b) {
  const std::size_t n = b.size();
  std::vector<double> d(n, 0.0);
  if (n > 0) b[n - 1] = 0.0;
  for (std::size_t l = 0; l < n; ++l) {
    for (int iteration = 0;; ++iteration) {
      std::size_t m = l;
      for (; m + 1 < n; ++m) {  // a negligible off-diagonal element splits the matrix
        const double scale = std::fabs(d[m]) + std::fabs(d[m + 1]);
        if (std::fabs(b[m]) + scale == scale) break;
      }
      if (m == l) break;
      if (iteration == 64) throw std::logic_error("jacobi_eigenvalues: QL did not converge");
      double g = (d[l + 1] - d[l]) / (2.0 * b[l]);  // Wilkinson shift
      double r = math::hypot(g, 1.0);
      g = d[m] - d[l] + b[l] / (g + (g < 0.0 ? -r : r));
      double s = 1.0, c = 1.0, p = 0.0;
      bool underflow = false;
      for (std::size_t i = m; i-- > l;) {  // plane rotations from m − 1 down to l
        const double f = s * b[i];
        const double e = c * b[i];
        r = math::hypot(f, g);
        b[i + 1] = r;
        if (r == 0.0) {  // recover from underflow
          d[i + 1] -= p;
          b[m] = 0.0;
          underflow = true;
          break;
        }
        s = f / r;
        c = g / r;
        g = d[i + 1] - p;
        r = (d[i] - g) * s + 2.0 * c * e;
        p = s * r;
        d[i + 1] = g + p;
        g = c * r - e;
      }
      if (underflow) continue;
      d[l] -= p;
      b[l] = g;
      b[m] = 0.0;
    }
  }
  std::sort(d.begin(), d.end());
  return d;
}

// √a in double-double: one Newton correction of the double square root (Karp & Markstein 1997).
DD dd_sqrt(DD a) {
  if (a.hi == 0.0) return {0.0, 0.0};
  const double s = std::sqrt(a.hi);
  const DD residual = math::dd::add(a, math::dd::neg(math::dd::two_product(s, s)));
  return math::dd::fast_two_sum(s, residual.hi / (2.0 * s));
}

// The recurrence p_{k+1} = a_k x p_k − b_k p_{k−1}, p_0 = 1, p_{−1} = 0, k = 0 … n−1.
struct Recurrence {
  std::vector<DD> a, b;
};

// p_n(x), p_{n−1}(x), p_{n−2}(x), all three multiplied by 2^−exponent.
struct ScaledValues {
  DD p, p1, p2;
  int exponent = 0;
};

// Evaluates the recurrence in double-double. Whenever |p_k| exceeds 2^256 the three values are
// multiplied by 2^−256 (exact) and the exponent is counted, so that the orthonormal Hermite
// polynomials, which grow like e^{x²/2} (up to 2^1500 at the largest node of order 1024), stay
// in range. No value becomes small enough to need the opposite scaling: Legendre polynomials
// stay of order n^{−1/2} … 1 on [−1, 1] and p_k(x) grows with |x| for Hermite.
ScaledValues evaluate(const Recurrence& r, DD x) {
  constexpr double kBig = 0x1p256;
  ScaledValues v{{1.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, 0};
  for (std::size_t k = 0; k < r.a.size(); ++k) {
    v.p2 = v.p1;
    v.p1 = v.p;
    v.p = math::dd::add(math::dd::mul(math::dd::mul(r.a[k], v.p1), x),
                        math::dd::neg(math::dd::mul(r.b[k], v.p2)));
    if (std::fabs(v.p.hi) > kBig) {
      for (DD* q : {&v.p, &v.p1, &v.p2}) *q = {std::ldexp(q->hi, -256), std::ldexp(q->lo, -256)};
      v.exponent += 256;
    }
  }
  return v;
}

// A polished node x = at + step (double-double): the last Newton step, below 2^−55 |x| (the next
// one would be below about 2^−90 |x|), and the values of the recurrence at its origin.
struct Polished {
  DD x, at, step;
  ScaledValues v;
};

// Newton's method x ← x − p_n(x)/p_n'(x) from the starting value x0; derivative(x, v) returns
// p_n'(x) scaled like v. Two steps suffice from a Golub–Welsch eigenvalue (error ≈ 1e−14).
template <class Derivative>
Polished newton(const Recurrence& r, double x0, Derivative derivative) {
  Polished s{{x0, 0.0}, {}, {}, {}};
  for (int iteration = 0; iteration < 8; ++iteration) {
    s.at = s.x;
    s.v = evaluate(r, s.x);
    s.step = math::dd::neg(math::dd::div(s.v.p, derivative(s.x, s.v)));
    s.x = math::dd::add(s.x, s.step);
    if (std::fabs(s.step.hi) <= 0x1p-55 * std::fabs(s.x.hi)) return s;
  }
  throw std::logic_error("gauss rule: Newton's method did not converge");
}

// The starting values: the nonnegative eigenvalues of the Jacobi matrix with off-diagonal
// elements b[0 … n−2], largest first; the middle node of an odd order is exactly 0.
std::vector<double> starting_values(std::vector<double> off_diagonal) {
  const std::size_t n = off_diagonal.size();
  const std::vector<double> eigenvalues = jacobi_eigenvalues(std::move(off_diagonal));
  std::vector<double> x((n + 1) / 2, 0.0);
  for (std::size_t i = 0; i < n / 2; ++i) x[i] = eigenvalues[n - 1 - i];
  return x;
}

// Rounds the weight m·2^e to double: exact scaling when the result is normal; below the normal
// range it becomes subnormal or 0 (not NaN), as any underflowing product does (rounded twice
// there, m then m·2^e: within one unit of 2^−1074).
double scaled_weight(DD m, int e) {
  return std::ldexp(math::dd::to_double(m), e);
}

// Stores the node x ≥ 0 at position n − 1 − i (ascending order) or i (descending order), its
// mirror image −x at the other one and the weight w at both. The middle node of an odd order
// (i = n − 1 − i) is +0.
void store_pair(QuadratureRule& rule, std::size_t i, double x, double w, bool ascending) {
  const std::size_t j = rule.nodes.size() - 1 - i;
  rule.nodes[ascending ? i : j] = -x;
  rule.nodes[ascending ? j : i] = x;
  rule.weights[i] = w;
  rule.weights[j] = w;
}

// The nodes must come out strictly monotonic: a Newton iteration that jumped to a neighbouring
// root would show here.
void check_monotonic(const QuadratureRule& rule, bool ascending) {
  for (std::size_t i = 0; i + 1 < rule.nodes.size(); ++i) {
    const bool ok =
        ascending ? rule.nodes[i] < rule.nodes[i + 1] : rule.nodes[i] > rule.nodes[i + 1];
    if (!ok || !std::isfinite(rule.weights[i])) throw std::logic_error("gauss rule: bad nodes");
  }
}
}  // namespace

// Legendre: P_{k+1} = ((2k+1)/(k+1)) x P_k − (k/(k+1)) P_{k−1}; Jacobi matrix off-diagonal
// k/√(4k² − 1). With (1 − x²)P_n' = n(P_{n−1} − x P_n), the weight 2/((1 − x²)P_n'(x_i)²) is
// 2(1 − x_i²)/(n P_{n−1}(x_i))² (Abramowitz & Stegun 25.4.29), where 1 − x_i² = (1 − x_i)(1 + x_i)
// is evaluated in double-double from the polished node: no cancellation near ±1.
QuadratureRule gauss_legendre(int n) {
  check_order("gauss_legendre", n);
  const ReferenceFpEnvironment fp;
  const auto size = static_cast<std::size_t>(n);
  Recurrence r{std::vector<DD>(size), std::vector<DD>(size)};
  std::vector<double> off_diagonal(size, 0.0);
  for (std::size_t k = 0; k < size; ++k) {
    const double kd = static_cast<double>(k);
    r.a[k] = math::dd::div({2.0 * kd + 1.0, 0.0}, {kd + 1.0, 0.0});
    r.b[k] = math::dd::div({kd, 0.0}, {kd + 1.0, 0.0});
    off_diagonal[k] = (kd + 1.0) / std::sqrt(4.0 * (kd + 1.0) * (kd + 1.0) - 1.0);
  }
  const double nd = static_cast<double>(n);
  // (1 − x²) as a double-double.
  const auto one_minus_square = [](DD x) {
    return math::dd::mul(math::dd::add(math::dd::neg(x), 1.0), math::dd::add(x, 1.0));
  };
  // P_n'(x) = n (P_{n−1} − x P_n)/(1 − x²).
  const auto derivative = [&](DD x, const ScaledValues& v) {
    const DD t = math::dd::add(v.p1, math::dd::neg(math::dd::mul(x, v.p)));
    return math::dd::div(math::dd::mul(t, nd), one_minus_square(x));
  };
  const std::vector<double> x0 = starting_values(std::move(off_diagonal));
  QuadratureRule rule{std::vector<double>(size), std::vector<double>(size)};
  for (std::size_t i = 0; i < x0.size(); ++i) {
    const Polished s = newton(r, x0[i], derivative);
    // P_{n−1} at the polished node, to first order in the last step: P_{n−1}' from the same
    // identity at order n − 1.
    const DD t = math::dd::add(s.v.p2, math::dd::neg(math::dd::mul(s.at, s.v.p1)));
    const DD slope = math::dd::div(math::dd::mul(t, nd - 1.0), one_minus_square(s.at));
    const DD p1 = math::dd::add(s.v.p1, math::dd::mul(slope, s.step));
    const DD np1 = math::dd::mul(p1, nd);
    const DD w = math::dd::div(math::dd::mul(one_minus_square(s.x), 2.0), math::dd::mul(np1, np1));
    store_pair(rule, i, math::dd::to_double(s.x), math::dd::to_double(w), true);
  }
  check_monotonic(rule, true);
  return rule;
}

// Hermite: the orthonormal polynomials H̃_k = p_k/π^{1/4}, p_{k+1} = √(2/(k+1)) x p_k −
// √(k/(k+1)) p_{k−1}, p_0 = 1; Jacobi matrix off-diagonal √(k/2); H̃_n' = √(2n) H̃_{n−1}. The
// weight is 2/H̃_n'(x_i)² = √π/(n p_{n−1}(x_i)²) (Golub & Welsch 1969, eq. 2.11 with the
// Christoffel–Darboux formula). p_{n−1} is carried as a mantissa and a power of two, so the
// weights of the outer nodes (≈ e^{−x²}: below 2^−1022 from order 371, below 2^−1075 from order
// 389) underflow to subnormals and 0 instead of overflowing.
QuadratureRule gauss_hermite(int n) {
  check_order("gauss_hermite", n);
  const ReferenceFpEnvironment fp;
  const auto size = static_cast<std::size_t>(n);
  Recurrence r{std::vector<DD>(size), std::vector<DD>(size)};
  std::vector<double> off_diagonal(size, 0.0);
  for (std::size_t k = 0; k < size; ++k) {
    const double kd = static_cast<double>(k);
    r.a[k] = dd_sqrt(math::dd::div({2.0, 0.0}, {kd + 1.0, 0.0}));
    r.b[k] = dd_sqrt(math::dd::div({kd, 0.0}, {kd + 1.0, 0.0}));
    off_diagonal[k] = std::sqrt(0.5 * (kd + 1.0));
  }
  const double nd = static_cast<double>(n);
  const DD sqrt_2n = dd_sqrt({2.0 * nd, 0.0});
  const DD sqrt_2n_2 = dd_sqrt({2.0 * nd - 2.0, 0.0});
  constexpr DD kSqrtPi = {0x1.c5bf891b4ef6bp+0, -0x1.618f13eb7ca89p-54};  // √π
  const auto derivative = [&](DD, const ScaledValues& v) { return math::dd::mul(sqrt_2n, v.p1); };
  const std::vector<double> x0 = starting_values(std::move(off_diagonal));
  QuadratureRule rule{std::vector<double>(size), std::vector<double>(size)};
  for (std::size_t i = 0; i < x0.size(); ++i) {
    const Polished s = newton(r, x0[i], derivative);
    // p_{n−1} at the polished node, to first order in the last step (p_{n−1}' = √(2n−2) p_{n−2}).
    const DD p1 = math::dd::add(s.v.p1, math::dd::mul(math::dd::mul(sqrt_2n_2, s.v.p2), s.step));
    const DD m = math::dd::div(kSqrtPi, math::dd::mul(math::dd::mul(p1, p1), nd));
    store_pair(rule, i, math::dd::to_double(s.x), scaled_weight(m, -2 * s.v.exponent), false);
  }
  check_monotonic(rule, false);
  return rule;
}

}  // namespace oceanref
