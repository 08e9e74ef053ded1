#!/usr/bin/env python3
"""reference/scene.schema.json stays in sync with the scene parser (src/scene/scene.cpp).

  tests/scene_schema_test.py PATH/TO/oceanref SOURCE_DIR

1. The schema is valid JSON Schema (draft 2020-12) and every scene in reference/scenes validates.
2. Keys: for every object of the schema, the keys the parser accepts there — read from its
   error for an unknown key ("unknown key (accepted: …)") — are exactly the schema's properties.
3. Types and ranges, generated from the schema for every leaf: just outside each bound (and 0
   for an exclusive minimum; for arrays each element on its own), a value of the wrong type, a
   string outside an enum and an array of the wrong length are rejected by both the schema and
   the parser (exit 2 naming the key's JSON path); each bound, each enum value and each boolean
   is accepted by both. So neither is looser than the other on what the schema states.
Runs the parser through `oceanref fields SCENE --at 0,0` on a tiny scene (8x8 grid, one
cascade), about 300 runs. Needs python3-jsonschema (tools/setup.sh); exit 77 (skip) without it.
"""
import copy
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

try:
    import jsonschema
except ImportError:
    print("SKIP: python3-jsonschema is not installed (tools/setup.sh installs it)")
    sys.exit(77)

binary, source = sys.argv[1], sys.argv[2]
schema = json.load(open(os.path.join(source, "reference", "scene.schema.json")))
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
failures = []
checks = 0

# A tiny valid scene: every mutation starts from it.
BASE = {"seed": 1, "waves": {"resolution": 8, "cascades": {"sizes": [50]}},
        "render": {"width": 8, "height": 8, "samples_per_pixel": 1}}
# Values a mutation of a key needs around it to be valid at all (cross-field rules the schema
# states with if/then, or that the parser checks and the schema describes).
CONTEXT = {
    "shading.sky_order": {"shading.accuracy": "fast"},
    "shading.sun_order": {"shading.accuracy": "fast"},
    # The schema's bounds, 9 and 59049, are caps of the nested grid from 1 spp.
    "render.max_samples_per_pixel": {"render.pixel_tolerance": 0.01, "render.pixel_pattern": "grid"},
    "render.pixel_pattern": {"render.pixel_tolerance": 0.01},
    "waves.choppiness": {"waves.allow_positive_choppiness": True},
    "waves.spectrum.peak_omega": {"waves.spectrum.allow_extrapolation": True},
    "waves.spectrum.alpha": {"waves.spectrum.allow_extrapolation": True},
    "waves.spectrum.fetch": {"waves.spectrum.allow_extrapolation": True},
    "waves.spectrum.wind_speed": {"waves.spectrum.allow_extrapolation": True},
    "waves.spectrum.gravity": {"waves.spectrum.allow_extrapolation": True},
    # direction_bins divides count; min_wavelength < max_wavelength.
    "waves.gerstner.count": {"waves.gerstner.direction_bins": 1},
    "waves.gerstner.direction_bins": {"waves.gerstner.count": 1024},
    "waves.gerstner.min_wavelength": {"waves.gerstner.max_wavelength": 100000},
}
# Values the schema accepts that the parser rejects in the tiny scene for a reason the schema
# describes but cannot state (model-dependent ranges, sizes, memory), and keys whose values are
# too expensive to accept in a test (an 8192² grid).
ACCEPT_SKIP = {
    ("waves.resolution", v) for v in (32, 64, 128, 256, 512, 1024, 2048, 4096, 8192)
} | {("waves.low_resolution", v) for v in (16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192)} | {
    # The parser is run through `fields --at`, which refuses a gerstner scene (it has no grids;
    # tests/test_wave_models.cpp parses one).
    ("waves.model", "gerstner")}


def set_path(document, path, value):
    keys = path.split(".")
    node = document
    for k in keys[:-1]:
        node = node.setdefault(k, {})
    node[keys[-1]] = value


