"""Scenes and their wave fields from Python: the canonical hash, strict validation, and the
fields bit for bit equal to the doubles behind `oceanref fields` (the golden manifest's
fields_f64_sha256, `fields --at` at grid nodes, the fields EXR's float32 channels)."""

import json

import numpy as np
import pytest

import oceanref
from conftest import csv_rows

# Small golden scenes (16-64 points per side): cheap, and between them multi-resolution,
# several cascades, choppiness and foam.
SCENES = ["mastin_spread_direct_tiny", "default_small", "jonswap_storm_whitecaps"]


def test_load_scene_from_path_dict_and_json(golden_scene, manifest, golden_hashes):
    path = golden_scene("default_small")
    a = oceanref.load_scene(path)
    with open(path) as f:
        text = f.read()
    b = oceanref.load_scene(text)
    c = oceanref.load_scene(json.loads(text))
    assert a.sha256 == b.sha256 == c.sha256
    assert a.sha256 == manifest["default_small"]["scene_sha256"] or not golden_hashes
    assert a.canonical == c.canonical
    assert json.loads(a.canonical)["seed"] == a.seed
    assert (a.width, a.height) == (manifest["default_small"]["width"],
                                   manifest["default_small"]["height"])


@pytest.mark.parametrize(
    "scene, path, text",
    [
        ({"waves": {"spectrum": {"wind_speed": -1}}}, "waves.spectrum.wind_speed", "must be in"),
        ({"waves": {"spectrum": {"wind_sped": 5}}}, "waves.spectrum.wind_sped", "unknown key"),
        ({"seed": "one"}, "seed", "expected"),
        ('{"seed": 1,}', "(scene JSON)", "not valid JSON"),
    ],
)
def test_bad_scene_raises_value_error_naming_the_key(scene, path, text):
    with pytest.raises(ValueError) as e:
        oceanref.load_scene(scene)
    assert str(e.value).startswith(path + ":"), str(e.value)
    assert text in str(e.value)


def test_missing_scene_file():
    with pytest.raises(FileNotFoundError):
        oceanref.load_scene("/nonexistent/scene.json")


@pytest.mark.parametrize("name", SCENES)
def test_fields_match_the_golden_hashes(name, golden_scene, manifest, golden_hashes):
    # The manifest's hashes come from `oceanref golden update` (the CLI's fields): equal hashes
    # mean every double and every float32 channel is identical, names and sizes included.
    f = oceanref.fields(golden_scene(name), threads=2)
    f32, f64 = oceanref.fields_sha256(f)
    if golden_hashes:
        assert f64 == manifest[name]["fields_f64_sha256"]
        assert f32 == manifest[name]["fields_sha256"]
    assert all(v.dtype == np.float64 for v in f.values())


def test_fields_equal_the_command_line_at_grid_nodes(golden_scene, cli):
    # `fields --at x,z` prints each cascade's FFT grid value (exact at a node) with 17 digits.
    path = golden_scene("mastin_spread_direct_tiny")  # L = 60 m, N = 16: nodes every 3.75 m
    scene = oceanref.load_scene(path)
    f = oceanref.fields(scene)
    L, N = scene.cascade_sizes[0], scene.resolution
    for m, n in [(3, 5), (0, 0), (15, 9)]:
        rows = csv_rows(cli("fields", path, "--at", f"{m * L / N},{n * L / N}"))
        checked = 0
        for r in rows:
            if r["cascade"] == "0":
                assert f["c0." + r["field"]][n, m] == float(r["fft"]), (m, n, r["field"])
                checked += 1
        assert checked == 8  # the eight spectral fields (--at prints no Jacobian or foam)


def test_fields_equal_the_fields_exr(golden_scene, cli, tmp_path):
    path = golden_scene("default_small")
    out = tmp_path / "fields.exr"
    cli("fields", path, "-o", out, "--threads", "2")
    f = oceanref.fields(path, threads=1)
    seen = set()
    for part in oceanref.read_exr(out):
        for channel, values in part["channels"].items():
            # The file's channel is the field name plus ".V" (Blender's layer.pass.channel);
            # fields() and the unit attributes use the field name.
            assert channel.endswith(".V"), channel
            name = channel[:-len(".V")]
            assert np.array_equal(values, f[name].astype(np.float32)), name
            assert part["attributes"]["oceanref.units." + name] in ("m", "1"), name
            seen.add(name)
    assert seen == set(f)


def test_time_changes_the_fields(golden_scene):
    path = golden_scene("mastin_spread_direct_tiny")
    scene = oceanref.load_scene(path)
    a = oceanref.fields(scene)
    b = oceanref.fields(scene, time=scene.time)
    c = oceanref.fields(scene, time=scene.time + 1.5)
    assert all(np.array_equal(a[k], b[k]) for k in a)
    assert not np.array_equal(a["c0.height"], c["c0.height"])
    with pytest.raises(ValueError, match="^time:"):
        oceanref.fields(scene, time=1e9)
    with pytest.raises(ValueError, match="^threads:"):
        oceanref.fields(scene, threads=-1)
