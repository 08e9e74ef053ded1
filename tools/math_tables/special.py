#!/usr/bin/python3
"""Polynomial tables for src/core/math_special.cpp (erf, erfc, lgamma, tgamma).

Run:  /usr/bin/python3 tools/math_tables/special.py > /tmp/special_tables.inc   (about 30 s)
and paste the output between the "BEGIN GENERATED TABLES" / "END GENERATED TABLES" markers of
src/core/math_special.cpp. Needs Debian's python3-mpmath. Progress goes to stderr.
tests/math_tables_check.cpp repeats each piece's acceptance test (below) against MPFR in ctest.

Every table is a list of pieces.  A piece approximates f(centre + t) for t in [t_min, t_max] by
p(t) = c_0 + c_1 t + ... + c_n t^n, obtained by interpolation at Chebyshev nodes (near-minimax,
Trefethen, "Approximation Theory and Approximation Practice", ch. 16) at 120 digits.  The first
n_dd coefficients are stored as double-doubles (hi, lo), the others as doubles; n_dd is chosen
so that the tail c_{n_dd} t^{n_dd} + ... evaluated in plain double contributes an error below
2^-65 relative to the result.  For pieces around a zero of f ("zero pieces") c_0 = 0 exactly, so
the result t * (c_1 + ...) keeps a small relative error near the zero.
"""
import math
import sys
import mpmath as mp
from mpmath import mpf

mp.mp.dps = 120
TARGET = mpf(2) ** -80  # relative approximation error of every piece (exact coefficients)
TAIL = mpf(2) ** -12  # tail (evaluated in double) relative to the result


def hexf(v):
    """A double as a C++ hex-float literal."""
    d = float(v)
    if d == 0.0:
        return "0.0" if mp.sign(v) >= 0 or d == 0 else "-0.0"
    return d.hex().replace("0x1.0000000000000p", "0x1p")


def split_dd(v):
    hi = float(v)
    lo = float(v - mpf(hi))
    return hi, lo


def cheb_nodes(a, b, m):
    return [(a + b) / 2 + (b - a) / 2 * mp.cos(mp.pi * (j + mpf(1) / 2) / m) for j in range(m)]


def fit(g, a, b, n):
    """Monomial coefficients (in t) of the degree-n interpolant of g at Chebyshev nodes."""
    h = max(abs(a), abs(b))
    ts = cheb_nodes(a, b, n + 1)
    A = mp.matrix(n + 1, n + 1)
    y = mp.matrix(n + 1, 1)
    for i, t in enumerate(ts):
        s = t / h
        for j in range(n + 1):
            A[i, j] = s ** j
        y[i] = g(t)
    d = mp.lu_solve(A, y)
    return [d[j] / h ** j for j in range(n + 1)]


def rounded(coefs, n_dd):
    out = []
    for i, c in enumerate(coefs):
        if i < n_dd:
            hi, lo = split_dd(c)
            out.append(mpf(hi) + mpf(lo))
        else:
            out.append(mpf(float(c)))
    return out


def peval(coefs, t):
    r = mpf(0)
    for c in reversed(coefs):
        r = r * t + c
    return r


def make_piece(f, centre, a, b, zero=False, max_deg=40, name=""):
    """Fit f(centre + t), t in [a, b]; returns (n_dd, coefs, err)."""
    g = (lambda t: f(t) / t) if zero else f
    samples = [a + (b - a) * mpf(k) / 127 for k in range(128)]
    if zero:
        samples = [s for s in samples if s != 0]
    fvals = [f(t) for t in samples]
    for n in range(5, max_deg + 1):
        if zero and n % 2 == 0:
            continue  # an even number of nodes keeps t = 0 (where f(t)/t is 0/0) off the grid
        m = n  # degree of the fitted g
        coefs = fit(g, a, b, m)
        if zero:
            coefs = [mpf(0)] + coefs
        # n_dd: leading coefficients kept in double-double
        h = max(abs(a), abs(b))
        fmin = min(abs(v) / (abs(s) if zero else 1) for v, s in zip(fvals, samples))
        n_dd = len(coefs)
        for k in range(1 if zero else 0, len(coefs) + 1):
            tail = sum(abs(coefs[i]) * h ** (i - (1 if zero else 0)) for i in range(k, len(coefs)))
            if tail <= TAIL * fmin:
                n_dd = k
                break
        err = max(abs(peval(coefs, s) - v) / abs(v) for s, v in zip(samples, fvals))
        if err <= TARGET:
            rc = rounded(coefs, n_dd)
            err = max(abs(peval(rc, s) - v) / abs(v) for s, v in zip(samples, fvals))
            assert err < mpf(2) ** -64, (name, err)
            err_exact = max(abs(peval(coefs, s) - v) / abs(v) for s, v in zip(samples, fvals))
            return n_dd, rc, err, coefs, (err_exact, min(abs(v) for v in fvals), a, b)
    raise RuntimeError("no fit for %s [%s, %s]" % (name, a, b))


