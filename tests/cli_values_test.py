#!/usr/bin/env python3
"""The values behind `oceanref`'s flags, each checked against an independent computation (issue
21): a flag that is parsed but ignored, read into the wrong setting or scaled wrongly fails here.

- spectrum: every model's S(omega) against its closed form written out here (Gamper eq. 3.36-3.54,
  3.66-3.68; Vincevicius eq. 1.9-1.10), with each parameter flag changed alone; the spreading
  functions normalised (the trapezoid rule over theta), cos2 and its printed form in closed form,
  the wind direction a rotation, the blend linear in b, the swell narrowing the spread; Theta(k)
  of --wavevector equal to S(omega) D(omega, theta) d(omega)/dk / k with the dispersion relation
  (deep, finite depth, capillary with k_m) solved here; the moments of --moments against the
  trapezoid rule over a dense --omega grid, --k-max moving them.
- brdf: zeta, p, the directional slope variances, Lambda (exact and rational erfc), F (exact and
  Schlick) and the BRDF against Bruneton 2010 written out here, for any normal and wind angle;
  the sea light linear in --sea-colour; --tolerance met by every error estimate; --order and
  --sun-order approaching the reference; --turbidity dimming the sun.
- bench lighting: the Schlick, rational-erfc and masking error statistics against the same sweeps
  written out here; the sun's printed/physical transmittance table; the sky integral converging
  with the order. bench synthesis: KissFFT = FFTW, stage times within the frame, the float error
  growing with time, every field's row.
- sky: Y, x, y and linear sRGB against Preetham's formulas (appendix A.2) and the sRGB primaries;
  --irradiance against a quadrature of the sky; the hemisphere image (--size) pixel by pixel.
- compare: every metric (max, RMS, RMSE, percentiles by nearest rank, ULP distance, failing
  count) for --abs, --rel, --floor, --ulp; --rel and --max-fail-share at their boundary;
  --channels C=G, --profile, --json, --suggest --safety --floor --name; --report's pictures
  decoded (the tone-mapped colour overview, value greys, fail mask, heat map).
- brdf against sky: every row of brdf, each against what it is made of (the sky and sun of `sky`,
  the fast errors' definition, the shortcuts, the F_mean fit). Every ranged flag of every
  command at the ends its --help states.
- render: --spp, --renderer and --threads against the scene's settings; --samples averaging to
  the pixels; --lighting-error bounding |fast - reference|; --max-memory at the estimate; every
  report line against the EXR written (hashes, error summaries, samples, antialiased pixels).
  fields: --time against the scene's time; --at at a node against the FFT. acf: the lags of
  --length and --samples-per-period, acf(0) = 1, one period of a single cascade along x and z
  (and not along the diagonal), --seed, --lines and --area reaching the estimate; --svg's plot
  read back: every point at its CSV value on the plot's own grid, titles centred, the legend;
  --map: the greys of the heights (fields --at), z upwards, periodic, the gap grey.
- bench render: --width, --height, --spp reaching the render (samples, the sea's share of a
  rolled camera's image), the slope budget's columns adding up.

    tests/cli_values_test.py PATH/TO/oceanref

NumPy and OpenImageIO's Python module (tools/setup.sh); skipped (exit 77) only without them.
"""
import base64
import csv
import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError:
    print("SKIP: NumPy or OpenImageIO's Python module is missing (tools/setup.sh installs them)")
    sys.exit(77)

binary = sys.argv[1]
source_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(source_root, "tools"))
import cli_reference  # noqa: E402  (tools/cli_reference.py: every command's path and --help)
failures = []
checks = 0


def check(ok, what):
    global checks
    checks += 1
    if not ok:
        failures.append(what)
        print("FAIL:", what, file=sys.stderr)
        if os.environ.get("OCEANREF_TESTS_FAIL_FAST"):  # tools/mutation.py: one is enough
            sys.exit(1)


def close(got, want, rel, what):
    got, want = float(got), float(want)  # JSON writes an infinity as "inf"
    ok = got == want or abs(got - want) <= rel * abs(want)
    check(ok, f"{what}: oceanref gives {got!r}, expected {want!r} (relative tolerance {rel})")


def oceanref(*args):
    r = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: oceanref {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}")
    return list(csv.DictReader(io.StringIO(r.stdout)))


def read_layers(path):
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    image.close()
    return {name: pixels[:, :, i] for i, name in enumerate(spec.channelnames)}


G = 9.81


# --- Spectra in omega (the closed forms) ---------------------------------------------------------

def pm(omega, alpha, omega_p, g=G):  # Gamper eq. 3.37
    return alpha * g * g / omega ** 5 * math.exp(-1.25 * (omega_p / omega) ** 4)


def jonswap(omega, alpha, omega_p, gamma=3.3, s_low=0.07, s_high=0.09, g=G):  # eq. 3.51
    sigma = s_low if omega <= omega_p else s_high
    r = math.exp(-((omega - omega_p) ** 2) / (2 * sigma * sigma * omega_p * omega_p))
    return pm(omega, alpha, omega_p, g) * gamma ** r


def jonswap_from_fetch(u, fetch, g=G):  # eq. 3.43, 3.52-3.54
    chi = g * fetch / (u * u)
    return 0.076 * chi ** -0.22, 2 * math.pi * g * 3.5 * chi ** -0.33 / u


def wavenumber_finite_depth(omega, h, g=G):
    """k with omega^2 = g k tanh(k h), by Newton's method from the deep-water k."""
    k = omega * omega / g
    for _ in range(100):
        f = g * k * math.tanh(k * h) - omega * omega
        df = g * math.tanh(k * h) + g * k * h / math.cosh(k * h) ** 2
        step = f / df
        k -= step
        if abs(step) < 1e-15 * k:
            break
    return k


def kitaigorodskii(omega, h, g=G):  # Vincevicius eq. 1.9: [k^-3 dk/domega]_h / [k^-3 dk/domega]_inf
    k = wavenumber_finite_depth(omega, h, g)
    d_omega_dk = (g * math.tanh(k * h) + g * k * h / math.cosh(k * h) ** 2) / (2 * omega)
    k_inf = omega * omega / g
    return (k ** -3 / d_omega_dk) / (k_inf ** -3 * (2 * omega / g))


def thompson_vincent(omega, h, g=G):  # Vincevicius eq. 1.10
    wh = omega * math.sqrt(h / g)
    return 0.5 * wh * wh if wh <= 1 else 1 - 0.5 * (2 - wh) ** 2 if wh < 2 else 1.0


def donelan(omega, u, fetch, g=G):  # Gamper eq. 3.66-3.68
    chi = g * fetch / (u * u)
    big_omega = 11.6 * chi ** -0.23
    omega_p = big_omega * g / u
    gamma = 1.7 if big_omega < 1 else 1.7 + 6 * math.log10(big_omega)
    sigma = 0.08 * (1 + 4 / big_omega ** 3)
    alpha = 0.006 * big_omega ** 0.55
    r = math.exp(-((omega - omega_p) ** 2) / (2 * sigma * sigma * omega_p * omega_p))
    return alpha * g * g / omega ** 4 / omega_p * math.exp(-(omega_p / omega) ** 4) * gamma ** r


def s_of(*args, omega):
    values = []
    for i in range(0, len(omega), 2000):  # the command line's length
        rows = oceanref("spectrum", *args, "--omega", ",".join(repr(w) for w in omega[i:i + 2000]))
        values += [float(r["S"]) for r in rows]
    return values


OMEGAS = [0.4, 0.7, 0.9, 1.3, 2.5]
TIGHT = 1e-12  # closed forms evaluated two ways: a few ulps of pow, exp and the order of products


def spectrum_case(args, expected, what, tol=TIGHT):
    for w, got in zip(OMEGAS, s_of(*args, omega=OMEGAS)):
        close(got, expected(w), tol, f"spectrum {' '.join(args)} at omega {w} ({what})")


spectrum_case(["--model", "pierson-moskowitz"], lambda w: pm(w, 0.0081, 0.855 * G / 10),
              "PM, U10 = 10")
spectrum_case(["--model", "pierson-moskowitz", "--wind-speed", "14"],
              lambda w: pm(w, 0.0081, 0.855 * G / 14), "--wind-speed")
spectrum_case(["--model", "pierson-moskowitz", "--gravity", "9.7"],
              lambda w: pm(w, 0.0081, 0.855 * 9.7 / 10, 9.7), "--gravity")
# U19.5: Theta = alpha g^2 / omega^5 exp(-0.74 (g / (U omega))^4) (Gamper eq. 3.36).
spectrum_case(["--model", "pierson-moskowitz", "--pm-wind", "u19.5", "--wind-speed", "12"],
              lambda w: 0.0081 * G * G / w ** 5 * math.exp(-0.74 * (G / (12 * w)) ** 4),
              "--pm-wind u19.5")
spectrum_case(["--model", "pierson-moskowitz", "--alpha", "0.01"],
              lambda w: pm(w, 0.01, 0.855 * G / 10), "--alpha")
spectrum_case(["--model", "pierson-moskowitz", "--peak-omega", "0.6"],
              lambda w: pm(w, 0.0081, 0.6), "--peak-omega")
alpha, omega_p = jonswap_from_fetch(10, 100000)
spectrum_case(["--model", "jonswap"], lambda w: jonswap(w, alpha, omega_p), "JONSWAP defaults")
alpha40, omega_p40 = jonswap_from_fetch(10, 40000)
spectrum_case(["--model", "jonswap", "--fetch", "40000"], lambda w: jonswap(w, alpha40, omega_p40),
              "--fetch")
alpha16, omega_p16 = jonswap_from_fetch(16, 100000)
spectrum_case(["--model", "jonswap", "--wind-speed", "16"], lambda w: jonswap(w, alpha16, omega_p16),
              "JONSWAP --wind-speed")
spectrum_case(["--model", "jonswap", "--gamma", "5"], lambda w: jonswap(w, alpha, omega_p, 5),
              "--gamma")
spectrum_case(["--model", "jonswap", "--sigma-low", "0.1"],
              lambda w: jonswap(w, alpha, omega_p, 3.3, 0.1), "--sigma-low")
spectrum_case(["--model", "jonswap", "--sigma-high", "0.12"],
              lambda w: jonswap(w, alpha, omega_p, 3.3, 0.07, 0.12), "--sigma-high")
spectrum_case(["--model", "jonswap", "--alpha", "0.02", "--peak-omega", "1.1"],
              lambda w: jonswap(w, 0.02, 1.1), "JONSWAP --alpha, --peak-omega")
alpha_x, omega_p_x = jonswap_from_fetch(10, 2e6)
spectrum_case(["--model", "jonswap", "--fetch", "2e6", "--allow-extrapolation"],
              lambda w: jonswap(w, alpha_x, omega_p_x), "--allow-extrapolation (chi > 1e4)")
# TMA: JONSWAP times the depth attenuation; Newton's k here against the library's solver.
spectrum_case(["--model", "tma", "--depth", "8"],
              lambda w: jonswap(w, alpha, omega_p) * kitaigorodskii(w, 8), "TMA --depth", 1e-9)
spectrum_case(["--model", "tma", "--depth", "8", "--tma-attenuation", "thompson-vincent"],
              lambda w: jonswap(w, alpha, omega_p) * thompson_vincent(w, 8),
              "--tma-attenuation thompson-vincent")
spectrum_case(["--model", "donelan"], lambda w: donelan(w, 10, 100000), "Donelan")
spectrum_case(["--model", "donelan", "--fetch", "30000", "--wind-speed", "8"],
              lambda w: donelan(w, 8, 30000), "Donelan --fetch, --wind-speed")
# The end of --omega's range (>= 0): S(0) = 0 for every model (each vanishes faster than any
# power of omega as omega -> 0), and a negative frequency is refused, naming the flag.
for model in ("pierson-moskowitz", "jonswap", "tma", "donelan", "unified", "phillips"):
    s0, s1 = s_of("--model", model, omega=[0.0, 0.9])
    check(s0 == 0.0 and s1 > 0.0, f"spectrum --model {model} --omega 0,0.9: S = {s0}, {s1}")
# -0 is 0: the same S and D (the swell's tanh(omega_p/omega) is 1 there, not tanh(-inf)).
zero = oceanref("spectrum", "--model", "jonswap", "--swell", "0.5", "--omega", "0,-0",
                "--theta-deg", "0,30")
check([(r["S"], r["D"]) for r in zero[:2]] == [(r["S"], r["D"]) for r in zero[2:]],
      f"spectrum --omega -0 differs from 0: {zero}")
refused = subprocess.run([binary, "spectrum", "--model", "jonswap", "--omega", "-0.1"],
                         capture_output=True, text=True)
check(refused.returncode == 2 and "--omega" in refused.stderr,
      f"spectrum --omega -0.1: exit {refused.returncode}, {refused.stderr.strip()}")


# --- Directional spreading -----------------------------------------------------------------------

THETAS = np.linspace(-180.0, 180.0, 1441)  # 0.25° steps


def spread(*args, omega=1.0, thetas=THETAS):
    rows = oceanref("spectrum", *args, "--omega", repr(omega), "--theta-deg",
                    ",".join(repr(float(t)) for t in thetas))
    return np.array([float(r["D"]) for r in rows])


def integral_over_theta(d, thetas=THETAS):
    return float(np.trapz(d, np.radians(thetas)))


for model in ("cos2", "cos4", "mitsuyasu", "hasselmann", "mastin", "gamper", "donelan",
              "donelan-banner", "unified"):
    for omega in (0.8, 2.0):
        d = spread("--model", "jonswap", "--spreading", model, omega=omega)
        # The trapezoid rule's error: smooth functions well under 1e-5 at 0.25°; cos2 and cos4
        # have a kink at ±90° (1e-6), donelan-banner's sech² peaks narrowly above omega_p.
        close(integral_over_theta(d), 1.0, 2e-4, f"--spreading {model}: the integral of D at "
                                                   f"omega {omega}")
        check(d.min() >= 0.0, f"--spreading {model}: D < 0")
cos2 = spread("--model", "jonswap", "--spreading", "cos2")
check(np.allclose(cos2, np.cos(np.radians(THETAS)) ** 2 / math.pi, rtol=1e-12, atol=1e-15),
      "--spreading cos2 is not cos^2(theta) / pi")
printed = spread("--model", "jonswap", "--spreading", "cos2", "--printed-spreading")
close(integral_over_theta(printed), math.pi, 1e-5, "--printed-spreading cos2: the integral")
printed4 = spread("--model", "jonswap", "--spreading", "cos4", "--printed-spreading")
close(integral_over_theta(printed4), 3 * math.pi / 4, 1e-5, "--printed-spreading cos4")
# The wind direction rotates D: D(theta; 30°) = D(theta - 30°; 0).
base = spread("--model", "jonswap", "--spreading", "hasselmann", thetas=THETAS[:1300])
turned = spread("--model", "jonswap", "--spreading", "hasselmann", "--wind-direction-deg", "30",
                thetas=THETAS[:1300] + 30.0)
