#!/usr/bin/env python3
"""Reproduces one wave component of reference/scenes/backend_example.json by hand, from the
exported stages (docs/BACKENDS.md, "Worked example"). Python's standard library only.

  docs/backend_example.py DIR     (DIR holds spectrum.exr, h0.exr, omega.exr, hkt.exr,
                                   fields.exr written by `oceanref fields --stage …`)
"""
import math
import re
import subprocess
import sys

folder = sys.argv[1]
worst = 0.0


def check(what, exported, by_hand):
    """Prints both; the gap is float32 rounding and the 9 decimals of --dumpdata (< 1e-6)."""
    global worst
    for x, y in zip(exported, by_hand):
        worst = max(worst, abs(x - y))
    print(f"{what}: exported {' '.join(f'{x:.9f}' for x in exported)}, "
          f"by hand {' '.join(f'{y:.9f}' for y in by_hand)}")
N, L, SEED, CASCADE, T, G = 16, 100.0, 7, 0, 2.0, 9.81
dk = 2 * math.pi / L


def pixels(name, part=0):
    """{(a, b): {channel name: value}} of one part: the channel names from oiiotool --info -v,
    the values from oiiotool --dumpdata (channels in the file's order, which is name order).
    A channel is the field name plus ".V" (docs/FILES.md): c0.h0.re.V holds field c0.h0.re."""
    def oiiotool(*args):
        return subprocess.run(["oiiotool", *args, f"-i:subimage={part}", f"{folder}/{name}.exr"],
                              capture_output=True, text=True, check=True).stdout
    names = re.search(r"channel list: (.*)", oiiotool("--info", "-v")).group(1).split(", ")
    return {(int(a), int(b)): dict(zip(names, map(float, values.split()), strict=True))
            for a, b, values in re.findall(r"Pixel \((\d+), (\d+)\): (.*)",
                                           oiiotool("--dumpdata"))}


M64 = (1 << 64) - 1


def mix64(x):  # SplitMix64 finalizer (src/waves/random.h)
    x = (x + 0x9E3779B97F4A7C15) & M64
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & M64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & M64
    return x ^ (x >> 31)


def normals(seed, cascade, alpha, beta):
    key = mix64(mix64(mix64(seed) ^ cascade) ^ ((alpha & 0xFFFFFFFF) | (beta & 0xFFFFFFFF) << 32))
    u1, u2 = (((mix64((key + n * 0xD1B54A32D192ED03) & M64) >> 11) + 0.5) * 2.0**-53
              for n in (0, 1))
    r = math.sqrt(-2 * math.log(u1))
    return r * math.cos(2 * math.pi * u2), r * math.sin(2 * math.pi * u2)


a, b = 3, 14                                          # array index: column a, row b
alpha, beta = (a if a < N // 2 else a - N), (b if b < N // 2 else b - N)
kx, kz = alpha * dk, beta * dk
k = math.hypot(kx, kz)
spectrum = pixels("spectrum")[(a, b)]
in_band, theta, variance = (spectrum[f"c0.{c}.V"] for c in ("in_band", "theta", "variance"))
print(f"(a, b) = ({a}, {b}): (alpha, beta) = ({alpha}, {beta}), k = ({kx:.9f}, {kz:.9f}) rad/m")
print(f"in_band {in_band:g}, Theta {theta:.9g} m^4 (compare: oceanref spectrum --model jonswap "
      f"--wind-speed 10 --fetch 100000 --wind-direction-deg 30 --wavevector {kx!r}:{kz!r})")
check("Theta dk^2 [m^2]", [variance], [theta * dk * dk])
xr, xi = normals(SEED, CASCADE, alpha, beta)
scale = math.sqrt(theta * dk * dk)                    # h0 = (xi_r + i xi_i)/sqrt2 * sqrt(2 Theta dk^2)
h0 = pixels("h0")
h0_re, h0_im = h0[(a, b)]["c0.h0.re.V"], h0[(a, b)]["c0.h0.im.V"]
check("h0 (re, im) [m]", [h0_re, h0_im], [xr * scale, xi * scale])
omega = pixels("omega")[(a, b)]["c0.omega.V"]
check("omega = sqrt(g k) [rad/s]", [omega], [math.sqrt(G * k)])
partner = h0[((N - a) % N, (N - b) % N)]               # h0(-k): the conjugate partner
m_re, m_im = partner["c0.h0.re.V"], partner["c0.h0.im.V"]
e = complex(math.cos(omega * T), -math.sin(omega * T))  # e^{-i omega t}
h = 0.5 * complex(h0_re, h0_im) * e + 0.5 * (complex(m_re, m_im) * e).conjugate()
hkt = {p: complex(v["c0.hkt.re.V"], v["c0.hkt.im.V"]) for p, v in pixels("hkt").items()}
check("h(k, t) (re, im) [m]", [hkt[(a, b)].real, hkt[(a, b)].imag], [h.real, h.imag])
# The fields: the unnormalized inverse DFT; at the sample (m, n) = (0, 0) every phase is 1, so
# eta(0, 0) = sum of Re h and d eta/dx (0, 0) = sum of Re(i kx h) = -sum kx Im h.
eta = sum(v.real for v in hkt.values())
slope_x = -sum((p[0] if p[0] < N // 2 else p[0] - N) * dk * v.imag for p, v in hkt.items()
               if p[0] != N // 2)                     # 0 on the Nyquist column (Gamper eq. 4.12)
f = pixels("fields")[(0, 0)]                           # part c0 (part 1 is sum)
check("c0.height(0, 0) = sum Re h [m]", [f["c0.height.V"]], [eta])
check("c0.slope_x(0, 0) = -sum kx Im h", [f["c0.slope_x.V"]], [slope_x])
print(f"largest difference {worst:.3g}")
sys.exit(0 if worst < 1e-6 else 1)