def emit_table(name, pieces, comment):
    """pieces: list of dicts with lo (x bound), centre triple, n_dd, coefs."""
    print("// %s" % comment)
    print("constexpr Piece k%sPieces[] = {" % name)
    off = 0
    for p in pieces:
        deg = len(p["coefs"]) - 1
        c = p["centre"]
        print("    {%s, %s, %s, %s, %s, %d, %d, %d},  // max rel. err %.1e" %
              (hexf(p["lo"]), hexf(p["hi"]), hexf(c[0]), hexf(c[1]), hexf(c[2]), p["n_dd"], deg,
               off, float(p["err"])))
        off += deg + 1 + p["n_dd"]
    print("};")
    print("constexpr double k%sCoefs[] = {" % name)
    for p in pieces:
        vals = []
        for i, c in enumerate(p["coefs"]):
            if i < p["n_dd"]:
                hi, lo = split_dd(c)
                vals += [hexf(hi), hexf(lo)]
            else:
                vals.append(hexf(c))
        print("    " + ", ".join(vals) + ",")
    print("};")
    print()


U = mpf(2) ** -53  # unit roundoff


def horner_bound(coefs, h):
    """(bound on |computed - exact|, bound on |value|) of plain double Horner of
    sum coefs[j] v^j for |v| <= h, v an exact double (Higham, "Accuracy and Stability of
    Numerical Algorithms", 5.1: running bounds with magnitudes A_j >= |sum_{k>=j} c_k v^(k-j)|)."""
    A = mpf(0)
    E = mpf(0)
    for j in range(len(coefs) - 1, -1, -1):
        prod = h * (A + E)  # |v * computed acc|
        A_new = abs(coefs[j]) + h * A
        if j < len(coefs) - 1:
            E = h * E + U * prod + U * (A_new + h * E + U * prod)
        A = A_new
    return E, A


def fast_eval_bound(p):
    """Bound on the relative error |computed - f| / |f| of eval_fast (math_special.cpp) on a piece
    of a non-zero function, |t| <= h: head + t^n_dd * tail, with
      approximation: 4 x the sampled max of |p_exact - f|/|f| (p_exact: the unrounded
        interpolant, ~2^-80, far below the rest) + sum |stored c_i - c_i| h^i / min|f| (rigorous);
      tail (double): even and odd parts by Horner in the computed t2 = t^2 (1 + d), |d| <= u,
        plus the change |E(t2) - E(t^2)| <= sum |e_j| j u h^(2j) (1+u)^j, then t*odd and the sum
        rounded; t^n_dd by n_dd - 1 roundings and the product t^n_dd * tail by one;
      head (double-double Horner from c_{n_dd-1}): D_i <= h D_{i+1} + 8 u^2 (A_i + h D_{i+1}
        + h A_{i+1}) (two exact products and sums, three roundings of terms below u |acc|);
      final DWPlusFP: 2 u^2 |result|."""
    err_exact, fmin, a, b = p["info"]
    h = max(abs(a), abs(b))
    coefs = rounded(p["coefs"], p["n_dd"])
    n_dd, deg = p["n_dd"], len(coefs) - 1
    tail = coefs[n_dd:]
    assert len(tail) >= 2
    h2 = h * h * (1 + U)
    even, odd = tail[0::2], tail[1::2]
    E_e, A_e = horner_bound(even, h2)
    E_o, A_o = horner_bound(odd, h2)
    E_e += sum(abs(c) * j * U * (h * h) ** j * (1 + U) ** j for j, c in enumerate(even))
    E_o += sum(abs(c) * j * U * (h * h) ** j * (1 + U) ** j for j, c in enumerate(odd))
    prod = h * (A_o + E_o)
    E_t = E_e + h * E_o + U * prod + U * (A_e + E_e + prod + U * prod)
    A_t = A_e + h * A_o
    tn_rel = (1 + U) ** n_dd - 1  # n_dd - 1 roundings of t^n_dd, one of the product
    E_tail = h ** n_dd * (E_t + (A_t + E_t) * tn_rel)
    head = coefs[:n_dd]
    A = [mpf(0)] * (n_dd + 1)
    for i in range(n_dd - 1, -1, -1):
        A[i] = abs(head[i]) + h * A[i + 1]
    D = mpf(0)
    for i in range(n_dd - 2, -1, -1):
        D = h * D + 8 * U * U * (A[i] + h * D + h * A[i + 1])
    total = sum(abs(c) * h ** i for i, c in enumerate(coefs))
    final = 2 * U * U * (total + E_tail + D) * (1 + U)
    rounding = sum(abs(coefs[i] - p["coefs"][i]) * h ** i for i in range(deg + 1))
    return 4 * err_exact + (rounding + E_tail + D + final) / fmin


