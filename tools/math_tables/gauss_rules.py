#!/usr/bin/python3
"""Reference Gauss-Hermite and Gauss-Legendre nodes and weights for tests/test_quadrature.cpp.

Run:  /usr/bin/python3 tools/math_tables/gauss_rules.py > /tmp/gauss_rules.inc   (about 2 min)
and paste the output between the "BEGIN GENERATED REFERENCES" / "END GENERATED REFERENCES"
markers of tests/test_quadrature.cpp. Needs Debian's python3-mpmath. Progress goes to stderr.
  --dump ORDER...   instead prints every node and weight of the given orders (both rules), as
                    "H|L order index node weight" with 25 significant digits, for comparisons.

The method is independent of src/spectrum/quadrature.cpp where it can be:
  * starting values by bisection with Sturm counts of the Jacobi matrix (Wilkinson, "The
    Algebraic Eigenvalue Problem", 1965, §5.36-5.39) in binary64, not by the QL method: the k-th
    eigenvalue is where the number of negative pivots of T - x I jumps from k to k + 1, so no
    root can be missed or found twice;
  * Newton's method on the three-term recurrence in 80-digit arithmetic (mpmath), until the
    step is below 10^-60;
  * the weights as the Christoffel function 1 / sum_{k<n} p_k(x_i)^2 of the orthonormal
    polynomials (Szego, "Orthogonal Polynomials", 1939, Thm. 3.4.2), not the derivative form the
    C++ code uses; both forms are computed here and must agree to 10^-50;
  * every rule is checked: sum of weights (sqrt(pi) and 2) and the moment of degree 2n - 2
    to 10^-45 relative, n distinct nodes.
"""
import math
import sys
import mpmath as mp
from mpmath import mpf

mp.mp.dps = 80
TEST_ORDERS = [199, 200, 400, 1024]


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def off_diagonal(kind, n):
    """Jacobi matrix off-diagonal b_1 .. b_{n-1} (zero diagonal) of the orthonormal family."""
    if kind == "H":
        return [math.sqrt(k / 2.0) for k in range(1, n)]
    return [k / math.sqrt(4.0 * k * k - 1.0) for k in range(1, n)]


def count_below(b2, x):
    """Number of eigenvalues < x (Sturm count: negative pivots of T - x I, LDL^T)."""
    count = 0
    d = -x
    if d < 0:
        count += 1
    for bb in b2:
        if d == 0.0:
            d = 1e-300
        d = -x - bb / d
        if d < 0:
            count += 1
    return count


def eigenvalue(b2, k, lo, hi):
    """The k-th smallest eigenvalue (k = 0 ...) by bisection to binary64 resolution."""
    while True:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            return mid
        if count_below(b2, mid) > k:
            hi = mid
        else:
            lo = mid


def orthonormal_values(kind, n, x):
    """p_0(x) ... p_n(x), orthonormal with respect to e^{-x^2} (H) or 1 on [-1, 1] (L)."""
    p = [mpf(0)] * (n + 1)
    if kind == "H":
        p[0] = mp.pi ** mpf(-0.25)
        if n >= 1:
            p[1] = mp.sqrt(2) * x * p[0]
        for k in range(1, n):
            p[k + 1] = (x * p[k] - mp.sqrt(mpf(k) / 2) * p[k - 1]) / mp.sqrt(mpf(k + 1) / 2)
    else:
        beta = [mpf(0)] + [mpf(k) / mp.sqrt(4 * mpf(k) ** 2 - 1) for k in range(1, n + 1)]
        p[0] = 1 / mp.sqrt(2)
        if n >= 1:
            p[1] = x * p[0] / beta[1]
        for k in range(1, n):
            p[k + 1] = (x * p[k] - beta[k] * p[k - 1]) / beta[k + 1]
    return p


def derivative(kind, n, x, p):
    """p_n'(x) from p_{n-1}, p_n (Hermite: sqrt(2n) p_{n-1}; Legendre: from (1 - x^2) P_n')."""
    if kind == "H":
        return mp.sqrt(2 * mpf(n)) * p[n - 1]
    # P_k = p_k / sqrt(k + 1/2); (1 - x^2) P_n' = n (P_{n-1} - x P_n)
    pn = p[n] / mp.sqrt(n + mpf(0.5))
    pn1 = p[n - 1] / mp.sqrt(n - mpf(0.5))
    return mp.sqrt(n + mpf(0.5)) * n * (pn1 - x * pn) / (1 - x * x)