check(np.allclose(turned, base, rtol=1e-12, atol=1e-12 * base.max()),
      "--wind-direction-deg is not a rotation")
# The blend is linear in b: D(1/2) = (D(0) + D(1)) / 2.
parts = [spread("--model", "jonswap", "--spread-blend", b, "--spreading", "mitsuyasu")
         for b in ("0", "0.5", "1")]
check(np.allclose(parts[1], 0.5 * (parts[0] + parts[2]), rtol=1e-12, atol=1e-15),
      "--spread-blend is not linear in b")
check(np.allclose(parts[0][np.abs(THETAS) <= 90],
                  2 / math.pi * np.cos(np.radians(THETAS[np.abs(THETAS) <= 90])) ** 2, rtol=1e-12),
      "--spread-blend 0 is not the forward cos^2")
# Swell narrows the cos-2s spread (its exponent grows by 16 tanh(...) xi^2) and keeps it normalised.
plain = spread("--model", "jonswap", "--spreading", "mitsuyasu", omega=0.6)
for swell_model in ("lutz", "alimardanov"):
    swell = spread("--model", "jonswap", "--spreading", "mitsuyasu", "--swell", "0.5",
                   "--swell-model", swell_model, omega=0.6)
    close(integral_over_theta(swell), 1.0, 2e-4, f"--swell-model {swell_model}: the integral")
    check(swell[720] > 1.2 * plain[720], f"--swell 0.5 --swell-model {swell_model}: D(0) "
                                         f"{swell[720]} not above {plain[720]}")
lutz = spread("--model", "jonswap", "--spreading", "mitsuyasu", "--swell", "0.5", omega=0.6)
alimardanov = spread("--model", "jonswap", "--spreading", "mitsuyasu", "--swell", "0.5",
                     "--swell-model", "alimardanov", omega=0.6)
check(abs(lutz[720] - alimardanov[720]) > 1e-3 * lutz[720],
      "--swell-model alimardanov gives Lutz's spread")


# --- Theta(k): S(omega) D(omega, theta) d(omega)/dk / k -------------------------------------------

def omega_and_slope(k, dispersion, depth=math.inf, k_m=370.0, g=G):
    if dispersion == "deep":
        w = math.sqrt(g * k)
        return w, w / (2 * k)
    if dispersion == "finite-depth":
        t = math.tanh(k * depth)
        w = math.sqrt(g * k * t)
        return w, g * (t + k * depth * (1 - t * t)) / (2 * w)
    w = math.sqrt(g * k * (1 + (k / k_m) ** 2))  # capillary
    return w, g * (1 + 3 * (k / k_m) ** 2) / (2 * w)


for args, dispersion, depth, k_m in (
        (["--model", "jonswap"], "deep", math.inf, 370.0),
        (["--model", "tma", "--depth", "12"], "finite-depth", 12.0, 370.0),
        (["--model", "jonswap", "--dispersion", "capillary"], "capillary", math.inf, 370.0),
        (["--model", "jonswap", "--dispersion", "capillary", "--capillary-wavenumber", "150"],
         "capillary", math.inf, 150.0),
        (["--model", "jonswap", "--dispersion", "finite-depth", "--depth", "30",
          "--wind-direction-deg", "20"], "finite-depth", 30.0, 370.0)):
    vectors = [(0.12, 0.03), (0.05, -0.09), (0.9, 0.4), (40.0, 25.0)]
    rows = oceanref("spectrum", *args, "--wavevector", ",".join(f"{x}:{z}" for x, z in vectors))
    for (kx, kz), row in zip(vectors, rows):
        k = math.hypot(kx, kz)
        w, slope = omega_and_slope(k, dispersion, depth, k_m)
        theta = math.degrees(math.atan2(kz, kx))
        sd = oceanref("spectrum", *args, "--omega", repr(w), "--theta-deg", repr(theta))[0]
        want = float(sd["S"]) * float(sd["D"]) * slope / k
        close(float(row["Theta"]), want, 1e-9, f"spectrum {' '.join(args)} --wavevector {kx}:{kz}")

# Phillips (Gamper eq. 3.73/3.74; Tessendorf): Theta(k) = A exp(-(kL)^-2 - (kl)^2) / k^4 x its
# cos2 spreading, cos^2(theta) as printed (eq. 3.73 exactly) or normalized, cos^2(theta)/pi;
# L = U^2/g, l = --phillips-suppression (default 0.001) x L, A = --alpha (default alpha_PM / 2).
for extra, speed, g, suppression, amplitude, norm in (
        ([], 12.0, G, 0.001, 0.00405, math.pi),
        (["--phillips-suppression", "0.05"], 12.0, G, 0.05, 0.00405, math.pi),
        (["--phillips-suppression", "0.02", "--gravity", "3.7", "--alpha", "0.01",
          "--printed-spreading"], 7.0, 3.7, 0.02, 0.01, 1.0)):
    args = ["--model", "phillips", "--wind-speed", repr(speed), *extra]
    vectors = [(0.12, 0.03), (0.05, -0.09), (0.9, 0.4), (3.0, 2.5), (-0.3, 0.1)]
    rows = oceanref("spectrum", *args, "--wavevector", ",".join(f"{x}:{z}" for x, z in vectors))
    big_l = speed * speed / g
    for (kx, kz), row in zip(vectors, rows):
        k = math.hypot(kx, kz)
        want = (amplitude * math.exp(-1 / (k * big_l) ** 2 - (k * suppression * big_l) ** 2) /
                k ** 4 * (kx / k) ** 2 / norm)
        close(float(row["Theta"]), want, 1e-9, f"spectrum {' '.join(args)} --wavevector {kx}:{kz}")


# --- Moments ----------------------------------------------------------------------------------

def moments_by_trapezoid(args, k_max):
    """m0 = int S d(omega) and mss = int k^2 S d(omega) over omega <= sqrt(g k_max) (deep water),
    by the trapezoid rule in log omega on 20 000 points."""
    w = np.geomspace(0.05, math.sqrt(G * k_max), 20000)
    s = np.array(s_of(*args, omega=list(w)))
    m0 = float(np.trapz(s * w, np.log(w)))
    mss = float(np.trapz(s * (w * w / G) ** 2 * w, np.log(w)))
    return m0, mss


for args, k_max in ((["--model", "jonswap"], None), (["--model", "pierson-moskowitz",
                                                       "--wind-speed", "7"], 40.0)):
    extra = [] if k_max is None else ["--k-max", repr(k_max)]
    row = oceanref("spectrum", *args, "--moments", *extra)[0]
    m0, mss = moments_by_trapezoid(args, 363.19 if k_max is None else k_max)
    close(float(row["m0"]), m0, 1e-5, f"spectrum {' '.join(args + extra)} --moments: m0")
    close(float(row["Hs"]), 4 * math.sqrt(m0), 1e-5, f"{' '.join(args + extra)}: Hs = 4 sqrt(m0)")
    close(float(row["mss"]), mss, 1e-4, f"{' '.join(args + extra)}: mss")
    close(float(row["mss_x"]) + float(row["mss_z"]), float(row["mss"]), 1e-12,
          f"{' '.join(args + extra)}: mss_x + mss_z = mss")


# --- brdf: the BRDF's terms (Bruneton 2010 eq. 7-15) ------------------------------------------

def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def smith_lambda(cos_theta, sigma2, erfc=math.erfc):  # Bruneton eq. 9
    nu = cos_theta / math.sqrt(2 * sigma2 * (1 - cos_theta * cos_theta))
    return max(0.0, (math.exp(-nu * nu) - nu * math.sqrt(math.pi) * erfc(nu)) /
               (2 * math.sqrt(math.pi) * nu))


def fresnel(c, n=1.333):  # unpolarised Fresnel reflectance, air to water
    cos_t = math.sqrt(1 - (1 - c * c) / (n * n))
    rs = (c - n * cos_t) / (c + n * cos_t)
    rp = (n * c - cos_t) / (n * c + cos_t)
    return 0.5 * (rs * rs + rp * rp)


def brdf_terms(view, sun, normal, sigma2, wind_deg, schlick=False, erfc=math.erfc):
    v, l, n = unit(view), unit(sun), unit(normal)
    w = math.radians(wind_deg)
    tx = unit(np.array([math.cos(w), 0.0, math.sin(w)]) -
              np.dot([math.cos(w), 0.0, math.sin(w)], n) * n)
    ty = np.cross(n, tx)
    h = unit(v + l)
    zh = float(np.dot(h, n))
    zx, zy = float(np.dot(h, tx)) / zh, float(np.dot(h, ty)) / zh
    p = math.exp(-0.5 * (zx * zx / sigma2[0] + zy * zy / sigma2[1])) / (
        2 * math.pi * math.sqrt(sigma2[0] * sigma2[1]))

    def directional(d):
        a, b = float(np.dot(d, tx)), float(np.dot(d, ty))
        return (sigma2[0] * a * a + sigma2[1] * b * b) / (a * a + b * b)

    zv, zl = float(np.dot(v, n)), float(np.dot(l, n))
    lv, ll = smith_lambda(zv, directional(v), erfc), smith_lambda(zl, directional(l), erfc)
    c = float(np.dot(v, h))
    f = 0.02 + 0.98 * (1 - c) ** 5 if schlick else fresnel(c)
    return {"zeta_x": zx, "zeta_y": zy, "p": p, "sigma2_view": directional(v),
            "sigma2_sun": directional(l), "Lambda_V": lv, "Lambda_L": ll, "F": f,
            "brdf_cos": f * p / (4 * zh ** 4 * zv * (1 + lv + ll))}


def brdf(*args):
    return {r["quantity"]: float(r["value"]) for r in oceanref("brdf", *args)}


def rational_erfc(x):  # Bruneton's approximation of erfc
    return 2 * math.exp(-x * x) / (2.319 * x + math.sqrt(4 + 1.52 * x * x))


for view, sun, normal, sigma2, wind, extra in (
        ("0,0.3,1", "0.3,0.5,-1", "0,1,0", (0.01, 0.006), 0, []),
        ("0.2,0.15,1", "-0.1,0.4,-1", "0,1,0", (0.02, 0.011), 35, []),
        ("0,0.3,1", "0.3,0.5,-1", "0.1,1,-0.05", (0.01, 0.006), 0, []),
        ("0,0.2,1", "0.1,0.3,-1", "0,1,0", (0.015, 0.008), -20, ["--fresnel", "schlick"]),
        ("0,0.1,1", "0.2,0.6,-1", "0,1,0", (0.03, 0.02), 10, ["--erfc", "rational"])):
    args = ["--view", view, "--sun", sun, "--normal", normal, "--sigma2",
            f"{sigma2[0]},{sigma2[1]}", "--wind-deg", str(wind), "--accuracy", "fast", *extra]
    got = brdf(*args)
    want = brdf_terms([float(x) for x in view.split(",")], [float(x) for x in sun.split(",")],
                      [float(x) for x in normal.split(",")], sigma2, wind,
                      schlick="schlick" in extra,
                      erfc=rational_erfc if "rational" in extra else math.erfc)
    for name, value in want.items():
        # zeta, p, sigma2, F: 1e-12; Lambda through erfc: 1e-9 (the portable erfc against libm's).
        close(got[name], value, 1e-9, f"brdf {' '.join(args)}: {name}")
    # The sea light is linear in the sea colour; the sky irradiance does not see it.
    double = brdf(*args, "--sea-colour", "0.0078432,0.0313726,0.0941176")
    single = brdf(*args, "--sea-colour", "0.0039216,0.0156863,0.0470588")
    for c in "RGB":
        close(double[f"L_sea.{c}"], 2 * single[f"L_sea.{c}"], 1e-12, f"brdf --sea-colour: L_sea.{c}")
        close(double[f"E_sky.{c}"], single[f"E_sky.{c}"], 0, f"brdf --sea-colour: E_sky.{c}")
# The reference integrals meet --tolerance, and the fast rules approach them as the orders grow.
ref_args = ["--view", "0,0.3,1", "--sun", "0.3,0.5,-1", "--sigma2", "0.01,0.006"]
for tolerance in ("1e-4", "1e-8"):
    r = brdf(*ref_args, "--tolerance", tolerance)
    # (F_mean's tolerance is on 1 - F_mean, the share the sea light carries.)
    for name, scale in (("L_sky.R", r["L_sky.R"]), ("L_sea.G", r["L_sea.G"]),
                        ("L_sun.B", r["L_sun.B"]), ("F_mean", 1 - r["F_mean"])):
        check(r[name + "_error"] <= float(tolerance) * scale,
              f"brdf --tolerance {tolerance}: {name}'s error {r[name + '_error']} over the tolerance")
loose, tight = brdf(*ref_args, "--tolerance", "1e-4"), brdf(*ref_args, "--tolerance", "1e-9")
for name in ("L_sky.R", "L_sea.G", "F_mean"):
    check(abs(loose[name] - tight[name]) <= loose[name + "_error"] + tight[name + "_error"],
          f"brdf --tolerance: {name} moved by more than the two error estimates")
check(loose["evaluations"] < tight["evaluations"], "brdf --tolerance 1e-9 did no more work")
# (The sky's rule is not monotonic in its order: 1, 4, 16 give errors of 5%, 0.5%, 1.4%.)
errors = [abs(brdf(*ref_args, "--accuracy", "fast", "--order", str(order))["L_sky.R"] -
              tight["L_sky.R"]) / tight["L_sky.R"] for order in (1, 128)]
check(errors[1] < 1e-3 < errors[0], f"brdf --order 1, 128: L_sky.R relative errors {errors}")
sun_errors = [abs(brdf(*ref_args, "--accuracy", "fast", "--sun-order", str(o))["L_sun.G"] -
                  tight["L_sun.G"]) for o in (1, 8)]
check(sun_errors[1] < sun_errors[0], f"brdf --sun-order 8 not closer than 1: {sun_errors}")
# Turbidity: a hazier sky is brighter near the horizon and dims the sun (Preetham).
clear, hazy = brdf(*ref_args, "--turbidity", "2"), brdf(*ref_args, "--turbidity", "6")
check(hazy["L_sun_incident.B"] < clear["L_sun_incident.B"], "brdf --turbidity 6 did not dim the sun")
check(hazy["E_sky.R"] > clear["E_sky.R"], "brdf --turbidity 6 did not raise the red sky irradiance")


# --- bench lighting and bench synthesis: the error tables that reference/ACCURACY.md quotes ------

