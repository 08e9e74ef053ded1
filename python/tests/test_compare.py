"""compare() on arrays and EXR files: the rule, non-finite mismatches, percentiles, profiles,
and the same verdict and text as `oceanref compare`."""

import numpy as np
import pytest

import oceanref


def image(seed=1, shape=(20, 30, 3)):
    return np.random.default_rng(seed).uniform(0.5, 2.0, shape)


def test_identical_images_pass():
    g = image()
    r = oceanref.compare(g, g)
    assert r and r.passed
    c = r.channel("R")
    assert c["max_absolute"] == 0 and c["values"] == 600 and c["failing"] == 0


def test_a_nan_candidate_fails_whatever_the_thresholds():
    g = image()
    c = g.copy()
    c[3, 4, 1] = np.nan
    r = oceanref.compare(c, g, rel=1e30, max_fail_share=1.0)
    assert not r.passed
    assert r.nonfinite_mismatches == 1
    assert r.channel("G")["nonfinite_mismatches"] == 1 and r.channel("R")["passed"]
    c[3, 4, 1] = np.inf
    assert not oceanref.compare(c, g, rel=1e30, max_fail_share=1.0)


def test_relative_threshold_and_percentiles():
    # A uniform relative error of 1e-3 (as float32: within 1e-6 of it).
    g = image()
    c = g * (1 + 1e-3)
    assert not oceanref.compare(c, g, rel=1e-4)
    r = oceanref.compare(c, g, rel=2e-3)
    assert r.passed
    ch = r.channel("B")
    for p in ("p50", "p90", "p99", "p99.9", "max"):
        assert ch["relative_percentiles"][p] == pytest.approx(1e-3, rel=1e-3)
    # One failing value in 600: allowed by max_fail_share 0.002, not by 0.001.
    c = g.copy()
    c[0, 0, 0] *= 1.5
    assert oceanref.compare(c, g, rel=1e-6, max_fail_share=0.002)
    assert not oceanref.compare(c, g, rel=1e-6, max_fail_share=0.001)
    with pytest.raises(ValueError, match=r"^max_fail_share: must be in \[0, 1\]"):
        oceanref.compare(c, g, max_fail_share=2)
    with pytest.raises(ValueError, match="^compare:"):
        oceanref.compare(c[:10], g)  # sizes differ


def test_exr_paths_and_the_command_line(cli, tmp_path):
    # Two renders of a golden EXR's pixels: the golden itself and a perturbed copy written by
    # nothing but this test (compared as arrays against the file).
    from conftest import SOURCE_DIR
    golden = SOURCE_DIR / "reference" / "golden" / "mastin_spread_direct_tiny.exr"
    (part,) = oceanref.read_exr(golden)
    rgb = np.stack([part["channels"][n] for n in "RGB"], axis=-1)
    r = oceanref.compare(str(golden), str(golden))
    assert r.passed
    assert r.text == cli("compare", golden, golden)
    assert oceanref.compare(rgb, str(golden)).passed
    assert not oceanref.compare(rgb * np.float32(1.01), str(golden), rel=1e-3).passed
    # The shipped float32 profile covers the spectral fields, not the Jacobian and foam: the
    # comparison is refused naming the first uncovered channel, as on the command line.
    fields = SOURCE_DIR / "reference" / "golden" / "mastin_spread_direct_tiny.fields.exr"
    profile = SOURCE_DIR / "reference" / "profiles" / "fields_float32.json"
    with pytest.raises(ValueError, match=r"no threshold for channel 'c0\.foam\.V'"):
        oceanref.compare(str(fields), str(fields), profile=profile)
    cli("compare", fields, fields, "--profile", profile, expect=2)
    assert oceanref.compare(str(fields), str(fields), rel=1e-6).passed
    with pytest.raises(ValueError, match="^golden:"):
        oceanref.compare(str(fields), str(tmp_path / "missing.exr"))
