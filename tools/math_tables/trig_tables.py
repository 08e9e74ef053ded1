#!/usr/bin/python3
"""Tables and constants of src/core/math_trig.cpp (sin, cos, tan, atan, asin, acos, sinpi_dd).

Run:  /usr/bin/python3 tools/math_tables/trig_tables.py > /tmp/trig_tables.inc
and paste the output between the GENERATED markers of src/core/math_trig.cpp.

Every value is computed with mpmath at 1500 bits and rounded to nearest; a double-double entry
is hi = RN(v), lo = RN(v − hi).
"""
from mpmath import mp, mpf, pi, sin, cos, atan, floor, log, factorial

mp.prec = 1500

# Bits of 2/π for the Payne–Hanek reduction: 32-bit words of 2/π preceded by 64 zero bits, so
# that word n holds the bits of weight 2^−(32n−63) … 2^−(32n−32). 40 words reach the 1216th
# bit, enough for |x| up to DBL_MAX with 8 words (256 bits) read from word ⌊(e + 62)/32⌋.
TWO_OVER_PI_WORDS = 40
SIN_TABLE_STEP = 128  # sin/cos table at i/128, i = 0..101 (|r| ≤ π/4 + a little)
SIN_TABLE_SIZE = 102
ATAN_TABLE_STEP = 64  # atan table at i/64, i = 0..64
SINPI_SIN_TERMS = 15  # sin(πr) = r·Σ c_j r^{2j}, j < 15, |r| ≤ 1/4: truncation < 2^−120
SINPI_COS_TERMS = 16  # cos(πr) = Σ d_j r^{2j}, j < 16, |r| ≤ 1/4: truncation < 2^−118


def hexf(v):
    f = float(v)
    return "0.0" if f == 0.0 else f.hex()


def dd(v):
    hi = float(v)
    lo = float(v - mpf(hi))
    return hi, lo


def truncate_bits(v, bits):
    """v rounded toward zero to `bits` significant bits (so that k·v is exact for small k)."""
    e = int(floor(log(abs(v), 2)))
    scale = mpf(2) ** (bits - 1 - e)
    return floor(v * scale) / scale


def emit_constants():
    pio2 = pi / 2
    c1 = truncate_bits(pio2, 33)
    c2 = truncate_bits(pio2 - c1, 33)
    c3 = truncate_bits(pio2 - c1 - c2, 33)
    c4 = mpf(float(pio2 - c1 - c2 - c3))
    print("// π/2 = kPio2Part1 + kPio2Part2 + kPio2Part3 + kPio2Part4 (error < 2^−150); the first")
    print("// three have 33 bits so that k·kPio2PartN is exact for |k| < 2^20 (Cody–Waite).")
    for name, v in (("kPio2Part1", c1), ("kPio2Part2", c2), ("kPio2Part3", c3), ("kPio2Part4", c4)):
        print(f"constexpr double {name} = {hexf(v)};")
    print(f"constexpr double kTwoOverPi = {hexf(2 / pi)};  // RN(2/π)")
    for name, v, what in (("kPiDD", pi, "π"), ("kPio2DD", pi / 2, "π/2")):
        hi, lo = dd(v)
        print(f"constexpr dd::DD {name} = {{{hexf(hi)}, {hexf(lo)}}};  // {what}")
    print(f"constexpr double kPio4 = {hexf(pi / 4)};  // RN(π/4)")
    print(f"constexpr double kThreePio4 = {hexf(3 * pi / 4)};  // RN(3π/4)")


