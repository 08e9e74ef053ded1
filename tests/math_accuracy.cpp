// Accuracy harness for the portable libm (src/core/math.h), measured against MPFR.
//
// For every function of oceanref::math it evaluates random arguments (several distributions per
// function, see MakeFunctions) plus a fixed list of hard cases, computes the exact value with MPFR
// at 256 bits, and reports
//   - the maximum error in ulps of the exact value, |y − exact| / ulp(exact) with
//     ulp(v) = 2^(max(e, −1022) − 52) for 2^e ≤ |v| < 2^(e+1) (so subnormal results are
//     measured in units of the smallest subnormal), and the argument where it occurs;
//   - the share of correctly rounded results (bit-identical to the round-to-nearest double of
//     the exact value);
//   - the same two figures for glibc's function on the same arguments, for context.
// Special values (NaN, ±∞, exact zeros, overflow to ±∞ and signed zeros) must match the
// correctly rounded result bit for bit: a mismatch counts as an infinite error and is listed.
// sincos must return exactly the bits of sin and cos.
//
// The result does not depend on the number of threads: the random samples of a function are
// split into fixed chunks, each drawn from its own counter-based generator keyed by (seed,
// function name, chunk index), and the per-chunk results are merged in chunk order.
//
// Usage: math_accuracy [--samples N] [--threads T] [--seed S] [--function NAME[,NAME...]]...
//                      [--max-ulp B] [--markdown]
// tools/math_accuracy.sh builds and runs it; ctest runs `--samples 20000 --max-ulp 0.5005`.
#include <mpfr.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cfloat>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/math.h"

namespace {

namespace om = oceanref::math;

constexpr mpfr_prec_t kExactBits = 256;   // working precision of the reference values
constexpr uint64_t kChunkSize = 1024;     // random samples per chunk (one RNG stream each)
constexpr size_t kMaxListedFailures = 8;  // infinite errors listed per function
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Counter-based random numbers (SplitMix64, Steele, Lea & Flood 2014): the stream of a chunk is
// a pure function of its key, so any thread can draw any chunk and get the same arguments.

uint64_t Mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t key) : state_(key) {}
  uint64_t Next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return Mix64(state_);
  }
  // Uniform on [0, 1) with 53 random bits.
  double Unit() { return static_cast<double>(Next() >> 11) * 0x1p-53; }

 private:
  uint64_t state_;
};

uint64_t HashName(std::string_view name) {  // FNV-1a, stable across runs and platforms
  uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : name) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return h;
}

uint64_t ChunkKey(uint64_t seed, std::string_view function, uint64_t chunk) {
  return Mix64(Mix64(Mix64(seed) ^ HashName(function)) ^ chunk);
}

// ---------------------------------------------------------------------------------------------
// Argument distributions.

enum class Shape {
  kUniform,     // lo + (hi − lo)·u
  kLogUniform,  // center + d, d with uniform biased exponent (subnormals included), random
                // mantissa and sign, kept if lo ≤ d ≤ hi and (for center ≠ 0) center + d ≠ center
  kInteger,  // an integer uniform in [lo, hi]
};

struct Dist {
  Shape shape = Shape::kUniform;
  double lo = 0.0, hi = 0.0, center = 0.0;
};

Dist Uniform(double lo, double hi) {
  return {Shape::kUniform, lo, hi, 0.0};
}
Dist LogUniform(double lo = -kInf, double hi = kInf, double center = 0.0) {
  return {Shape::kLogUniform, lo, hi, center};
}
Dist Integer(double lo, double hi) {
  return {Shape::kInteger, lo, hi, 0.0};
}

// A double whose bits are uniform over the finite doubles of either sign: uniform over the
// exponent range in log scale, with random mantissa bits.
double RandomFiniteDouble(SplitMix64& rng) {
  for (;;) {
    const uint64_t bits = rng.Next();
    const double d = std::bit_cast<double>(bits);
    if (std::isfinite(d)) return d;
  }
}

// One draw, or NaN if the draw falls outside the distribution's range (the caller retries).
double Draw(const Dist& dist, SplitMix64& rng) {
  switch (dist.shape) {
    case Shape::kUniform:
      return dist.lo + (dist.hi - dist.lo) * rng.Unit();
    case Shape::kLogUniform: {
      const double d = RandomFiniteDouble(rng);
      const double x = dist.center + d;
      const bool moved = dist.center == 0.0 || x != dist.center;  // not a wasted x = center
      return d >= dist.lo && d <= dist.hi && moved ? x : kNaN;
    }
    case Shape::kInteger:
      return std::floor(dist.lo + (dist.hi - dist.lo + 1.0) * rng.Unit());
  }
  return kNaN;
}

struct Args {
  double x = 0.0, y = 0.0;  // y only for two-argument functions
};

// The distributions of a function are used round-robin, sample i from dists[i % size]. For a
// one-argument function only `x` is used.
struct ArgDist {
  Dist x, y;
};

// ---------------------------------------------------------------------------------------------
// The functions under test.

enum class Arity { kUnary, kBinary, kSinCos };

using Unary = double (*)(double);
using Binary = double (*)(double, double);
using MpfrUnary = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t);
using MpfrBinary = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_srcptr, mpfr_rnd_t);

struct FunctionSpec {
  const char* name = "";
  Arity arity = Arity::kUnary;
  Unary ours1 = nullptr, glibc1 = nullptr;
  MpfrUnary exact1 = nullptr;
  Binary ours2 = nullptr, glibc2 = nullptr;
  MpfrBinary exact2 = nullptr;
  std::vector<ArgDist> dists;
};

FunctionSpec Fn1(const char* name, Unary ours, Unary glibc, MpfrUnary exact,
                 std::vector<Dist> dists) {
  FunctionSpec f;
  f.name = name;
  f.arity = Arity::kUnary;
  f.ours1 = ours;
  f.glibc1 = glibc;
  f.exact1 = exact;
  for (const Dist& d : dists) f.dists.push_back({d, Dist{}});
  return f;
}

FunctionSpec Fn2(const char* name, Binary ours, Binary glibc, MpfrBinary exact,
                 std::vector<ArgDist> dists) {
  FunctionSpec f;
  f.name = name;
  f.arity = Arity::kBinary;
  f.ours2 = ours;
  f.glibc2 = glibc;
  f.exact2 = exact;
  f.dists = std::move(dists);
  return f;
}

int MpfrLgamma(mpfr_ptr rop, mpfr_srcptr op, mpfr_rnd_t rnd) {  // ln|Γ(x)|
  int sign = 0;
  return mpfr_lgamma(rop, &sign, op, rnd);
}

double GlibcLgamma(double x) {  // the reentrant variant: no write to the global signgam
  int sign = 0;
  return ::lgamma_r(x, &sign);
}