def bench_tables(*args):
    """A bench's output as tables and its '#' lines: a line of names only starts a CSV table (a
    list of rows); name,value lines right under a '#' line form a table of their own (a dict)."""
    r = subprocess.run([binary, "bench", *map(str, args)], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: oceanref bench {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}")

    def number(x):
        try:
            float(x)
            return True
        except ValueError:
            return False

    tables, comments, header, pairs = [], [], None, None
    for line in r.stdout.splitlines():
        fields = line.split(",")
        if line.startswith("#"):
            comments.append(line)
            header, pairs = None, None
        elif not any(number(x) for x in fields):
            header = fields
            tables.append([])
        elif header is None:
            if pairs is None:
                pairs = {}
                tables.append(pairs)
            pairs[fields[0]] = float(fields[1])
        else:
            tables[-1].append(dict(zip(header, fields)))
    return tables, "\n".join(comments)


class Errors:  # the bench's relative-error statistics, written out again
    def __init__(self):
        self.max, self.sum, self.count = 0.0, 0.0, 0

    def add(self, approximate, exact):
        if exact != 0:
            e = abs(approximate - exact) / abs(exact)
            self.max, self.sum, self.count = max(self.max, e), self.sum + e, self.count + 1


def masking(cos_theta, sigma2, erfc):  # G1 = 1 / (1 + Lambda); Lambda = 0 seen from straight up
    return 1 / (1 + (smith_lambda(cos_theta, sigma2, erfc) if cos_theta < 1 else 0.0))


errors = {"fresnel_schlick": Errors(), "erfc_rational": Errors(), "masking": Errors()}
c = 0.0
while c <= 1.0 + 1e-12:  # the bench's own sweeps, step for step (the same doubles)
    errors["fresnel_schlick"].add(0.02 + 0.98 * (1 - c) ** 5, fresnel(c))
    c += 0.001
x = 0.001
while x <= 10.0:
    errors["erfc_rational"].add(rational_erfc(x), math.erfc(x))
    x += 0.001
for s2 in (1e-3, 5e-3, 0.01, 0.02, 0.05, 0.1):
    for zenith in range(0, 90, 5):
        for _ in range(7):  # seven azimuths: the masking sees only the zenith angle
            cos_v = math.cos(math.radians(zenith))
            errors["masking"].add(masking(cos_v, s2, rational_erfc), masking(cos_v, s2, math.erfc))
lighting, _ = bench_tables("lighting", "--order", 16)
rows = {r["approximation"].split(" ")[0]: r for r in lighting[0]}
for name, row in (("fresnel_schlick", "fresnel_schlick_vs_exact"),
                  ("erfc_rational", "erfc_rational_vs_exact"),
                  ("masking", "masking_1/(1+lambda)_rational_vs_exact")):
    e = errors[name]
    check(int(rows[row]["samples"]) == e.count, f"bench lighting {row}: {rows[row]['samples']} "
          f"samples, the sweep has {e.count}")
    # The portable erfc and cos against Python's libm: far below the errors measured (1e-4..0.2).
    close(rows[row]["max_relative_error"], e.max, 1e-6, f"bench lighting {row}: max")
    close(rows[row]["mean_relative_error"], e.sum / e.count, 1e-6, f"bench lighting {row}: mean")
for row in ("mean_fresnel_fit_vs_gauss_hermite", "sky_mirror_lookup_vs_integral",
            "sky_filtered_lookup_vs_integral"):
    check(int(rows[row]["samples"]) == 6 * 18 * 7, f"bench lighting {row}: not 756 samples")
    check(0 < float(rows[row]["mean_relative_error"]) < float(rows[row]["max_relative_error"]),
          f"bench lighting {row}: mean and max errors {rows[row]}")
# Preetham's sun: a longer air path dims it, and the printed transmittance (appendix A.5) agrees
# with the physical one overhead only.
sun = lighting[1]
zeniths = [float(r["sun_zenith_deg"]) for r in sun]
check(zeniths == [0, 30, 45, 60, 70, 80, 85, 88], f"bench lighting: sun zeniths {zeniths}")
physical = [float(r["Y_physical"]) for r in sun]
check(all(a > b > 0 for a, b in zip(physical, physical[1:])),
      f"bench lighting: the sun's Y does not fall with its zenith angle: {physical}")
for r in sun:
    close(r["ratio"], float(r["Y_printed"]) / float(r["Y_physical"]), 1e-12,
          f"bench lighting: printed/physical at {r['sun_zenith_deg']} deg")
close(sun[0]["ratio"], 1.0, 1e-3, "bench lighting: printed and physical transmittance overhead")
check(float(sun[3]["ratio"]) < 0.5, "bench lighting: the printed transmittance at 60 deg")
# The sky integral converges with the Gauss-Hermite order.
orders = lighting[2]
check([int(r["order"]) for r in orders] == [4, 8, 16, 32, 64, 128],
      f"bench lighting: orders {[r['order'] for r in orders]}")
sky_y = [float(r[next(k for k in r if k.startswith("L_sky_Y"))]) for r in orders]
check(abs(sky_y[4] - sky_y[5]) < 1e-3 * sky_y[5] < abs(sky_y[0] - sky_y[5]),
      f"bench lighting: L_sky_Y by order {sky_y} does not converge")

synthesis, notes = bench_tables("synthesis", "--cascades", 2, "--resolution", 32, "--frames", 16,
                         "--threads", 1)
check([r["fft"] for r in synthesis[0]] == ["kissfft", "fftw"], "bench synthesis: the FFT rows")
for r in synthesis[0]:
    # Each frame's four stages are timed inside it, so the stages' means over the 16 frames take
    # time and sum to no more than the mean frame (a stage summed instead of averaged would be
    # 16 times its share: the smallest, unpacking, is ~3% of a frame, the time outside the
    # stages ~1%).
    stages = [float(r[k]) for k in ("evolve_ms", "pack_ms", "transform_ms", "unpack_ms")]
    check(min(stages) > 0 and sum(stages) <= float(r["frame_ms_mean"]),
          f"bench synthesis {r['fft']}: stage times {r}")
difference = float(notes.split("largest field difference kissfft vs fftw: ")[1].split()[0])
check(difference < 1e-14, f"bench synthesis: KissFFT and FFTW fields differ by {difference}")
lookup = {r["field"]: r for r in synthesis[1]}
check(sorted(lookup) == ["height", "jacobian-1", "slope"], f"bench synthesis: lookups {lookup}")
for field, r in lookup.items():
    direct = float(r["max_abs_direct"])
    error = float(r[next(k for k in r if k.startswith("max_abs_bilinear_minus_direct"))])
    check(0 < error < direct, f"bench synthesis: bilinear {field} error {error}, field {direct}")
float_rows = synthesis[2]
FIELDS = ["height", "slope_x", "slope_z", "disp_x", "disp_z", "ddx_dx", "ddz_dz", "ddx_dz"]
check([(r["time_s"], r["field"]) for r in float_rows] ==
      [(t, f) for t in ("10", "1000") for f in FIELDS], "bench synthesis: float rows' order")
for near, far in zip(float_rows[:8], float_rows[8:]):
    close(near["relative"], float(near["max_abs_float_minus_double"]) /
          float(near["max_abs_double"]), 1e-12, f"bench synthesis: relative of {near['field']}")
    # float's phase omega t loses digits as t grows: 1e-7 of the field at 10 s, 1e-5 at 1000 s.
    check(float(near["relative"]) < 2e-6 < float(far["relative"]) < 2e-4,
          f"bench synthesis: float error of {near['field']} at 10 s and 1000 s: "
          f"{near['relative']}, {far['relative']}")

# bench study --quick: every table of the study on small sizes, each against its most exact
# setting. A fast-lit scene whose stormy variant folds (whitecap threshold 0.5).
with tempfile.TemporaryDirectory() as study_dir:
    study_scene = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                              "reference/scenes/golden/pm_high_sun.json")))
    study_scene["shading"] = {"accuracy": "fast", "whitecaps": True, "whitecap_threshold": 0.5}
    study_path = os.path.join(study_dir, "scene.json")
    json.dump(study_scene, open(study_path, "w"))
    study, study_notes = bench_tables("study", "--quick", "--scene", study_path)
check(len(study) == 12, f"bench study --quick: {len(study)} tables, expected 12")
fft = study[0]  # 1. the FFT's fields at grid nodes equal direct summation, to rounding
check(fft["max_abs_difference_at_nodes"] < 1e-12 and fft["direct_seconds_per_point"] > 0,
      f"bench study: FFT vs direct {fft}")
sampled = study[1]  # 2. the sampled spectrum misses less with more nodes and more cascades
check([(r["N"], r["cascades"]) for r in sampled] == [("32", "1"), ("32", "2"), ("64", "1"),
                                                      ("64", "2")], "bench study: N x cascades")
for quantity in ("Hs_relative_error", "mss_relative_error"):
    e = [abs(float(r[quantity])) for r in sampled]
    check(e[0] > e[1] and e[2] > e[3] and e[0] > e[2] and e[1] > e[3],
          f"bench study: {quantity} by N and cascades {e}")
# The same sums written out: Theta(k) dk^2 (spectrum --wavevector) over each cascade's nodes in its
# band [previous Nyquist, pi N / L) (golden-ratio sizes from 800 m), against the continuous
# moments to lambda_min = 1.73 cm (spectrum --moments).
study_spectrum = ["--model", "pierson-moskowitz", "--wind-speed", 8, "--wind-direction-deg", 20,
                  "--spreading", "hasselmann"]