def scene_with(path, value):
    document = copy.deepcopy(BASE)
    for p, v in CONTEXT.get(path, {}).items():
        set_path(document, p, v)
    if path.startswith("waves.cascades."):  # the cascades object holds sizes or the rest
        document["waves"]["cascades"] = {}
    set_path(document, path, value)
    return document


def parse(document):
    """Runs the parser: (exit status, stderr)."""
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(document, f)
        name = f.name
    try:
        r = subprocess.run([binary, "fields", name, "--at", "0,0", "--threads", "1"],
                           capture_output=True, text=True)
    finally:
        os.unlink(name)
    return r.returncode, r.stderr.strip()


def expect(path, value, valid):
    global checks
    checks += 1
    document = scene_with(path, value)
    schema_ok = validator.is_valid(document)
    status, err = parse(document)
    what = f"{path} = {json.dumps(value)}"
    if schema_ok != valid:
        failures.append(f"{what}: the schema {'accepts' if schema_ok else 'rejects'} it")
    if valid and status != 0:
        failures.append(f"{what}: the parser rejects it (exit {status}): {err}")
    if not valid:
        if status != 2:
            failures.append(f"{what}: the parser exits {status}, expected 2")
        elif path not in err:
            failures.append(f"{what}: the parser's error does not name the key: {err}")


def objects(node, path=""):
    """(path, schema) of every object with properties, depth first."""
    if "properties" in node:
        yield path, node
        for key, sub in node["properties"].items():
            yield from objects(sub, f"{path}.{key}" if path else key)


def leaves(node, path=""):
    for key, sub in node.get("properties", {}).items():
        p = f"{path}.{key}" if path else key
        if "properties" in sub:
            yield from leaves(sub, p)
        else:
            yield p, sub


# 1. Every example scene validates.
for f in sorted(glob.glob(os.path.join(source, "reference", "scenes", "**", "*.json"),
                          recursive=True)):
    checks += 1
    errors = [e.message for e in validator.iter_errors(json.load(open(f)))]
    if errors:
        failures.append(f"{f}: invalid by the schema: {errors[:3]}")

# 2. The same keys per object.
for path, node in objects(schema):
    checks += 1
    document = copy.deepcopy(BASE) if path else {}
    if path:
        if path == "waves.cascades":
            document["waves"]["cascades"] = {}
        set_path(document, path + ".zz_unknown", 1)
    else:
        document = dict(BASE, zz_unknown=1)
    status, err = parse(document)
    m = re.search(r"unknown key \(accepted: ([^)]*)\)", err)
    if status != 2 or not m:
        failures.append(f"{path or '(top level)'}: no unknown-key error from the parser: {err}")
        continue
    accepted = set(m.group(1).split(", "))
    declared = set(node["properties"])
    if accepted != declared:
        failures.append(f"{path or '(top level)'}: parser keys {sorted(accepted - declared)} "
                        f"not in the schema, schema keys {sorted(declared - accepted)} not in "
                        f"the parser")

# 3. Types and ranges of every leaf.
def numeric_checks(path, s, integer):
    step = (lambda b: 1) if integer else (lambda b: max(abs(b) * 1e-9, 1e-12))
    if "minimum" in s:
        expect(path, s["minimum"], True)
        expect(path, s["minimum"] - step(s["minimum"]), False)
    if "exclusiveMinimum" in s:
        expect(path, s["exclusiveMinimum"], False)
        expect(path, s["exclusiveMinimum"] + step(1.0), True)
    if "maximum" in s:
        expect(path, s["maximum"], True)
        expect(path, s["maximum"] + step(s["maximum"]), False)