// Domain notes: the generic rejection in DrawArgs also drops arguments whose glibc result is
// ±∞ or NaN, so e.g. LogUniform() for exp covers exactly the finite-result domain.
std::vector<FunctionSpec> MakeFunctions() {
  const double kAll = kInf;
  std::vector<FunctionSpec> f;
  f.push_back(Fn1("exp", om::exp, [](double x) { return std::exp(x); }, mpfr_exp,
                  {Uniform(-1, 1), Uniform(-745.2, 709.8), LogUniform()}));
  f.push_back(Fn1("expm1", om::expm1, [](double x) { return std::expm1(x); }, mpfr_expm1,
                  {Uniform(-1, 1), Uniform(-40, 709.8), LogUniform()}));
  f.push_back(Fn1("log", om::log, [](double x) { return std::log(x); }, mpfr_log,
                  {Uniform(0, 10), LogUniform(-0.5, 0.5, 1.0), LogUniform(0, kAll)}));
  f.push_back(Fn1("log1p", om::log1p, [](double x) { return std::log1p(x); }, mpfr_log1p,
                  {Uniform(-1, 10), Uniform(-0.5, 0.5), LogUniform(-1, kAll)}));
  f.push_back(Fn1("log10", om::log10, [](double x) { return std::log10(x); }, mpfr_log10,
                  {Uniform(0, 10), LogUniform(-0.5, 0.5, 1.0), LogUniform(0, kAll)}));
  f.push_back(Fn2("pow", om::pow, [](double x, double y) { return std::pow(x, y); }, mpfr_pow,
                  {{Uniform(0, 10), Uniform(-30, 30)},
                   {LogUniform(-0x1p-8, 0x1p-8, 1.0), Uniform(-0x1p16, 0x1p16)},
                   {LogUniform(0, kAll), LogUniform()},
                   {Uniform(-10, 0), Integer(-60, 60)}}));
  f.push_back(Fn1("sin", om::sin, [](double x) { return std::sin(x); }, mpfr_sin,
                  {Uniform(-10, 10), LogUniform()}));
  f.push_back(Fn1("cos", om::cos, [](double x) { return std::cos(x); }, mpfr_cos,
                  {Uniform(-10, 10), LogUniform()}));
  f.push_back(Fn1("tan", om::tan, [](double x) { return std::tan(x); }, mpfr_tan,
                  {Uniform(-10, 10), LogUniform()}));
  FunctionSpec sincos;
  sincos.name = "sincos";
  sincos.arity = Arity::kSinCos;
  sincos.dists = {{Uniform(-10, 10), Dist{}}, {LogUniform(), Dist{}}};
  f.push_back(sincos);
  f.push_back(Fn1("atan", om::atan, [](double x) { return std::atan(x); }, mpfr_atan,
                  {Uniform(-10, 10), LogUniform()}));
  f.push_back(Fn2("atan2", om::atan2, [](double y, double x) { return std::atan2(y, x); },
                  mpfr_atan2,
                  {{Uniform(-10, 10), Uniform(-10, 10)}, {LogUniform(), LogUniform()}}));
  f.push_back(
      Fn1("asin", om::asin, [](double x) { return std::asin(x); }, mpfr_asin,
          {Uniform(-1, 1), LogUniform(-1, 0, 1.0), LogUniform(0, 1, -1.0), LogUniform(-1, 1)}));
  f.push_back(
      Fn1("acos", om::acos, [](double x) { return std::acos(x); }, mpfr_acos,
          {Uniform(-1, 1), LogUniform(-1, 0, 1.0), LogUniform(0, 1, -1.0), LogUniform(-1, 1)}));
  f.push_back(Fn1("sinh", om::sinh, [](double x) { return std::sinh(x); }, mpfr_sinh,
                  {Uniform(-10, 10), Uniform(-711, 711), LogUniform()}));
  f.push_back(Fn1("cosh", om::cosh, [](double x) { return std::cosh(x); }, mpfr_cosh,
                  {Uniform(-10, 10), Uniform(-711, 711), LogUniform()}));
  f.push_back(Fn1("tanh", om::tanh, [](double x) { return std::tanh(x); }, mpfr_tanh,
                  {Uniform(-10, 10), Uniform(-25, 25), LogUniform()}));
  f.push_back(Fn2("hypot", om::hypot, [](double x, double y) { return std::hypot(x, y); },
                  mpfr_hypot,
                  {{Uniform(-10, 10), Uniform(-10, 10)}, {LogUniform(), LogUniform()}}));
  f.push_back(Fn1("cbrt", om::cbrt, [](double x) { return std::cbrt(x); }, mpfr_cbrt,
                  {Uniform(-10, 10), LogUniform()}));
  f.push_back(Fn1("erf", om::erf, [](double x) { return std::erf(x); }, mpfr_erf,
                  {Uniform(-6, 6), Uniform(-30, 30), LogUniform()}));
  f.push_back(Fn1("erfc", om::erfc, [](double x) { return std::erfc(x); }, mpfr_erfc,
                  {Uniform(-6, 6), Uniform(-30, 30), LogUniform()}));
  f.push_back(Fn1("lgamma", om::lgamma, GlibcLgamma, MpfrLgamma,
                  {Uniform(-10, 10), Uniform(-200, 200), LogUniform(-0.1, 0.1, 1.0),
                   LogUniform(-0.1, 0.1, 2.0), Uniform(-2.5, -2.4), LogUniform()}));
  f.push_back(Fn1("tgamma", om::tgamma, [](double x) { return std::tgamma(x); }, mpfr_gamma,
                  {Uniform(-10, 10), Uniform(-190, 172), LogUniform()}));
  return f;
}

// ---------------------------------------------------------------------------------------------
// Hard cases.

std::vector<double> WithBothSigns(std::vector<double> v) {
  const size_t n = v.size();
  for (size_t i = 0; i < n; ++i) v.push_back(-v[i]);
  return v;
}

// Every hard value together with its two floating-point neighbours, sorted and deduplicated
// (so thresholds are probed on both sides).
std::vector<double> WithNeighbours(const std::vector<double>& values) {
  std::vector<uint64_t> bits;
  for (double v : values) {
    for (double w : {std::nextafter(v, -kInf), v, std::nextafter(v, kInf)}) {
      bits.push_back(std::bit_cast<uint64_t>(w));
    }
  }
  std::sort(bits.begin(), bits.end());
  bits.erase(std::unique(bits.begin(), bits.end()), bits.end());
  std::vector<double> out;
  for (uint64_t b : bits) out.push_back(std::bit_cast<double>(b));
  return out;
}

// The hard-case tables are laid out by hand (clang-format would put one value per line).
// clang-format off

// Arguments every one-argument function sees: zeros, subnormals, DBL_MIN/MAX, powers of two
// around the usual "x is tiny" thresholds, small integers, huge values, ±∞ and NaN.
std::vector<double> CommonHardValues() {
  std::vector<double> v = WithBothSigns({
      0.0, DBL_TRUE_MIN, 0x1p-1050, 0x0.fffffffffffffp-1022, DBL_MIN, 0x1p-600, 0x1p-60,
      0x1p-54, 0x1p-53, 0x1p-30, 0x1p-28, 0x1p-27, 0x1p-26, 0x1p-10, 0.25, 0.5, 0.75, 1.0, 1.5,
      2.0, 3.0, 4.0, 5.0, 10.0, 100.0, 1000.0, 0x1p52, 0x1p53, 0x1p60, 1e22, 0x1p300, 0x1p1000,
      DBL_MAX, kInf});
  v.push_back(kNaN);
  return v;
}