def rule(kind, n):
    """Nonnegative nodes (descending) and their weights, to 80 digits."""
    b = off_diagonal(kind, n)
    b2 = [v * v for v in b]
    bound = 2.0 * max(b, default=0.0) + 1.0
    nodes, weights = [], []
    for k in range(n - 1, n // 2 - 1, -1):  # the nonnegative eigenvalues, largest first
        if 2 * k == n - 1:
            x = mpf(0)
        else:
            x = mpf(eigenvalue(b2, k, 0.0, bound))
            for _ in range(20):
                p = orthonormal_values(kind, n, x)
                step = p[n] / derivative(kind, n, x, p)
                x -= step
                if abs(step) < mpf(10) ** -60 * abs(x):
                    break
            else:
                raise RuntimeError("no convergence %s %d %d" % (kind, n, k))
        p = orthonormal_values(kind, n, x)
        christoffel = 1 / mp.fsum(v * v for v in p[:n])
        if kind == "H":
            w = 2 / derivative(kind, n, x, p) ** 2
        else:
            w = 2 * (1 - x * x) / (n * p[n - 1] / mp.sqrt(n - mpf(0.5))) ** 2
        assert abs(w - christoffel) <= mpf(10) ** -50 * christoffel, (kind, n, k)
        nodes.append(x)
        weights.append(w)
    check(kind, n, nodes, weights)
    return nodes, weights


def check(kind, n, nodes, weights):
    """Sum of weights and the moment of degree 2n - 2 against the exact values; distinct nodes."""
    full = [(x, w) for x, w in zip(nodes, weights)]
    full += [(-x, w) for x, w in zip(nodes, weights) if x != 0]
    assert len(full) == n and len({mp.nstr(x, 40) for x, _ in full}) == n, (kind, n)
    m = n - 1
    if kind == "H":
        exact0, exact2m = mp.sqrt(mp.pi), mp.gamma(m + mpf(0.5))
    else:
        exact0, exact2m = mpf(2), mpf(2) / (2 * m + 1)
    s0 = mp.fsum(w for _, w in full)
    s2m = mp.fsum(w * x ** (2 * m) for x, w in full)
    assert abs(s0 - exact0) < mpf(10) ** -45 * exact0, (kind, n, s0)
    assert abs(s2m - exact2m) < mpf(10) ** -45 * exact2m, (kind, n, s2m)


def hexf(v):
    """v rounded to the nearest double (also below the normal range) as a C++ hex literal."""
    if abs(v) < mpf(2) ** -1022:
        d = float(mp.nint(v * mpf(2) ** 1074)) * 2.0 ** -1074  # exact: an integer times 2^-1074
    else:
        d = float(v)
    return "0.0" if d == 0.0 else d.hex()


def emit(kind, n, nodes, weights, picks):
    name = "kHermite" if kind == "H" else "kLegendre"
    print("constexpr RuleReference %s%d[] = {" % (name, n))
    for i in picks:
        x, w = nodes[i], weights[i]
        print("    {%d, %s, %s},  // %s, %s" % (i, hexf(x), hexf(w), mp.nstr(x, 20),
                                              mp.nstr(w, 20)))
    print("};")


def picks_for(kind, nodes, weights):
    """The largest node, the middle of the nonnegative nodes, the smallest positive node and 0
    (odd orders); for Hermite also the node with the smallest normal weight and the one next
    to it outwards (weight subnormal or 0)."""
    h = len(nodes)
    picks = {0, h // 2, h - 1, max(i for i, x in enumerate(nodes) if x > 0)}
    if kind == "H":
        normal = [i for i, w in enumerate(weights) if w >= mpf(2) ** -1022]
        picks.add(normal[0])
        if normal[0] > 0:
            picks.add(normal[0] - 1)
    return sorted(picks)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--dump":
        for n in map(int, sys.argv[2:]):
            for kind in "HL":
                log(kind, n)
                nodes, weights = rule(kind, n)
                for i, (x, w) in enumerate(zip(nodes, weights)):
                    print(kind, n, i, mp.nstr(x, 25), mp.nstr(w, 25))
        return
    print("// Generated by tools/math_tables/gauss_rules.py (mpmath, %d digits): {index among the" % mp.mp.dps)
    print("// nonnegative nodes, largest first; node; weight}, each rounded to the nearest double.")
    for kind in "HL":
        for n in TEST_ORDERS:
            log(kind, n)
            nodes, weights = rule(kind, n)
            emit(kind, n, nodes, weights, picks_for(kind, nodes, weights))


if __name__ == "__main__":
    main()
