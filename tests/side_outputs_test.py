#!/usr/bin/env python3
"""The side outputs of `oceanref render`, read back by independent readers (issue 21):

- the PNG preview: every chunk's CRC (zlib.crc32), the IHDR, and the pixels decoded here (inflate
  and the five PNG row filters, written below) equal OpenImageIO's decoding, and equal the
  preview as docs/FILES.md defines it, recomputed here from the EXR: Reinhard 2002 with the key
  render.tone_key, L̄_w = exp(mean ln(1e-4 + L)) over the pixels and L_white the largest scaled
  luminance, then the sRGB transfer function, rounded to 8 bits (within one step: the library
  takes L̄_w and L_white from the doubles, this test from the float32 pixels);
- the EXR's line offset table read here: each entry points at the chunk of its lines, the
  chunks contiguous to the end of the file (OpenEXR's reader rebuilds a broken table silently);
- the EXR's `oceanref.pixel_sha256` recomputed with hashlib from the decoded pixels; the seed,
  the renderer and the unresolved slope variance attributes against the scene and `probe`;
- every AOV layer (depth, coverage, normal, x0, sun, sky, sea, lighting_error, pixel_error)
  recomputed from `oceanref probe`'s samples of four pixels (sky, horizon, two of sea) exactly as
  the renderer resolves them (FILES.md), rounded to float32: the same bits; the foam layer is
  zero exactly where no sample has whitecap coverage; and worldToNDC maps each sea sample's
  surface point to within a pixel of where the sample was taken.

    tests/side_outputs_test.py PATH/TO/oceanref SOURCE_DIR

OpenImageIO's and NumPy's Python modules (tools/setup.sh); skipped (exit 77) only without them.
"""
import base64
import csv
import hashlib
import io
import json
import math
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

try:
    import numpy as np
    import OpenImageIO as oiio
except ImportError:
    print("SKIP: NumPy or OpenImageIO's Python module is missing (tools/setup.sh installs them)")
    sys.exit(77)

binary, source = sys.argv[1:3]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what, file=sys.stderr)
        if os.environ.get("OCEANREF_TESTS_FAIL_FAST"):  # tools/mutation.py: one is enough
            sys.exit(1)


def run(*args):
    r = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: oceanref {' '.join(map(str, args))} exited {r.returncode}: {r.stderr}")
    return r.stdout


# --- A PNG decoder (RFC 2083 / ISO 15948), for 8-bit RGB without interlace --------------------

def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else b if pb <= pc else c