// The doubles nearest to k·π/2 for small and some large k (rounded by MPFR), the classic worst
// case of trigonometric argument reduction, and other huge values.
std::vector<double> TrigHardValues() {
  std::vector<double> v;
  std::vector<unsigned long> multiples = {1000, 1000000, 1000000000, 1000000000000,
                                          1000000000000000, 1000000000000000000};
  for (unsigned long k = 1; k <= 64; ++k) multiples.push_back(k);
  mpfr_t t;
  mpfr_init2(t, 2 * kExactBits);
  for (unsigned long k : multiples) {
    mpfr_const_pi(t, MPFR_RNDN);
    mpfr_mul_ui(t, t, k, MPFR_RNDN);
    mpfr_div_2ui(t, t, 1, MPFR_RNDN);
    v.push_back(mpfr_get_d(t, MPFR_RNDN));
  }
  mpfr_clear(t);
  v.insert(v.end(), {
      0x1.921fb54442d18p+1, 0x1.921fb54442d18p+0, 0x1.921fb54442d18p-1, 0x1.921fb54442d18p+2,
      0x1.921fb54442d18p+10, 0x1.921fb54442d18p+20, 0x1.921fb54442d18p+60,
      6381956970095103.0 * 0x1p797,  // = 0x1.6ac5b262ca1ffp+849, cos x ≈ −2^−61
      1e22, 1e300, 0x1p1023, 0x1p-1022 * 3});
  return WithBothSigns(v);
}

// Branch thresholds, overflow/underflow limits (computed with mpmath), exact cases, zeros and
// poles of each function; UnaryHardCases adds both neighbours of every value.
std::vector<double> SpecificHardValues(std::string_view name) {
  if (name == "exp" || name == "expm1") {
    return {0x1.62e42fefa39efp+9,  // overflow threshold
            -0x1.74910d52d3052p+9,  // below: result rounds to 0
            -0x1.6232bdd7abcd2p+9,  // result DBL_MIN
            709.78, 710.0, -745.0, -746.0, -708.0, -37.0, -38.0, 0x1.62e42fefa39efp-1,
            -0x1.62e42fefa39efp-1, 1e-300};
  }
  if (name == "log" || name == "log10") {
    return {0x1.5bf0a8b145769p+1, 0x1.0000000000001p0, 0x1.fffffffffffffp-1, 1e-5, 1e22, 1e308,
            1e-308, 10.0, 0x1.6a09e667f3bcdp-1, 0x1.6a09e667f3bcdp0, -1e-300};
  }
  if (name == "log1p") {
    return {-1.0, -0x1.fffffffffffffp-1, -0.5, 0x1.b7e151628aed3p+0, 1e300, -2.0, 0x1p-1074,
            0x1.6a09e667f3bcdp-1 - 1.0, 0x1.6a09e667f3bcdp0 - 1.0};
  }
  if (name == "sin" || name == "cos" || name == "tan" || name == "sincos") {
    return TrigHardValues();
  }
  if (name == "atan") return {0x1p54, 0x1p-27, 0.4375, 0.6875, 1.1875, 2.4375, 0x1p66};
  if (name == "asin" || name == "acos") {
    return WithBothSigns({0x1.fffffffffffffp-1, 0.5, 0.5625, 0.875, 0x1.0000000000001p0,
                          0x1.6a09e667f3bcdp-1, 0x1p-27});
  }
  if (name == "sinh" || name == "cosh") {  // 0x1.633ce8fb9f87ep+9: overflow threshold
    return WithBothSigns({0x1.633ce8fb9f87ep+9, 0x1.62e42fefa39efp+9, 710.0, 22.0, 0x1p-28});
  }
  if (name == "tanh") return WithBothSigns({19.0, 19.0615, 22.0, 0.55, 0x1p-28, 0x1p-55});
  if (name == "cbrt") {
    return WithBothSigns({8.0, 27.0, 0.125, 1e300, 1e-300, 0x1p-1073, 0x1p-1071, 0x1p1023});
  }
  if (name == "erf" || name == "erfc") {  // 0x1.b39dc41e48bfcp+4: erfc rounds to 0 above
    return WithBothSigns({0.84375, 1.25, 2.857142857142857, 5.9, 6.0, 26.5, 27.0, 27.2,
                          0x1.b39dc41e48bfcp+4, 28.0, 0x1p-28, 0x1p-56});
  }
  if (name == "lgamma") {
    // Zeros of ln|Γ| (hard for the relative error), poles, near 1 and 2 (zeros), the minimum
    // of Γ, the overflow threshold 0x1.754d9278b51a8p+1014.
    return {-2.457024738220800586, -2.747682646727412692, -3.143580888349980, -3.955294284858579,
            -4.039361839740537, -0.5, -1.5, -2.5, -170.5, -1e10 - 0.5, -1.0, -2.0, -3.0,
            1.0 + 0x1p-30, 1.0 - 0x1p-30, 2.0 + 0x1p-30, 2.0 - 0x1p-30, 1.4616321449683623,
            0x1.754d9278b51a8p+1014, 0x1p1014, 0x1p1015};
  }
  if (name == "tgamma") {
    // 0x1.573fae561f647p+7 ≈ 171.62: overflow threshold; exact factorials; negative
    // half-integers down to where Γ underflows.
    return {0x1.573fae561f647p+7, 171.0, 172.0, 170.5, 23.0, 24.0, 0.5, -0.5, -1.5, -170.5,
            -171.5, -176.5, -177.5, -183.5, -184.5, -1.0, -2.0, -1e-300, 1e-308,
            1.4616321449683623};
  }
  return {};
}

// clang-format on

