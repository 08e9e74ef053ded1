"""Spectra from Python: closed forms, published values, the command line's numbers, moments
against an independent NumPy quadrature, and errors."""

import math

import numpy as np
import pytest

import oceanref
from conftest import csv_rows

G = 9.81
ALPHA_PM, BETA_PM = 8.1e-3, 0.74  # Pierson-Moskowitz 1964 (Gamper eq. 3.36)


def test_pierson_moskowitz_closed_form():
    # S(ω) = αg²ω⁻⁵ exp(−β (g/(U19.5 ω))⁴). Tolerance 1e-14 relative: a handful of roundings
    # and the portable exp (≤ 1 ulp) against NumPy's exp.
    u = 15.0
    omega = np.linspace(0.2, 4.0, 200)
    s = oceanref.spectrum("pierson-moskowitz", omega, wind_speed=u, pm_wind="u19.5")
    expected = ALPHA_PM * G**2 / omega**5 * np.exp(-BETA_PM * (G / (u * omega)) ** 4)
    np.testing.assert_allclose(s, expected, rtol=1e-14, atol=0)
    assert s.shape == omega.shape
    # The peak: ω_p = (4β/5)^{1/4} g/U19.5 ≈ 0.877 g/U (Gamper eq. 3.38).
    spec = oceanref.Spectrum("pierson_moskowitz", wind_speed=u, pm_wind="u19.5")
    assert spec.peak_frequency == pytest.approx((0.8 * BETA_PM) ** 0.25 * G / u, rel=1e-15)
    # A setting must change the output.
    assert not np.array_equal(s, oceanref.spectrum("pierson-moskowitz", omega, wind_speed=u))


def test_pierson_moskowitz_significant_wave_height():
    # m0 up to ω_m = √(g k_max) (deep water) in closed form: αU⁴/(4βg²) · exp(−β (g/(U ω_m))⁴);
    # the published rule of thumb Hs = 4√m0 ≈ 0.21 U19.5²/g (Pierson & Moskowitz 1964).
    u = 12.0
    k_max = 10.0
    m = oceanref.moments("pierson-moskowitz", k_max=k_max, wind_speed=u, pm_wind="u19.5")
    omega_m = math.sqrt(G * k_max)
    m0 = ALPHA_PM * u**4 / (4 * BETA_PM * G**2) * math.exp(-BETA_PM * (G / (u * omega_m)) ** 4)
    assert m["m0"] == pytest.approx(m0, rel=1e-9)  # quadrature tolerance 1e-10
    assert m["Hs"] == pytest.approx(4 * math.sqrt(m0), rel=1e-9)
    assert m["Hs"] * G / u**2 == pytest.approx(0.21, abs=0.005)  # published to 2 digits
    assert m["m0_error"] < 1e-8 * m["m0"]


def test_spectrum_equals_the_command_line(cli):
    omega = [0.3, 0.5, 0.8, 1.1, 2.0, 5.0]
    out = cli("spectrum", "--model", "jonswap", "--wind-speed", "14", "--fetch", "80000",
              "--gamma", "2.5", "--omega", ",".join(map(str, omega)))
    expected = np.array([float(r["S"]) for r in csv_rows(out)])  # 17 digits: round trip
    s = oceanref.spectrum("jonswap", omega, wind_speed=14, fetch=80000, gamma=2.5)
    assert np.array_equal(s, expected)
    out = cli("spectrum", "--model", "jonswap", "--wind-speed", "14", "--wavevector",
              "0.05:0.01,-0.02:0.03,0.1:-0.2")
    rows = csv_rows(out)
    theta = oceanref.Theta("jonswap", [float(r["kx"]) for r in rows],
                           [float(r["kz"]) for r in rows], wind_speed=14)
    assert np.array_equal(theta, [float(r["Theta"]) for r in rows])
    # Alimardanov's swell form (Algorithm 2) as the command line has it, and not Lutz's.
    out = cli("spectrum", "--model", "jonswap", "--wind-speed", "14", "--spreading", "hasselmann",
              "--swell", "0.8", "--swell-model", "alimardanov", "--wavevector",
              "0.05:0.01,-0.02:0.03,0.3:-0.2")
    rows = csv_rows(out)
    kx, kz = [float(r["kx"]) for r in rows], [float(r["kz"]) for r in rows]
    kw = dict(wind_speed=14, spreading="hasselmann", swell=0.8)
    theta = oceanref.Theta("jonswap", kx, kz, swell_model="alimardanov", **kw)
    assert np.array_equal(theta, [float(r["Theta"]) for r in rows])
    assert not np.array_equal(theta, oceanref.Theta("jonswap", kx, kz, **kw))
    out = cli("spectrum", "--model", "tma", "--depth", "20", "--moments")
    m = oceanref.moments("tma", depth=20)
    row = csv_rows(out)[0]
    for key in ("m0", "Hs", "mss_x", "mss_z", "mss"):
        assert m[key] == float(row[key]), key


def simpson(y, x, axis=-1):
    """Composite Simpson on a uniform grid (odd number of points)."""
    y = np.moveaxis(y, axis, -1)
    h = (x[-1] - x[0]) / (len(x) - 1)
    return h / 3 * (y[..., 0] + y[..., -1] + 4 * y[..., 1:-1:2].sum(-1) + 2 * y[..., 2:-1:2].sum(-1))