def emit_two_over_pi():
    pad = 64
    nbits = 32 * TWO_OVER_PI_WORDS - pad
    b = int(floor((2 / pi) * mpf(2) ** nbits))  # bits b_1 … b_nbits of 2/π
    words = []
    for n in range(TWO_OVER_PI_WORDS):
        # word n holds padded bit indices 32n … 32n+31, i.e. 2/π bits j = 32n−63 … 32n−32
        top = 32 * n - pad + 32  # last bit j of the word
        if top <= 0:
            words.append(0)
        else:
            words.append((b >> (nbits - top)) & 0xFFFFFFFF)
    print("// Payne–Hanek: 2/π in 32-bit words after 64 zero bits; word n holds the bits of weight")
    print("// 2^−(32n−63) … 2^−(32n−32) of 2/π, most significant first.")
    print(f"constexpr std::uint32_t kTwoOverPiBits[{TWO_OVER_PI_WORDS}] = {{")
    for n in range(0, TWO_OVER_PI_WORDS, 4):
        print("    " + " ".join(f"0x{w:08X}u," for w in words[n:n + 4]))
    print("};")


def emit_sin_cos_table():
    print(f"// sin and cos at a_i = i/{SIN_TABLE_STEP}, i = 0..{SIN_TABLE_SIZE - 1}, as double-doubles.")
    print("struct SinCosEntry {")
    print("  double sin_hi, sin_lo, cos_hi, cos_lo;")
    print("};")
    print(f"constexpr SinCosEntry kSinCosTable[{SIN_TABLE_SIZE}] = {{")
    for i in range(SIN_TABLE_SIZE):
        a = mpf(i) / SIN_TABLE_STEP
        sh, sl = dd(sin(a))
        ch, cl = dd(cos(a))
        print(f"    {{{hexf(sh)}, {hexf(sl)}, {hexf(ch)}, {hexf(cl)}}},")
    print("};")


def emit_atan_table():
    n = ATAN_TABLE_STEP
    print(f"// atan(i/{n}), i = 0..{n}, as double-doubles.")
    print(f"constexpr dd::DD kAtanTable[{n + 1}] = {{")
    for i in range(n + 1):
        hi, lo = dd(atan(mpf(i) / n))
        print(f"    {{{hexf(hi)}, {hexf(lo)}}},")
    print("};")


def emit_kernel_coefficients():
    print("// Taylor coefficients of the short kernels (|t| ≤ 1/256 for sin/cos, ≤ 1/128 for atan).")
    for name, v, what in (
        ("kInv6", mpf(1) / 6, "1/3!"),
        ("kInv120", mpf(1) / 120, "1/5!"),
        ("kInv5040", mpf(1) / 5040, "1/7!"),
        ("kInv24", mpf(1) / 24, "1/4!"),
        ("kInv720", mpf(1) / 720, "1/6!"),
        ("kInv3", mpf(1) / 3, "1/3"),
        ("kInv5", mpf(1) / 5, "1/5"),
        ("kInv7", mpf(1) / 7, "1/7"),
        ("kInv9", mpf(1) / 9, "1/9"),
    ):
        print(f"constexpr double {name} = {hexf(v)};  // {what}")


def emit_sinpi_coefficients():
    print("// sinpi_dd: Taylor coefficients in r² of sin(πr)/r, c_j = (−1)^j π^(2j+1)/(2j+1)!, and of")
    print("// cos(πr), d_j = (−1)^j π^(2j)/(2j)!, as double-doubles.")
    print(f"constexpr dd::DD kSinPiCoeff[{SINPI_SIN_TERMS}] = {{")
    for j in range(SINPI_SIN_TERMS):
        hi, lo = dd((-1) ** j * pi ** (2 * j + 1) / factorial(2 * j + 1))
        print(f"    {{{hexf(hi)}, {hexf(lo)}}},")
    print("};")
    print(f"constexpr dd::DD kCosPiCoeff[{SINPI_COS_TERMS}] = {{")
    for j in range(SINPI_COS_TERMS):
        hi, lo = dd((-1) ** j * pi ** (2 * j) / factorial(2 * j))
        print(f"    {{{hexf(hi)}, {hexf(lo)}}},")
    print("};")


if __name__ == "__main__":
    print("// ---- generated by: /usr/bin/python3 tools/math_tables/trig_tables.py ----")
    emit_constants()
    emit_two_over_pi()
    emit_sin_cos_table()
    emit_atan_table()
    emit_kernel_coefficients()
    emit_sinpi_coefficients()
    print("// ---- end of generated tables ----")
