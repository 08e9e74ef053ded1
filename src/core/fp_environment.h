// The floating-point environment the reference path assumes, and a guard that establishes it.
//
// Every result of oceanref is defined for IEEE-754 round-to-nearest-even with subnormals
// computed in full: no flush-to-zero (FTZ) and no denormals-are-zero (DAZ). A host program that
// links the library may have changed that state (e.g. a library built with -ffast-math links
// crtfastmath.o, which sets FTZ/DAZ at start-up), so each entry point of the pipeline holds a
// ReferenceFpEnvironment: it saves the caller's state, sets the reference state for the duration
// of the call and restores the caller's state afterwards. Threads started inside the call
// inherit the reference state (POSIX: a new thread inherits the creator's FP environment).
//
// The entry points that hold one: parse_scene/load_scene, make_sky, integrate,
// gauss_legendre/gauss_hermite, realize_ocean,
// synthesize_ocean, accumulate_foam, combine_on_footprint, slope_variance_budget (and
// slope_budget, unresolved_slope_variance), scene_render_job, render,
// probe_pixel, and the oceanref program's main. A host that calls lower-level functions directly
// should hold a ReferenceFpEnvironment itself (tests/test_portable_math.cpp shows the sequence).
#pragma once

#include <cstdint>
#include <string>

namespace oceanref {

// The parts of the FP control state that change results, as read from the CPU.
struct FpState {
  int rounding = 0;                 // FE_TONEAREST, FE_UPWARD, … (<cfenv>)
  bool flush_to_zero = false;       // x86 MXCSR.FZ / aarch64 FPCR.FZ
  bool denormals_are_zero = false;  // x86 MXCSR.DAZ (aarch64: FPCR.FZ covers inputs too)
  std::uint64_t raw = 0;            // MXCSR or FPCR, restored verbatim
};

FpState current_fp_state();
// Round to nearest, FTZ and DAZ off.
bool is_reference_fp_state(const FpState& s);
// "round-to-nearest, FTZ off, DAZ off" or what differs from it.
std::string describe(const FpState& s);

// Sets the reference state for its lifetime and restores the caller's state on destruction.
class ReferenceFpEnvironment {
 public:
  ReferenceFpEnvironment();
  ~ReferenceFpEnvironment();
  ReferenceFpEnvironment(const ReferenceFpEnvironment&) = delete;
  ReferenceFpEnvironment& operator=(const ReferenceFpEnvironment&) = delete;

 private:
  FpState saved_;
};

// For tests: puts the CPU into the given flush-to-zero / denormals-are-zero / rounding state.
void set_fp_state(bool flush_to_zero, bool denormals_are_zero, int rounding);

}  // namespace oceanref