def test_moments_against_numpy_quadrature():
    # JONSWAP with cos² spreading, wind at 30°: m0 = ∫S dω, mss = ∫k²Ψ dk and
    # mss_x = ∬ k_x² Θ dk from the spectrum Python returns, integrated here by Simpson's rule in
    # u = ln ω (or ln k) and the periodic trapezoid rule in θ (cos² is C¹ where it reaches 0,
    # so the trapezoid error is O(h³) ≈ 1e-7; the cos-2s family's cusp behind the wind would
    # need far more points at high k, where s → 0). Tolerance 2e-6 relative; the library's own
    # quadrature error is < 1e-10.
    kw = dict(wind_speed=11.0, fetch=60000.0, wind_direction_deg=30.0, spreading="cos2")
    spec = oceanref.Spectrum("jonswap", **kw)
    k_max = 60.0
    m = spec.moments(k_max)
    omega_max = math.sqrt(G * k_max)  # deep water: ω = √(gk)
    u = np.linspace(math.log(0.3 * spec.peak_frequency), math.log(omega_max), 20001)
    w = np.exp(u)
    m0 = simpson(spec.frequency(w) * w, u)
    assert m0 == pytest.approx(m["m0"], rel=2e-6)
    v = np.linspace(math.log(spec.peak_wavenumber * 0.09), math.log(k_max), 20001)
    k = np.exp(v)
    mss = simpson(k**2 * spec.wavenumber(k) * k, v)
    assert mss == pytest.approx(m["mss"], rel=2e-6)
    # Θ on a polar grid: ∬ f dk_x dk_z = ∫∫ f k dθ dk.
    v = np.linspace(math.log(spec.peak_wavenumber * 0.09), math.log(k_max), 4001)
    k = np.exp(v)[:, None]
    theta = np.linspace(-math.pi, math.pi, 1440, endpoint=False)[None, :]
    kx, kz = k * np.cos(theta), k * np.sin(theta)
    th = oceanref.Theta("jonswap", kx, kz, **kw)
    dtheta = 2 * math.pi / 1440

    def polar(f):
        return simpson((f * th).sum(axis=1) * dtheta * k[:, 0] ** 2, v)  # k dk = k² du

    assert polar(1.0) == pytest.approx(m["m0"], rel=2e-6)
    assert polar(kx**2) == pytest.approx(m["mss_x"], rel=2e-6)
    assert polar(kz**2) == pytest.approx(m["mss_z"], rel=2e-6)
    assert m["mss_x"] + m["mss_z"] == pytest.approx(m["mss"], rel=1e-9)
    # The wind direction moves slope variance between the axes.
    m0deg = oceanref.moments("jonswap", k_max=k_max, wind_speed=11.0, fetch=60000.0,
                             spreading="cos2")
    assert m0deg["mss_x"] > m["mss_x"] * 1.01


def test_spreading_integrates_to_one():
    # Normalized spreading: ∫D dθ = 1 at every frequency (periodic trapezoid, 1440 points).
    theta = np.linspace(-180.0, 180.0, 1440, endpoint=False)
    for model in ("hasselmann", "mitsuyasu", "donelan-banner", "cos2"):
        for w in (0.6, 1.0, 3.0):
            d = oceanref.spreading("jonswap", w, theta, spreading=model)
            assert d.sum() * (2 * math.pi / 1440) == pytest.approx(1.0, rel=1e-6), (model, w)


@pytest.mark.parametrize(
    "call, key, text",
    [
        (lambda: oceanref.spectrum("jonswap", 1.0, wind_speed=100.0), "wind_speed", "[0.1, 60]"),
        (lambda: oceanref.spectrum("jonswap", 1.0, fetch=0.5), "fetch", "[1, 10000000]"),
        (lambda: oceanref.spectrum("nope", 1.0), "model", "pierson-moskowitz"),
        (lambda: oceanref.spectrum("jonswap", 1.0, spreading="x"), "spreading", "mitsuyasu"),
        (lambda: oceanref.spectrum("jonswap", 1.0, windspeed=3), "windspeed", "unknown keyword"),
        (lambda: oceanref.spectrum("jonswap", 1.0, wind_direction_deg=1000),
         "wind_direction_deg", "[-720, 720]"),
        (lambda: oceanref.moments("jonswap", k_max=0.001), "k_max", "peak wavenumber"),
        # Choices: the same table and message as scene files and the command line.
        (lambda: oceanref.spectrum("pierson-moskowitz", 1.0, pm_wind="u20"), "pm_wind",
         "expected u10 or u19.5; got 'u20'"),
        (lambda: oceanref.spectrum("jonswap", 1.0, dispersion="shallow"), "dispersion",
         "expected one of deep, finite-depth, capillary; got 'shallow'"),
    ],
)
def test_bad_input_raises_value_error_naming_the_key(call, key, text):
    with pytest.raises(ValueError) as e:
        call()
    assert str(e.value).startswith(key + ":"), str(e.value)
    assert text in str(e.value)
