// Adaptive Gauss–Kronrod (G7/K15) quadrature of vector-valued integrands whose values may carry
// their own error estimates: the building block of the reference lighting integrals, which are
// iterated integrals (an outer adaptive rule whose integrand is an inner adaptive integral).
//
// Error accounting: the estimate of a result is the sum over the final intervals of QUADPACK's
// rescaled |K15 − G7| (rescaled_error below) plus the K15-weighted integral of the integrand's
// own errors (the inner integrals' estimates carried into the outer one). Like every such
// estimate it assumes that each interval's integrand is smooth: callers put breakpoints at the
// integrand's kinks, cusps and steep turns (reference_lighting.cpp). A result is converged
// when, for every channel c,
//   error[c] ≤ max(absolute[c], relative·|value[c]|).
// Deterministic: the interval with the largest rule error relative to its channel budgets is
// split first (ties: the leftmost), and sums run in the fixed order of the intervals.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <span>
#include <vector>

#include "core/quadrature.h"

namespace oceanref {

template <std::size_t N>
struct Estimate {
  std::array<double, N> value{};
  std::array<double, N> error{};  // estimated absolute error, ≥ 0
  long evaluations = 0;           // innermost integrand evaluations
  bool converged = true;
};

template <std::size_t N>
struct CubatureTolerance {
  double relative = 1e-6;
  std::array<double, N> absolute{};  // per channel, ≥ 0
  int max_intervals = 200;           // per adaptive integral
};

namespace cubature_detail {
// Kronrod 15-point abscissae on [0, 1] (descending, last 0) and weights, Gauss 7-point weights
// (QUADPACK qk15; Piessens et al. 1983).
inline constexpr std::array<double, 8> kKronrodNodes = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
inline constexpr std::array<double, 8> kKronrodWeights = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr std::array<double, 4> kGaussWeights = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

template <std::size_t N>
struct Interval {
  double a = 0.0, b = 0.0;
  std::array<double, N> value{};
  std::array<double, N> rule_error{};     // |K15 − G7|
  std::array<double, N> carried_error{};  // ∫ (integrand's own error), K15-weighted
};

// QUADPACK's error estimate of the K15 result (Piessens et al. 1983, qk15): |K15 − G7| is the
// error of G7, far larger than K15's own; it is rescaled by (200|K15 − G7|/σ)^{3/2} relative to
// the integrand's deviation σ = ∫|f − mean|, an empirical law that holds for smooth integrands
// (checked in the tests by tightening the tolerance and comparing with brute force), with a
// floor of 50 ulps of ∫|f| for rounding.
inline double rescaled_error(double kronrod_minus_gauss, double deviation, double magnitude) {
  double e = kronrod_minus_gauss;
  if (kronrod_minus_gauss > 0.0 && deviation > 0.0) {
    const double ratio = 200.0 * kronrod_minus_gauss / deviation;
    e = ratio < 1.0 ? deviation * ratio * std::sqrt(ratio) : std::fmax(deviation, e);
  }
  return std::fmax(e, 50.0 * std::numeric_limits<double>::epsilon() * magnitude);
}

// The G7/K15 pair on one interval; f(x) returns an Estimate<N> (value and its error at x). The
// evaluations and any unconverged inner integral are recorded in `totals`.
template <std::size_t N, class F>
Interval<N> kronrod_interval(const F& f, double a, double b, Estimate<N>& totals) {
  Interval<N> r{a, b, {}, {}, {}};
  const double center = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  std::array<Estimate<N>, 15> samples;  // centre, then the pairs ∓x_j
  samples[0] = f(center);
  for (std::size_t j = 0; j < 7; ++j) {
    samples[2 * j + 1] = f(center - half * kKronrodNodes[j]);
    samples[2 * j + 2] = f(center + half * kKronrodNodes[j]);
  }
  const auto kronrod_weight = [](std::size_t i) {
    return i == 0 ? kKronrodWeights[7] : kKronrodWeights[(i - 1) / 2];
  };
  for (const Estimate<N>& e : samples) {
    totals.evaluations += e.evaluations > 0 ? e.evaluations : 1;
    totals.converged = totals.converged && e.converged;
  }
  for (std::size_t c = 0; c < N; ++c) {
    double kronrod = 0.0;
    double gauss = kGaussWeights[3] * samples[0].value[c];
    double carried = 0.0;
    for (std::size_t i = 0; i < 15; ++i) {
      kronrod += kronrod_weight(i) * samples[i].value[c];
      carried += kronrod_weight(i) * samples[i].error[c];
      const std::size_t j = (i - 1) / 2;  // the Gauss nodes are the odd Kronrod ones
      if (i > 0 && j % 2 == 1) gauss += kGaussWeights[j / 2] * samples[i].value[c];
    }
    // ∫|f − mean| over the interval (QUADPACK's resasc): the scale of the rescaled estimate.
    double deviation = 0.0;
    double magnitude = 0.0;
    for (std::size_t i = 0; i < 15; ++i) {
      deviation += kronrod_weight(i) * std::fabs(samples[i].value[c] - 0.5 * kronrod);
      magnitude += kronrod_weight(i) * std::fabs(samples[i].value[c]);
    }
    r.value[c] = kronrod * half;
    r.rule_error[c] =
        rescaled_error(std::fabs((kronrod - gauss) * half), deviation * half, magnitude * half);
    r.carried_error[c] = carried * half;
    if (!std::isfinite(r.value[c])) r.rule_error[c] = std::numeric_limits<double>::infinity();
  }
  // The channels are one integrand's components (R, G, B of one radiance): a channel whose
  // K15 − G7 happens to cancel must not claim more accuracy than its siblings, so every channel
  // gets at least the largest relative rule error times its own magnitude.
  double relative = 0.0;
  for (std::size_t c = 0; c < N; ++c) {
    if (std::fabs(r.value[c]) > 0.0) {
      relative = std::fmax(relative, r.rule_error[c] / std::fabs(r.value[c]));
    }
  }
  for (std::size_t c = 0; c < N; ++c) {
    r.rule_error[c] = std::fmax(r.rule_error[c], relative * std::fabs(r.value[c]));
  }
  return r;
}
}  // namespace cubature_detail

// ∫ f over [b_0, b_last], split first at the breakpoints (ascending; repeated ones are skipped),
// then adaptively. f(x) returns an Estimate<N>: its value and the error of that value (0 for an
// exact point evaluation, an inner integral's estimate otherwise).
template <std::size_t N, class F>
Estimate<N> integrate_adaptive(const F& f, std::span<const double> breakpoints,
                               const CubatureTolerance<N>& tolerance) {
  using cubature_detail::Interval;
  Estimate<N> result;
  result.evaluations = 0;
  std::vector<Interval<N>> intervals;
  for (std::size_t i = 0; i + 1 < breakpoints.size(); ++i) {
    if (breakpoints[i + 1] > breakpoints[i]) {
      intervals.push_back(
          cubature_detail::kronrod_interval<N>(f, breakpoints[i], breakpoints[i + 1], result));
    }
  }
  std::array<double, N> budget{};
  const auto total = [&] {
    result.value = {};
    result.error = {};
    for (const Interval<N>& piece : intervals) {
      for (std::size_t c = 0; c < N; ++c) {
        result.value[c] += piece.value[c];
        result.error[c] += piece.rule_error[c] + piece.carried_error[c];
      }
    }
    bool accepted = true;
    for (std::size_t c = 0; c < N; ++c) {
      budget[c] = std::fmax(tolerance.absolute[c], tolerance.relative * std::fabs(result.value[c]));
      if (!(result.error[c] <= budget[c])) accepted = false;
    }
    return accepted;
  };
  while (true) {
    const bool accepted = total();
    // Done, or an inner integral failed (its error is in the estimate; refining cannot help).
    if (accepted || !result.converged) return result;
    // The interval whose rule error uses most of the channels' budgets.
    std::size_t worst = intervals.size();
    double worst_share = 0.0;
    for (std::size_t i = 0; i < intervals.size(); ++i) {
      double share = 0.0;
      for (std::size_t c = 0; c < N; ++c) {
        const double e = intervals[i].rule_error[c];
        if (e > 0.0) share = std::fmax(share, budget[c] > 0.0 ? e / budget[c] : e * 1e300);
      }
      if (share > worst_share) {
        worst_share = share;
        worst = i;
      }
    }
    const bool full = static_cast<int>(intervals.size()) >= tolerance.max_intervals;
    if (worst == intervals.size() || full || !std::isfinite(worst_share)) {
      result.converged = false;  // out of intervals, or only the carried errors are left
      return result;
    }
    const double a = intervals[worst].a;
    const double b = intervals[worst].b;
    const double mid = 0.5 * (a + b);
    if (!(mid > a && mid < b)) {
      result.converged = false;
      return result;
    }
    intervals[worst] = cubature_detail::kronrod_interval<N>(f, a, mid, result);
    intervals.insert(std::next(intervals.begin(), static_cast<std::ptrdiff_t>(worst) + 1),
                     cubature_detail::kronrod_interval<N>(f, mid, b, result));
  }
}

// ∫ e^{−x²} f(x) dx over the whole line by Gauss–Hermite rules of increasing order (the span,
// ascending): the first two are compared, then each next one with the last, until the
// difference (reported as the error: it bounds the lower rule's error, so it is pessimistic for
// the higher one returned) plus the carried errors is within the tolerance. Not converged when
// the rules run out. For integrands smooth on the scale of the Gaussian this needs far fewer
// points than adaptive Kronrod on pieces.
template <std::size_t N, class F>
Estimate<N> integrate_gauss_hermite(const F& f, std::span<const QuadratureRule> rules,
                                    const CubatureTolerance<N>& tolerance) {
  Estimate<N> previous;
  Estimate<N> current;
  current.evaluations = 0;
  for (std::size_t r = 0; r < rules.size(); ++r) {
    previous = current;
    current = Estimate<N>{};
    current.evaluations = previous.evaluations;
    const QuadratureRule& rule = rules[r];
    std::array<double, N> carried{};
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
      const Estimate<N> e = f(rule.nodes[i]);
      current.evaluations += e.evaluations > 0 ? e.evaluations : 1;
      current.converged = current.converged && e.converged;
      for (std::size_t c = 0; c < N; ++c) {
        current.value[c] += rule.weights[i] * e.value[c];
        carried[c] += rule.weights[i] * e.error[c];
      }
    }
    if (r == 0) continue;
    bool accepted = true;
    for (std::size_t c = 0; c < N; ++c) {
      current.error[c] = std::fabs(current.value[c] - previous.value[c]) + carried[c];
      const double budget =
          std::fmax(tolerance.absolute[c], tolerance.relative * std::fabs(current.value[c]));
      if (!(current.error[c] <= budget)) accepted = false;
    }
    if (accepted) return current;
  }
  current.converged = false;
  return current;
}

}  // namespace oceanref