def emit_bound(name, pieces):
    """The largest fast_eval_bound of a table, rounded up to 3 significant bits, as a constant."""
    m = max(fast_eval_bound(p) for p in pieces)
    e = int(mp.floor(mp.log(m, 2)))
    bound = mp.ceil(m / mpf(2) ** (e - 2)) * mpf(2) ** (e - 2)
    sys.stderr.write("%s eval bound 2^%.2f\n" % (name, float(mp.log(m, 2))))
    print("// eval_fast relative error bound on every k%sPieces piece (largest piece bound 2^%.2f)" %
          (name, float(mp.log(m, 2))))
    print("constexpr double k%sEvalErr = %s;" % (name, hexf(bound)))
    print()


def emit_exp_table():
    """2^(j/128) as double-doubles and ln2/128 in three parts for the fast e^(-x^2) of erfc."""
    print("// Tang's table-driven exp (1989): 2^(j/128) = hi + lo, j = 0..127")
    print("constexpr DD kExp2Table[] = {")
    for j in range(128):
        hi, lo = split_dd(mpf(2) ** (mpf(j) / 128))
        print("    {%s, %s}," % (hexf(hi), hexf(lo)))
    print("};")
    l = mp.log(2) / 128
    m, e = mp.frexp(l)
    hi = mp.floor(m * 2 ** 35) / mpf(2) ** 35 * mpf(2) ** e  # 35 bits: k hi exact for k < 2^18
    mid = float(l - hi)
    lo = float(l - hi - mpf(mid))
    print("// ln2/128 = kLn2By128Hi + kLn2By128Mid + kLn2By128Lo; the high part has 35 bits")
    print("constexpr double kLn2By128Hi = %s;" % hexf(hi))
    print("constexpr double kLn2By128Mid = %s;" % hexf(mid))
    print("constexpr double kLn2By128Lo = %s;" % hexf(lo))
    print("constexpr double k128ByLn2 = %s;" % hexf(128 / mp.log(2)))
    print("// Taylor coefficients (-1)^n/n!, n = 3..7, of e^(-r)")
    print("constexpr double kExpNegTaylor[] = {%s};" %
          ", ".join(hexf(mpf(-1) ** n / mp.factorial(n)) for n in range(3, 8)))
    print()


def bisect(f, a, b):
    """A root of f in [a, b] (f(a), f(b) of opposite signs), to 2^-400."""
    fa = f(a)
    for _ in range(400):
        m = (a + b) / 2
        fm = f(m)
        if fm == 0:
            return m
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return (a + b) / 2


def triple(v):
    a = float(v)
    b = float(v - a)
    c = float(v - a - b)
    return (a, b, c)


def piece(f, lo, hi, centre, zero=False, name="", var_lo=None, var_hi=None, max_deg=40):
    """f is a function of x; fitted as f(centre + t)."""
    cm = mpf(centre[0]) + mpf(centre[1]) + mpf(centre[2])
    a = mpf(lo) - cm if var_lo is None else var_lo
    b = mpf(hi) - cm if var_hi is None else var_hi
    n_dd, rc, err, coefs, info = make_piece(lambda t: f(cm + t), cm, a, b, zero=zero, name=name,
                                           max_deg=max_deg)
    sys.stderr.write("%s [%g, %g] deg %d n_dd %d err %.2e\n" % (name, lo, hi, len(coefs) - 1,
                                                                 n_dd, float(err)))
    return {"lo": lo, "hi": hi, "centre": centre, "n_dd": n_dd, "coefs": coefs, "err": err,
            "info": info}


def uniform_cells(f, lo, hi, per_unit, name, zeros=()):
    """Cells [lo + i/per_unit, lo + (i+1)/per_unit]; centre = midpoint or the zero it touches."""
    pieces = []
    n = int(round((hi - lo) * per_unit))
    for i in range(n):
        a = lo + mpf(i) / per_unit
        b = lo + mpf(i + 1) / per_unit
        z = [c for c in zeros if a <= c <= b]
        if z:
            pieces.append(piece(f, float(a), float(b), (z[0], 0.0, 0.0), zero=True, name=name))
        else:
            pieces.append(piece(f, float(a), float(b), (float((a + b) / 2), 0.0, 0.0), name=name))
    return pieces


