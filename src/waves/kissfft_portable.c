/* KissFFT (Debian's kissfft source package, fetched by tools/setup.sh; not committed) compiled
 * with double scalars and with the project's portable cosine and sine for its twiddle factors:
 * kiss_fft_alloc computes e^{±2πik/N} with cos() and sin(), and the platform's libm differs in
 * the last bit between CPUs and architectures (DESIGN.md, determinism contract). The system
 * headers come first, so the two macros below reach only KissFFT's own code. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Defined in waves/fft.cpp: oceanref::math::cos and oceanref::math::sin. */
double oceanref_kissfft_cos(double phase);
double oceanref_kissfft_sin(double phase);
#define cos oceanref_kissfft_cos
#define sin oceanref_kissfft_sin

#include "kiss_fft.c"
