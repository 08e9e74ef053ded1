// The determinism guards (core/fp_environment.h, the build flags) and published values of the
// portable elementary functions (core/math.h). Their accuracy against MPFR is measured by
// tests/math_accuracy.cpp (ctest `math_accuracy`, tools/math_accuracy.sh for the full run).
#include <doctest/doctest.h>

#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/fp_environment.h"
#include "core/math.h"
#include "io/sha256.h"
#include "raster/renderer.h"
#include "scene/scene.h"

using namespace oceanref;

namespace {
// a·b + c for inputs the compiler cannot see: a contracting build computes it with one rounding.
double product_plus(double a, double b, double c) {
  return a * b + c;
}
volatile double g_one = 1.0;
}  // namespace

TEST_CASE("no contraction: a·b + c is rounded twice, as -ffp-contract=off promises") {
  // (1 + 2⁻³⁰)(1 − 2⁻³⁰) = 1 − 2⁻⁶⁰ exactly, which rounds to 1: the sum is then 0 unfused and
  // −2⁻⁶⁰ fused.
  const double a = g_one + 0x1p-30;
  const double b = g_one - 0x1p-30;
  CHECK(product_plus(a, b, -g_one) == 0.0);
}

TEST_CASE("published values: huge-argument reduction (Ng 1992) and exact cases") {
  // sin and cos of 10²² (K. C. Ng, Argument reduction for huge arguments, Sun 1992): the
  // correctly rounded doubles of −0.852200849767188801772…, 0.523214785395138945497….
  CHECK(math::sin(1e22) == -0x1.b453ab76bf397p-1);
  CHECK(math::cos(1e22) == 0x1.0be2cef01c8f4p-1);
  // sin(π as a double) = π − double(π) = 1.2246467991473532e−16 (correctly rounded).
  CHECK(math::sin(0x1.921fb54442d18p+1) == 0x1.1a62633145c07p-53);
  // Values that are exact.
  CHECK(math::exp(0.0) == 1.0);
  CHECK(math::log(1.0) == 0.0);
  CHECK(math::log10(1.0) == 0.0);
  CHECK(math::log10(1e22) == 22.0);
  CHECK(math::pow(2.0, 10.0) == 1024.0);
  CHECK(math::pow(-3.0, 3.0) == -27.0);
  CHECK(math::hypot(3.0, 4.0) == 5.0);
  CHECK(math::cbrt(-27.0) == -3.0);
  CHECK(math::erfc(0.0) == 1.0);
  CHECK(math::lgamma(1.0) == 0.0);
  CHECK(math::lgamma(2.0) == 0.0);
  CHECK(math::tgamma(5.0) == 24.0);
  CHECK(math::tgamma(21.0) == 2432902008176640000.0);
  CHECK(math::atan2(0.0, -1.0) == 0x1.921fb54442d18p+1);
  // On the diagonals the ratio is 1 at every scale: the correctly rounded π/4 and 3π/4.
  for (const double x : {1.0, 3.0e300, 2.0e-300, 5.0e-324}) {
    CAPTURE(x);
    CHECK(math::atan2(x, x) == 0x1.921fb54442d18p-1);
    CHECK(math::atan2(x, -x) == 0x1.2d97c7f3321d2p+1);
    CHECK(math::atan2(-x, -x) == -0x1.2d97c7f3321d2p+1);
  }
  CHECK(std::signbit(math::atan2(-0.0, 1.0)));
  // Classical constants, correctly rounded.
  CHECK(math::exp(1.0) == 0x1.5bf0a8b145769p+1);
  CHECK(math::log(2.0) == 0x1.62e42fefa39efp-1);
  CHECK(4.0 * math::atan(1.0) == 0x1.921fb54442d18p+1);
  CHECK(math::erf(1.0) == 0x1.af767a741088bp-1);  // 0.8427007929497149
}

TEST_CASE("exp near 0: the correctly rounded 1 + x + x²/2 on both sides of the midpoints") {
  // For |x| <= 2^-53, e^x = 1 + x + x²/2 + …: the neighbours of 1 are 1 - 2^-53 and 1 + 2^-52,
  // the midpoints 1 - 2^-54 and 1 + 2^-53 (the random arguments of tests/math_accuracy.cpp never
  // come this close to 0).
  CHECK(math::exp(0x1.8p-54) == 1.0);             // 1 + 1.5·2^-54: below the upper midpoint
  CHECK(math::exp(-0x1.8p-54) == 1.0 - 0x1p-53);  // 1 - 1.5·2^-54: below the lower midpoint
  CHECK(math::exp(0x1p-53) == 1.0 + 0x1p-52);     // 2^-107 above the upper midpoint
  CHECK(math::exp(-0x1p-54) == 1.0);              // 2^-109 above the lower midpoint
  CHECK(math::exp(-0x1.fffffffffffffp-54) == 1.0 - 0x1p-53);
  CHECK(math::exp(0x1p-60) == 1.0);
  CHECK(math::exp(-0x1p-60) == 1.0);
  CHECK(math::exp(0x1p-1074) == 1.0);
  CHECK(math::exp(-0.0) == 1.0);
}

TEST_CASE("sincos equals sin and cos bit for bit") {
  for (double x = -50.0; x < 50.0; x += 0.37) {
    const math::SinCos s = math::sincos(x);
    CHECK(std::bit_cast<std::uint64_t>(s.sin) == std::bit_cast<std::uint64_t>(math::sin(x)));
    CHECK(std::bit_cast<std::uint64_t>(s.cos) == std::bit_cast<std::uint64_t>(math::cos(x)));
  }
}