continuous = oceanref("spectrum", *study_spectrum, "--moments", "--k-max", 2 * math.pi / 0.0173)[0]
header = study_notes.split("to lambda_min (Hs ")[1].split(")")[0]  # "H m, mss M"
close(header.split(" m, mss ")[0], continuous["Hs"], 1e-12, "bench study: the continuous Hs")
close(header.split(" m, mss ")[1], continuous["mss"], 1e-12, "bench study: the continuous mss")
for r in sampled:
    n, count = int(r["N"]), int(r["cascades"])
    sizes = [800.0 * (1 - 2 / (1 + math.sqrt(5))) ** i for i in range(count)]
    nodes, lower = [], 0.0
    for size in sizes:
        dk, upper = 2 * math.pi / size, math.pi * n / size
        for b in range(-n // 2, n // 2):
            for a in range(-n // 2, n // 2):
                k = math.hypot(a * dk, b * dk)
                if 0 < k and lower <= k < upper:
                    nodes.append((a * dk, b * dk, dk))
        lower = upper
    theta = [t for i in range(0, len(nodes), 1000) for t in oceanref(  # (a command line's limit)
        "spectrum", *study_spectrum,
        "--wavevector", ",".join(f"{kx!r}:{kz!r}" for kx, kz, _ in nodes[i:i + 1000]))]
    m0 = sum(float(t["Theta"]) * dk * dk for t, (_, _, dk) in zip(theta, nodes))
    mss = sum(float(t["Theta"]) * (kx * kx + kz * kz) * dk * dk
              for t, (kx, kz, dk) in zip(theta, nodes))
    close(1 + float(r["Hs_relative_error"]), 4 * math.sqrt(m0) / float(continuous["Hs"]), 1e-9,
          f"bench study: N {n}, {count} cascades: sampled Hs")
    close(1 + float(r["mss_relative_error"]), mss / float(continuous["mss"]), 1e-9,
          f"bench study: N {n}, {count} cascades: sampled mss")
for table, column, settings in ((study[2], "grid", ["32", "64", "128"]),
                                (study[3], "spp", ["1", "4"])):
    # 3-4. images approach the finest grid (256^2) and the most samples (16 spp)
    check([r[column] for r in table] == settings, f"bench study: {column} rows")
    e = [float(r["relative_rmse"]) for r in table]
    check(all(1 > a > b > 0 for a, b in zip(e, e[1:])), f"bench study: {column} errors {e}")
check("# 3. projected-grid resolution (80x45, 1 spp) vs 256^2" in study_notes and
      "# 4. samples per pixel (40x24, grid 128) vs 16 spp" in study_notes,
      "bench study --quick: the sizes of sections 3 and 4")
foam = study[4]  # 5. whitecap footprints: a share of the nodes, and the Gaussian model's distance
check(0 < foam["mean_coverage"] < 1 and
      0 < foam["mean_abs_difference"] < foam["max_abs_difference"] < 1,
      f"bench study: whitecap statistics {foam}")
modes = {r["interpolation"]: r for r in study[5]}  # 6. interpolation against direct summation
check(list(modes) == ["bilinear", "bicubic", "direct"], "bench study: interpolation rows")
for q in ("max_abs_height_error_m", "max_abs_slope_error"):
    check(float(modes["direct"][q]) == 0 < float(modes["bicubic"][q]) <
          float(modes["bilinear"][q]), f"bench study: {q} by interpolation")
# 7-8: the synthesis and lighting benches above, on the same settings: the same values.
check(study[7:9] == synthesis[1:3], "bench study --quick: synthesis tables differ from "
      "bench synthesis --cascades 2 --resolution 32 --frames 1")
check(study[9:12] == lighting, "bench study --quick: lighting tables differ from bench lighting "
      "--order 16")

# --- sky: Preetham 1999 (its appendix A.2), the sRGB primaries, the irradiance by quadrature ----

def perez(theta, gamma, a, b, c, d, e):  # Preetham eq. 3
    horizon = math.exp(b / math.cos(theta)) if math.cos(theta) > 0 else 0.0
    return (1 + a * horizon) * (1 + c * math.exp(d * gamma) + e * math.cos(gamma) ** 2)


def preetham_xyY(direction, turbidity, sun_zenith, sun_azimuth):
    t = turbidity
    coefficients = {
        "Y": (0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251,
              0.1206 * t - 2.5771, -0.0670 * t + 0.3703),
        "x": (-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125,
              -0.0641 * t - 0.8989, -0.0033 * t + 0.0452),
        "y": (-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102,
              -0.0441 * t - 1.6537, -0.0109 * t + 0.0529)}
    ts = min(sun_zenith, math.pi / 2)
    chi = (4 / 9 - t / 120) * (math.pi - 2 * ts)
    zenith = {"Y": 1000 * ((4.0453 * t - 4.9710) * math.tan(chi) - 0.2155 * t + 2.4192)}
    for name, m in (("x", ((0.00166, -0.00375, 0.00209, 0), (-0.02903, 0.06377, -0.03202, 0.00394),
                           (0.11693, -0.21196, 0.06052, 0.25886))),
                    ("y", ((0.00275, -0.00610, 0.00317, 0), (-0.04214, 0.08970, -0.04153, 0.00516),
                           (0.15346, -0.26756, 0.06670, 0.26688)))):
        th = (ts ** 3, ts ** 2, ts, 1.0)
        zenith[name] = sum(tt * sum(mij * thj for mij, thj in zip(row, th))
                           for tt, row in zip((t * t, t, 1.0), m))
    d = unit(direction)
    sun = np.array([math.sin(ts) * math.cos(sun_azimuth), math.cos(ts),
                    math.sin(ts) * math.sin(sun_azimuth)])
    gamma = math.acos(min(1.0, max(-1.0, float(np.dot(d, sun)))))
    theta = math.acos(min(1.0, max(0.0, float(d[1]))))
    return {k: zenith[k] * perez(theta, gamma, *coefficients[k]) / perez(0.0, ts, *coefficients[k])
            for k in ("x", "y", "Y")}


def xyz_from_xyY(x, y, big_y):
    return np.array([x * big_y / y, big_y, (1 - x - y) * big_y / y])


# linear sRGB from XYZ: the primaries' and D65's chromaticities (IEC 61966-2-1).
primaries = np.column_stack([xyz_from_xyY(0.64, 0.33, 1), xyz_from_xyY(0.30, 0.60, 1),
                             xyz_from_xyY(0.15, 0.06, 1)])
white_scale = np.linalg.solve(primaries, xyz_from_xyY(0.3127, 0.3290, 1))
XYZ_TO_SRGB = np.linalg.inv(primaries * white_scale)


def sky_dir(direction, *args):
    return oceanref("sky", *args, "--dir", ",".join(repr(float(v)) for v in direction))[0]


for zenith_deg, azimuth_deg, turbidity in ((40, 0, 2.5), (70, 120, 2.5), (20, -60, 6), (85, 30, 9.5)):
    args = ["--sun-zenith-deg", str(zenith_deg), "--sun-azimuth-deg", str(azimuth_deg),
            "--turbidity", str(turbidity)]
    for direction in ((0, 1, 0), (0.5, 0.5, 0.7), (-0.9, 0.2, 0.1), (0.1, 0.05, -1)):
        row = sky_dir(direction, *args)
        want = preetham_xyY(direction, turbidity, math.radians(zenith_deg),
                            math.radians(azimuth_deg))
        where = f"sky {' '.join(args)} --dir {direction}"
        close(float(row["Y"]), want["Y"], 1e-9, where + ": Y")
        close(float(row["chroma_x"]), want["x"], 1e-9, where + ": x")
        close(float(row["chroma_y"]), want["y"], 1e-9, where + ": y")
        rgb = XYZ_TO_SRGB @ xyz_from_xyY(want["x"], want["y"], want["Y"])
        for c, value in zip("RGB", rgb):
            close(float(row[c]), value, 1e-9, where + ": " + c)
    # The horizontal irradiance: E = integral of L cos(theta) over the hemisphere, by the
    # midpoint rule in (cos theta, phi) on 400 x 800 cells (the sun disk excluded: --irradiance is
    # the sky's).
    e = oceanref("sky", *args, "--irradiance")[0]
    mu = (np.arange(400) + 0.5) / 400
    phi = (np.arange(800) + 0.5) / 800 * 2 * math.pi
    total = np.zeros(3)
    for m in mu:
        s_theta = math.sqrt(1 - m * m)
        for p_ in phi[::8]:  # the azimuth on every 8th cell, weighted 8x: smooth in phi
            xyY = preetham_xyY((s_theta * math.cos(p_), m, s_theta * math.sin(p_)), turbidity,
                               math.radians(zenith_deg), math.radians(azimuth_deg))
            total += xyz_from_xyY(xyY["x"], xyY["y"], xyY["Y"]) * m
    total *= (1 / 400) * (2 * math.pi / 100)
    where = f"sky {' '.join(args)} --irradiance"
    for k, name in enumerate(("E_X", "E_Y", "E_Z")):
        close(float(e[name]), total[k], 2e-3, f"{where}: {name}")
    # Its RGB is the XYZ's; its error estimate is within the default tolerance 1e-9.
    rgb = XYZ_TO_SRGB @ np.array([float(e["E_X"]), float(e["E_Y"]), float(e["E_Z"])])
    for c, value in zip("RGB", rgb):
        close(float(e[c]), value, 1e-9, f"{where}: {c}")
    check(0 < float(e["relative_error"]) <= 1e-9, f"{where}: relative_error {e['relative_error']}")
    # The sun: its chromaticity and RGB are those of one XYZ; below the horizon all 0.
    s = oceanref("sky", *args, "--sun")[0]
    sun_xyz = xyz_from_xyY(float(s["chroma_x"]), float(s["chroma_y"]), float(s["Y"]))
    for c, value in zip("RGB", XYZ_TO_SRGB @ sun_xyz):
        close(float(s[c]), value, 1e-9, f"sky {' '.join(args)} --sun: {c} from Y, chroma_x, chroma_y")
# --sun: the disk's angular radius and the transmittance form; a set sun gives 0 everywhere.
sun = oceanref("sky", "--sun-zenith-deg", "40", "--sun")[0]
check(all(float(v) == 0 for k, v in oceanref("sky", "--sun-zenith-deg", "95", "--sun")[0].items()
          if k != "angular_radius_rad"), "sky --sun-zenith-deg 95 --sun: the set sun is not 0")
close(float(sun["angular_radius_rad"]), math.radians(0.2667), 2e-3, "sky --sun: angular radius")
printed = oceanref("sky", "--sun-zenith-deg", "40", "--sun", "--printed-transmittance")[0]
check(float(printed["Y"]) != float(sun["Y"]), "sky --printed-transmittance changes nothing")
check(float(oceanref("sky", "--sun-zenith-deg", "75", "--sun")[0]["Y"]) < float(sun["Y"]),
      "sky --sun: a lower sun is not dimmer")
# --size N -o: the hemisphere image, pixel (row, column) the direction at radius r = theta/(pi/2).
def sky_hemisphere_image():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sky.exr")
        subprocess.run([binary, "sky", "--sun-zenith-deg", "50", "--sun-azimuth-deg", "30",
                        "--size", "16", "-o", path], check=True, capture_output=True)
        image = oiio.ImageInput.open(path)
        spec = image.spec()
        pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
        image.close()
        y_index = list(spec.channelnames).index("Y")
        for row_, column in ((8, 8), (3, 10), (12, 2), (0, 0)):
            u = (2 * column + 1) / 16 - 1
            v = (2 * row_ + 1) / 16 - 1
            r = math.hypot(u, v)
            if r > 1:
                check(pixels[row_, column, y_index] == 0, f"sky --size: ({row_}, {column}) outside "
                                                          "the disk is not 0")
                continue
            zen, az = 0.5 * math.pi * r, math.atan2(v, u)
            want = preetham_xyY((math.sin(zen) * math.cos(az), math.cos(zen),
                                 math.sin(zen) * math.sin(az)), 2.5, math.radians(50),
                                math.radians(30))["Y"]
            close(float(pixels[row_, column, y_index]), want, 1e-6,
                  f"sky --size 16: Y at ({row_}, {column})")
    # The sun disk adds the sun's radiance (sky --sun) to the sky's: on a 9-pixel image the
    # centre of pixel (4, 6) is at zenith 90 * 4/9 = 40 deg, azimuth 0 - the sun's direction.
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sun.exr")
        subprocess.run([binary, "sky", "--sun-zenith-deg", "40", "--size", "9", "-o", path],
                       check=True, capture_output=True)
        layers = read_layers(path)
    sun = oceanref("sky", "--sun-zenith-deg", "40", "--sun")[0]
    for column, disk in ((6, 1.0), (5, 0.0)):
        u, v = (2 * column + 1) / 9 - 1, 0.0
        direction = (math.sin(math.pi / 2 * u), math.cos(math.pi / 2 * u), 0.0)
        sky_only = oceanref("sky", "--sun-zenith-deg", "40",
                            "--dir", ",".join(map(repr, direction)))[0]
        for c in ("Y", "R", "G", "B"):
            close(float(layers[c][4, column]), float(sky_only[c]) + disk * float(sun[c]), 1e-6,
                  f"sky --size 9, sun at 40 deg: {c} at (4, {column})")


sky_hemisphere_image()


# --- brdf against sky: every row of brdf, each against what it is made of -----------------------
# The sky and sun of `sky` at the sun's zenith and azimuth, L_sun = the disk's reflectance x the
# incident sun, the fast errors = |fast - reference| + the reference's estimate, the real-time
# shortcuts, the demo's F_mean fit.
def brdf_rows():
    args = ["--view", "0.1,0.25,1", "--sun", "0.3,0.5,-1", "--sigma2", "0.012,0.005",
            "--wind-deg", "15", "--turbidity", "3"]
    fast, ref = brdf(*args, "--accuracy", "fast", "--order", "4"), brdf(*args)
    rgb_terms = ["L_sun_incident", "L_sun", "L_sky", "L_sky_filtered", "L_sky_mirror", "E_sky",
                 "L_sea"]
    names = ["zeta_x", "zeta_y", "p", "sigma2_view", "sigma2_sun", "Lambda_V", "Lambda_L", "F",
             "brdf_cos", "F_mean", "F_mean_error", "F_mean_fit", "sun_reflectance",
             "sun_reflectance_error", "evaluations", "converged"]
    names += [f"{t}.{c}" for t in rgb_terms for c in "RGB"]
    names += [f"{t}.{c}_error" for t in ("L_sun", "L_sky", "L_sea") for c in "RGB"]
    for mode, got in (("fast", fast), ("reference", ref)):
        check(sorted(got) == sorted(names), f"brdf --accuracy {mode}: rows "
              f"{sorted(set(got) ^ set(names))} missing or unexpected")
        check(got["converged"] == 1, f"brdf --accuracy {mode}: not converged")
    sun = unit([0.3, 0.5, -1])
    sky_args = ["--sun-zenith-deg", repr(math.degrees(math.acos(sun[1]))), "--sun-azimuth-deg",
                repr(math.degrees(math.atan2(sun[2], sun[0]))), "--turbidity", "3"]
    incident = oceanref("sky", *sky_args, "--sun")[0]
    irradiance = oceanref("sky", *sky_args, "--irradiance")[0]
    view, n = unit([0.1, 0.25, 1]), np.array([0.0, 1.0, 0.0])
    mirror_sky = sky_dir(2 * float(np.dot(view, n)) * n - view, *sky_args)
    for c in "RGB":
        for mode, got in (("fast", fast), ("reference", ref)):
            where = f"brdf --accuracy {mode}: "
            close(got[f"L_sun_incident.{c}"], float(incident[c]), 1e-9, where + f"L_sun_incident.{c}")
            close(got[f"E_sky.{c}"], float(irradiance[c]), 1e-9, where + f"E_sky.{c}")
            close(got[f"L_sun.{c}"], got["sun_reflectance"] * got[f"L_sun_incident.{c}"], 1e-12,
                  where + f"L_sun.{c} = sun_reflectance x L_sun_incident")
            # L_sea = (1 - F_mean) x sea colour x E_sky / pi (Bruneton 2010 section 4.3).
            sea = (0.0039216, 0.0156863, 0.0470588)["RGB".index(c)]
            close(got[f"L_sea.{c}"], (1 - got["F_mean"]) * sea * got[f"E_sky.{c}"] / math.pi,
                  1e-12, where + f"L_sea.{c}")
            # The real-time shortcut: the sky in the mirror direction times F_mean of the same
            # rule (the fast order, or 64 for reference, whose F_mean is nearly the converged one).
            close(got[f"L_sky_mirror.{c}"], got["F_mean"] * float(mirror_sky[c]),
                  1e-12 if mode == "fast" else 1e-6, where + f"L_sky_mirror.{c}")
        close(ref[f"L_sun.{c}_error"], ref["sun_reflectance_error"] * ref[f"L_sun_incident.{c}"],
              1e-12, f"brdf: L_sun.{c}_error = sun_reflectance_error x L_sun_incident")
        close(ref[f"L_sea.{c}_error"], ref["F_mean_error"] *
              (0.0039216, 0.0156863, 0.0470588)["RGB".index(c)] * ref[f"E_sky.{c}"] / math.pi,
              1e-12, f"brdf: L_sea.{c}_error = F_mean_error x sea colour x E_sky / pi")
        for t in ("L_sun", "L_sky", "L_sea"):
            close(fast[f"{t}.{c}_error"],
                  abs(fast[f"{t}.{c}"] - ref[f"{t}.{c}"]) + ref[f"{t}.{c}_error"], 1e-9,
                  f"brdf --accuracy fast: {t}.{c}_error = |fast - reference| + its estimate")
    for name in ("F_mean", "sun_reflectance"):
        close(fast[name + "_error"], abs(fast[name] - ref[name]) + ref[name + "_error"], 1e-9,
              f"brdf --accuracy fast: {name}_error = |fast - reference| + its estimate")
    # The terms the modes share are the same numbers; the fast errors are measured by the
    # reference's work.
    for name in ("p", "F", "brdf_cos", "Lambda_V", "E_sky.G", "L_sun_incident.G", "F_mean_fit"):
        check(fast[name] == ref[name], f"brdf: {name} differs between the modes")
    check(fast["evaluations"] == ref["evaluations"] > 0, "brdf: the fast errors' evaluations")
    # The demo's fitted mean Fresnel (src/FORMULAS.md, misprint 29), sigma_V the slope deviation
    # along the view.
    sigma_v = math.sqrt(fast["sigma2_view"])
    fit = 0.02 + 0.98 * (1 - float(np.dot(view, n))) ** (5 * math.exp(-2.69 * sigma_v)) / (
        1 + 22.7 * sigma_v ** 1.5)
    close(fast["F_mean_fit"], fit, 1e-12, "brdf: F_mean_fit (Bruneton eq. 15)")
    # Filtered sky: the mirror sky averaged over the facets' reflections -> the mirror's at small
    # slopes; at larger ones it is the average of the sky over the reflected directions.
    narrow = brdf("--view", "0.1,0.25,1", "--sun", "0.3,0.5,-1", "--sigma2", "1e-6,1e-6",
                  "--turbidity", "3", "--accuracy", "fast")
    for c in "RGB":
        close(narrow[f"L_sky_filtered.{c}"], narrow[f"L_sky_mirror.{c}"], 1e-2,
              f"brdf --sigma2 1e-6: L_sky_filtered.{c} -> L_sky_mirror")
    order = 4
    xs, ws = np.polynomial.hermite.hermgauss(order)
    wind = math.radians(15)
    tx = unit(np.array([math.cos(wind), 0.0, math.sin(wind)]))
    ty = np.cross(n, tx)
    total = np.zeros(3)
    for i in range(order):
        for j in range(order):
            zx, zy = math.sqrt(2 * 0.012) * xs[i], math.sqrt(2 * 0.005) * xs[j]
            m = unit(n - zx * tx - zy * ty)
            # (below the horizon the sky is continued by its horizon limit: `sky --dir` too)
            row = sky_dir(2 * float(np.dot(view, m)) * m - view, *sky_args)
            total += ws[i] * ws[j] / math.pi * np.array([float(row[c]) for c in "RGB"])
    for k, c in enumerate("RGB"):
        close(fast[f"L_sky_filtered.{c}"], fast["F_mean"] * total[k], 1e-9,
              f"brdf --order {order}: L_sky_filtered.{c} against the sky at the reflected facets")


brdf_rows()


# --- Range ends: every flag's range, as --help states it, is the one enforced ---------------------

def ranged_flags(path):
    """(flag, kind, lo, hi) of every option whose --help shows a validator range, in order (a
    TEXT option's range is a number's: number_in)."""
    text = cli_reference.help_text(binary, path)
    pattern = re.compile(r"^\s+(?:-\w,)?(--[\w-]+) (INT|FLOAT|TEXT):\w+ in \[([^\],]+?)(?:, | - )([^\]]+)\]")
    return [(m[1], m[2], m[3], m[4]) for m in map(pattern.match, text.splitlines()) if m]


def range_ends():
    """Just outside each end: exit 2 naming the flag. Each end itself: not refused (an unexpected
    argument makes the run fail after every option's check, naming that argument instead)."""
    tested = 0
    for path in cli_reference.commands(binary):
        for flag, kind, lo, hi in ranged_flags(path):
            where = f"oceanref {' '.join(path)} {flag}"
            if kind == "INT":
                inside, outside = [lo, hi], [str(int(lo) - 1), str(int(hi) + 1)]
            else:
                inside = [repr(float(lo)), repr(float(hi))]
                outside = [repr(math.nextafter(float(lo), -math.inf)),
                           repr(math.nextafter(float(hi), math.inf))]
            for value in outside:  # (the sentinel stops a wrongly accepted run at once)
                r = subprocess.run([binary, *path, f"{flag}={value}", "--range-sentinel"],
                                   capture_output=True, text=True)
                check(r.returncode == 2 and r.stderr.startswith(f"oceanref: {flag}: "),
                      f"{where} {value}: outside [{lo}, {hi}] but not refused: {r.stderr.strip()}")
            for value in inside:
                r = subprocess.run([binary, *path, f"{flag}={value}", "--range-sentinel"],
                                   capture_output=True, text=True)
                check(f"oceanref: {flag}: " not in r.stderr,
                      f"{where} {value}: the end of [{lo}, {hi}] refused: {r.stderr.strip()}")
            tested += 1
    check(tested >= 49, f"range ends: only {tested} ranged flags found in the help")


range_ends()


# --- compare: every metric and threshold flag against the definitions (docs/BACKENDS.md) --------

def write_rgb(path, pixels, names=("R", "G", "B")):
    out = oiio.ImageOutput.create(path)
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], pixels.shape[2], "float")
    spec.channelnames = names
    out.open(path, spec)
    out.write_image(pixels)
    out.close()


