#!/usr/bin/python3
"""Tables and constants of src/core/math_exp_log.cpp (Tang's table-driven exp and log).

Run:  /usr/bin/python3 tools/math_tables/exp_log_tables.py > /tmp/exp_log_tables.inc
and paste the output between the GENERATED markers of src/core/math_exp_log.cpp.

Every value is computed with mpmath at 300 bits and rounded to nearest; a double-double entry
is hi = RN(v), lo = RN(v − hi).
"""
from mpmath import mp, mpf, log, exp, ln2, floor

mp.prec = 300


def hexf(v):
    f = float(v)
    if f == 0.0:
        return "0.0"
    mant, exp = f.hex().split("p")
    mant = mant.rstrip("0").rstrip(".")
    return f"{mant}p{exp}"


def dd(v):
    hi = float(v)
    lo = float(v - mpf(hi))
    return hi, lo


def veltkamp_split(a):
    """Dekker/Veltkamp split of the double a, computed with IEEE doubles exactly as dd::split does."""
    t = 134217729.0 * a
    hi = t - (t - a)
    return hi, a - hi


def round_bits(v, bits):
    """v rounded to nearest to `bits` significant bits."""
    e = int(floor(log(abs(v), 2)))
    scale = mpf(2) ** (bits - 1 - e)
    return mp.nint(v * scale) / scale


def truncate_bits(v, bits):
    """v rounded toward zero to `bits` significant bits (so that k·v is exact for small k)."""
    e = int(floor(log(abs(v), 2)))
    scale = mpf(2) ** (bits - 1 - e)
    return floor(v * scale) / scale


def emit_exp():
    n = 4096
    step = ln2 / n
    l1 = truncate_bits(step, 30)
    l2 = truncate_bits(step - l1, 30)
    l3 = mpf(float(step - l1 - l2))
    l4 = mpf(float(step - l1 - l2 - l3))
    print("// exp: 2^(k/4096) = 2^q · T1[j1] · T2[j2] with k = 4096·q + 64·j1 + j2.")
    print(f"constexpr double kInvStep = {hexf(n / ln2)};  // 4096/ln 2")
    print("// ln2/4096 = kStep1 + kStep2 + kStep3 + kStep4; kStep1 and kStep2 have 30 bits so that")
    print("// k·kStep1 and k·kStep2 are exact for |k| < 2^23.")
    for name, v in (("kStep1", l1), ("kStep2", l2), ("kStep3", l3), ("kStep4", l4)):
        print(f"constexpr double {name} = {hexf(v)};")
    for name, den in (("kExp2Coarse", 64), ("kExp2Fine", 4096)):
        what = "2^(j/64)" if den == 64 else "2^(j/4096)"
        print(f"// {name}[j] = {what}, j = 0..63, as double-double {{hi, lo}}.")
        print(f"constexpr dd::DD {name}[64] = {{")
        for j in range(64):
            hi, lo = dd(mpf(2) ** (mpf(j) / den))
            print(f"    {{{hexf(hi)}, {hexf(lo)}}},")
        print("};")
    for name, den in (("kExp2CoarseSplit", 64), ("kExp2FineSplit", 4096)):
        print(f"// {name}[j] = dd::split(hi of the table above), precomputed (bit-identical).")
        print(f"constexpr dd::DD {name}[64] = {{")
        for j in range(64):
            hi, lo = veltkamp_split(dd(mpf(2) ** (mpf(j) / den))[0])
            print(f"    {{{hexf(hi)}, {hexf(lo)}}},")
        print("};")


def emit_exp_fast():
    n = 128
    step = ln2 / n
    l1 = truncate_bits(step, 35)
    l2 = truncate_bits(step - l1, 35)
    l3 = mpf(float(step - l1 - l2))
    print("// exp fast path: 2^(k/128) = 2^q · kExpFast[j] with k = 128·q + j (Tang 1989, one table).")
    print(f"constexpr double kInvStepFast = {hexf(n / ln2)};  // 128/ln 2")
    print("// ln2/128 = kFastStep1 + kFastStep2 + kFastStep3 (+ < 2^-130); kFastStep1 and kFastStep2")
    print("// have 35 bits so that k·kFastStep1 and k·kFastStep2 are exact for |k| < 2^18.")
    for name, v in (("kFastStep1", l1), ("kFastStep2", l2), ("kFastStep3", l3)):
        print(f"constexpr double {name} = {hexf(v)};")
    print("// kExpFast[j] = {hi, mid}: hi = 2^(j/128) rounded to 26 bits (so hi·y is exact for a")
    print("// 27-bit y), mid = RN(2^(j/128) − hi); |2^(j/128) − hi − mid| < 2^−79.")
    print("constexpr dd::DD kExpFast[128] = {")
    for j in range(n):
        v = mpf(2) ** (mpf(j) / n)
        hi = round_bits(v, 26)
        mid = mpf(float(v - hi))
        assert abs(v - hi - mid) < mpf(2) ** -79 and abs(mid) <= mpf(2) ** -26
        print(f"    {{{hexf(hi)}, {hexf(mid)}}},")
    print("};")