def decode_png(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG signature"
    pos, chunks = 8, []
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        crc, = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        check(zlib.crc32(kind + body) == crc, f"PNG chunk {kind!r} at byte {pos}: CRC mismatch")
        chunks.append((kind, body))
        pos += 12 + length
    check(chunks[0][0] == b"IHDR" and chunks[-1] == (b"IEND", b""), "PNG: IHDR first, IEND last")
    width, height, depth, colour, compression, filtering, interlace = struct.unpack(
        ">IIBBBBB", chunks[0][1])
    check((depth, colour, compression, filtering, interlace) == (8, 2, 0, 0, 0),
          f"PNG: not 8-bit RGB without interlace: {depth, colour, compression, filtering, interlace}")
    check(all(len(b) <= 65536 for k, b in chunks if k == b"IDAT"), "PNG: an IDAT over 64 KiB")
    raw = zlib.decompress(b"".join(b for k, b in chunks if k == b"IDAT"))
    stride = 3 * width
    check(len(raw) == height * (stride + 1), "PNG: the inflated size is not H (1 + 3 W)")
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        check(kind <= 4, f"PNG: row {y} has filter type {kind}")
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = previous[i]
            c = previous[i - 3] if i >= 3 else 0
            line[i] = (line[i] + (0, a, b, (a + b) // 2, paeth(a, b, c))[kind]) & 0xFF
        rows.append(bytes(line))
        previous = line
    return np.frombuffer(b"".join(rows), np.uint8).reshape(height, width, 3)


def read_exr(path):
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    image.close()
    return spec, {name: pixels[:, :, i] for i, name in enumerate(spec.channelnames)}


def exr_chunks(data):
    """The scanline chunks of a single-part EXR as its header and line offset table give them
    (OpenEXR file layout): [(offset, y, size)], the compression and the data window."""
    check(data[:4] == b"\x76\x2f\x31\x01", "EXR: no magic number")
    pos, attributes = 8, {}
    while data[pos] != 0:
        name_end = data.index(b"\0", pos)
        type_end = data.index(b"\0", name_end + 1)
        size, = struct.unpack("<i", data[type_end + 1:type_end + 5])
        attributes[data[pos:name_end].decode()] = data[type_end + 5:type_end + 5 + size]
        pos = type_end + 5 + size
    pos += 1
    compression = attributes["compression"][0]
    xmin, ymin, xmax, ymax = struct.unpack("<iiii", attributes["dataWindow"])
    lines = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32}[compression]  # none, RLE, ZIPS, ZIP, PIZ
    count = (ymax - ymin + lines) // lines
    offsets = struct.unpack(f"<{count}Q", data[pos:pos + 8 * count])
    chunks = []
    for offset in offsets:
        y, size = struct.unpack("<ii", data[offset:offset + 8])
        chunks.append((offset, y, size))
    return chunks, lines, (ymin, ymax)


def srgb(c):
    c = min(max(c, 0.0), 1.0)
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


with tempfile.TemporaryDirectory() as tmp:
    scene = json.load(open(os.path.join(source, "reference", "scenes", "default.json")))
    scene["render"].update({"width": 24, "height": 14, "samples_per_pixel": 4})
    scene_path = os.path.join(tmp, "scene.json")
    json.dump(scene, open(scene_path, "w"))
    exr_path, png_path = os.path.join(tmp, "r.exr"), os.path.join(tmp, "r.png")
    run("render", scene_path, "-o", exr_path, "--png", png_path, "--aov", "--threads", "2")
    spec, ch = read_exr(exr_path)
    w, h = spec.width, spec.height

    # --- The preview ---------------------------------------------------------------------------
    mine = decode_png(open(png_path, "rb").read())
    theirs = oiio.ImageInput.open(png_path)
    theirs_pixels = theirs.read_image(0, 0, 0, 3, "uint8")
    theirs.close()
    check(mine.shape == (h, w, 3) and np.array_equal(mine, theirs_pixels),
          "PNG: this decoder and OpenImageIO's disagree")
    rgb = np.stack([ch["R"], ch["G"], ch["B"]], axis=-1).astype(np.float64)
    lum = 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]
    log_average = math.exp(np.mean(np.log(1e-4 + np.maximum(lum, 0.0))))
    key = scene["render"].get("tone_key", 0.18)
    white = key / log_average * lum.max()
    expected = np.zeros((h, w, 3), np.int64)
    for y in range(h):
        for x in range(w):
            lw = lum[y, x]
            if lw <= 0.0:
                continue
            l = key / log_average * lw
            scale = l * (1.0 + l / (white * white)) / (1.0 + l) / lw
            for c in range(3):
                expected[y, x, c] = math.floor(255.0 * srgb(rgb[y, x, c] * scale) + 0.5)
    diff = np.abs(expected - mine.astype(np.int64))
    check(diff.max() <= 1 and (diff == 0).mean() >= 0.99,
          f"PNG preview: Reinhard + sRGB from the EXR differs by up to {diff.max()} "
          f"({(diff == 0).mean():.3f} of values exact)")
    check(len(np.unique(mine)) > 20, "PNG preview: fewer than 20 distinct values")

    # --- The EXR's line offset table (a reader that trusts it finds every chunk) ---------------
    tall = json.loads(json.dumps(scene))
    tall["render"].update({"width": 8, "height": 40, "samples_per_pixel": 1})
    tall["shading"]["accuracy"] = "fast"
    tall["shading"].pop("tolerance", None)
    tall_path = os.path.join(tmp, "tall.json")
    json.dump(tall, open(tall_path, "w"))
    run("render", tall_path, "-o", os.path.join(tmp, "tall.exr"), "--threads", "2")
    data = open(os.path.join(tmp, "tall.exr"), "rb").read()
    chunks, lines, (ymin, ymax) = exr_chunks(data)
    check(len(chunks) == 3, f"EXR: {len(chunks)} chunks of 16 lines for 40 rows")
    check([y for _, y, _ in chunks] == list(range(ymin, ymax + 1, lines)),
          f"EXR: the line offset table points at chunks of lines {[y for _, y, _ in chunks]}")
    check(all(a[0] + 8 + a[2] == b[0] for a, b in zip(chunks, chunks[1:])) and
          chunks[-1][0] + 8 + chunks[-1][2] == len(data),
          "EXR: the chunks the offset table gives are not contiguous up to the end of the file")

    # --- Attributes ----------------------------------------------------------------------------
    interleaved = np.stack([ch["R"], ch["G"], ch["B"]], axis=-1).astype("<f4").tobytes()
    check(spec.getattribute("oceanref.pixel_sha256") == hashlib.sha256(interleaved).hexdigest(),
          "oceanref.pixel_sha256 is not the SHA-256 of the decoded pixels")
    check(str(spec.getattribute("oceanref.seed")) == str(scene["seed"]), "oceanref.seed")
    check(spec.getattribute("oceanref.renderer") == "raster", "oceanref.renderer")

    # --- The layers against probe --------------------------------------------------------------
    world_to_ndc = np.array(spec.getattribute("worldToNDC"), np.float64).reshape(4, 4)
    kinds = set()
    for x, y in ((0, 0), (12, 6), (12, 10), (20, 13)):
        text = run("probe", scene_path, "--pixel", f"{x},{y}", "--threads", "2")
        lines = text.splitlines()
        samples = list(csv.DictReader(io.StringIO("\n".join(lines[:-2]))))
        n = len(samples)
        check(n == 4, f"probe {x},{y}: {n} samples, not 4")
        per_sample = 1.0 / n
        hits = [s for s in samples if s["hit"] == "1"]
        kinds.add("sky" if not hits else "sea" if len(hits) == n else "horizon")
        # Each sample's error columns: the lighting error is the sum of the three terms' errors,
        # scaled by the whitecaps' share 1 - W (the foam is not integrated, so has no error),
        # exactly as the renderer combines them (the same operations in the same order).
        for s in samples:
            for c in "RGB":
                terms = float(s[f"sun_error_{c}"]) + float(s[f"sky_error_{c}"]) + \
                    float(s[f"sea_error_{c}"])
                combined = terms * (1.0 - float(s["foam_coverage"]))
                check(combined == float(s[f"error_{c}"]),
                      f"probe {x},{y} sample {s['sample']}: error_{c} {s[f'error_{c}']} is not "
                      f"(sun + sky + sea error) x (1 - W) = {combined!r}")

        def layer_sum(column):
            total = 0.0
            for s in samples:
                total += per_sample * float(s[column])
            return total

        def hit_mean(column):
            total = 0.0
            for s in hits:
                total += float(s[column])
            return total / len(hits) if hits else 0.0

        expect = {"coverage": len(hits) * per_sample, "depth": hit_mean("depth"),
                  "normal.R": hit_mean("normal_x"), "normal.G": hit_mean("normal_y"),
                  "normal.B": hit_mean("normal_z"), "x0.R": hit_mean("x0"), "x0.G": 0.0,
                  "x0.B": hit_mean("z0")}
        for c in "RGB":
            for term in ("sun", "sky", "sea"):
                expect[f"{term}.{c}"] = layer_sum(f"{term}_{c}")
            expect[f"lighting_error.{c}"] = layer_sum(f"error_{c}")
            values = [float(s[c]) for s in samples]
            mean = layer_sum(c)
            squares = 0.0
            for v in values:
                squares += (v - mean) * (v - mean)
            expect[f"pixel_error.{c}"] = 3.0 * math.sqrt(squares / (n * (n - 1.0)))
            expect[c] = mean
            foamless = all(float(s["foam_coverage"]) == 0.0 for s in samples)
            check((ch[f"foam.{c}"][y, x] == 0.0) == foamless,
                  f"foam.{c} at {x},{y}: {ch[f'foam.{c}'][y, x]} with "
                  f"{'no' if foamless else 'some'} whitecap coverage in the samples")
        for name, value in expect.items():
            written = ch[name][y, x]
            check(np.float32(value).tobytes() == written.tobytes(),
                  f"layer {name} at {x},{y}: the EXR holds {written!r}, probe's samples give "
                  f"{np.float32(value)!r}")
        for s in hits:
            p = np.array([float(s["x"]), float(s["y"]), float(s["z"]), 1.0]) @ world_to_ndc
            ndc = p[:2] / p[3]
            px = (ndc[0] * w, ndc[1] * h)
            check(abs(px[0] - float(s["image_x"])) < 1 and abs(px[1] - float(s["image_y"])) < 1,
                  f"worldToNDC maps sample {s['sample']} of {x},{y} to {px}, taken at "
                  f"{s['image_x']}, {s['image_y']}")
        if hits:
            sigma2 = spec.getattribute("oceanref.unresolved_slope_variance")
            check(sigma2 is not None and
                  [float(v) for v in str(sigma2).replace(",", " ").split()] ==
                  [float(hits[0]["sigma2_upwind"]), float(hits[0]["sigma2_crosswind"])],
                  f"oceanref.unresolved_slope_variance {sigma2!r} is not probe's sigma2 "
                  f"{hits[0]['sigma2_upwind']}, {hits[0]['sigma2_crosswind']}")
    check(kinds == {"sky", "sea", "horizon"}, f"the probed pixels cover {sorted(kinds)}")
    check(ch["coverage"].min() == 0.0 and ch["coverage"].max() == 1.0, "coverage spans 0..1")
    check(ch["foam.R"].max() > 0.0, "the default scene shows no foam in the foam layer")

    # --- The compare report's crops: centred on the worst value ---------------------------------
    # A golden gradient and a candidate that differs in one pixel only, (20, 10) of 40 x 30: the
    # first crop row's golden and candidate pictures (15 x 15 values around it, enlarged 8x)
    # differ in the centre value's 8 x 8 block and nowhere else.
    yy, xx = np.mgrid[0:30, 0:40]
    gradient = (0.2 + 0.01 * xx + 0.005 * yy).astype(np.float32)
    spiked = gradient.copy()
    spiked[10, 20] += 1.0
    for name, plane in (("gold", gradient), ("spiked", spiked)):
        out = oiio.ImageOutput.create(os.path.join(tmp, name + ".exr"))
        out.open(os.path.join(tmp, name + ".exr"), oiio.ImageSpec(40, 30, 3, "float"))
        out.write_image(np.repeat(plane[:, :, None], 3, axis=2))
        out.close()
    report = os.path.join(tmp, "report")
    r = subprocess.run([binary, "compare", os.path.join(tmp, "spiked.exr"),
                        os.path.join(tmp, "gold.exr"), "--report", report],
                       capture_output=True, text=True)
    check(r.returncode == 1, f"compare of a spiked image exited {r.returncode}: {r.stderr}")
    page = open(os.path.join(report, "index.html")).read()
    # The part's heading: a single-level image has no "level" in it (only mip levels > 0 do).
    heading = re.findall(r"<h2>part [^<]*</h2>", page)
    check(heading == ["<h2>part (single): 40&times;30, FAIL, failing pixels 0.0833%</h2>"],
          f"the report's part headings are {heading}")
    row = page[page.index('<table class="crops">'):]
    row = row[row.index("<tr><td>"):row.index("</tr>", row.index("<tr><td>"))]
    check(row.startswith("<tr><td>(20, 10)"), f"the first worst value is not (20, 10): {row[:40]}")
    crops = [decode_png(base64.b64decode(uri)) for uri in
             re.findall(r'src="data:image/png;base64,([^"]+)"', row)]
    check(len(crops) == 3 and all(c.shape == (120, 120, 3) for c in crops),
          f"the crop row holds {len(crops)} pictures of {[c.shape for c in crops]}")
    changed = np.argwhere(np.any(crops[0] != crops[1], axis=2))
    check(len(changed) == 64 and changed.min(axis=0).tolist() == [56, 56] and
          changed.max(axis=0).tolist() == [63, 63],
          f"golden and candidate crops differ at {changed.min(axis=0) if len(changed) else None}"
          f"..{changed.max(axis=0) if len(changed) else None} ({len(changed)} pixels), "
          "not in the centre value's block 56..63")

print(f"side_outputs: {len(failures)} failures")
sys.exit(1 if failures else 0)
