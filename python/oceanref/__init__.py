"""oceanref: a deterministic CPU reference renderer for spectral ocean surfaces, from Python.

The library, not the command line: spectra, the wave fields of a scene, sky and BRDF probes,
the reference lighting integrals with their error estimates, the reference image, and the
conformance comparison. NumPy arrays in and out:

* fields are float64 (the doubles behind the float32 channels of ``oceanref fields -o``), keyed
  by field name (``c0.height``; the file's channel is the field name plus ``.V``);
* ``render`` returns float64 linear radiance (cd/m² per linear sRGB channel, D65): rounded to
  float32 it is bit for bit the R, G, B of ``oceanref render -o``;
* ``read_exr`` returns float32 channels, as stored, under the file's channel names.

Units are SI (ω rad/s, k rad/m, S(ω) m²·s, Θ(k) m⁴, lengths m); angles are degrees at this
interface. Invalid input raises ValueError with the message the command line prints
("key: accepted range, got value"); unreadable files raise ValueError naming the file.
"""

import hashlib
import json as _json
import os as _os

import numpy as _np

from . import _core

__version__ = _core.__version__
DEFAULT_K_MAX = _core.DEFAULT_K_MAX  #: 2π/1.73 cm [rad/m], the moments' default upper limit
SUN_ANGULAR_RADIUS = _core.SUN_ANGULAR_RADIUS  #: [rad]
Spectrum = _core.Spectrum
Scene = _core.Scene

__all__ = [
    "__version__", "build_info", "Spectrum", "spectrum", "spreading", "Theta", "moments",
    "Scene", "load_scene", "fields", "fields_sha256", "render", "pixel_sha256",
    "radiance_f64_sha256", "read_exr", "sky_radiance", "sky_xyY", "sun_radiance",
    "sky_irradiance", "brdf", "mean_fresnel_reference", "reflected_sky_reference",
    "reflected_sun_reference", "compare", "CompareResult",
]


def build_info():
    """The build of the compiled module: version, compiler, build type, the flags that reach the
    compiler, the elementary-function library, and the Python and pybind11 versions."""
    return dict(_core._build_info)


# --- spectra ---------------------------------------------------------------------------------

def spectrum(model, omega, **settings):
    """S(ω) [m²·s] of MODEL at angular frequencies ``omega`` [rad/s] (any shape).

    MODEL: phillips, pierson-moskowitz, jonswap, tma, donelan, unified. Settings (keywords, as the
    scene file's waves.spectrum/spreading keys and the flags of ``oceanref spectrum``):
    wind_speed [m/s] (10), fetch [m] (1e5), depth [m] (inf), gravity [m/s²] (9.81),
    wind_direction_deg (0), spreading, dispersion, swell, spread_blend, gamma, alpha,
    peak_frequency [rad/s], sigma_low, sigma_high, pm_wind ("u10" | "u19.5"), tma_attenuation,
    phillips_suppression, capillary_wavenumber [rad/m], printed_spreading, allow_extrapolation.
    """
    return Spectrum(model, **settings).frequency(omega)


def spreading(model, omega, theta_deg, **settings):
    """D(ω, θ) [1/rad] of MODEL's spreading (``spreading=`` chooses another) at ω [rad/s] and
    absolute wave directions θ [deg] (0 = +x, broadcast against ω)."""
    w, t = _np.broadcast_arrays(_np.asarray(omega, float), _np.asarray(theta_deg, float))
    return Spectrum(model, **settings).spreading(_np.ascontiguousarray(w), _np.ascontiguousarray(t))


def Theta(model, kx, kz, **settings):  # noqa: N802 (the symbol of the formulas)
    """Θ(k_x, k_z) [m⁴], the wavevector spectrum (∬Θ dk_x dk_z = m0), at wavevectors [rad/m]
    (broadcast)."""
    x, z = _np.broadcast_arrays(_np.asarray(kx, float), _np.asarray(kz, float))
    return Spectrum(model, **settings).wavevector(_np.ascontiguousarray(x), _np.ascontiguousarray(z))


def moments(model, k_max=None, **settings):
    """Moments of the continuous spectrum up to k_max [rad/m] (default DEFAULT_K_MAX) by adaptive
    quadrature, as ``oceanref spectrum --moments``: dict with m0 [m²], Hs = 4√m0 [m], mss_x,
    mss_z, mss (mean square slopes) and the quadrature error estimates m0_error, mss_x_error,
    mss_z_error."""
    return Spectrum(model, **settings).moments(k_max)


# --- scenes, fields, render ------------------------------------------------------------------