def ordered(f):  # float32 bits on one monotonic integer line (the ULP distance's)
    i = f.view(np.int32).astype(np.int64)
    return np.where(i < 0, -(i & 0x7FFFFFFF), i)


def channel_metrics(g, c, a=0.0, r=0.0, floor=0.0, ulp=0):
    g64, c64 = g.astype(np.float64).ravel(), c.astype(np.float64).ravel()
    rms = math.sqrt(float(np.mean(g64 * g64)))
    scale = np.maximum(np.abs(g64), floor * rms)
    diff = np.abs(c64 - g64)
    with np.errstate(divide="ignore", invalid="ignore"):  # (0/0 where both are zero)
        rel = np.where(diff == 0, 0.0, diff / scale)
    ulps = np.abs(ordered(c.ravel()) - ordered(g.ravel()))
    fails = ~(diff <= a + r * scale) & (ulps > ulp)
    ranks = sorted(rel)
    n = len(ranks)
    pct = [ranks[min(max(math.ceil(q / 100 * n), 1), n) - 1] for q in (50, 90, 99, 99.9)]
    rmse = math.sqrt(float(np.mean(diff * diff)))
    peak = float(np.abs(g64).max())  # PSNR: 20 log10(peak |golden| / RMSE); -inf for a zero golden
    psnr = math.inf if rmse == 0 else -math.inf if peak == 0 else 20 * math.log10(peak / rmse)
    return {"max_rel": float(rel.max()), "max_abs": float(diff.max()), "golden_rms": rms,
            "max_ulp": int(ulps.max()), "failing": int(fails.sum()),
            "rel_percentiles": pct + [float(rel.max())], "rmse": rmse, "psnr_db": psnr,
            "rel_map": rel.reshape(g.shape), "fail_map": fails.reshape(g.shape)}


def compare(*args, expect=None):
    r = subprocess.run([binary, "compare", *map(str, args), "--format", "json"],
                       capture_output=True, text=True)
    if r.returncode not in (0, 1):
        sys.exit(f"FAIL: oceanref compare {' '.join(map(str, args))}: {r.stderr}")
    result = json.loads(r.stdout)
    if expect is not None:
        check(r.returncode == expect, f"compare {' '.join(map(str, args))}: exit {r.returncode}, "
                                      f"expected {expect}")
    return {c["golden"]: c for c in result["parts"][0]["channels"]}, r.returncode


def compare_flags():
    with tempfile.TemporaryDirectory() as tmp:
        rng = np.random.default_rng(7)
        g = rng.uniform(0.0, 2.0, (24, 32, 3)).astype(np.float32)
        g[0, 0, 1] = 0.0  # a zero of the golden: the floor decides its scale
        c = g.copy()
        c[..., 0] *= (1 + rng.normal(0, 1e-3, (24, 32))).astype(np.float32)
        c[..., 1] += rng.normal(0, 1e-4, (24, 32)).astype(np.float32)
        c[3, 5, 2] = np.nextafter(c[3, 5, 2], np.float32(9), dtype=np.float32)  # one ULP
        gp, cp = os.path.join(tmp, "g.exr"), os.path.join(tmp, "c.exr")
        write_rgb(gp, g)
        write_rgb(cp, c)
        for flags, thresholds in (([], {}), (["--floor", "0.5"], {"floor": 0.5}),
                                  (["--rel", "2e-3", "--floor", "0.1"], {"r": 2e-3, "floor": 0.1}),
                                  (["--abs", "1e-4", "--floor", "0.1"], {"a": 1e-4, "floor": 0.1}),
                                  (["--ulp", "1", "--floor", "0.1"], {"ulp": 1, "floor": 0.1})):
            got, _ = compare(cp, gp, *flags)
            for k, name in enumerate("RGB"):
                want = channel_metrics(g[..., k], c[..., k], **thresholds)
                for key in ("max_rel", "max_abs", "golden_rms", "rmse", "psnr_db"):
                    close(got[name][key], want[key], 1e-12, f"compare {' '.join(flags)}: {name} {key}")
                for key in ("max_ulp", "failing"):
                    check(got[name][key] == want[key], f"compare {' '.join(flags)}: {name} {key} "
                                                       f"{got[name][key]}, expected {want[key]}")
                for q, (a_, b_) in enumerate(zip(got[name]["rel_percentiles"],
                                                 want["rel_percentiles"])):
                    close(a_, b_, 1e-12, f"compare {' '.join(flags)}: {name} percentile {q}")
        # A golden of zeros: PSNR -inf where the candidate differs, +inf where it does not.
        zero = np.zeros_like(g)
        zero_path, mixed_path = os.path.join(tmp, "zero.exr"), os.path.join(tmp, "mixed.exr")
        write_rgb(zero_path, zero)
        mixed = zero.copy()
        mixed[..., 0] = c[..., 0]
        write_rgb(mixed_path, mixed)
        got, _ = compare(mixed_path, zero_path)
        for name in "RGB":
            close(got[name]["psnr_db"], channel_metrics(zero[..., 0], mixed[..., "RGB".index(name)])
                  ["psnr_db"], 0, f"compare against a zero golden: {name} psnr_db")
        check(float(got["R"]["psnr_db"]) == -math.inf and float(got["G"]["psnr_db"]) == math.inf,
              f"compare against a zero golden: PSNR {got['R']['psnr_db']}, {got['G']['psnr_db']}")
        # The thresholds at their boundary: R's largest relative error passes --rel equal to it
        # (|c - g| <= R s) and fails just below; --max-fail-share at the failing share.
        worst = channel_metrics(g[..., 0], c[..., 0], floor=0.1)["max_rel"]
        compare(cp, gp, "--channels", "R", "--floor", "0.1", "--rel", repr(worst * (1 + 1e-9)),
                expect=0)
        compare(cp, gp, "--channels", "R", "--floor", "0.1", "--rel", repr(worst * (1 - 1e-6)),
                expect=1)
        share = channel_metrics(g[..., 1], c[..., 1], r=5e-5, floor=0.1)["failing"] / g[..., 1].size
        check(0 < share < 1, f"compare: the G channel's failing share {share} is not between 0 and 1")
        compare(cp, gp, "--channels", "G", "--floor", "0.1", "--rel", "5e-5", "--max-fail-share",
                repr(share), expect=0)
        compare(cp, gp, "--channels", "G", "--floor", "0.1", "--rel", "5e-5", "--max-fail-share",
                repr(share * 0.999), expect=1)
        # --channels CANDIDATE=GOLDEN: the candidate's G against the golden's R.
        got, _ = compare(cp, gp, "--channels", "G=R", "--floor", "0.1")
        want = channel_metrics(g[..., 0], c[..., 1], floor=0.1)
        close(got["R"]["max_abs"], want["max_abs"], 1e-12, "compare --channels G=R: max_abs")
        check(list(got) == ["R"], f"compare --channels G=R compared {list(got)}")
        text = subprocess.run([binary, "compare", cp, gp, "--channels", "G=R", "--floor", "0.1"],
                              capture_output=True, text=True).stdout
        check(any(line.split()[:1] == ["G=R"] for line in text.splitlines()),
              f"compare --channels G=R: the text table does not name the row G=R:\n{text}")
        # A profile file with the same thresholds gives the same verdicts as the flags.
        profile = os.path.join(tmp, "profile.json")
        json.dump({"default": {"rel": 2e-3, "floor": 0.1},
                   "channels": [{"match": "G", "rel": 5e-5, "floor": 0.1}]}, open(profile, "w"))
        got, _ = compare(cp, gp, "--profile", profile)
        check(got["R"]["failing"] == channel_metrics(g[..., 0], c[..., 0], r=2e-3, floor=0.1)["failing"]
              and got["G"]["failing"] == channel_metrics(g[..., 1], c[..., 1], r=5e-5,
                                                         floor=0.1)["failing"],
              "compare --profile: the failing counts are not the profile's thresholds'")
        # --json FILE holds what --format json prints.
        out = os.path.join(tmp, "out.json")
        subprocess.run([binary, "compare", cp, gp, "--json", out], capture_output=True)
        printed = subprocess.run([binary, "compare", cp, gp, "--format", "json"],
                                 capture_output=True, text=True).stdout
        check(json.load(open(out)) == json.loads(printed), "compare --json differs from --format json")
        # --suggest: rel = safety x the largest relative error over the runs (floor as given).
        c2 = g.copy()
        c2[..., 0] *= np.float32(1.0005)
        c2p = os.path.join(tmp, "c2.exr")
        write_rgb(c2p, c2)
        runs = os.path.join(tmp, "runs.txt")
        open(runs, "w").write(f"{cp}\n{c2p}\n")
        suggested = os.path.join(tmp, "suggested.json")
        subprocess.run([binary, "compare", "--suggest", "--list", runs, gp, "--safety", "3",
                        "--floor", "0.1", "-o", suggested, "--name", "mine"], check=True,
                       capture_output=True)
        rule = json.load(open(suggested))
        check(rule.get("name") == "mine", f"compare --suggest --name: the profile is named "
                                          f"{rule.get('name')}")
        for k, name in enumerate("RGB"):
            worst_k = max(channel_metrics(g[..., k], x[..., k], floor=0.1)["max_rel"] for x in (c, c2))
            rules = [r for r in rule["channels"] if r["match"] == name]
            check(len(rules) == 1, f"compare --suggest: {len(rules)} rules for {name}")
            if rules:
                close(rules[0]["rel"], 3 * worst_k, 1e-12, f"compare --suggest --safety 3: {name} rel")
                close(rules[0]["floor"], 0.1, 0, f"compare --suggest --floor: {name}")
        # The profile's derivation names up to 4 runs' candidates, in order; more, the list file.
        for count in (4, 5):
            listed = [cp, c2p, c2p, cp, c2p][:count]
            open(runs, "w").write("".join(f"{x}\n" for x in listed))
            subprocess.run([binary, "compare", "--suggest", "--list", runs, gp, "-o", suggested],
                           check=True, capture_output=True)
            derivation = json.load(open(suggested))["derivation"].split(";")[0]
            named = " ".join(os.path.basename(x) for x in listed)
            want = (f"oceanref compare --suggest over {count} run(s): " +
                    (named if count <= 4 else f"listed in {runs}"))
            check(derivation == want, f"compare --suggest over {count} runs: derivation "
                                      f"{derivation!r}, expected {want!r}")
        compare_text_table(cp, gp, g, c)


def compare_text_table(cp, gp, g, c):
    """The text table of compare: each row the JSON's numbers (%.3g, as printed), its worst
    pixel the one of largest relative error (row-major first among ties) with its two values."""
    flags = ["--rel", "2e-3", "--floor", "0.1", "--ulp", "3"]
    got, _ = compare(cp, gp, *flags)
    text = subprocess.run([binary, "compare", cp, gp, *flags], capture_output=True,
                          text=True).stdout.splitlines()
    rows = {line.split()[0]: line.split() for line in text if line.split()[:1] in (["R"], ["G"], ["B"])}
    check(sorted(rows) == ["B", "G", "R"], f"compare text: rows {sorted(rows)}:\n{text}")
    short = lambda v: "%.3g" % float(v)  # noqa: E731 (compare.cpp short_number)
    for k, name in enumerate("RGB"):
        j, row = got[name], rows.get(name, [])
        worst = channel_metrics(g[..., k], c[..., k], r=2e-3, floor=0.1, ulp=3)["rel_map"]
        y, x = np.unravel_index(int(np.argmax(worst)), worst.shape)
        want = [name, j["result"].upper() if j["result"] == "fail" else j["result"],
                short(100 * j["failing_share"]) + "%",
                *[short(v) for v in j["rel_percentiles"]], short(j["max_abs"]),
                short(j["golden_rms"]), str(j["max_ulp"]),
                f"A={short(j['threshold']['abs'])}", f"R={short(j['threshold']['rel'])}",
                f"F={short(j['threshold']['floor'])}", f"U={j['threshold']['ulp']}"]
        if worst.max() > 0:
            want += [f"{x},{y}", "(g", short(g[y, x, k]) + ",", "c", short(c[y, x, k]) + ")"]
        check(row == want, f"compare text row {name}: {row}, expected {want}")


compare_flags()


def png_from_data_uri(uri, tmp):
    """A data:image/png;base64 URI of the report, decoded by OpenImageIO: rows x columns x 3."""
    prefix = "data:image/png;base64,"
    check(uri.startswith(prefix), f"compare --report: not a PNG data URI: {uri[:40]}")
    path = os.path.join(tmp, "picture.png")
    open(path, "wb").write(base64.b64decode(uri[len(prefix):]))
    image = oiio.ImageInput.open(path)
    pixels = image.read_image(0, 0, 0, 3, "uint8")
    image.close()
    return pixels.astype(np.int64)


