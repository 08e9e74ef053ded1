"""The reference image from Python equals the command line's render bit for bit."""

import numpy as np
import pytest

import oceanref

# A tiny fast-lighting scene: 40×24 pixels, one sample each.
TINY = {
    "seed": 7,
    "waves": {"spectrum": {"model": "jonswap", "wind_speed": 9, "fetch": 40000},
              "cascades": {"sizes": [50]}, "resolution": 16},
    "camera": {"position": [0, 5, 0], "look_at": [0, 0, 40]},
    "grid": {"columns": 40, "rows": 40},
    "atmosphere": {"sun_zenith_deg": 60, "sun_azimuth_deg": 80, "turbidity": 2.5},
    "shading": {"accuracy": "fast"},
    "render": {"width": 40, "height": 24, "samples_per_pixel": 1},
}


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    import json
    path = tmp_path_factory.mktemp("scene") / "tiny.json"
    path.write_text(json.dumps(TINY))
    return path


def test_render_equals_the_command_line(tiny, cli, tmp_path):
    out = tmp_path / "tiny.exr"
    cli("render", tiny, "-o", out, "--threads", "2")
    (part,) = oceanref.read_exr(out)
    img = oceanref.render(tiny, threads=1)
    assert img.shape == (24, 40, 3) and img.dtype == np.float64
    for c, name in enumerate("RGB"):
        assert np.array_equal(img[:, :, c].astype(np.float32), part["channels"][name]), name
    assert oceanref.pixel_sha256(img) == part["attributes"]["oceanref.pixel_sha256"]
    assert oceanref.radiance_f64_sha256(img) == part["attributes"]["oceanref.radiance_f64_sha256"]
    assert oceanref.load_scene(tiny).sha256 == part["attributes"]["oceanref.scene_sha256"]
    assert img.max() > 0.0  # the sea and sky are lit


def test_render_matches_a_golden_image(golden_scene, manifest, golden_hashes):
    # mastin_spread_direct_tiny: reference lighting, 48×27 at 1 spp.
    name = "mastin_spread_direct_tiny"
    img = oceanref.render(golden_scene(name), threads=2)
    assert img.shape == (27, 48, 3)
    if not golden_hashes:
        return
    assert oceanref.pixel_sha256(img) == manifest[name]["pixel_sha256"]
    assert oceanref.radiance_f64_sha256(img) == manifest[name]["radiance_f64_sha256"]


def test_spp_and_aov(tiny):
    a = oceanref.render(tiny, threads=2, aov=True)
    assert np.array_equal(a["radiance"], oceanref.render(tiny, threads=2))
    # The terms add up to the radiance where the sea covers the whole pixel (1 spp; no foam).
    sea = a["coverage"] == 1.0
    assert sea.sum() > 100
    total = a["sun"] + a["sky"] + a["sea"] + a["foam"]
    np.testing.assert_allclose(total[sea], a["radiance"][sea], rtol=1e-12, atol=0)
    b = oceanref.render(tiny, threads=2, spp=4)
    assert not np.array_equal(b, a["radiance"])  # the setting reaches the image
    with pytest.raises(ValueError, match=r"^spp: must be a square number in \[1, 1024\], got 3"):
        oceanref.render(tiny, spp=3)
    # The pixel integral's error (issue 20): 0 from one sample, the samples' spread from four.
    assert not a["pixel_error"].any()
    b = oceanref.render(tiny, threads=2, spp=4, aov=True)
    assert b["pixel_error"].shape == (24, 40, 3) and (b["pixel_error"] > 0).mean() > 0.5
    assert "pixel_samples" not in b
    # Adaptive sampling: the samples behind each pixel (one refinement at least from 1 spp).
    adaptive = dict(TINY, render=dict(TINY["render"], pixel_tolerance=0.05, pixel_pattern="grid",
                                      max_samples_per_pixel=81))
    c = oceanref.render(adaptive, threads=2, aov=True)
    assert set(np.unique(c["pixel_samples"])) <= {9.0, 81.0} and (c["pixel_samples"] == 9).any()
    assert c["capped_pixels"] <= (c["pixel_samples"] == 81).sum()
    # The fast lighting error is estimated only when asked.
    assert not a["lighting_error"].any()
    d = oceanref.render(tiny, threads=2, aov=True, lighting_error=True)
    assert (d["lighting_error"] > 0).any()
    # Same samples: every sample of the 2×2 grid, each pixel their mean (row-major, 1/4 each).
    e = oceanref.render(tiny, threads=2, spp=4, samples=True)
    assert e["samples"].shape == (48, 80, 3) and "sun" not in e
    s = e["samples"]
    mean = 0.25 * s[0::2, 0::2] + 0.25 * s[0::2, 1::2] + 0.25 * s[1::2, 0::2]
    mean = mean + 0.25 * s[1::2, 1::2]
    np.testing.assert_array_equal(mean, e["radiance"])
    np.testing.assert_array_equal(e["radiance"], b["radiance"])
    with pytest.raises(ValueError, match=r"^samples: the fixed grid's samples only"):
        oceanref.render(adaptive, samples=True)
    # The second renderer: the same image up to rounding (tests/test_tracer.cpp: within 1e-9).
    f = oceanref.render(tiny, threads=2, spp=4, renderer="raytrace")
    np.testing.assert_allclose(f, b["radiance"], rtol=1e-9, atol=1e-12)
    with pytest.raises(ValueError, match=r"^renderer: expected one of raster, raytrace, raytrace_surface"):
        oceanref.render(tiny, renderer="pathtrace")