def load_scene(source):
    """A validated Scene from a file path, a dict, or JSON text (a string starting with '{').

    Scene.canonical is the canonical JSON that is hashed, Scene.sha256 its SHA-256 (the EXR
    attribute oceanref.scene_sha256). A dict or JSON text is validated like a file; errors name
    the JSON path of the key (ValueError)."""
    if isinstance(source, dict):
        return _core._scene_from_json(_json.dumps(source))
    if isinstance(source, (str, _os.PathLike)):
        text = _os.fspath(source)
        if text.lstrip().startswith("{"):
            return _core._scene_from_json(text)
        if not _os.path.exists(text):
            raise FileNotFoundError(f"{text}: cannot open the scene file")
        return _core._scene_from_file(text)
    raise TypeError("load_scene: expected a path, a dict or JSON text, got "
                    f"{type(source).__name__}")


def _scene(scene):
    return scene if isinstance(scene, Scene) else load_scene(scene)


def fields(scene, time=None, threads=0):
    """Every wave field of the scene at ``time`` [s] (default: the scene's), as
    ``oceanref fields -o`` writes them: {field name: float64 array (N, N)}.

    Keys are field names, not the file's channel names: the channel of field ``c0.height`` in
    the file (and in ``read_exr``) is ``c0.height.V`` (docs/FILES.md). Names c<i>.height, disp_x, disp_z [m]; c<i>.slope_x, slope_z, ddx_dx, ddz_dz, ddx_dz,
    jacobian, foam [1] per cascade i; sum.height, slope_x, slope_z, jacobian, normal_x,
    normal_y, normal_z, foam on cascade 0's footprint. Element [n, m] is the sample at
    x = m·L/N, z = n·L/N (docs/FILES.md). Rounded to float32 these are the EXR's channels bit for
    bit; fields_sha256 gives the golden manifest's hashes. ``threads``: 0 = every core; the
    values are identical for any count."""
    return _core._fields(_scene(scene), time, threads)


def _hash_fields(values, dtype):
    h = hashlib.sha256()
    for name in sorted(values):
        h.update(name.encode() + b"\0")
        h.update(_np.ascontiguousarray(values[name], dtype=dtype).tobytes())
    return h.hexdigest()


def fields_sha256(values):
    """(fields_sha256, fields_f64_sha256) of a fields dict, as reference/golden/manifest.json
    defines them (docs/FILES.md): every field in name order, its field name (``c0.height``, not
    the file's channel ``c0.height.V``) and a NUL byte, then its values as little-endian float32
    (first hash) or float64 (second)."""
    return _hash_fields(values, "<f4"), _hash_fields(values, "<f8")


def render(scene, threads=0, spp=None, aov=False, lighting_error=False, samples=False,
           renderer=None, max_memory=8 * 2**30):
    """The reference image of a scene: float64 array (height, width, 3) of linear radiance
    [cd/m² per linear sRGB channel, D65], the values behind ``oceanref render -o``'s R, G, B
    (equal bit for bit after float32 rounding; pixel_sha256 gives the EXR's hash).

    spp: samples per pixel, a square number in [1, 1024] (default: the scene's). threads: 0 =
    every core; the image is identical for any count. With aov=True or samples=True returns a
    dict: radiance, unconverged_samples, integrand_evaluations, unresolved_slope_variance
    (upwind, crosswind); with aov=True also sun, sky, sea, foam, normal, x0, lighting_error,
    pixel_error (H, W, 3), depth [m], coverage (H, W); with adaptive sampling
    (render.pixel_tolerance) pixel_samples (H, W) and
    capped_pixels. lighting_error=True: for shading.accuracy "fast", also the reference
    lighting of every sample, so that lighting_error is the fast mode's error (as ``oceanref
    render --lighting-error``; costs a reference render). samples=True: the dict also holds
    samples (H·S, W·S, 3), every sample of the fixed S×S grid (sample (c, r) at image position
    ((c + ½)/S, (r + ½)/S); each pixel the mean of its S×S samples), as ``oceanref render
    --samples``; not with render.pixel_tolerance. renderer: "raster", "raytrace" (the
    height-field ray tracer on the same grid, which also reflects the scene's objects) or
    "raytrace_surface" (the ray tracer against the continuous surface: ground-truth
    visibility), as ``oceanref render --renderer``; None: the scene's render.renderer. max_memory:
    bytes; a render whose estimated buffers need more raises RuntimeError (as ``oceanref render
    --max-memory``).
    """
    result = _core._render(_scene(scene), threads, spp, aov, bool(lighting_error),
                           bool(samples), "" if renderer is None else str(renderer),
                           float(max_memory))
    return result if aov or samples else result["radiance"]