def luminance(rgb):  # BT.709 Y of linear sRGB, the last axis R, G, B
    return (0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]).astype(np.float64)


def srgb_bytes(linear):  # IEC 61966-2-1 encoding, clamped, rounded to 8 bits
    c = np.clip(linear, 0.0, 1.0)
    encoded = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.rint(255 * np.clip(encoded, 0.0, 1.0)).astype(np.int64)


def compare_report_pictures():
    """The pictures of compare --report, decoded and checked against what they show: the colour
    overview tone-mapped with the golden's exposure (Reinhard's global operator, key 0.18, white
    the golden's brightest), each channel's values grey between the golden's range, the fail
    mask red exactly where the values fail, the heat map brighter for larger errors."""
    with tempfile.TemporaryDirectory() as tmp:
        rng = np.random.default_rng(11)
        g = rng.uniform(1.0, 3.0, (12, 20, 3)).astype(np.float32)  # lo well above 0
        g[2, 3] = (40.0, 35.0, 30.0)  # a highlight sets the white point
        c = g.copy()
        c[..., 0] *= (1 + rng.normal(0, 3e-3, (12, 20))).astype(np.float32)
        c[5:8, 10:14] *= np.float32(1.5)  # a region 50% brighter: beyond the golden's range
        gp, cp = os.path.join(tmp, "g.exr"), os.path.join(tmp, "c.exr")
        write_rgb(gp, g)
        write_rgb(cp, c)
        report_dir = os.path.join(tmp, "report")
        subprocess.run([binary, "compare", cp, gp, "--rel", "2e-3", "--report", report_dir],
                       capture_output=True)
        html = open(os.path.join(report_dir, "index.html")).read()
        flips = re.findall(r'<figure class="flip" data-golden="([^"]+)" data-candidate="([^"]+)"',
                           html)
        check(len(flips) == 4, f"compare --report: {len(flips)} flip figures, expected 1 + 3")
        if len(flips) != 4:
            return
        # The colour overview: Reinhard (eq. 4) on the luminance, with the golden's log-average
        # (delta 1e-4) and white for both pictures.
        y_g = luminance(g)
        average = math.exp(float(np.mean(np.log(1e-4 + np.maximum(y_g, 0)))))
        white = float((0.18 / average * y_g).max())
        for k, (name, x) in enumerate((("golden", g), ("candidate", c))):
            y = luminance(x)
            l = 0.18 / average * y
            scale = l * (1 + l / white ** 2) / (1 + l) / y
            want = srgb_bytes(x.astype(np.float64) * scale[..., None])
            got = png_from_data_uri(flips[0][k], tmp)
            check(got.shape == want.shape and np.abs(got - want).max() <= 1,
                  f"compare --report: the {name}'s colour overview is not its tone mapping "
                  f"(largest byte difference {np.abs(got - want).max() if got.shape == want.shape else got.shape})")
        sections = re.split(r'<section class="channel"', html)[1:]
        names = [re.search(r'data-channel="([^"]+)"', s_)[1] for s_ in sections]
        check(names == list("BGR"), f"compare --report: the channel sections {names} (EXR order)")
        for name, section, (golden_uri, candidate_uri) in zip(names, sections, flips[1:]):
            k = "RGB".index(name)
            lo, hi = float(g[..., k].min()), float(g[..., k].max())
            for side, x, uri in (("golden", g, golden_uri), ("candidate", c, candidate_uri)):
                want = np.rint(255 * np.clip((x[..., k].astype(np.float64) - lo) / (hi - lo), 0, 1))
                got = png_from_data_uri(uri, tmp)
                check(got.shape[:2] == want.shape and np.abs(got[..., 0] - want).max() <= 1 and
                      (got[..., 0] == got[..., 1]).all() and (got[..., 1] == got[..., 2]).all(),
                      f"compare --report: {name}'s {side} values are not grey from {lo} to {hi}")
            m = channel_metrics(g[..., k], c[..., k], r=2e-3)
            mask = png_from_data_uri(re.search(r'<img class="mask" src="([^"]+)"', section)[1], tmp)
            red = (mask == (230, 30, 30)).all(axis=-1)
            check(np.array_equal(red, m["fail_map"]) and
                  ((mask == (225, 225, 225)).all(axis=-1) | red).all(),
                  f"compare --report: {name}'s fail mask is not red exactly where values fail")
            heat = png_from_data_uri(re.search(r'<img class="heat" src="([^"]+)"', section)[1], tmp)
            check(np.abs(heat - heat_colours(m["rel_map"])).max() <= 1,
                  f"compare --report: {name}'s heat map is not the error's colour scale")
            # The legend: a 300-pixel bar of the same scale, ticks at each decade and the
            # threshold R = 2e-3 marked where it lies, (log10 R + 9)/9 of the way: 210 px.
            legend = re.search(r'<div class="legend">(.*?)</div> relative error', section)
            check(legend is not None, f"compare --report: {name} has no legend")
            if legend is None:
                continue
            bar = png_from_data_uri(re.search(r'<img src="([^"]+)"[^>]*alt="colour bar"',
                                              legend[1])[1], tmp)
            decades = -9 + 9 * (np.arange(300) + 0.5) / 300
            check(bar.shape == (14, 300, 3) and
                  np.abs(bar - heat_colours(10.0 ** decades)[None, :, :]).max() <= 1,
                  f"compare --report: {name}'s colour bar is not the heat map's scale")
            ticks = re.findall(r'<span class="tick" style="left:(\d+)px">1e(-?\d+)</span>', legend[1])
            check(ticks == [(str(300 * k // 9), str(k - 9)) for k in range(10)],
                  f"compare --report: {name}'s legend ticks {ticks}")
            marks = re.findall(r'<span class="threshold" style="left:(\d+)px"', legend[1])
            check(marks == [str(round(300 * (math.log10(2e-3) + 9) / 9))] == ["210"] and
                  "the white mark is the threshold R = 0.002" in section,
                  f"compare --report: {name}'s threshold mark at {marks} px, expected 210")


def heat_colours(e):
    """The report's heat colour of relative errors (docs: 1e-9 to 1 on a log scale, clamped;
    black for 0): linear between five anchors from dark blue to pale yellow, lighter for larger."""
    anchors = np.array([(20, 11, 82), (110, 30, 130), (200, 50, 80), (245, 140, 20),
                        (252, 250, 170)], float)
    with np.errstate(divide="ignore"):
        t = np.clip((np.log10(e) + 9) / 9, 0, 1)
    k = np.minimum(np.floor(4 * t), 3).astype(int)
    f = (4 * t - k)[..., None]
    colours = np.rint(anchors[k] + f * (anchors[k + 1] - anchors[k])).astype(np.int64)
    colours[e == 0] = 0
    return colours


compare_report_pictures()


def compare_report_single_parts():
    """Two single-part files are compared part to part whatever their names (compare's rule);
    the report shows that pair too: a golden part named 'beauty' against an unnamed candidate
    gives the colour overview and one section per channel, named after the golden's part."""
    with tempfile.TemporaryDirectory() as tmp:
        g = np.random.default_rng(5).uniform(1.0, 2.0, (6, 8, 3)).astype(np.float32)
        gp, cp = os.path.join(tmp, "g.exr"), os.path.join(tmp, "c.exr")
        out = oiio.ImageOutput.create(gp)
        spec = oiio.ImageSpec(8, 6, 3, "float")
        spec.attribute("oiio:subimagename", "beauty")
        out.open(gp, spec)
        out.write_image(g)
        out.close()
        write_rgb(cp, g * np.float32(1.01))
        report_dir = os.path.join(tmp, "report")
        r = subprocess.run([binary, "compare", cp, gp, "--report", report_dir],
                           capture_output=True, text=True)
        check(r.returncode == 1 and "part 'beauty'" in r.stdout,
              f"compare of a named and an unnamed single part: {r.returncode} {r.stdout}")
        html = open(os.path.join(report_dir, "index.html")).read()
        flips = re.findall(r'<figure class="flip"', html)
        sections = re.findall(r'<section class="channel" [^>]*data-channel="([^"]+)"', html)
        check(len(flips) == 4 and sections == ["beauty/B", "beauty/G", "beauty/R"],
              f"compare --report of a named and an unnamed single part: {len(flips)} flip "
              f"figures (expected 4), channel sections {sections}")


compare_report_single_parts()


def compare_report_nonfinite_and_ssim():
    """compare --report counts a non-finite mismatch in the rule and in its channel's heading and
    paints the pixel magenta in the colour overview; a profile's min_ssim is stated beside the
    SSIM as given (not rounded) with its verdict, pass at 0.5 and FAIL at 0.999999 for the same
    1% noise."""
    with tempfile.TemporaryDirectory() as tmp:
        rng = np.random.default_rng(3)
        g = rng.uniform(1.0, 2.0, (16, 16, 3)).astype(np.float32)
        c = (g * (1 + rng.normal(0, 0.01, g.shape))).astype(np.float32)
        gp, cp, np_ = (os.path.join(tmp, n) for n in ("g.exr", "c.exr", "nan.exr"))
        write_rgb(gp, g)
        write_rgb(cp, c)
        nan = g.copy()
        nan[4, 9, 1] = np.nan
        write_rgb(np_, nan)
        report_dir = os.path.join(tmp, "nan")
        subprocess.run([binary, "compare", np_, gp, "--report", report_dir], capture_output=True)
        html = open(os.path.join(report_dir, "index.html")).read()
        check("a non-finite mismatch always fails (<b>1 non-finite mismatches</b>)." in html,
              "compare --report: the rule does not count the non-finite mismatch")
        headings = re.findall(r'<h3>[^<]*G: FAIL[^\n]*', html)
        check(len(headings) == 1 and ", <b>1 non-finite mismatches</b></h3>" in headings[0],
              f"compare --report: channel G's heading {headings}")
        flip = re.search(r'<figure class="flip" data-golden="([^"]+)" data-candidate="([^"]+)"', html)
        overview = png_from_data_uri(flip[2], tmp)
        magenta = (overview == (255, 0, 255)).all(axis=-1)
        check(magenta[4, 9] and magenta.sum() == 1,
              f"compare --report: the non-finite pixel is not the one magenta pixel "
              f"({int(magenta.sum())} magenta)")
        for min_ssim, verdict in ((0.5, "pass"), (0.999999, "FAIL")):
            profile = os.path.join(tmp, "profile.json")
            open(profile, "w").write(json.dumps({"default": {"rel": 1}, "min_ssim": min_ssim}))
            report_dir = os.path.join(tmp, f"ssim{verdict}")
            subprocess.run([binary, "compare", cp, gp, "--profile", profile, "--report", report_dir],
                           capture_output=True)
            html = open(os.path.join(report_dir, "index.html")).read()
            check(f", min_ssim {min_ssim}: {verdict}</p>" in html,  # as given, not rounded
                  f"compare --report with min_ssim {min_ssim}: no '{verdict}' verdict beside SSIM")


compare_report_nonfinite_and_ssim()


def compare_suggest_refusals():
    """compare --suggest refuses runs no threshold can accept, naming the run and the channel: a
    NaN against a number, a difference where the golden is 0 (with --floor 0), and a candidate
    with a channel the golden does not have. Run 1 is the golden against itself."""
    with tempfile.TemporaryDirectory() as tmp:
        g = np.full((4, 6, 3), 2.0, np.float32)
        gp = os.path.join(tmp, "g.exr")
        write_rgb(gp, g)
        nan, zero = g.copy(), g.copy()
        nan[1, 2, 1] = np.nan
        g0 = g.copy()
        g0[3, 5, 2] = 0.0
        zero[3, 5, 2] = 1e-3
        cases = (("nan.exr", nan, gp, "^oceanref: --suggest: run 2: channel 'G' has 1 non-finite "
                  "mismatches: no threshold accepts them$"),
                 ("zero.exr", zero, os.path.join(tmp, "g0.exr"),
                  "^oceanref: --suggest: run 2: channel 'B' differs where the golden is 0: raise "
                  "--floor$"),
                 ("other.exr", g, gp, "^oceanref: compare: \\(unnamed part\\): candidate channel\\(s\\) "
                  "'X' have no counterpart among the golden's 'B', 'G', 'R'"))
        write_rgb(os.path.join(tmp, "g0.exr"), g0)
        for name, pixels, golden, message in cases:
            path = os.path.join(tmp, name)
            write_rgb(path, pixels, names=("R", "G", "X") if name == "other.exr" else ("R", "G", "B"))
            r = subprocess.run([binary, "compare", "--suggest", "--floor", "0", golden, path, golden],
                               capture_output=True, text=True)
            check(r.returncode == 2 and re.search(message, r.stderr.strip()) is not None,
                  f"compare --suggest g.exr {name}: exit {r.returncode}, {r.stderr.strip()!r}")


compare_suggest_refusals()


# --- render, fields, acf: each flag equals the scene setting it stands for, or its definition ----

def report(*args):
    r = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: oceanref {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}")
    return dict(line.split(",", 1) for line in r.stdout.splitlines() if "," in line)


def check_relative_summary(printed, prefix, errors, values, where):
    """A report's error summary against the layers it summarises: the relative errors e/|l| (+inf
    for e > 0 at l = 0); the max exact (to float32's 1e-6), the quantiles the lower edges of 2^-8
    wide bins of rank floor(q n): within 2^-7 below the order statistic (render_output.h)."""
    e, l = errors.astype(np.float64).ravel(), np.abs(values.astype(np.float64).ravel())
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = np.sort(np.where(l > 0, e / l, np.where(e > 0, np.inf, 0.0)))
    close(printed[prefix + "max_relative"], relative[-1], 1e-5, f"{where}: {prefix}max_relative")
    for key, q in (("median_relative", 0.5), ("p50_relative", 0.5), ("p99_relative", 0.99)):
        if prefix + key not in printed:
            continue
        v, rank = float(printed[prefix + key]), int(q * len(relative))
        check(relative[max(rank - 1, 0)] * (1 - 1 / 128) <= v <=
              relative[min(rank + 1, len(relative) - 1)] * (1 + 1e-6),
              f"{where}: {prefix}{key} {v} is not the rank-{rank} value "
              f"{relative[rank]} of the layers")


def render_report_lines(printed, path, plain):
    """render's report lines: each against the EXR it wrote (layers and header) or its meaning.
    `printed` and `path` a 4-spp fast render with --aov --lighting-error; `plain` the same
    render without --lighting-error."""
    layers = read_layers(path)
    spec = oiio.ImageInput.open(path).spec()
    where = "render --aov --lighting-error"
    for key in ("pixel_sha256", "radiance_f64_sha256"):
        check(printed[key] == spec.getattribute("oceanref." + key),
              f"{where}: {key} is not the EXR's oceanref.{key}")
    check(printed["pixel_sha256"] == plain["pixel_sha256"] and
          printed["radiance_f64_sha256"] == plain["radiance_f64_sha256"],
          f"{where}: the image differs from the render without --lighting-error")
    check(printed["radiance_f64_sha256"] != printed["pixel_sha256"], f"{where}: the two hashes agree")
    sea = layers["coverage"].ravel() > 0
    rgb = lambda prefix: np.stack([layers[prefix + c] for c in "RGB"], axis=-1).reshape(-1, 3)
    check_relative_summary(printed, "lighting_error_", rgb("lighting_error.")[sea],
                           rgb("")[sea], where)
    check_relative_summary(printed, "pixel_error_", rgb("pixel_error."), rgb(""), where)
    # The pixel error is 3 standard errors of the mean of the 2 x 2 stratified samples, > 0.
    check(0 < float(printed["pixel_error_p50_relative"]) <= float(printed["pixel_error_p99_relative"]),
          f"{where}: pixel_error p50 {printed['pixel_error_p50_relative']} p99 "
          f"{printed['pixel_error_p99_relative']}")
    check("pixel_samples_mean" not in printed and "capped_pixels" not in printed,
          f"{where}: samples reported for a fixed-spp render")
    check(printed["unconverged_samples"] == "0", f"{where}: unconverged_samples")
    # The integrand evaluations are the reference lighting's that measured the fast one's error.
    check(int(printed["integrand_evaluations"]) > 100 * 16 * 10 * 4 * float(sea.mean()) > 0 and
          plain["integrand_evaluations"] == "0" and "lighting_error_median_relative" not in plain,
          f"{where}: integrand_evaluations {printed['integrand_evaluations']}, "
          f"{plain['integrand_evaluations']} without")


def render_fields_acf_flags():
    with tempfile.TemporaryDirectory() as tmp:
        source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        base = json.load(open(os.path.join(source, "reference", "scenes", "golden",
                                           "default_small.json")))
        base["render"].update({"width": 16, "height": 10, "samples_per_pixel": 4})
        base["shading"]["accuracy"] = "fast"

        def scene_file(name, **render):
            scene = json.loads(json.dumps(base))
            scene["render"].update(render)
            path = os.path.join(tmp, name + ".json")
            json.dump(scene, open(path, "w"))
            return path

        fast = scene_file("fast")
        out = os.path.join(tmp, "out.exr")
        # --spp and --renderer are the scene's samples_per_pixel and renderer.
        check(report("render", fast, "-o", out, "--spp", "9")["pixel_sha256"] ==
              report("render", scene_file("spp9", samples_per_pixel=9), "-o", out)["pixel_sha256"],
              "render --spp 9 is not the scene with samples_per_pixel 9")
        check(report("render", fast, "-o", out, "--renderer", "raytrace")["pixel_sha256"] ==
              report("render", scene_file("rt", renderer="raytrace"), "-o", out)["pixel_sha256"],
              "render --renderer raytrace is not the scene with render.renderer raytrace")
        one = report("render", fast, "-o", out, "--threads", "1")
        check(one["pixel_sha256"] == report("render", fast, "-o", out, "--threads", "2")["pixel_sha256"],
              "render --threads 1 and 2 differ")
        # --samples: each pixel is the mean of its S x S samples (float32 of each: 1e-6).
        samples_path = os.path.join(tmp, "samples.exr")
        report("render", fast, "-o", out, "--samples", samples_path)
        pixels, samples = read_layers(out), read_layers(samples_path)
        for name in "RGB":
            means = samples[name].reshape(10, 2, 16, 2).mean(axis=(1, 3))
            check(np.allclose(means, pixels[name], rtol=1e-6, atol=1e-6 * pixels[name].max()),
                  f"render --samples: the mean of the samples of {name} is not the pixel")
        # --lighting-error: every pixel's fast radiance within its lighting_error (+ the pixel
        # error: none, the same samples) of the reference render's.
        with_error = os.path.join(tmp, "error.exr")
        printed = report("render", fast, "-o", with_error, "--aov", "--lighting-error")
        render_report_lines(printed, with_error, one)
        # Adaptive sampling: the samples behind the pixels (the samples layer) and the capped ones.
        adaptive_path = os.path.join(tmp, "adaptive.exr")
        adaptive = report("render", scene_file("adaptive", pixel_tolerance=0.1,
                                               pixel_pattern="grid", max_samples_per_pixel=36),
                          "-o", adaptive_path, "--aov")
        per_pixel = read_layers(adaptive_path)["samples"].astype(np.float64)
        close(adaptive["pixel_samples_mean"], per_pixel.mean(), 1e-12, "render: pixel_samples_mean")
        close(adaptive["pixel_samples_max"], 36, 0, "render: pixel_samples_max")
        capped = int(adaptive["capped_pixels"])
        check(0 < capped <= int((per_pixel == 36).sum()) and per_pixel.min() == 4,
              f"render: capped_pixels {capped} of {int((per_pixel == 36).sum())} at the cap")
        check("antialiased_pixels" not in adaptive, "render: antialiased_pixels without antialiasing")
        # Mastin's antialiasing: the pixels whose BT.709 luminance contrast with a neighbour in
        # the S x S render exceeds the setting (README), +-1% for contrasts at float32's edge.
        y = luminance(np.stack([pixels[c] for c in "RGB"], axis=-1))
        flagged = np.zeros(y.shape, bool)
        for a, b in ((y[:, 1:], y[:, :-1]), (y[1:, :], y[:-1, :])):
            with np.errstate(divide="ignore", invalid="ignore"):
                high = np.abs(a - b) > 0.1 * (a + b)
            if a.shape[1] < y.shape[1]:
                flagged[:, 1:] |= high
                flagged[:, :-1] |= high
            else:
                flagged[1:, :] |= high
                flagged[:-1, :] |= high
        aa = report("render", scene_file("aa", mastin_antialiasing=0.1), "-o", out)
        want = int(flagged.sum())
        check(0 < want < y.size and abs(int(aa["antialiased_pixels"]) - want) <= max(1, want // 100),
              f"render mastin_antialiasing 0.1: antialiased_pixels {aa['antialiased_pixels']}, "
              f"{want} pixels over the contrast")
        reference = scene_file("ref")
        scene = json.load(open(reference))
        scene["shading"]["accuracy"] = "reference"
        json.dump(scene, open(reference, "w"))
        ref_path = os.path.join(tmp, "ref.exr")
        report("render", reference, "-o", ref_path)
        f_, r_ = read_layers(with_error), read_layers(ref_path)
        for name in "RGB":
            bound = f_[f"lighting_error.{name}"].astype(np.float64)
            gap = np.abs(f_[name].astype(np.float64) - r_[name])
            check(np.all(gap <= bound * (1 + 1e-5) + 1e-6 * np.abs(r_[name])),
                  f"render --lighting-error: |fast - reference| of {name} exceeds lighting_error")
            check(bound.max() > 0, f"render --lighting-error: lighting_error.{name} is 0")
        # --max-memory: the report's estimate is the boundary; K/M/G are powers of 1024.
        estimate = int(one["memory_estimate_bytes"])
        kib = -(-estimate // 1024)
        ok = subprocess.run([binary, "render", fast, "-o", out, "--max-memory", f"{kib}K"],
                            capture_output=True, text=True)
        refused = subprocess.run([binary, "render", fast, "-o", out, "--max-memory",
                                  f"{estimate // 1024 - 1}K"], capture_output=True, text=True)
        check(ok.returncode == 0 and refused.returncode != 0,
              f"render --max-memory: {kib}K gave exit {ok.returncode}, {estimate // 1024 - 1}K exit "
              f"{refused.returncode} (estimate {estimate} bytes)")
        # bench render: --width, --height and --spp are the render's (the samples per second
        # times the time are its 12 x 8 x 9 samples; the sea's share of the image is the mean
        # coverage of `render` at that size); the stages lie within the total; the slope budget's
        # columns add up (resolved + sigma2 = moment) for every normals and interpolation.
        # The camera rolled, so that the horizon crosses the image aslant and the sea's share
        # depends on the width as well as the height.
        rolled = json.loads(json.dumps(base))
        rolled["camera"]["up"] = [0.4, 1, 0]
        rolled_path = os.path.join(tmp, "rolled.json")
        json.dump(rolled, open(rolled_path, "w"))
        tables, comments = bench_tables("render", "--scene", rolled_path, "--width", 12, "--height",
                                        8, "--spp", 9, "--threads", 1)
        check(" at 12x8, 9 spp, 1 threads;" in comments, f"bench render: header {comments!r}")
        stages = {r["stage"]: float(r["seconds"]) for r in tables[0]}
        close(stages["samples_per_second"] * stages["render_total"], 12 * 8 * 9, 1e-9,
              "bench render: samples per second x render time")
        check(sum(stages[k] for k in ("synthesis", "grid", "raster", "shading")) <=
              stages["render_total"] * (1 + 1e-9) and all(v > 0 for v in stages.values()),
              f"bench render: a stage unmeasured or beyond the total {stages}")
        sized = os.path.join(tmp, "sized.exr")
        rolled["render"].update({"width": 12, "height": 8, "samples_per_pixel": 9})
        json.dump(rolled, open(rolled_path, "w"))
        report("render", rolled_path, "-o", sized, "--aov")
        sea_share = float(comments.split("sea covers ")[1].split(" of the image")[0])
        close(sea_share, read_layers(sized)["coverage"].astype(np.float64).mean(), 1e-6,
              "bench render: the sea's share of the image")
        check(0 < sea_share < 1, f"bench render: sea share {sea_share}")
        check([r["interpolation"] for r in tables[1]] == ["bilinear", "bicubic", "direct"],
              f"bench render: interpolation rows {tables[1]}")
        budget = tables[2]
        check(len(budget) >= 6 and len({(r["normals"], r["interpolation"]) for r in budget}) ==
              len(budget) // 2, f"bench render: slope budget rows {budget}")
        for r in budget:
            what = f"bench render: slope budget {r['normals']} {r['interpolation']} {r['axis']}"
            close(float(r["resolved"]) + float(r["sigma2"]), float(r["moment"]), 1e-9, what)
            close(float(r["identity_error"]) + 1,
                  (float(r["resolved"]) + float(r["sigma2"])) / float(r["moment"]), 1e-12, what)
        # fields --time is the scene's time.
        timed = json.loads(json.dumps(base))
        timed["time"] = 2.5
        timed_path = os.path.join(tmp, "timed.json")
        json.dump(timed, open(timed_path, "w"))
        a = subprocess.run([binary, "fields", fast, "--time", "2.5", "--at", "3,4"], capture_output=True,
                           text=True).stdout
        b = subprocess.run([binary, "fields", timed_path, "--at", "3,4"], capture_output=True,
                           text=True).stdout
        c_ = subprocess.run([binary, "fields", fast, "--at", "3,4"], capture_output=True, text=True).stdout
        check(a == b and a != c_, "fields --time 2.5 is not the scene at time 2.5")
        # fields --at x,z: the direct sum at a grid node equals the FFT there.
        rows = list(csv.DictReader(io.StringIO(subprocess.run(
            [binary, "fields", fast, "--at", "0,0"], capture_output=True, text=True).stdout)))
        for row in rows:
            if row["cascade"] == "0":
                close(float(row["direct"]), float(row["fft"]), 1e-9,
                      f"fields --at 0,0: cascade 0 {row['field']} direct sum against the FFT")
        # Off the nodes, the `sum` rows are the shaded surface: in each column (grids read
        # bilinearly, direct sums) the normal is (-slope_x, 1, -slope_z) normalized, and the last
        # column is fft - direct.
        rows = {r["field"]: r for r in csv.DictReader(io.StringIO(subprocess.run(
            [binary, "fields", fast, "--at", "3.7,11.2"], capture_output=True, text=True).stdout))
            if r["cascade"] == "sum"}
        for column in ("fft", "direct"):
            sx, sz = float(rows["slope_x"][column]), float(rows["slope_z"][column])
            norm = math.sqrt(sx * sx + 1 + sz * sz)
            for axis, value in (("x", -sx / norm), ("y", 1 / norm), ("z", -sz / norm)):
                close(float(rows["normal_" + axis][column]), value, 1e-12,
                      f"fields --at 3.7,11.2: the sum's {column} normal_{axis} from its slopes")
        for field, r in rows.items():
            check(float(r["difference"]) == float(r["fft"]) - float(r["direct"]),
                  f"fields --at 3.7,11.2: sum {field}: difference is not fft - direct")
        check(float(rows["slope_x"]["fft"]) != float(rows["slope_x"]["direct"]),
              "fields --at 3.7,11.2: the grids and the direct sum agree off the nodes (no test)")
        # acf: lags k/S periods up to --length, acf(0) = 1; a single cascade of period L along x
        # or z repeats after one period; the start points and lines change the estimate.
        single = json.loads(json.dumps(base))
        single["waves"]["cascades"] = {"sizes": [64]}
        single["waves"].pop("low_resolution", None)
        single_path = os.path.join(tmp, "single.json")
        json.dump(single, open(single_path, "w"))

        def acf(*args):
            text = subprocess.run([binary, "acf", single_path, "--threads", "1", *map(str, args)],
                                  capture_output=True, text=True)
            if text.returncode != 0:
                sys.exit(f"FAIL: oceanref acf {' '.join(map(str, args))}: {text.stderr}")
            return list(csv.DictReader(io.StringIO(text.stdout)))

        rows = acf("--lines", 16, "--length", 2, "--samples-per-period", 4, "--area", 4)
        check([float(r["tau_periods"]) for r in rows] == [k / 4 for k in range(9)],
              "acf --length 2 --samples-per-period 4: the lags are not k/4 periods, k = 0..8")
        check([float(r["tau_m"]) for r in rows] == [64 * k / 4 for k in range(9)],
              "acf: tau_m is not tau_periods x 64 m")
        check(float(rows[0]["acf"]) == 1.0, "acf(0) is not 1")
        for direction in (0, 90):
            r1 = acf("--lines", 16, "--length", 1, "--samples-per-period", 2, "--area", 4,
                     "--direction-deg", direction)
            close(float(r1[-1]["acf"]), 1.0, 1e-9, f"acf --direction-deg {direction}: one period")
        diagonal = acf("--lines", 16, "--length", 1, "--samples-per-period", 2, "--area", 4,
                       "--direction-deg", 45)
        check(abs(float(diagonal[-1]["acf"]) - 1.0) > 1e-3,
              "acf --direction-deg 45: one period along the diagonal repeats the surface")
        for flag, value in (("--seed", 2), ("--lines", 8), ("--area", 2)):
            given = {"--lines": 16, "--area": 4, flag: value}
            other = acf("--lines", given["--lines"], "--length", 2, "--samples-per-period", 4,
                        "--area", given["--area"], *([flag, value] if flag == "--seed" else []))
            check(float(other[3]["acf"]) != float(rows[3]["acf"]), f"acf {flag} {value} changes nothing")

        # The components: without choppiness there is no horizontal displacement (its columns
        # empty, its variances 0) and the vector ACF is the height's; with it, the vector ACF is
        # the mean of the three weighted by the printed variances r~_c(0) (to rounding), between
        # the least and the greatest; each is 1 at lag 0.
        for chop in (0, -1.5):
            scene = json.loads(json.dumps(single))
            scene["waves"]["choppiness"] = chop
            path = os.path.join(tmp, f"chop{chop}.json")
            json.dump(scene, open(path, "w"))
            text = subprocess.run([binary, "acf", path, "--threads", "1", "--lines", "16",
                                   "--length", "2", "--samples-per-period", "4", "--area", "4"],
                                  capture_output=True, text=True).stdout
            rows = list(csv.DictReader(io.StringIO(text)))
            parts = ("acf_disp_x", "acf_height", "acf_disp_z")
            check(len(rows) == 9 and all(float(rows[0][c]) == 1.0 for c in parts if rows[0][c]),
                  f"acf choppiness {chop}: the components at lag 0 {rows[:1]}")
            variances = [float(rows[0][k]) for k in
                         ("variance_disp_x", "variance_height", "variance_disp_z")]
            check(all(r[k] == rows[0][k] for r in rows for k in r if k.startswith("variance_")),
                  f"acf choppiness {chop}: the variances differ between rows")
            for r in rows:
                if chop == 0:
                    check(r["acf_disp_x"] == r["acf_disp_z"] == "" and r["acf"] == r["acf_height"]
                          and variances[0] == variances[2] == 0 < variances[1],
                          f"acf without choppiness: {r}")
                else:
                    c = [float(r[k]) for k in parts]
                    weighted = sum(a * v for a, v in zip(c, variances)) / sum(variances)
                    check(min(c) - 1e-12 <= float(r["acf"]) <= max(c) + 1e-12 and
                          (len(set(c)) == 3 or r["tau_m"] == "0") and min(variances) > 0 and
                          abs(float(r["acf"]) - weighted) <= 1e-14, f"acf choppiness {chop}: {r}")
        acf_plot(single, tmp)


def acf_plot(single, tmp):
    """acf --svg shows the CSV. The plot's frame is read from the plot itself (the grid lines of
    periods 0 and 1 and of r = -0.6 and 1.0, found by their labels); then every point of every
    scene's line lies at its (tau/L, acf) of the CSV, the grid spans the lags, the title and the
    axis labels are centred on the plot area, and the legend gives each line's colour and scene
    name beside the plot, one entry under the other."""
    import xml.etree.ElementTree as ET
    paths = []
    # (20 characters: the legend's room, 152 px right of the swatches at 11 px type.)
    for name, seed in (("calm_one_with_a_name", 1), ("calm<two>", 2)):
        scene = json.loads(json.dumps(single))
        scene["seed"] = seed
        scene["shading"]["interpolation"] = "direct"  # the map's heights: direct sums
        paths.append(os.path.join(tmp, name + ".json"))
        json.dump(scene, open(paths[-1], "w"))
    csv_path, svg_path = os.path.join(tmp, "plot.csv"), os.path.join(tmp, "plot.svg")
    map_path = os.path.join(tmp, "map.png")
    r = subprocess.run([binary, "acf", *paths, "--threads", "1", "--lines", "16", "--length", "3",
                        "--samples-per-period", "4", "--area", "4", "-o", csv_path, "--svg",
                        svg_path, "--map", map_path, "--map-pixels", "16"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: oceanref acf --svg: {r.stderr}")
    rows = list(csv.DictReader(open(csv_path)))
    ns = "{http://www.w3.org/2000/svg}"
    svg = ET.parse(svg_path).getroot()
    lines = [{k: float(v) for k, v in e.attrib.items() if k in ("x1", "y1", "x2", "y2")} | {
        "stroke": e.get("stroke")} for e in svg.iter(ns + "line")]
    texts = [(e.text, float(e.get("x")), float(e.get("y")), e.get("text-anchor")) for e in
             svg.iter(ns + "text")]
    px = 0.011  # positions are written to 0.01 px
    # Periods: vertical grid lines, each with its integer label under it.
    period_x = {int(t): x for t, x, _, a in texts if a == "middle" and t.isdigit() and
                any(l["x1"] == l["x2"] == x for l in lines)}
    check(sorted(period_x) == [0, 1, 2, 3], f"acf --svg: period grid lines {sorted(period_x)}")
    x0, unit = period_x[0], period_x[1] - period_x[0]
    for p, x in period_x.items():
        check(abs(x - (x0 + p * unit)) <= 3 * px, f"acf --svg: grid line of period {p} at x {x}")
    # Values: horizontal grid lines from the left edge, each labelled at its left.
    value_y = {}
    for t, x, y, a in texts:
        if a == "end":
            match = [l for l in lines if l["y1"] == l["y2"] and abs(l["y1"] + 4 - y) <= px and
                     l["x1"] == x0 and abs(l["x1"] - 6 - x) <= px]
            check(len(match) == 1, f"acf --svg: the label {t} has no grid line")
            value_y[float(t)] = y - 4
    check(sorted(value_y) == [-0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0],
          f"acf --svg: value grid lines {sorted(value_y)}")
    y_of = lambda v: value_y[-0.6] + (value_y[1.0] - value_y[-0.6]) * (min(max(v, -0.6), 1) + 0.6) / 1.6
    for v, y in value_y.items():
        check(abs(y - y_of(v)) <= 3 * px, f"acf --svg: grid line of r = {v} at y {y}")
    right = x0 + 3 * unit  # the longest lag: 3 periods
    check(all(abs(l["x2"] - right) <= 3 * px for l in lines if l["x1"] == x0 and l["y1"] == l["y2"]),
          "acf --svg: the value grid lines do not end at the longest lag")
    # Every point of each scene's line.
    polylines = list(svg.iter(ns + "polyline"))
    check(len(polylines) == 2, f"acf --svg: {len(polylines)} lines for 2 scenes")
    names = [os.path.basename(p)[:-5] for p in paths]
    for name, line in zip(names, polylines):
        data = [(float(r["tau_periods"]), float(r["acf"])) for r in rows if r["scene"] == name]
        points = [tuple(map(float, xy.split(","))) for xy in line.get("points").split()]
        check(len(points) == len(data) == 13, f"acf --svg: {name}: {len(points)} points")
        for (tau, a), (x, y) in zip(data, points):
            check(abs(x - (x0 + tau * unit)) <= 4 * px and abs(y - y_of(a)) <= 4 * px,
                  f"acf --svg: {name}: the point of tau {tau}, acf {a} is at ({x}, {y})")
    # Titles centred on the plot area (the y label on its height, rotated about its anchor).
    centre_x, centre_y = (x0 + right) / 2, (value_y[1.0] + value_y[-0.6]) / 2
    title = [t for t in texts if t[0].startswith("Autocorrelation")]
    x_label = [t for t in texts if t[0].startswith("lag")]
    check(len(title) == len(x_label) == 1 and abs(title[0][1] - centre_x) <= 3 * px and
          abs(x_label[0][1] - centre_x) <= 3 * px and title[0][2] < value_y[1.0] and
          x_label[0][2] > value_y[-0.6], f"acf --svg: title or x label off the centre {title} {x_label}")
    y_label = [e for e in svg.iter(ns + "text") if e.text.startswith("r(")]
    check(len(y_label) == 1 and abs(float(y_label[0].get("y")) - centre_y) <= 3 * px and
          y_label[0].get("transform") == f"rotate(-90 {y_label[0].get('x')} {y_label[0].get('y')})"
          and float(y_label[0].get("x")) < x0, f"acf --svg: y label {y_label and y_label[0].attrib}")
    # The legend: right of the plot, a line of each scene's colour beside its (escaped) name.
    legend = [l for l in lines if l["x1"] > right and l["y1"] == l["y2"]]
    check([l["stroke"] for l in legend] == [p.get("stroke") for p in polylines] and
          len({l["stroke"] for l in legend}) == 2, f"acf --svg: legend colours {legend}")
    labels = [t for t in texts if t[0] in names]
    check([t[0] for t in labels] == names, f"acf --svg: legend names {labels}")
    for l, t in zip(legend, labels):
        check(t[1] > l["x2"] and abs(t[2] - (l["y1"] + 4)) <= px,
              f"acf --svg: the name {t[0]} is not beside its line")
        # A swatch: a visible stretch of the line (20 px) right of the plot, before the name.
        check(right < l["x1"] and l["x2"] - l["x1"] >= 15,
              f"acf --svg: the legend line of {t[0]} runs from {l['x1']} to {l['x2']}")
    check(len(legend) == 2 and legend[1]["y1"] - legend[0]["y1"] >= 11 and
          float(svg.get("height")) > legend[-1]["y1"],
          f"acf --svg: legend entries overlap or leave the image {legend}")
    # Each name inside the image, at 0.6 em (6.6 px) per character of 11 px sans-serif.
    for t in labels:
        check(t[1] + 6.6 * len(t[0]) <= float(svg.get("width")),
              f"acf --svg: the legend name {t[0]} runs past the image's right edge from x {t[1]}")
    # --map: the scenes' heights side by side (16 pixels over 4 x 4 periods of 64 m each, 8 grey
    # pixels apart), grey = 1/2 + eta/(6 sigma), z upwards. The heights of the first scene at its
    # first period's pixel centres come from `fields --at` (direct sums, as the map's scene
    # interpolates), sigma^2 is the CSV's variance_height (the map's own estimate): each byte is
    # round(255 (1/2 + eta/(6 sigma))) exactly. The periodic ocean repeats every 4 pixels.
    image = oiio.ImageInput.open(map_path)
    spec = image.spec()
    rgb = np.rint(image.read_image(0, 0, 0, spec.nchannels, "float") * 255)
    image.close()
    check((spec.width, spec.height, spec.nchannels) == (40, 16, 3),
          f"acf --map: {spec.width} x {spec.height} x {spec.nchannels}")
    # Grey: R = G = B in every pixel.
    check(np.array_equal(rgb[:, :, 0], rgb[:, :, 1]) and np.array_equal(rgb[:, :, 0], rgb[:, :, 2]),
          "acf --map: a pixel is not grey (R, G, B differ)")
    grey = rgb[:, :, 0]
    check(np.all(grey[:, 16:24] == 128), "acf --map: the gap between the maps is not grey 128")
    left, right_map = grey[:, :16], grey[:, 24:]
    check(np.array_equal(left, np.roll(left, 4, axis=0)) and
          np.array_equal(left, np.roll(left, 4, axis=1)), "acf --map: not periodic over 4 pixels")
    check(not np.array_equal(left, right_map), "acf --map: the two scenes' maps are the same")
    eta, g = [], []
    for row in range(4):
        for m in range(4):
            at = subprocess.run([binary, "fields", paths[0], "--at", f"{16 * (m + 0.5)},{16 * (row + 0.5)}"],
                                capture_output=True, text=True)
            eta.append(float(next(r for r in csv.DictReader(io.StringIO(at.stdout))
                                  if r["field"] == "height")["direct"]))
            g.append(left[15 - row, m] / 255 - 0.5)
    eta, g = np.array(eta), np.array(g)
    check(np.all(np.abs(g) < 0.49) and np.ptp(g) > 0.2,
          f"acf --map: greys {g * 255 + 127.5} of heights {eta}")
    sigma = math.sqrt(float(next(r for r in rows if r["scene"] == "calm_one_with_a_name")
                            ["variance_height"]))
    expected = [math.floor(255 * min(max(0.5 + e / (6 * sigma), 0.0), 1.0) + 0.5) for e in eta]
    check(list(np.rint(g * 255 + 127.5)) == expected,
          f"acf --map: greys {list(g * 255 + 127.5)}, expected round(255 (1/2 + eta/(6 sigma))) "
          f"{expected}")


def unconverged_samples_counted():
    """render's unconverged_samples (and its warning) against `probe`. A calm sea seen at the
    horizon, its spectrum cut at the grid's waves (waves.minimum_wavelength), so that the
    unresolved slope variance is near its floor (crosswind 1e-10) and the lighting lobes are
    needle-thin at grazing views: at the tightest tolerance (1e-10) a few of the 32 x 16
    samples miss it. A missed integral's error exceeds the tolerance relative to its value, so
    those pixels are among the ones whose lighting_error exceeds it relative to theirs (3, the
    next below at 1e-10 itself); `probe` of each says which of them did not converge."""
    with tempfile.TemporaryDirectory() as tmp:
        scene = {"seed": 3,
                 "waves": {"spectrum": {"model": "jonswap", "wind_speed": 3, "fetch": 1000},
                           "cascades": {"sizes": [20]}, "resolution": 64,
                           "minimum_wavelength": 2},
                 "camera": {"position": [0, 0.3, 0], "look_at": [0, 0.3, 1000],
                            "vertical_fov_deg": 6},
                 "grid": {"columns": 64, "rows": 64}, "atmosphere": {"sun_zenith_deg": 60},
                 "shading": {"accuracy": "reference", "tolerance": 1e-10},
                 "render": {"width": 32, "height": 16, "samples_per_pixel": 1}}
        path, out = os.path.join(tmp, "calm.json"), os.path.join(tmp, "calm.exr")
        json.dump(scene, open(path, "w"))
        counts = []
        for threads in (1, 2):
            r = subprocess.run([binary, "render", path, "-o", out, "--aov", "--threads",
                                str(threads)], capture_output=True, text=True)
            printed = dict(line.split(",", 1) for line in r.stdout.splitlines() if "," in line)
            counts.append(int(printed.get("unconverged_samples", "-1")))
            check(r.returncode == 0 and r.stderr == (
                f"oceanref: warning: {counts[-1]} samples missed the lighting tolerance (their "
                "error estimates are in --aov lighting_error)\n"),
                f"render of a calm sea at 1e-10, {threads} threads: exit {r.returncode}, "
                f"stderr {r.stderr!r}")
        layers = read_layers(out)
        error = np.stack([layers["lighting_error." + c] for c in "RGB"], axis=-1)
        value = np.stack([layers[c] for c in "RGB"], axis=-1)
        relative = (error / value).max(axis=-1)
        candidates = np.argwhere(relative > 1e-10)
        below = np.unravel_index(np.argmax(np.where(relative > 1e-10, 0, relative)),
                                 relative.shape)
        probed = []
        for row, column in [*candidates, below]:
            samples = oceanref("probe", path, "--pixel", f"{column},{row}", "--threads", "1")
            probed.append(sum(s["converged"] == "0" for s in samples if s["sample"] != "pixel"))
        check(counts[0] == counts[1] == sum(probed[:-1]) > 0 and probed[-1] == 0 and
              len(candidates) <= 8,
              f"unconverged_samples {counts} (1 and 2 threads); probe: {probed} unconverged at "
              f"{candidates.tolist()} and the next pixel {below}")


unconverged_samples_counted()
render_fields_acf_flags()


print(f"cli_values: {checks} checks, {len(failures)} failures")
sys.exit(1 if failures else 0)
