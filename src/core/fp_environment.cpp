#include "core/fp_environment.h"

#include <cfenv>

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#define OCEANREF_X86_64 1
#elif defined(__aarch64__)
#define OCEANREF_AARCH64 1
#else
#error "oceanref: the FP environment guard knows x86-64 and aarch64 only"
#endif

// core/math.h refuses -ffast-math and FLT_EVAL_METHOD != 0 at compile time (determinism contract).
#include "core/math.h"

namespace oceanref {

namespace {
#if OCEANREF_X86_64
constexpr std::uint64_t kFlushToZero = 0x8000;       // MXCSR bit 15
constexpr std::uint64_t kDenormalsAreZero = 0x0040;  // MXCSR bit 6
std::uint64_t read_control() {
  return _mm_getcsr();
}
void write_control(std::uint64_t v) {
  _mm_setcsr(static_cast<unsigned>(v));
}
#else
constexpr std::uint64_t kFlushToZero = std::uint64_t{1} << 24;  // FPCR.FZ
constexpr std::uint64_t kDenormalsAreZero = 0;                  // FPCR.FZ covers inputs
std::uint64_t read_control() {
  std::uint64_t v = 0;
  __asm__ __volatile__("mrs %0, fpcr" : "=r"(v));
  return v;
}
void write_control(std::uint64_t v) {
  __asm__ __volatile__("msr fpcr, %0" : : "r"(v));
}
#endif
}  // namespace

FpState current_fp_state() {
  const std::uint64_t raw = read_control();
  return {std::fegetround(), (raw & kFlushToZero) != 0,
          kDenormalsAreZero != 0 && (raw & kDenormalsAreZero) != 0, raw};
}

bool is_reference_fp_state(const FpState& s) {
  return s.rounding == FE_TONEAREST && !s.flush_to_zero && !s.denormals_are_zero;
}

std::string describe(const FpState& s) {
  const char* rounding = s.rounding == FE_TONEAREST    ? "round-to-nearest"
                         : s.rounding == FE_UPWARD     ? "round-upward"
                         : s.rounding == FE_DOWNWARD   ? "round-downward"
                         : s.rounding == FE_TOWARDZERO ? "round-toward-zero"
                                                       : "unknown rounding";
  return std::string(rounding) + ", FTZ " + (s.flush_to_zero ? "on" : "off") + ", DAZ " +
         (s.denormals_are_zero ? "on" : "off");
}

void set_fp_state(bool flush_to_zero, bool denormals_are_zero, int rounding) {
  std::uint64_t raw = read_control() & ~(kFlushToZero | kDenormalsAreZero);
  if (flush_to_zero) raw |= kFlushToZero;
  if (denormals_are_zero) raw |= kDenormalsAreZero;
  write_control(raw);
  std::fesetround(rounding);
}

ReferenceFpEnvironment::ReferenceFpEnvironment() : saved_(current_fp_state()) {
  if (!is_reference_fp_state(saved_)) set_fp_state(false, false, FE_TONEAREST);
}

ReferenceFpEnvironment::~ReferenceFpEnvironment() {
  if (!is_reference_fp_state(saved_)) {
    write_control(saved_.raw);
    std::fesetround(saved_.rounding);
  }
}

}  // namespace oceanref
