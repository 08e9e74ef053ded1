"""SSIM in compare (conformance/compare.h) against an independent NumPy computation of Wang,
Bovik, Sheikh and Simoncelli 2004 with the HDR mapping compare states: equal to 1 exactly for
identical images, equal to the NumPy value to 1e-9 (both in double; the NumPy side takes every
11x11 window directly with two-pass moments, compare filters separably with E[x^2] - mu^2, so
they round differently), decreasing as noise grows, and a profile's min_ssim decides pass/fail.
"""

import json

import numpy as np
import pytest
from numpy.lib.stride_tricks import sliding_window_view

import oceanref


def hdr_image(seed=3, height=40, width=56):
    """Linear radiance [cd/m^2]: a sky-like gradient, texture and a few very bright highlights."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:height, 0:width]
    base = 2000.0 * (1.0 + y / height)[..., None] * np.array([0.8, 1.0, 1.3])
    texture = 1.0 + 0.3 * np.sin(x / 3.0)[..., None] * rng.uniform(0.5, 1.0, (height, width, 3))
    image = base * texture
    image[5, 7] = 1e6  # a sun glint
    image[30, 40:43] = 5e5
    return image.astype(np.float32)


def noisy(image, sigma, seed=11):
    rng = np.random.default_rng(seed)
    return (image * (1.0 + sigma * rng.standard_normal(image.shape))).astype(np.float32)


def numpy_ssim(golden, candidate):
    """SSIM of two (H, W, 3) linear RGB float32 images, as compare.h defines it."""

    def luminance(rgb):
        rgb = rgb.astype(np.float64)
        return np.maximum(0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2], 0.0)

    yg, yc = luminance(golden), luminance(candidate)
    key = np.exp(np.mean(np.log(yg + 1e-3)))  # the golden's log-average luminance

    def display(y):  # Reinhard's global operator with key 0.18, then 1/2.2
        return (y / (y + key / 0.18)) ** (1.0 / 2.2)

    x, y = display(yg), display(yc)
    r = np.arange(11) - 5.0
    w = np.exp(-(r[:, None] ** 2 + r[None, :] ** 2) / (2 * 1.5**2))
    w /= w.sum()
    wx, wy = sliding_window_view(x, (11, 11)), sliding_window_view(y, (11, 11))
    mx = (wx * w).sum(axis=(-2, -1))
    my = (wy * w).sum(axis=(-2, -1))
    dx, dy = wx - mx[..., None, None], wy - my[..., None, None]
    vx = (dx * dx * w).sum(axis=(-2, -1))
    vy = (dy * dy * w).sum(axis=(-2, -1))
    cxy = (dx * dy * w).sum(axis=(-2, -1))
    c1, c2 = 0.01**2, 0.03**2
    s = (2 * mx * my + c1) * (2 * cxy + c2) / ((mx**2 + my**2 + c1) * (vx + vy + c2))
    return s.mean(), s.size, key


def compare_ssim(candidate, golden, **kwargs):
    r = oceanref.compare(candidate, golden, rel=1e30, floor=1.0, **kwargs)
    (part,) = json.loads(r.json)["parts"]
    return r, part["ssim"]


def test_ssim_of_an_image_with_itself_is_exactly_one():
    g = hdr_image()
    r, s = compare_ssim(g, g)
    assert s["value"] == 1.0
    assert s["channels"] == "R,G,B" and s["windows"] == (40 - 10) * (56 - 10)
    assert "SSIM (R,G,B luminance" in r.text and "1.000000" in r.text


@pytest.mark.parametrize("sigma", [1e-3, 1e-2, 0.1])
def test_ssim_matches_numpy(sigma):
    g = hdr_image()
    c = noisy(g, sigma)
    _, s = compare_ssim(c, g)
    expected, windows, key = numpy_ssim(g, c)
    assert s["windows"] == windows
    assert s["key_luminance"] == pytest.approx(key, rel=1e-12)
    assert s["value"] == pytest.approx(expected, abs=1e-9)
    assert s["value"] < 1.0


def test_ssim_decreases_as_noise_grows():
    g = hdr_image()
    values = [compare_ssim(noisy(g, sigma), g)[1]["value"] for sigma in (1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3)]
    assert all(a > b for a, b in zip(values, values[1:])), values
    assert values[0] > 0.999 and values[-1] < 0.9


def test_min_ssim_in_a_profile_decides(tmp_path):
    g = hdr_image()
    c = noisy(g, 0.03)
    value = compare_ssim(c, g)[1]["value"]
    for min_ssim, passes in ((value - 1e-4, True), (value + 1e-4, False)):
        profile = tmp_path / "p.json"
        profile.write_text(json.dumps({"default": {"rel": 1e30, "floor": 1}, "min_ssim": min_ssim}))
        r = oceanref.compare(c, g, profile=str(profile))
        assert r.passed == passes
        assert json.loads(r.json)["parts"][0]["ssim"]["min_ssim"] == min_ssim
    # A single-channel image is read as Y: its SSIM is that of the luminance alone.
    lum = (0.2126 * g[..., 0] + 0.7152 * g[..., 1] + 0.0722 * g[..., 2]).astype(np.float32)
    _, s = compare_ssim(lum, lum)
    assert s["channels"] == "Y" and s["value"] == 1.0