def emit_log():
    ln2_hi = truncate_bits(ln2, 42)
    ln2_mid = mpf(float(ln2 - ln2_hi))
    ln2_lo = mpf(float(ln2 - ln2_hi - ln2_mid))
    print("// ln 2 = kLn2Hi + kLn2Mid + kLn2Lo; kLn2Hi has 42 bits so that e·kLn2Hi is exact for")
    print("// |e| < 2^11.")
    for name, v in (("kLn2Hi", ln2_hi), ("kLn2Mid", ln2_mid), ("kLn2Lo", ln2_lo)):
        print(f"constexpr double {name} = {hexf(v)};")
    print("// log, accurate path and log_dd: for i = 0..128, invc = RN(1/(1 + i/128)) and")
    print("// logc = −ln(invc) as double-double; entry 128 is {0.5, 0, 0}: the caller adds 1 to the")
    print("// exponent instead (ln x near 1 stays relative-accurate on both sides of 1).")
    print("struct LogEntry {")
    print("  double invc, logc_hi, logc_lo;")
    print("};")
    print("constexpr LogEntry kLogAccurate[129] = {")
    for i in range(129):
        if i == 128:
            print("    {0x1p-1, 0.0, 0.0},")
            continue
        invc = float(1 / (1 + mpf(i) / 128))
        hi, lo = dd(-log(mpf(invc)))
        print(f"    {{{hexf(invc)}, {hexf(hi)}, {hexf(lo)}}},")
    print("};")
    print("// log, fast path: for i = 0..256, c = 1 + i/256 and invc = round(512/c)/512 (at most 10 bits, so that")
    print("// m·invc − 1 is exact, see reduce_log), logc = −ln(invc) as double-double; entry 256 is")
    print("// {0.5, 0, 0}: the caller adds 1 to the exponent instead (ln x near 1 stays relative-accurate")
    print("// on both sides of 1). Over each entry's interval |m·invc − 1| < 2^-8.4.")
    print("constexpr LogEntry kLogFast[257] = {")
    rmax = mpf(0)
    for i in range(257):
        if i == 256:
            invc = mpf(1) / 2
            lo_m, hi_m = 2 - mpf(1) / 512, mpf(2)
            rmax = max(rmax, abs(lo_m * invc - 1), abs(hi_m * invc - 1))
            print("    {0x1p-1, 0.0, 0.0},")
            continue
        c = 1 + mpf(i) / 256
        invc = mp.nint(512 / c) / 512
        lo_m = max(mpf(1), c - mpf(1) / 512)
        hi_m = c + mpf(1) / 512
        rmax = max(rmax, abs(lo_m * invc - 1), abs(hi_m * invc - 1))
        hi, lo = dd(-log(invc))
        print(f"    {{{hexf(invc)}, {hexf(hi)}, {hexf(lo)}}},")
    print("};")
    assert rmax < mpf(2) ** -8.4, rmax


def emit_coefficients():
    print("// Double-double constants of the accurate paths.")
    for k in (3, 5, 6):
        hi, lo = dd(mpf(1) / k)
        print(f"constexpr dd::DD kInv{k} = {{{hexf(hi)}, {hexf(lo)}}};  // 1/{k}")
    hi, lo = dd(1 / log(10))
    print(f"constexpr dd::DD kInvLn10 = {{{hexf(hi)}, {hexf(lo)}}};  // 1/ln 10")


if __name__ == "__main__":
    print("// ---- generated by: /usr/bin/python3 tools/math_tables/exp_log_tables.py ----")
    emit_exp()
    emit_exp_fast()
    emit_log()
    emit_coefficients()
    print("// ---- end of generated tables ----")