for path, s in leaves(schema):
    if path == "objects":
        # An array of objects (parsed here, not loaded: `fields` reads no OBJ file).
        expect(path, [], True)
        expect(path, [{"obj": "buoy.obj", "position": [0, 0, 10], "rotation_deg": [0, 45, 0],
                       "scale": 2, "material": {"albedo": [0.8, 0.2, 0.1]}}], True)
        expect(path, [{"position": [0, 0, 10]}], False)  # no obj
        expect(path, [{"obj": ""}], False)
        expect(path, [{"obj": "buoy.obj", "zz_unknown": 1}], False)
        expect(path, [{"obj": "buoy.obj", "scale": 0}], False)
        expect(path, [{"obj": "buoy.obj", "rotation_deg": [0, 361, 0]}], False)
        expect(path, [{"obj": "buoy.obj", "material": {"albedo": [0.5, 1.5, 0.5]}}], False)
        expect(path, [{"obj": "buoy.obj"}] * 65, False)
        continue
    if path == "waves.cascades.band_edges":
        # Its length and bounds follow from the cascades (the parser checks them against each
        # cascade's Nyquist wavenumber: tests/test_waves.cpp); here beside the default four
        # cascades of 1000 m at N = 8 (Nyquist 0.025, 0.041, 0.066 and 0.107 rad/m).
        expect(path, [0.01, 0.03, 0.05], True)
        expect(path, [0, 0.03, 0.05], False)
        expect(path, [0.01, 0.03, 2e6], False)
        continue
    kind = s.get("type")
    if "enum" in s:
        for v in s["enum"]:
            if (path, v) not in ACCEPT_SKIP:
                expect(path, v, True)
        expect(path, "zz-not-a-choice" if kind == "string" else 12345, False)
    elif kind in ("number", "integer"):
        numeric_checks(path, s, kind == "integer")
    elif kind == "boolean":
        expect(path, True, True)
        expect(path, False, True)
        expect(path, "yes", False)
    elif kind == "array":
        n = s.get("minItems", 1)
        item = s["items"]
        good = s.get("default", [item.get("minimum", 0)] * n)
        expect(path, good, True)
        expect(path, good + [good[0]] * (s.get("maxItems", 99) - len(good) + 1), False)
        for bound, sign in (("minimum", -1), ("maximum", 1)):
            if bound not in item:
                continue
            for i in range(len(good)):  # each element's range on its own
                v = copy.deepcopy(good)
                v[i] = item[bound] + sign * max(abs(item[bound]) * 1e-9, 1e-12)
                expect(path, v, False)
                v[i] = item[bound]
                expect(path, v, True)
    elif "anyOf" in s:  # choppiness: a number or one per cascade
        for sub in s["anyOf"]:
            if sub.get("type") == "number":
                numeric_checks(path, sub, False)
        expect(path, [s["anyOf"][0]["minimum"]], True)
    if kind in ("number", "integer") or "anyOf" in s or (kind == "array"):
        expect(path, "1", False)  # a string is never a number

# Cross-field rules the schema states.
expect("shading.tolerance", 1e-6, True)
checks += 1
fast_tolerance = scene_with("shading.accuracy", "fast")
fast_tolerance["shading"]["tolerance"] = 1e-6
if validator.is_valid(fast_tolerance) or parse(fast_tolerance)[0] != 2:
    failures.append("shading.tolerance with accuracy fast: not rejected by both")
for chop in (0.5, [0.5]):
    checks += 1
    positive = copy.deepcopy(BASE)
    positive["waves"]["choppiness"] = chop
    if validator.is_valid(positive) or parse(positive)[0] != 2:
        failures.append(f"waves.choppiness = {chop} without allow_positive_choppiness: not "
                        "rejected by both")
checks += 1
both = scene_with("waves.cascades.sizes", [50])
both["waves"]["cascades"]["count"] = 1
if validator.is_valid(both) or parse(both)[0] != 2:
    failures.append("waves.cascades with sizes and count: not rejected by both")

for f in failures:
    print("FAIL:", f, file=sys.stderr)
print(f"scene_schema_test: {checks} checks, {len(failures)} failed")
sys.exit(1 if failures else 0)