def pixel_sha256(image):
    """SHA-256 of an (H, W, 3) image as float32 little-endian R, G, B per pixel, row-major: the
    EXR attribute oceanref.pixel_sha256 and the manifest's pixel_sha256."""
    return hashlib.sha256(_np.ascontiguousarray(image, dtype="<f4").tobytes()).hexdigest()


def radiance_f64_sha256(image):
    """SHA-256 of the float64 radiance (little-endian R, G, B per pixel, row-major): the EXR
    attribute oceanref.radiance_f64_sha256."""
    return hashlib.sha256(_np.ascontiguousarray(image, dtype="<f8").tobytes()).hexdigest()


def read_exr(path):
    """Every part and level of an EXR file: a list of dicts with name, level, width, height,
    channels {name: float32 array (height, width)} and attributes {name: string}."""
    return _core._read_exr(_os.fspath(path))


# --- sky and BRDF probes ---------------------------------------------------------------------

def _directions(direction):
    d = _np.asarray(direction, float)
    if d.shape[-1:] != (3,):
        raise ValueError("direction: expected x,y,z or an array of shape (..., 3)")
    return d, _np.ascontiguousarray(d.reshape(-1, 3))


def sky_radiance(direction, sun_zenith_deg, sun_azimuth_deg=0.0, turbidity=2.5):
    """Preetham sky radiance [cd/m² per linear sRGB channel] towards ``direction`` (x, y, z, +Y
    up; any shape (..., 3), normalized here), without the sun disk; as ``oceanref sky --dir``.
    sun_zenith_deg in [0, 180], sun_azimuth_deg in [-720, 720] (from +x towards +z),
    turbidity in [2, 10]."""
    d, flat = _directions(direction)
    rgb, _ = _core._sky(flat, sun_zenith_deg, sun_azimuth_deg, turbidity)
    return rgb.reshape(d.shape)


def sky_xyY(direction, sun_zenith_deg, sun_azimuth_deg=0.0, turbidity=2.5):  # noqa: N802
    """Chromaticity x, y and luminance Y [cd/m²] of the sky towards ``direction`` (..., 3)."""
    d, flat = _directions(direction)
    _, xyY = _core._sky(flat, sun_zenith_deg, sun_azimuth_deg, turbidity)
    return xyY.reshape(d.shape)


def sun_radiance(sun_zenith_deg, sun_azimuth_deg=0.0, turbidity=2.5):
    """The sun disk's radiance: dict rgb, xyz [cd/m²], direction, angular_radius_rad."""
    return _core._sun(sun_zenith_deg, sun_azimuth_deg, turbidity)


def sky_irradiance(sun_zenith_deg, sun_azimuth_deg=0.0, turbidity=2.5):
    """Horizontal irradiance of the sky dome (sun excluded): dict rgb, xyz [lx for Y],
    relative_error (the quadrature's estimate)."""
    return _core._sky_irradiance(sun_zenith_deg, sun_azimuth_deg, turbidity)


def brdf(view, light, sigma2, normal=(0.0, 1.0, 0.0), wind_deg=0.0, fresnel="exact",
         erfc="exact"):
    """Every term of the Bruneton 2010 ocean BRDF for one pair of directions (towards the viewer,
    towards the light; +Y up), slope variances sigma2 = (upwind, crosswind) each in [1e-6, 1],
    the mean normal and the wind direction [deg]: dict zeta_x, zeta_y (the reflecting facet's
    slope), p (slope density), sigma2_view, sigma2_light, lambda_view, lambda_light (Smith Λ),
    fresnel (F(V·h)), brdf_cos (f(L, V)·cos θ_L) [1/sr]. fresnel: exact | schlick | unity;
    erfc: exact | rational."""
    return _core._brdf(view, light, sigma2, normal, wind_deg, fresnel, erfc)


def mean_fresnel_reference(view, sigma2, normal=(0.0, 1.0, 0.0), wind_deg=0.0, tolerance=1e-6,
                           fresnel="exact", erfc="exact"):
    """F̄, the mean Fresnel reflectance seen from ``view``, converged to a relative ``tolerance``
    (in [1e-10, 1e-2]) of 1 − F̄: dict value, error (estimated absolute), evaluations,
    converged."""
    return _core._mean_fresnel_reference(view, sigma2, normal, wind_deg, tolerance, fresnel, erfc)


def reflected_sky_reference(view, sigma2, sun_zenith_deg, sun_azimuth_deg=0.0, turbidity=2.5,
                            normal=(0.0, 1.0, 0.0), wind_deg=0.0, tolerance=1e-6, absolute=0.0,
                            fresnel="exact", erfc="exact"):
    """∫ f(L, V) L_sky(L) cos θ_L dω_L [cd/m² per linear sRGB channel], the reflected sky, per
    channel to max(absolute, tolerance·|value|): dict value (3,), error (3,), evaluations,
    converged."""
    return _core._reflected_sky_reference(view, sigma2, sun_zenith_deg, sun_azimuth_deg,
                                          turbidity, normal, wind_deg, tolerance, absolute,
                                          fresnel, erfc)