// ln|Γ(x)| by MPFR, rounded to a double (its sign is what the bisection below needs).
double MpfrLgammaValue(double x) {
  mpfr_t a, r;
  mpfr_inits2(256, a, r, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(a, x, MPFR_RNDN);
  MpfrLgamma(r, a, MPFR_RNDN);
  const double v = mpfr_get_d(r, MPFR_RNDN);
  mpfr_clears(a, r, static_cast<mpfr_ptr>(nullptr));
  return v;
}

// The two zeros of ln|Γ| in each (−n−1, −n), n = 2 … 18, found by bisection on MPFR's value
// (|Γ| → ∞ at both poles and is below 1 at −n − ½), and 17 points spread over ±6% of each zero's
// distance to its pole: there ln|Γ| changes by orders of magnitude within 1e−10 for large n,
// and no random argument lands (the portable lgamma has a narrow expansion around each zero).
std::vector<double> LgammaZeroNeighbourhoods() {
  std::vector<double> out;
  for (int n = 2; n <= 18; ++n) {
    const double middle = -n - 0.5;
    for (const double pole : {-n - 1.0, -1.0 * n}) {
      double positive = pole, negative = middle;  // lgamma > 0 near the pole, < 0 at the middle
      for (int i = 0; i < 200; ++i) {
        const double m = negative + 0.5 * (positive - negative);
        if (m == negative || m == positive) break;
        (MpfrLgammaValue(m) > 0.0 ? positive : negative) = m;
      }
      const double step = (positive - pole) / 128.0;
      for (int k = -8; k <= 8; ++k) out.push_back(positive + k * step);
    }
  }
  return out;
}

std::vector<double> UnaryHardCases(std::string_view name) {
  std::vector<double> v = CommonHardValues();
  const std::vector<double> s = SpecificHardValues(name);
  v.insert(v.end(), s.begin(), s.end());
  if (name == "lgamma") {
    const std::vector<double> z = LgammaZeroNeighbourhoods();
    v.insert(v.end(), z.begin(), z.end());
  }
  return WithNeighbours(v);
}

// Values crossed with each other for the two-argument functions: they include every C99
// Annex F special pair (±0, ±∞, NaN, ±1, finite non-integers, odd and even integers).
std::vector<double> EdgeValues() {
  std::vector<double> v = WithBothSigns({0.0, DBL_TRUE_MIN, DBL_MIN, 0.5, 1.0, 1.5, 2.0, 3.0, 10.0,
                                         0x1p52 + 1, 0x1p53, DBL_MAX, kInf});
  v.push_back(kNaN);
  return v;
}

std::vector<Args> CrossProduct(const std::vector<double>& xs, const std::vector<double>& ys) {
  std::vector<Args> out;
  for (double x : xs) {
    for (double y : ys) out.push_back({x, y});
  }
  return out;
}

// The arguments nearest a rounding midpoint found by --near-midpoints (its output).
struct NearMidpointCase {
  const char* function;
  double x, y;
};
const std::vector<NearMidpointCase> kNearMidpointCases = {
#include "math_near_midpoints.inc"
};

// clang-format off
std::vector<Args> BinaryHardCases(std::string_view name) {
  std::vector<double> xs = EdgeValues();
  std::vector<double> ys = EdgeValues();
  std::vector<Args> extra;
  if (name == "pow") {
    // x near 1 with large y, exact powers at the overflow and underflow limits.
    xs.insert(xs.end(), {0x1.0000000000001p0, 0x1.fffffffffffffp-1, -8.0, 0.1, 1e10});
    ys.insert(ys.end(), {1.0 / 3.0, -0.5, 1023.0, 1024.0, -1022.0, -1074.0, -1075.0, 0x1p62,
                         -0x1p62, 0x1p52 + 2, 1e300, -1e300, 4.5, -4.5});
    extra = {{10, 308}, {10, 309}, {10, -323}, {10, -324}, {0x1.0000000000001p0, 0x1p60},
             {2, -1074.5}, {2, 1023.999}, {-2, 1023}, {-2, -1075}, {0.5, 1074}, {0.5, 1075},
             {DBL_MIN, -1}, {DBL_MAX, 0.5}, {2.5, 775.5}, {0x1.fffffffffffffp-1, 0x1p62}};
  } else if (name == "atan2") {
    extra = {{DBL_TRUE_MIN, DBL_MAX}, {DBL_MAX, DBL_TRUE_MIN}, {1e-300, 1e300},
             {-1e-300, -1e300}, {1, 0x1p60}, {0x1p-60, 1}, {1, -0x1p60}};
  } else if (name == "hypot") {
    extra = {{3, 4}, {0x1p1023, 0x1p1023}, {DBL_MAX, 1}, {0x1.6a09e667f3bccp+1023, 0x1p1022},
             {0x1p-1074, 0x1p-1074}, {0x1p-1022, 0x1p-1074}, {1e300, 1e-300}, {1, 0x1p-27}};
  }
  std::vector<Args> out = CrossProduct(xs, ys);
  out.insert(out.end(), extra.begin(), extra.end());
  return out;
}
// clang-format on

// ---------------------------------------------------------------------------------------------
// Measurement.

// Per-thread MPFR state (MPFR keeps its constant caches thread-local when built with TLS, which
// main checks).
struct Worker {
  mpfr_t x, y, exact, exact2, diff;
  Worker() {
    mpfr_inits2(53, x, y, static_cast<mpfr_ptr>(nullptr));
    mpfr_inits2(kExactBits, exact, exact2, diff, static_cast<mpfr_ptr>(nullptr));
  }
  ~Worker() {
    mpfr_clears(x, y, exact, exact2, diff, static_cast<mpfr_ptr>(nullptr));
    mpfr_free_cache();
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;
};

bool SameResult(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

struct Verdict {
  double ulps = 0.0;               // error in ulps of the exact value (∞ for a wrong special)
  bool correctly_rounded = false;  // y is the round-to-nearest double of the exact value
};

// |y − exact| / ulp(exact), computed in MPFR. mpfr_get_exp gives E with 2^(E−1) ≤ |v| < 2^E.
double UlpError(Worker& w, double y, mpfr_srcptr exact) {
  mpfr_set_d(w.diff, y, MPFR_RNDN);
  mpfr_sub(w.diff, w.diff, exact, MPFR_RNDN);
  mpfr_abs(w.diff, w.diff, MPFR_RNDN);
  const mpfr_exp_t e = mpfr_get_exp(exact) - 1;
  const mpfr_exp_t ulp_exponent = std::max<mpfr_exp_t>(e, -1022) - 52;
  mpfr_div_2si(w.diff, w.diff, ulp_exponent, MPFR_RNDN);
  return mpfr_get_d(w.diff, MPFR_RNDN);
}

// The verdict on one result y. mpfr_get_d rounds to nearest-even including in the subnormal
// range (checked by CheckMpfrGetD); double rounding through the 256-bit value could only matter
// for a value within 2^−256 relative of a midpoint.
Verdict Judge(Worker& w, double y, mpfr_srcptr exact) {
  const double rounded = mpfr_get_d(exact, MPFR_RNDN);
  Verdict v;
  v.correctly_rounded = SameResult(y, rounded);
  const bool special = mpfr_nan_p(exact) || mpfr_inf_p(exact) || mpfr_zero_p(exact) ||
                       std::isinf(rounded) || (rounded == 0.0 && y == 0.0);
  if (special) {
    v.ulps = v.correctly_rounded ? 0.0 : kInf;
  } else if (!std::isfinite(y)) {
    v.ulps = kInf;
  } else {
    v.ulps = UlpError(w, y, exact);
  }
  return v;
}

Verdict Worst(const Verdict& a, const Verdict& b) {
  return {std::max(a.ulps, b.ulps), a.correctly_rounded && b.correctly_rounded};
}

struct Stats {
  uint64_t count = 0, correctly_rounded = 0;
  double max_ulps = -1.0;
  Args at_max;

  void Add(const Verdict& v, const Args& a) {
    ++count;
    if (v.correctly_rounded) ++correctly_rounded;
    if (v.ulps > max_ulps) {
      max_ulps = v.ulps;
      at_max = a;
    }
  }
  // Merging in sample order keeps the first argument among equal maxima.
  void Merge(const Stats& o) {
    count += o.count;
    correctly_rounded += o.correctly_rounded;
    if (o.max_ulps > max_ulps) {
      max_ulps = o.max_ulps;
      at_max = o.at_max;
    }
  }
};

struct TaskResult {
  Stats ours, glibc;
  // Our results with an infinite error (wrong special value, ±∞ or NaN instead of a finite
  // result, sincos ≠ sin/cos), in sample order.
  std::vector<std::string> failures;
};

std::string Hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

// "x" or "(x, y)" in hex floats.
std::string ArgsText(const FunctionSpec& f, const Args& a) {
  return f.arity == Arity::kBinary ? "(" + Hex(a.x) + ", " + Hex(a.y) + ")" : Hex(a.x);
}

void NoteFailure(TaskResult& r, const FunctionSpec& f, const Args& a, const std::string& what) {
  if (r.failures.size() >= kMaxListedFailures) return;
  const std::string args = ArgsText(f, a);
  const std::string call = f.arity == Arity::kBinary ? args : "(" + args + ")";
  r.failures.push_back(f.name + call + ": " + what);
}

std::string Mismatch(double got, mpfr_srcptr exact) {
  return "got " + Hex(got) + ", expected " + Hex(mpfr_get_d(exact, MPFR_RNDN));
}

void MeasureUnary(const FunctionSpec& f, const Args& a, Worker& w, TaskResult& r) {
  mpfr_set_d(w.x, a.x, MPFR_RNDN);
  f.exact1(w.exact, w.x, MPFR_RNDN);
  const double ours = f.ours1(a.x);
  const Verdict v = Judge(w, ours, w.exact);
  if (std::isinf(v.ulps)) NoteFailure(r, f, a, Mismatch(ours, w.exact));
  r.ours.Add(v, a);
  r.glibc.Add(Judge(w, f.glibc1(a.x), w.exact), a);
}

void MeasureBinary(const FunctionSpec& f, const Args& a, Worker& w, TaskResult& r) {
  mpfr_set_d(w.x, a.x, MPFR_RNDN);
  mpfr_set_d(w.y, a.y, MPFR_RNDN);
  f.exact2(w.exact, w.x, w.y, MPFR_RNDN);
  const double ours = f.ours2(a.x, a.y);
  const Verdict v = Judge(w, ours, w.exact);
  if (std::isinf(v.ulps)) NoteFailure(r, f, a, Mismatch(ours, w.exact));
  r.ours.Add(v, a);
  r.glibc.Add(Judge(w, f.glibc2(a.x, a.y), w.exact), a);
}

// sincos: both outputs against MPFR (the worse of the two counts), and bit-identity with sin
// and cos (a difference is an infinite error).
void MeasureSinCos(const FunctionSpec& f, const Args& a, Worker& w, TaskResult& r) {
  mpfr_set_d(w.x, a.x, MPFR_RNDN);
  mpfr_sin_cos(w.exact, w.exact2, w.x, MPFR_RNDN);
  const om::SinCos ours = om::sincos(a.x);
  Verdict v = Worst(Judge(w, ours.sin, w.exact), Judge(w, ours.cos, w.exact2));
  if (std::isinf(v.ulps)) {
    NoteFailure(r, f, a,
                "sin " + Mismatch(ours.sin, w.exact) + "; cos " + Mismatch(ours.cos, w.exact2));
  }
  const double s = om::sin(a.x), c = om::cos(a.x);
  if (std::bit_cast<uint64_t>(s) != std::bit_cast<uint64_t>(ours.sin) ||
      std::bit_cast<uint64_t>(c) != std::bit_cast<uint64_t>(ours.cos)) {
    v.ulps = kInf;
    NoteFailure(r, f, a,
                "not bit-identical to sin/cos: sincos gives (" + Hex(ours.sin) + ", " +
                    Hex(ours.cos) + "), sin/cos give (" + Hex(s) + ", " + Hex(c) + ")");
  }
  r.ours.Add(v, a);
  double gs = 0.0, gc = 0.0;
  ::sincos(a.x, &gs, &gc);
  r.glibc.Add(Worst(Judge(w, gs, w.exact), Judge(w, gc, w.exact2)), a);
}

void Measure(const FunctionSpec& f, const Args& a, Worker& w, TaskResult& r) {
  switch (f.arity) {
    case Arity::kUnary:
      return MeasureUnary(f, a, w, r);
    case Arity::kBinary:
      return MeasureBinary(f, a, w, r);
    case Arity::kSinCos:
      return MeasureSinCos(f, a, w, r);
  }
}

// glibc's result decides whether an argument is in the domain of the random samples: the
// result must be finite and not NaN (overflow, poles and NaN results are hard cases).
bool InDomain(const FunctionSpec& f, const Args& a) {
  double y = 0.0;
  switch (f.arity) {
    case Arity::kUnary:
      y = f.glibc1(a.x);
      break;
    case Arity::kBinary:
      y = f.glibc2(a.x, a.y);
      break;
    case Arity::kSinCos:
      y = std::sin(a.x) + std::cos(a.x);
      break;
  }
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(y);
}

// Sample i of a chunk: distribution i mod size, redrawn until it is in the domain.
Args DrawArgs(const FunctionSpec& f, uint64_t i, SplitMix64& rng) {
  const ArgDist& d = f.dists[i % f.dists.size()];
  for (int attempt = 0; attempt < 100000; ++attempt) {
    Args a{Draw(d.x, rng), f.arity == Arity::kBinary ? Draw(d.y, rng) : 0.0};
    if (InDomain(f, a)) return a;
  }
  std::fprintf(stderr, "math_accuracy: %s: distribution %" PRIu64 " rejects every draw\n", f.name,
               i % f.dists.size());
  std::exit(2);
}

// A unit of work: the hard cases of a function (chunk == kHardChunk) or one chunk of its random
// samples.
constexpr uint64_t kHardChunk = ~0ULL;

struct Task {
  size_t function = 0;  // index into the selected functions
  uint64_t chunk = 0, begin = 0, end = 0;
};

struct Options {
  uint64_t samples = 10000000, seed = 1;
  unsigned threads = 2;
  std::vector<std::string> functions;
  double max_ulp = -1.0;  // < 0: no limit
  bool markdown = false;
  uint64_t near_midpoints = 0;  // > 0: search mode (PrintNearMidpoints)
};

void RunTask(const FunctionSpec& f, const std::vector<Args>& hard, const Task& t, uint64_t seed,
             Worker& w, TaskResult& r) {
  if (t.chunk == kHardChunk) {
    for (const Args& a : hard) Measure(f, a, w, r);
    return;
  }
  SplitMix64 rng(ChunkKey(seed, f.name, t.chunk));
  for (uint64_t i = t.begin; i < t.end; ++i) Measure(f, DrawArgs(f, i, rng), w, r);
}

// Hard cases first, then chunk 0 of every function, chunk 1 of every function, ...: the costly
// references (erfc, Γ) are spread over the run, which keeps the threads busy until the end.
// Each function's tasks stay in sample order, the order in which their results are merged.
std::vector<Task> MakeTasks(size_t functions, uint64_t samples) {
  std::vector<Task> tasks;
  for (size_t fi = 0; fi < functions; ++fi) tasks.push_back({fi, kHardChunk, 0, 0});
  for (uint64_t begin = 0, chunk = 0; begin < samples; begin += kChunkSize, ++chunk) {
    for (size_t fi = 0; fi < functions; ++fi) {
      tasks.push_back({fi, chunk, begin, std::min(samples, begin + kChunkSize)});
    }
  }
  return tasks;
}

std::vector<TaskResult> RunAll(const std::vector<FunctionSpec>& fns,
                               const std::vector<std::vector<Args>>& hard,
                               const std::vector<Task>& tasks, const Options& opt) {
  std::vector<TaskResult> results(tasks.size());
  std::atomic<size_t> next{0};
  auto work = [&] {
    Worker w;
    for (size_t i; (i = next.fetch_add(1)) < tasks.size();) {
      const Task& t = tasks[i];
      RunTask(fns[t.function], hard[t.function], t, opt.seed, w, results[i]);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned i = 1; i < opt.threads; ++i) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  return results;
}

// ---------------------------------------------------------------------------------------------
// Near-midpoint arguments: where a result is hardest to round correctly. A fast path whose error
// bound is violated by a little (a dropped low-order term, a coefficient off by less than an ulp)
// is still right for almost every argument; it misrounds only those whose exact result lies
// within that error of a midpoint between two doubles. Random samples rarely come that close
// (one in 2^13 within 2^−14 ulp); the search keeps the closest of many, and every run measures
// them and requires every one correctly rounded (tests/math_near_midpoints.inc). The search keeps
// only arguments the functions round correctly: for the few functions that are not correctly
// rounded everywhere (reference/ACCURACY.md), the misrounded arguments nearest a midpoint are
// their known residue, not a regression.

// The distance of an exact value to the nearest rounding midpoint, in ulps (0 to 0.5); ∞ for a
// value without one (zero, infinite, NaN).
double MidpointDistance(Worker& w, mpfr_srcptr exact) {
  if (!mpfr_number_p(exact) || mpfr_zero_p(exact)) return kInf;
  const mpfr_exp_t e = mpfr_get_exp(exact) - 1;
  const mpfr_exp_t ulp_exponent = std::max<mpfr_exp_t>(e, -1022) - 52;
  mpfr_abs(w.diff, exact, MPFR_RNDN);
  mpfr_div_2si(w.diff, w.diff, ulp_exponent, MPFR_RNDN);  // |v| in ulps
  mpfr_frac(w.diff, w.diff, MPFR_RNDN);
  return std::fabs(mpfr_get_d(w.diff, MPFR_RNDN) - 0.5);
}

struct NearMidpoint {
  double distance;
  Args args;
};

// Our result is the correctly rounded one (sincos: both; special values bit for bit).
bool RoundsCorrectly(const FunctionSpec& f, const Args& a, Worker& w) {
  mpfr_set_d(w.x, a.x, MPFR_RNDN);
  switch (f.arity) {
    case Arity::kUnary:
      f.exact1(w.exact, w.x, MPFR_RNDN);
      return SameResult(f.ours1(a.x), mpfr_get_d(w.exact, MPFR_RNDN));
    case Arity::kBinary:
      mpfr_set_d(w.y, a.y, MPFR_RNDN);
      f.exact2(w.exact, w.x, w.y, MPFR_RNDN);
      return SameResult(f.ours2(a.x, a.y), mpfr_get_d(w.exact, MPFR_RNDN));
    case Arity::kSinCos: {
      mpfr_sin_cos(w.exact, w.exact2, w.x, MPFR_RNDN);
      const om::SinCos ours = om::sincos(a.x);
      return SameResult(ours.sin, mpfr_get_d(w.exact, MPFR_RNDN)) &&
             SameResult(ours.cos, mpfr_get_d(w.exact2, MPFR_RNDN));
    }
  }
  return false;
}

// The K arguments nearest a midpoint among n draws of distribution d (for sincos: of sin or cos)
// that the function rounds correctly.
std::vector<NearMidpoint> SearchNearMidpoints(const FunctionSpec& f, size_t d, uint64_t n,
                                              uint64_t k, uint64_t seed, Worker& w) {
  FunctionSpec one = f;
  one.dists = {f.dists[d]};
  SplitMix64 rng(ChunkKey(seed ^ 0x6e6561722d6d6964ULL, f.name, d));  // "near-mid"
  std::vector<NearMidpoint> best;
  for (uint64_t i = 0; i < n; ++i) {
    const Args a = DrawArgs(one, 0, rng);
    mpfr_set_d(w.x, a.x, MPFR_RNDN);
    double distance = kInf;
    if (f.arity == Arity::kSinCos) {
      mpfr_sin_cos(w.exact, w.exact2, w.x, MPFR_RNDN);
      distance = std::min(MidpointDistance(w, w.exact), MidpointDistance(w, w.exact2));
    } else if (f.arity == Arity::kBinary) {
      mpfr_set_d(w.y, a.y, MPFR_RNDN);
      f.exact2(w.exact, w.x, w.y, MPFR_RNDN);
      distance = MidpointDistance(w, w.exact);
    } else {
      f.exact1(w.exact, w.x, MPFR_RNDN);
      distance = MidpointDistance(w, w.exact);
    }
    if ((best.size() < k || distance < best.back().distance) && RoundsCorrectly(f, a, w)) {
      const auto at =
          std::upper_bound(best.begin(), best.end(), distance,
                           [](double v, const NearMidpoint& b) { return v < b.distance; });
      best.insert(at, {distance, a});
      if (best.size() > k) best.pop_back();
    }
  }
  return best;
}

// The search over every selected function and distribution (one task each, any thread), printed
// as the C++ table tests/math_near_midpoints.inc in function order.
void PrintNearMidpoints(const std::vector<FunctionSpec>& fns, const Options& opt) {
  std::vector<std::pair<size_t, size_t>> jobs;
  for (size_t i = 0; i < fns.size(); ++i) {
    for (size_t d = 0; d < fns[i].dists.size(); ++d) jobs.push_back({i, d});
  }
  std::vector<std::vector<NearMidpoint>> found(jobs.size());
  std::atomic<size_t> next{0};
  auto work = [&] {
    Worker w;
    for (size_t j; (j = next.fetch_add(1)) < jobs.size();) {
      found[j] = SearchNearMidpoints(fns[jobs[j].first], jobs[j].second, opt.samples,
                                     opt.near_midpoints, opt.seed, w);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned i = 1; i < opt.threads; ++i) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  std::printf("// Generated by `math_accuracy --near-midpoints %" PRIu64 " --samples %" PRIu64
              " --seed %" PRIu64
              "` (tests/math_accuracy.cpp):\n// per function and argument "
              "distribution, the correctly rounded arguments whose exact result lies nearest\n// "
              "a rounding midpoint, with that distance in ulps. Do not edit; regenerate.\n"
              "// clang-format off\n",
              opt.near_midpoints, opt.samples, opt.seed);
  for (size_t j = 0; j < jobs.size(); ++j) {
    const FunctionSpec& f = fns[jobs[j].first];
    for (const NearMidpoint& m : found[j]) {
      std::printf("{\"%s\", %s, %s},  // %.2e ulp\n", f.name, Hex(m.args.x).c_str(),
                  Hex(m.args.y).c_str(), m.distance);
    }
  }
  std::printf("// clang-format on\n");
}

// Every near-midpoint argument of the selected functions rounds correctly; the failures are
// printed. Returns their number.
int CheckNearMidpoints(const std::vector<FunctionSpec>& fns) {
  Worker w;
  int wrong = 0, count = 0;
  for (const FunctionSpec& f : fns) {
    for (const NearMidpointCase& c : kNearMidpointCases) {
      if (f.name != std::string_view(c.function)) continue;
      ++count;
      if (!RoundsCorrectly(f, {c.x, c.y}, w)) {
        std::fprintf(stderr, "FAIL: %s misrounds %s, an argument near a rounding midpoint\n",
                     f.name, ArgsText(f, {c.x, c.y}).c_str());
        ++wrong;
      }
    }
  }
  std::printf("%d near-midpoint arguments (tests/math_near_midpoints.inc): %d misrounded\n", count,
              wrong);
  return wrong;
}

// ---------------------------------------------------------------------------------------------
// Self-check of the reference rounding: mpfr_get_d must round to nearest-even at the subnormal
// position, not at 53 bits.

bool CheckMpfrGetD() {
  struct Case {
    long mantissa, exponent;  // value mantissa·2^exponent
    double expected;
  };
  const Case cases[] = {
      {1, -1075, 0.0},                     // half the smallest subnormal: tie to even 0
      {3, -1075, 0x1p-1073},               // 1.5 subnormal units: tie to even 2 units
      {67, -1076, 17 * 0x1p-1074},         // 16.75 units → 17
      {5, -1076, 0x1p-1074},               // 1.25 units → 1
      {(1L << 53) - 1, -1075, 0x1p-1022},  // midpoint below DBL_MIN: tie to even DBL_MIN
      {(1L << 54) - 3, -1076, 0x1.ffffffffffffep-1023},  // 0.25 unit above: down
      {(1L << 54) - 1, 970, kInf},     // midpoint DBL_MAX–2^1024: tie to even, overflow
      {(1L << 55) - 3, 969, DBL_MAX},  // below that midpoint: DBL_MAX
  };
  mpfr_t t;
  mpfr_init2(t, kExactBits);
  bool ok = true;
  for (const Case& c : cases) {
    for (double sign : {1.0, -1.0}) {
      mpfr_set_si_2exp(t, c.mantissa, c.exponent, MPFR_RNDN);
      if (sign < 0) mpfr_neg(t, t, MPFR_RNDN);
      const double got = mpfr_get_d(t, MPFR_RNDN);
      if (!SameResult(got, sign * c.expected)) {
        std::fprintf(stderr, "math_accuracy: mpfr_get_d(%ld·2^%ld) = %a, expected %a\n", c.mantissa,
                     c.exponent, got, sign * c.expected);
        ok = false;
      }
    }
  }
  mpfr_clear(t);
  return ok;
}

// ---------------------------------------------------------------------------------------------
// Report.

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown CPU";
}

std::string Compiler() {
#if defined(__clang__)
  std::string version = __clang_version__;  // "14.0.6 " on Debian: trailing space
  while (!version.empty() && version.back() == ' ') version.pop_back();
  return "clang++ " + version;
#elif defined(__GNUC__)
  return std::string("g++ ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string Today() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

// part/total in percent, truncated (never rounded up to 100) with enough decimals that a single
// sample shows.
std::string Percent(uint64_t part, uint64_t total) {
  if (total == 0) return "-";
  if (part == total) return "100%";
  const int decimals = std::max(2, static_cast<int>(std::to_string(total).size()) - 3);
  if (total >= (1ULL << 32)) {  // part·100·10^decimals could overflow: plain double
    return std::to_string(100.0 * static_cast<double>(part) / static_cast<double>(total)) + "%";
  }
  uint64_t scale = 1;
  for (int i = 0; i < decimals; ++i) scale *= 10;
  const uint64_t fixed = part * 100 * scale / total;  // ≤ total² < 2^64
  std::string fraction = std::to_string(fixed % scale);
  fraction.insert(0, static_cast<size_t>(decimals) - fraction.size(), '0');
  return std::to_string(fixed / scale) + "." + fraction + "%";
}

std::string Ulps(double u) {
  if (std::isinf(u)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%#.3g", u);
  return buf;
}

struct Row {
  const FunctionSpec* f;
  TaskResult total;
};

void PrintTable(const std::vector<Row>& rows, bool markdown) {
  const char* head[] = {"function",
                        "samples",
                        "max ulp",
                        "at argument",
                        "correctly rounded",
                        "glibc max ulp",
                        "glibc correctly rounded"};
  if (markdown) {
    std::printf("| %s | %s | %s | %s | %s | %s | %s |\n", head[0], head[1], head[2], head[3],
                head[4], head[5], head[6]);
    std::printf("|---|---:|---:|---|---:|---:|---:|\n");
  } else {
    std::printf("%-8s %10s %9s  %-48s %14s %9s %14s\n", head[0], head[1], head[2], head[3], "CR",
                "glibc ulp", "glibc CR");
  }
  for (const Row& r : rows) {
    const Stats& o = r.total.ours;
    const Stats& g = r.total.glibc;
    const std::string at = ArgsText(*r.f, o.at_max);
    if (markdown) {
      std::printf("| %s | %" PRIu64 " | %s | `%s` | %s | %s | %s |\n", r.f->name, o.count,
                  Ulps(o.max_ulps).c_str(), at.c_str(),
                  Percent(o.correctly_rounded, o.count).c_str(), Ulps(g.max_ulps).c_str(),
                  Percent(g.correctly_rounded, g.count).c_str());
    } else {
      std::printf("%-8s %10" PRIu64 " %9s  %-48s %14s %9s %14s\n", r.f->name, o.count,
                  Ulps(o.max_ulps).c_str(), at.c_str(),
                  Percent(o.correctly_rounded, o.count).c_str(), Ulps(g.max_ulps).c_str(),
                  Percent(g.correctly_rounded, g.count).c_str());
    }
  }
}

void PrintFailures(const std::vector<Row>& rows, bool markdown) {
  bool any = false;
  for (const Row& r : rows) {
    for (const std::string& s : r.total.failures) {
      if (!any) {
        std::printf("\nInfinite errors (first %zu per function):\n%s", kMaxListedFailures,
                    markdown ? "\n" : "");
        any = true;
      }
      std::printf(markdown ? "- `%s`\n" : "  %s\n", s.c_str());
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Command line.

[[noreturn]] void Usage(const std::string& error) {
  if (!error.empty()) std::fprintf(stderr, "math_accuracy: %s\n", error.c_str());
  std::fprintf(stderr,
               "usage: math_accuracy [--samples N] [--threads T] [--seed S]\n"
               "                     [--function NAME[,NAME...]]... [--max-ulp B] [--markdown]\n"
               "                     [--near-midpoints K]\n"
               "  --samples N    random arguments per function (default 1e7), plus hard cases\n"
               "  --threads T    worker threads (default 2; results do not depend on T)\n"
               "  --seed S       random seed (default 1)\n"
               "  --function F   only these functions (repeatable, comma-separated)\n"
               "  --max-ulp B    exit 1 if a function's max error exceeds B ulps or an\n"
               "                 argument of tests/math_near_midpoints.inc is misrounded\n"
               "  --markdown     print a markdown table\n"
               "  --near-midpoints K  instead: per function and distribution, the K arguments\n"
               "                 of --samples random ones whose exact result lies nearest a\n"
               "                 rounding midpoint, as tests/math_near_midpoints.inc\n");
  std::exit(2);
}

double ParseNumber(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v >= 0) || v > 0x1p63) {
    Usage("bad value for " + option + ": " + text);
  }
  return v;
}

uint64_t ParseCount(const std::string& option, const std::string& text) {  // accepts 1e7
  const double v = ParseNumber(option, text);
  if (v != std::floor(v)) Usage("bad value for " + option + ": " + text);
  return static_cast<uint64_t>(v);
}

Options ParseOptions(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i], value;
    const size_t eq = arg.find('=');
    if (eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg.resize(eq);
    }
    const bool takes_value = arg != "--markdown" && arg != "--help" && arg != "-h";
    if (takes_value && eq == std::string::npos) {
      if (i + 1 >= argc) Usage(arg + " needs a value");
      value = argv[++i];
    }
    if (arg == "--samples") {
      opt.samples = ParseCount(arg, value);
    } else if (arg == "--threads") {
      opt.threads = static_cast<unsigned>(std::clamp<uint64_t>(ParseCount(arg, value), 1, 256));
    } else if (arg == "--seed") {
      char* end = nullptr;
      opt.seed = std::strtoull(value.c_str(), &end, 0);
      if (value.empty() || *end != '\0') Usage("bad value for --seed: " + value);
    } else if (arg == "--function") {
      for (size_t b = 0; b <= value.size();) {
        const size_t comma = std::min(value.find(',', b), value.size());
        if (comma > b) opt.functions.push_back(value.substr(b, comma - b));
        b = comma + 1;
      }
    } else if (arg == "--max-ulp") {
      opt.max_ulp = ParseNumber(arg, value);
    } else if (arg == "--markdown") {
      opt.markdown = true;
    } else if (arg == "--near-midpoints") {
      opt.near_midpoints = ParseCount(arg, value);
    } else if (arg == "--help" || arg == "-h") {
      Usage("");
    } else {
      Usage("unknown option " + arg);
    }
  }
  return opt;
}

std::vector<FunctionSpec> SelectFunctions(const Options& opt) {
  std::vector<FunctionSpec> all = MakeFunctions();
  if (opt.functions.empty()) return all;
  std::vector<FunctionSpec> chosen;
  for (const FunctionSpec& f : all) {
    if (std::find(opt.functions.begin(), opt.functions.end(), f.name) != opt.functions.end()) {
      chosen.push_back(f);
    }
  }
  for (const std::string& name : opt.functions) {
    const auto same = [&](const FunctionSpec& f) { return name == f.name; };
    if (std::none_of(all.begin(), all.end(), same)) {
      std::string names;
      for (const FunctionSpec& f : all) names += std::string(" ") + f.name;
      Usage("unknown function " + name + "; known:" + names);
    }
  }
  return chosen;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = ParseOptions(argc, argv);
  if (!CheckMpfrGetD()) return 2;
  if (opt.threads > 1 && !mpfr_buildopt_tls_p()) {
    std::fprintf(stderr, "math_accuracy: MPFR is not thread-safe here; use --threads 1\n");
    return 2;
  }
  const std::vector<FunctionSpec> fns = SelectFunctions(opt);
  if (opt.near_midpoints > 0) {
    PrintNearMidpoints(fns, opt);
    return 0;
  }
  std::vector<std::vector<Args>> hard;
  for (const FunctionSpec& f : fns) {
    if (f.arity == Arity::kBinary) {
      hard.push_back(BinaryHardCases(f.name));
    } else {
      std::vector<Args> h;
      for (double x : UnaryHardCases(f.name)) h.push_back({x, 0.0});
      hard.push_back(h);
    }
  }
  const std::vector<Task> tasks = MakeTasks(fns.size(), opt.samples);
  const std::vector<TaskResult> results = RunAll(fns, hard, tasks, opt);

  std::vector<Row> rows;
  for (const FunctionSpec& f : fns) rows.push_back({&f, {}});
  for (size_t i = 0; i < tasks.size(); ++i) {
    TaskResult& total = rows[tasks[i].function].total;
    total.ours.Merge(results[i].ours);
    total.glibc.Merge(results[i].glibc);
    for (const std::string& s : results[i].failures) {
      if (total.failures.size() < kMaxListedFailures) total.failures.push_back(s);
    }
  }

  std::printf("%s%s | %s | %s | MPFR %s at %ld bits | seed %" PRIu64 ", %" PRIu64
              " random samples per function + hard cases, %u threads\n",
              opt.markdown ? "" : "# ", Today().c_str(), CpuModel().c_str(), Compiler().c_str(),
              mpfr_get_version(), static_cast<long>(kExactBits), opt.seed, opt.samples,
              opt.threads);
  if (opt.markdown) std::printf("\n");
  PrintTable(rows, opt.markdown);
  PrintFailures(rows, opt.markdown);

  std::fflush(stdout);  // the table before any FAIL line on stderr
  // The near-midpoint arguments are a check (with --max-ulp, as ctest runs it), always printed.
  const int misrounded = CheckNearMidpoints(fns);
  int status = opt.max_ulp >= 0 && misrounded > 0 ? 1 : 0;
  if (opt.max_ulp >= 0) {
    for (const Row& r : rows) {
      if (r.total.ours.max_ulps > opt.max_ulp) {
        std::fprintf(stderr, "FAIL: %s max error %s ulp > %g at %s\n", r.f->name,
                     Ulps(r.total.ours.max_ulps).c_str(), opt.max_ulp,
                     ArgsText(*r.f, r.total.ours.at_max).c_str());
        status = 1;
      }
    }
  }
  return status;
}
