"""Sky and BRDF probes and the reference lighting integrals: the command line's numbers, known
limits and closed forms, and error estimates that bound the actual error."""

import math

import numpy as np
import pytest

import oceanref
from conftest import csv_rows

N_WATER = 1.333


def fresnel(cos_i):
    """Unpolarized Fresnel reflectance of air-water (Born & Wolf §1.5)."""
    cos_t = math.sqrt(1 - (1 - cos_i**2) / N_WATER**2)
    rs = (cos_i - N_WATER * cos_t) / (cos_i + N_WATER * cos_t)
    rp = (N_WATER * cos_i - cos_t) / (N_WATER * cos_i + cos_t)
    return 0.5 * (rs**2 + rp**2)


def test_sky_radiance_equals_the_command_line(cli):
    dirs = np.array([[0, 1, 0], [0.3, 0.2, 0.9], [-0.5, 0.05, 0.1], [0.2, 0.7, -0.3]])
    out = cli("sky", "--sun-zenith-deg", 50, "--sun-azimuth-deg", 30, "--turbidity", 3,
              "--dir", ";".join(",".join(map(str, d)) for d in dirs))
    rows = csv_rows(out)
    rgb = oceanref.sky_radiance(dirs, sun_zenith_deg=50, sun_azimuth_deg=30, turbidity=3)
    xyY = oceanref.sky_xyY(dirs, sun_zenith_deg=50, sun_azimuth_deg=30, turbidity=3)
    assert rgb.shape == (4, 3)
    for i, r in enumerate(rows):
        assert list(rgb[i]) == [float(r["R"]), float(r["G"]), float(r["B"])]
        assert xyY[i, 2] == float(r["Y"])
    one = oceanref.sky_radiance((0.3, 0.2, 0.9), 50, 30, 3)  # unnormalized, any shape
    assert np.array_equal(one, rgb[1])
    # Turbidity reaches the sky.
    assert not np.array_equal(oceanref.sky_radiance(dirs, 50, 30, 6), rgb)
    with pytest.raises(ValueError, match=r"^turbidity: must be in \[2, 10\]"):
        oceanref.sky_radiance(dirs, 50, 30, 11)
    with pytest.raises(ValueError, match=r"^sun_zenith_deg: must be in \[0, 180\]"):
        oceanref.sky_radiance(dirs, -1)


def test_brdf_equals_the_command_line(cli):
    view, sun = (0.1, 0.5, 0.8), (-0.3, 0.6, -0.7)
    out = cli("brdf", "--view", "0.1,0.5,0.8", "--sun", "-0.3,0.6,-0.7", "--sigma2",
              "0.01,0.02", "--wind-deg", "20", "--accuracy", "fast")
    row = {r["quantity"]: float(r["value"]) for r in csv_rows(out)}
    t = oceanref.brdf(view, sun, (0.01, 0.02), wind_deg=20)
    for ours, theirs in [("zeta_x", "zeta_x"), ("zeta_y", "zeta_y"), ("p", "p"),
                         ("lambda_view", "Lambda_V"), ("lambda_light", "Lambda_L"),
                         ("fresnel", "F"), ("brdf_cos", "brdf_cos")]:
        assert t[ours] == row[theirs], ours


def test_brdf_closed_forms():
    # View = light = normal: the reflecting facet is flat, F = ((n-1)/(n+1))², p(0) =
    # 1/(2π σx σy), Λ(1) = 0. Tolerance 1e-14: a few roundings.
    t = oceanref.brdf((0, 1, 0), (0, 1, 0), (0.01, 0.04))
    assert t["zeta_x"] == 0 and t["zeta_y"] == 0
    assert t["fresnel"] == pytest.approx(((N_WATER - 1) / (N_WATER + 1)) ** 2, rel=1e-14)
    assert t["p"] == pytest.approx(1 / (2 * math.pi * 0.1 * 0.2), rel=1e-14)
    assert t["lambda_view"] == 0 and t["lambda_light"] == 0
    assert oceanref.brdf((0, 1, 0), (0, 1, 0), (0.01, 0.04), fresnel="unity")["fresnel"] == 1
    with pytest.raises(ValueError, match=r"^sigma2: expected \(sx, sy\) with each in \[1e-6, 1\]"):
        oceanref.brdf((0, 1, 0), (0, 1, 0), (0.0, 0.1))
    with pytest.raises(ValueError, match="^view: the vector must not be zero"):
        oceanref.brdf((0, 0, 0), (0, 1, 0), (0.1, 0.1))
    with pytest.raises(ValueError, match="^fresnel:"):
        oceanref.brdf((0, 1, 0), (0, 1, 0), (0.1, 0.1), fresnel="fast")


def test_mean_fresnel_smooth_limit():
    # σ² → 0: F̄ → F(V·N). At σ² = 1e-6 the facets tilt by ~1e-3 rad, so F̄ differs from F at
    # 60° by ~1e-5 relative; tolerance 1e-4.
    view = (math.sin(math.radians(60)), math.cos(math.radians(60)), 0)
    r = oceanref.mean_fresnel_reference(view, (1e-6, 1e-6), tolerance=1e-8)
    assert r["converged"]
    assert r["value"] == pytest.approx(fresnel(0.5), rel=1e-4)
    assert oceanref.mean_fresnel_reference(view, (0.02, 0.02))["value"] != r["value"]


def test_reference_error_estimates_bound_the_error():
    # A loose integral's estimated error covers its distance from a tight one.
    view = (0.4, 0.3, 0.866)
    sigma2 = (0.02, 0.01)
    sky = dict(sun_zenith_deg=60, sun_azimuth_deg=45, turbidity=2.5)
    loose = oceanref.reflected_sky_reference(view, sigma2, tolerance=1e-3, **sky)
    tight = oceanref.reflected_sky_reference(view, sigma2, tolerance=1e-9, **sky)
    assert tight["converged"] and loose["converged"]
    assert np.all(np.abs(loose["value"] - tight["value"]) <= loose["error"] + tight["error"])
    assert np.all(tight["error"] <= 1e-9 * np.abs(tight["value"]) * 1.0001)
    assert np.all(tight["value"] > 0)
    loose = oceanref.mean_fresnel_reference(view, sigma2, tolerance=1e-2)
    tight = oceanref.mean_fresnel_reference(view, sigma2, tolerance=1e-10)
    assert abs(loose["value"] - tight["value"]) <= loose["error"] + tight["error"]


def test_reflected_sun_against_the_brdf():
    # Over the sun's small disk (ρ = 0.2667°) a rough BRDF (σ² = 0.02) is nearly constant:
    # ∫_disk f cos θ dω ≈ brdf_cos(centre)·Ω_sun, Ω_sun = 2π(1 − cos ρ); the variation across the
    # disk is O(ρ²/σ²) ≈ 1e-3 at most, tolerance 2e-3.
    sun = (0.0, math.cos(math.radians(40)), math.sin(math.radians(40)))
    view = (0.1, 0.6, -0.75)
    r = oceanref.reflected_sun_reference(view, sun, (0.02, 0.02), tolerance=1e-8)
    omega = 2 * math.pi * (1 - math.cos(oceanref.SUN_ANGULAR_RADIUS))
    centre = oceanref.brdf(view, sun, (0.02, 0.02))["brdf_cos"]
    assert r["converged"] and r["value"] > 0
    assert r["value"] == pytest.approx(centre * omega, rel=2e-3)
    assert r["error"] <= 1e-8 * r["value"] * 1.0001
