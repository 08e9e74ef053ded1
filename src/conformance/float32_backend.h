// The float32 example backend: the worked example of a backend checked against oceanref. It
// computes the raw wave fields of every cascade entirely in float32, as a GPU compute shader
// would: h(k, t) = ½h0(k)e^{−iωt} + ½h0(−k)* e^{iωt} (Gamper eq. 4.7) with float phases and
// float complex products, the field multipliers of waves/fields.h rounded to float, and an FFTW
// single-precision inverse 2-D transform (FFTW_BACKWARD: e^{+i…}, unnormalized, the convention of
// waves/fft.h). Its fields are compared with oceanref's double fields (rounded to float32, as
// `oceanref fields` writes them) by the compare library with reference/profiles/fields_float32.json
// (tests/test_conformance.cpp, `oceanref bench float32`).
#pragma once

#include <vector>

#include "io/exr.h"
#include "waves/fields.h"
#include "waves/ocean.h"

namespace oceanref {

// Deliberate defects, to show that the shipped profile catches real bugs.
enum class Float32Defect {
  none,
  drop_conjugate_term,  // h = ½h0(k)e^{−iωt} only: not Hermitian (a classic port bug)
  half_float_phase,     // ωt rounded to float16-like precision (11 significant bits)
};

// One field of one pattern at time t, row-major [n·N + m] like CascadeFields::values.
std::vector<float> float32_field(const PatternSpectrum& s, double time, Field field,
                                 Float32Defect defect = Float32Defect::none);

// The raw fields of every cascade as EXR parts: per cascade i one part "c<i>" on N_h with the
// fields of the high-resolution grid and, when N_l < N_h, one part "c<i>.low" on N_l with η, D_x,
// D_z; channels "c<i>.<field>" (waves/fields.h kFieldNames), sample (m, n) at x = m L/N,
// z = n L/N.
std::vector<ExrPart> float32_fields_parts(const Ocean& ocean, double time,
                                          Float32Defect defect = Float32Defect::none);
// oceanref's double fields in the same layout, rounded to float32: the golden side.
std::vector<ExrPart> reference_fields_parts(const Ocean& ocean, double time, int threads);

}  // namespace oceanref