// IEEE 754-2019 §6.2: an operation on a signalling NaN delivers a quiet NaN (as glibc's libm
// does); passing the argument back unchanged would hand a backend a bit pattern no arithmetic
// makes. The NaN is built at run time so that no call is folded at compile time.
TEST_CASE("a signalling NaN comes back quiet from every function") {
  volatile std::uint64_t bits = 0x7ff0000000000001u;  // exponent all ones, quiet bit clear
  const double snan = std::bit_cast<double>(bits + 0);
  REQUIRE(std::isnan(snan));
  REQUIRE((std::bit_cast<std::uint64_t>(snan) & 0x0008000000000000u) == 0);
  const auto quiet = [](double y) {
    return std::isnan(y) && (std::bit_cast<std::uint64_t>(y) & 0x0008000000000000u) != 0;
  };
  using Unary = double (*)(double);
  const std::vector<std::pair<const char*, Unary>> unary{
      {"exp", math::exp},      {"expm1", math::expm1}, {"log", math::log},
      {"log1p", math::log1p},  {"log10", math::log10}, {"sin", math::sin},
      {"cos", math::cos},      {"tan", math::tan},     {"atan", math::atan},
      {"asin", math::asin},    {"acos", math::acos},   {"sinh", math::sinh},
      {"cosh", math::cosh},    {"tanh", math::tanh},   {"cbrt", math::cbrt},
      {"erf", math::erf},      {"erfc", math::erfc},   {"lgamma", math::lgamma},
      {"tgamma", math::tgamma}};
  for (const auto& entry : unary) {
    INFO(entry.first);
    CHECK(quiet(entry.second(snan)));
    CHECK(quiet(entry.second(-snan)));
  }
  CHECK(quiet(math::sincos(snan).sin));
  CHECK(quiet(math::sincos(snan).cos));
  CHECK(quiet(math::pow(snan, 2.0)));
  CHECK(quiet(math::pow(2.0, snan)));
  CHECK(quiet(math::atan2(snan, 1.0)));
  CHECK(quiet(math::atan2(1.0, snan)));
  CHECK(quiet(math::hypot(snan, 1.0)));
  CHECK(quiet(math::hypot(1.0, snan)));
}

namespace {
// A small scene whose samples reach the subnormal range (grazing sun: the sun's transmittance
// e^{−τ} underflows). Parsed text → JSON numbers before the test changes the rounding mode (the
// host's own strtod follows its rounding mode; that is the host's business).
const nlohmann::json kSmallScene = nlohmann::json::parse(R"({"seed": 9, "time": 3.0,
      "waves": {"spectrum": {"model": "jonswap", "wind_speed": 12, "fetch": 80000},
                "cascades": {"sizes": [90, 21]}, "resolution": 32, "choppiness": -0.9},
      "camera": {"position": [0, 3, 0], "look_at": [2, 1, 50]},
      "grid": {"columns": 64, "rows": 64},
      "atmosphere": {"sun_zenith_deg": 89.5, "sun_azimuth_deg": 80, "turbidity": 9},
      "shading": {"whitecaps": true, "accuracy": "fast", "sky_order": 3, "sun_order": 1},
      "render": {"width": 32, "height": 18, "samples_per_pixel": 1}})");

// The library calls a host makes to render it, and the SHA-256 of the double radiance.
std::string small_render_hash() {
  const Scene scene = parse_scene(kSmallScene);
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const RenderJob job = scene_render_job(scene, ocean, 2);
  const RenderedImage image = render(job, unresolved_slope_variance(job, scene.waves));
  std::vector<std::uint8_t> bytes;
  for (const Vec3& v : image.radiance) {
    for (const double c : v) append_bytes(bytes, c);
  }
  return sha256_hex(bytes);
}
}  // namespace

TEST_CASE("a host's flush-to-zero, denormals-are-zero and rounding mode change nothing") {
  const std::string reference = small_render_hash();
  REQUIRE(is_reference_fp_state(current_fp_state()));
  struct Restore {  // the other tests run in the reference state whatever happens here
    ~Restore() { set_fp_state(false, false, FE_TONEAREST); }
  } restore;
  // The state a -ffast-math host (crtfastmath) or a careless library leaves behind.
  set_fp_state(true, true, FE_UPWARD);
  const FpState host = current_fp_state();
  REQUIRE(host.flush_to_zero);
  REQUIRE(host.rounding == FE_UPWARD);
  // The test can see the difference: under FTZ a subnormal result becomes 0.
  volatile double tiny = 0x1p-1030;
  volatile double scaled = tiny * 0.5;
  set_fp_state(false, false, FE_TONEAREST);
  CHECK(scaled == 0.0);
  set_fp_state(true, true, FE_UPWARD);
  const std::string under_host_state = small_render_hash();
  const FpState after = current_fp_state();
  set_fp_state(false, false, FE_TONEAREST);
  CHECK(under_host_state == reference);
  // The caller's state is restored after each call.
  CHECK(after.flush_to_zero);
  CHECK(after.rounding == FE_UPWARD);
  CHECK(after.raw == host.raw);
}

TEST_CASE("the reference state is described for --version and error messages") {
  CHECK(describe(current_fp_state()) == "round-to-nearest, FTZ off, DAZ off");
}