def main():
    print("// Generated by: /usr/bin/python3 tools/math_tables/special.py (python3-mpmath %s)" %
          mp.__version__)
    print("// Piece: {x_min, x_max, centre (hi, lo, lo2), n_dd, degree, offset into coefs}.")
    print()

    # --- erf on [0, 0.5]: erf(x) = x * g(x^2), g(u) = erf(sqrt u) / sqrt u.
    def g_erf(u):
        if u == 0:
            return 2 / mp.sqrt(mp.pi)
        r = mp.sqrt(u)
        return mp.erf(r) / r
    p = piece(g_erf, 0.0, 1.0 / 16, (0.0, 0.0, 0.0), name="erf_small")
    emit_table("ErfSmall", [p], "erf(x) = x g(x^2) for |x| < 1/4, g(u) = erf(sqrt u)/sqrt u, u in [0, 1/16]")
    emit_bound("ErfSmall", [p])

    # --- erf(x) itself on cells of width 1/8 on [0.25, 6] (no exponential needed for erf).
    pcs = uniform_cells(mp.erf, 0.25, 6.0, 8, "erf")
    emit_table("Erf", pcs, "erf(x), cells of width 1/8 on [0.25, 6]")
    emit_bound("Erf", pcs)

    # --- erfc(x) = exp(-x^2) * erfcx(x) on a uniform grid of cells of width 1/4 on [0.5, 27.25].
    erfcx = lambda x: mp.erfc(x) * mp.exp(x * x)
    pcs = uniform_cells(erfcx, 0.5, 27.25, 4, "erfcx")
    emit_table("Erfcx", pcs, "erfcx(x) = exp(x^2) erfc(x), cells of width 1/4 on [0.5, 27.25]")
    emit_bound("Erfcx", pcs)
    emit_exp_table()

    # --- lgamma on a uniform grid of cells of width 1/8 on [0.75, 10]; the cells next to the zeros
    # x = 1 and x = 2 are expanded around the zero (c_0 = 0).
    lg = lambda x: mp.log(abs(mp.gamma(x)))
    pcs = uniform_cells(lg, 0.75, 10.0, 8, "lgamma", zeros=(1.0, 2.0))
    emit_table("Lgamma", pcs, "ln Gamma(x), cells of width 1/8 on [0.75, 10]")

    # Stirling remainder: lgamma(x) = (x-1/2) ln x - x + ln(2 pi)/2 + W(1/x^2)/x, x >= 10.
    def W(z):
        if z == 0:
            return mpf(1) / 12
        x = 1 / mp.sqrt(z)
        return (mp.loggamma(x) - ((x - mpf(1) / 2) * mp.log(x) - x + mp.log(2 * mp.pi) / 2)) * x
    pw = piece(W, 0.0, 0.01, (0.0, 0.0, 0.0), name="stirling")
    emit_table("Stirling", [pw], "W(z), z = 1/x^2 in [0, 1/100]: Stirling remainder times x")

    # Negative zeros of lgamma: two in each (-n-1, -n), n = 2 .. 18.
    zp = []
    for n in range(2, 19):
        xmin = bisect(mp.digamma, mpf(-n - 1) + mpf(10) ** -30, mpf(-n) - mpf(10) ** -30)
        lo_int, hi_int = -n - 1, -n
        eps = mpf(10) ** -60
        for (a, b) in ((mpf(lo_int) + eps, xmin), (xmin, mpf(hi_int) - eps)):
            z = bisect(lg, a, b)
            slope = abs(mp.digamma(z))
            dist = min(abs(z - lo_int), abs(z - hi_int))
            r = min(mpf(2) ** -4 / slope, dist / 4)
            zt = triple(z)
            # the piece covers the doubles inside [z - r, z + r] only
            x_lo = float(z - r)
            if x_lo < z - r:
                x_lo = math.nextafter(x_lo, math.inf)
            x_hi = float(z + r)
            if x_hi > z + r:
                x_hi = math.nextafter(x_hi, -math.inf)
            pz = piece(lg, x_lo, x_hi, zt, zero=True,
                       name="lgamma zero n=%d z=%s" % (n, mp.nstr(z, 17)), var_lo=-r, var_hi=r)
            zp.append(pz)
    emit_table("LgammaNegZero", zp,
               "ln|Gamma(z + t)| around the zeros z of lgamma in (-n-1, -n), n = 2..18, "
               "two per interval (left then right); z = hi + lo + lo2")


if __name__ == "__main__":
    main()