def reflected_sun_reference(view, sun, sigma2, sun_radius=None, normal=(0.0, 1.0, 0.0),
                            wind_deg=0.0, tolerance=1e-6, absolute=0.0, fresnel="exact",
                            erfc="exact"):
    """∫_disk f(L, V) cos θ_L dω_L over the sun disk of angular radius ``sun_radius`` [rad]
    (default SUN_ANGULAR_RADIUS) around ``sun``: the reflectance that, times L_sun, is the
    reflected sun; to max(absolute, tolerance·|value|): dict value, error, evaluations,
    converged."""
    radius = SUN_ANGULAR_RADIUS if sun_radius is None else sun_radius
    return _core._reflected_sun_reference(view, sun, sigma2, radius, normal, wind_deg, tolerance,
                                          absolute, fresnel, erfc)


# --- compare ---------------------------------------------------------------------------------

class CompareResult:
    """The outcome of compare(): ``passed`` (also the truth value), ``parts`` (per part: name,
    passed, failing_share, not_compared, channels with golden, candidate, passed, threshold,
    max_absolute, max_relative, rmse, psnr, max_ulp, absolute_percentiles and
    relative_percentiles {p50, p90, p99, p99.9, max}, values, failing, nonfinite_mismatches),
    ``nonfinite_mismatches``, ``text`` (as ``oceanref compare`` prints) and ``json``."""

    def __init__(self, d):
        self.passed = d["passed"]
        self.parts = d["parts"]
        self.nonfinite_mismatches = d["nonfinite_mismatches"]
        self.parts_not_compared = d["parts_not_compared"]
        self.text = d["text"]
        self.json = d["json"]

    def __bool__(self):
        return self.passed

    def channel(self, name, part=None):
        """The result of the channel whose golden name is ``name`` (in ``part``, if given)."""
        for p in self.parts:
            if part is None or p["name"] == part:
                for c in p["channels"]:
                    if c["golden"] == name:
                        return c
        raise KeyError(name)

    def __repr__(self):
        return f"CompareResult(passed={self.passed})"


_NAMES = {1: ["Y"], 3: ["R", "G", "B"], 4: ["R", "G", "B", "A"]}


def _parts(key, image):
    if isinstance(image, (str, _os.PathLike)):
        return _os.fspath(image)
    if isinstance(image, dict):  # {channel: 2-D array}, e.g. a fields dict (field names, no .V)
        return [("", {k: _np.asarray(v) for k, v in image.items()})]
    a = _np.asarray(image)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3 or a.shape[2] not in _NAMES:
        raise ValueError(f"{key}: expected an EXR path, a dict of 2-D channels, or an array of "
                         f"shape (H, W), (H, W, 3) or (H, W, 4); got shape {a.shape}")
    return [("", {n: a[:, :, i] for i, n in enumerate(_NAMES[a.shape[2]])})]


def compare(candidate, golden, profile=None, rel=0.0, abs=0.0, floor=0.0, ulp=0,  # noqa: A002
            max_fail_share=0.0, channels=None, converged=False):
    """Compares a candidate with a golden image by the rule of ``oceanref compare`` (README,
    conformance/compare.h): per value, pass if |c − g| ≤ abs + rel·max(|g|, floor·RMS(g)) or
    within ``ulp`` float32 ULPs; a channel passes if at most ``max_fail_share`` of its values
    fail; any non-finite mismatch (NaN or ±Inf against anything else) fails the comparison.

    candidate, golden: EXR paths, arrays (H, W) → channel Y, (H, W, 3) → R, G, B, (H, W, 4) →
    R, G, B, A (compared as float32), or dicts {channel: 2-D array}. profile: a profile file
    (reference/profiles/*.json) instead of the uniform thresholds. channels: "R,G,B" or
    "cand=golden,…". converged: add the golden's own error (its pixel_error and
    lighting_error layers) to the tolerance of R, G, B, as ``oceanref compare --converged``.
    Returns a CompareResult (truthy when it passes)."""
    d = _core._compare(_parts("candidate", candidate), _parts("golden", golden),
                       None if profile is None else _os.fspath(profile), float(abs), float(rel),
                       float(floor), int(ulp), float(max_fail_share), channels or "",
                       bool(converged),
                       candidate if isinstance(candidate, str) else "<array>",
                       golden if isinstance(golden, str) else "<array>")
    return CompareResult(d)