def test_max_memory_refuses_a_render_before_it_starts(tiny):
    big = dict(TINY, render={"width": 4096, "height": 4096, "samples_per_pixel": 4})
    # 4096² pixels at 4 spp: about 3.9 GiB of buffers, over a 1 GiB limit, refused at once;
    # with the layers (aov=True: 152 more bytes per pixel and 26 more EXR channels) about 7.9 GiB.
    with pytest.raises(RuntimeError, match=r"needs an estimated 40[0-9]{2}(\.[0-9])? MiB .*"
                                           r"over the limit of 1024 MiB; raise it with max_memory="):
        oceanref.render(big, max_memory=2**30)
    with pytest.raises(RuntimeError, match=r"needs an estimated 81[0-9]{2}(\.[0-9])? MiB .*"
                                           r"over the limit of 1024 MiB; raise it with max_memory="):
        oceanref.render(big, aov=True, max_memory=2**30)
    with pytest.raises(ValueError, match="max_memory"):
        oceanref.render(tiny, max_memory=1000)
    assert oceanref.render(tiny, max_memory=2**24).shape == (24, 40, 3)


def test_objects_and_their_reflection(cli, tmp_path):
    """A scene with an OBJ object: relative to the scene file, the same bits as the command line,
    and the ray tracer's reflection of it (render.renderer or renderer=)."""
    import json
    import shutil
    from conftest import SOURCE_DIR
    shutil.copy(SOURCE_DIR / "reference" / "objects" / "buoy.obj", tmp_path / "buoy.obj")
    scene = dict(TINY, camera={"position": [0, 2.5, 0], "look_at": [0, 0.6, 14]},
                 objects=[{"obj": "buoy.obj", "position": [0, 0, 12], "scale": 1.5,
                           "material": {"albedo": [0.8, 0.15, 0.1]}}])
    path = tmp_path / "buoy_scene.json"
    path.write_text(json.dumps(scene))
    raster = oceanref.render(path, threads=2)
    sea = oceanref.render(dict(scene, objects=[]), threads=2)
    assert (raster != sea).any(axis=2).sum() > 10  # the buoy is seen
    traced = oceanref.render(path, threads=2, renderer="raytrace")
    # Beyond rounding (the two renderers' doubles differ in the last bits: within 1e-9), only
    # the buoy's reflection in the sea differs.
    reflected = (np.abs(traced - raster) > 1e-9 * np.abs(raster) + 1e-12).any(axis=2)
    assert 0 < reflected.sum() < reflected.size // 4
    out = tmp_path / "traced.exr"
    cli("render", path, "-o", out, "--renderer", "raytrace", "--threads", "2")
    (part,) = oceanref.read_exr(out)
    assert part["attributes"]["oceanref.renderer"] == "raytrace"
    assert oceanref.radiance_f64_sha256(traced) == part["attributes"]["oceanref.radiance_f64_sha256"]
    # The scene's own render.renderer is what renderer=None uses.
    path.write_text(json.dumps(dict(scene, render=dict(scene["render"], renderer="raytrace"))))
    np.testing.assert_array_equal(oceanref.render(path, threads=1), traced)
