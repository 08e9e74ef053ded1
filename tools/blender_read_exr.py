"""What Blender reads from an OpenEXR file, checked against OpenImageIO (issue 13).

Two modes, used by tools/blender_check.sh:

  blender -b --factory-startup --python tools/blender_read_exr.py -- FILE OUTDIR
      Inside Blender: load FILE with bpy.data.images.load and write OUTDIR/blender.json (image
      type, size, the layers and passes Blender's compositor offers) plus, for a multilayer
      file, every pass as its own float32 EXR (a compositor Image node per layer, each enabled
      output linked to a File Output node, one compositor-only render), or, for a single-layer
      file, image.pixels (RGBA float32, bottom row first) as OUTDIR/pixels.f32.

  python3 tools/blender_read_exr.py compare FILE OUTDIR [BLENDER_LOG]
      With OpenImageIO's Python module: read every part and channel of FILE, work out where
      Blender should put each channel (the rule below), and check that Blender's output holds
      every channel with bit-identical values (NaN matches NaN; the compositor copies float32
      values without arithmetic, so any difference is an error), at the part's size or, for a
      part smaller than part 0, padded to part 0's size (reported as PADDED, with the corner
      where the values are and what the rest holds).
      Exit 0 when every channel is seen with the right values, 1 otherwise.

Blender 3.4's rule (source/blender/imbuf/intern/openexr/openexr_api.cpp): a file is multilayer
when it has more than one part, has multiView, or a channel name of part 0 contains a dot.
Every channel of every part (part names are ignored) is split from the right at dots: the last
token is the channel id (one character, any letter; or two characters whose second is one of
X Y Z R G B U V A; or red/green/blue/alpha/depth), the token before it the pass, the rest the
layer. A channel whose last token is anything else ("height", "re", "disp_x") is dropped with
"multilayer read: unknown channel token". Every pass buffer has the size of part 0's data
window. Passes of one channel become a Value, of three or four an RGBA/vector whose channels are
placed by letter (R G B A if one of the first three is B, else X Y Z W if one is Y, else U V A);
other channel counts give no compositor data. A single-layer file is read as R, G, B, A only.
"""

import json
import os
import re
import sys


# --------------------------------------------------------------------------- Blender side


def blender_main(path, outdir):
    import bpy
    import numpy as np

    os.makedirs(outdir, exist_ok=True)
    report = {"file": path}
    img = bpy.data.images.load(path, check_existing=False)
    img.pixels[0:1]  # forces the load (multilayer files are parsed here)
    report["type"] = img.type
    report["size"] = list(img.size)
    report["channels"] = img.channels
    report["has_data"] = bool(img.has_data)

    if img.type != "MULTILAYER":
        n = len(img.pixels)
        report["pixels"] = n
        if n:
            arr = np.empty(n, dtype=np.float32)
            img.pixels.foreach_get(arr)
            arr.tofile(os.path.join(outdir, "pixels.f32"))
        write_report(outdir, report)
        return

    scene = bpy.context.scene
    scene.use_nodes = True
    tree = scene.node_tree
    for node in list(tree.nodes):  # no Render Layers node: the scene itself is not rendered
        tree.nodes.remove(node)
    composite = tree.nodes.new("CompositorNodeComposite")
    out = tree.nodes.new("CompositorNodeOutputFile")
    out.base_path = os.path.join(outdir, "")
    out.format.file_format = "OPEN_EXR"
    out.format.color_depth = "32"
    out.format.exr_codec = "ZIP"
    out.file_slots.clear()

    probe = tree.nodes.new("CompositorNodeImage")
    probe.image = img
    report["layers"] = image_node_layers(probe)
    tree.nodes.remove(probe)

    passes = []
    for layer in report["layers"]:
        node = tree.nodes.new("CompositorNodeImage")
        node.image = img
        node.layer = layer
        for socket in node.outputs:
            if not socket.enabled:
                continue
            slot = "p%04d_" % len(passes)
            out.file_slots.new(slot)
            tree.links.new(socket, out.inputs[-1])
            passes.append({"layer": layer, "pass": socket.name, "socket": socket.type,
                           "file": slot + "%04d.exr" % scene.frame_current})
    report["passes"] = passes
    if passes:
        # The Composite node must exist for a render; it gets any pass (its result is unused).
        tree.links.new(out.inputs[0].links[0].from_socket, composite.inputs[0])
        scene.render.resolution_x = max(img.size[0], 4)
        scene.render.resolution_y = max(img.size[1], 4)
        scene.render.resolution_percentage = 100
        bpy.ops.render.render()
    write_report(outdir, report)


def image_node_layers(node):
    """The layers a compositor Image node offers: the dynamic enum's items, read from the error
    Blender raises for a value that is not one of them."""
    try:
        node.layer = "\x01 no such layer"
    except TypeError as error:
        message = str(error)
    else:
        return []
    found = message.split(" not found in ", 1)
    return re.findall(r"'([^']*)'", found[1]) if len(found) == 2 else []


def write_report(outdir, report):
    with open(os.path.join(outdir, "blender.json"), "w") as f:
        json.dump(report, f, indent=1)


# --------------------------------------------------------------------------- comparison side

TWO_LETTER_IDS = "XYZRGBUVA"
WORD_IDS = {"red": "R", "green": "G", "blue": "B", "alpha": "A", "depth": "Z"}


def split_channel(name):
    """Blender 3.4's split of a multilayer channel name: (layer, pass, channel id), or None
    when Blender drops the channel."""
    if len(name) == 1:
        return ("", {"R": "Combined", "G": "Combined", "B": "Combined", "A": "Combined",
                     "Z": "Depth"}.get(name, name), name.upper())
    head, _, token = name.rpartition(".")
    if not head:
        # "depth", "coverage": no layer, no pass token. Blender keeps some of these in a layer
        # without a name, which the compositor's Image node does not offer.
        return ("", name, "")
    if len(token) == 1:
        chan = token.upper()
    elif len(token) == 2 and token[1].upper() in TWO_LETTER_IDS:
        chan = token[1].upper()
    elif token.lower() in WORD_IDS:
        chan = WORD_IDS[token.lower()]
    else:
        return None
    layer, _, pass_name = head.rpartition(".")
    if not pass_name:
        return None
    return (layer, pass_name, chan)


def pass_slots(chan_ids):
    """Where Blender puts the channels of one pass (in file order) in its buffer."""
    if len(chan_ids) in (3, 4):
        first3 = chan_ids[:3]
        if "B" in first3:
            order = "RGBA"
        elif "Y" in first3:
            order = "XYZW"
        else:
            order = "UVA"
        return [order.index(c) if c in order else 0 for c in chan_ids]
    return list(range(len(chan_ids)))


def read_parts(path):
    import OpenImageIO as oiio

    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise SystemExit("OpenImageIO cannot open %s: %s" % (path, oiio.geterror()))
    parts = []
    index = 0
    while inp.seek_subimage(index, 0):
        spec = inp.spec()
        pixels = inp.read_image(index, 0, 0, spec.nchannels, oiio.FLOAT)
        if pixels is None:
            raise SystemExit("OpenImageIO cannot read part %d of %s: %s"
                             % (index, path, inp.geterror()))
        pixels = pixels.reshape(spec.height, spec.width, spec.nchannels)
        parts.append({"index": index, "width": spec.width, "height": spec.height,
                      "x": spec.x, "y": spec.y, "multiview": spec.getattribute("multiView"),
                      "names": list(spec.channelnames), "pixels": pixels})
        index += 1
    inp.close()
    return parts


def same_values(a, b):
    import numpy as np

    return a.shape == b.shape and bool(np.array_equal(a, b, equal_nan=True))


def compare(path, outdir, log_path=None):
    import numpy as np

    parts = read_parts(path)
    with open(os.path.join(outdir, "blender.json")) as f:
        report = json.load(f)
    problems = []
    channels = sum(len(p["names"]) for p in parts)
    multilayer = (len(parts) > 1 or parts[0]["multiview"] is not None
                  or any("." in n for n in parts[0]["names"]))
    print("%s: %d part(s), %d channel(s); Blender: type %s, size %s, layers %s"
          % (path, len(parts), channels, report["type"], report["size"],
             report.get("layers", "-")))
    seen = 0
    padded = []  # channels Blender holds padded to part 0's size, values identical
    if not multilayer:
        if report["type"] == "MULTILAYER":
            problems.append("Blender reads it as MULTILAYER, expected a single-layer image")
        part = parts[0]
        h, w = part["height"], part["width"]
        pix = None
        if report.get("pixels") and report["size"] == [w, h]:
            pix = np.fromfile(os.path.join(outdir, "pixels.f32"), dtype=np.float32)
            pix = pix.reshape(h, w, 4)[::-1]  # Blender's rows run bottom-up
        else:
            problems.append("Blender has no pixels of size %dx%d (size %s)"
                            % (w, h, report["size"]))
        for c, name in enumerate(part["names"]):
            slot = "RGBA".find(name) if len(name) == 1 else -1
            if slot < 0:
                problems.append("channel %s: not read (a single-layer file is read as R, G, "
                                "B, A only)" % name)
            elif pix is not None:
                if same_values(pix[:, :, slot], part["pixels"][:, :, c]):
                    seen += 1
                else:
                    problems.append("channel %s: values differ" % name)
    else:
        if report["type"] != "MULTILAYER":
            problems.append("Blender reads it as %s (has_data %s), expected MULTILAYER"
                            % (report["type"], report["has_data"]))
        part0 = parts[0]
        blender_passes = {(p["layer"], p["pass"]): p for p in report.get("passes", [])}
        # Group the channels into passes the way Blender does (over all parts, file order).
        groups = {}
        for part in parts:
            for c, name in enumerate(part["names"]):
                split = split_channel(name)
                if split is None:
                    problems.append("channel %s (part %d): Blender drops it (unknown channel "
                                    "token %r)" % (name, part["index"], name.rpartition(".")[2]))
                    continue
                layer, pass_name, chan = split
                groups.setdefault((layer, pass_name), []).append((part, c, name, chan))
        for (layer, pass_name), members in groups.items():
            slots = pass_slots([m[3] for m in members])
            got = blender_passes.get((layer, pass_name))
            if got is None:
                for part, c, name, chan in members:
                    problems.append("channel %s: Blender shows no pass %r in layer %r"
                                    % (name, pass_name, layer))
                continue
            pix = read_blender_pass(os.path.join(outdir, got["file"]))
            for (part, c, name, chan), slot in zip(members, slots):
                want = part["pixels"][:, :, c]
                h, w = want.shape
                where = "channel %s (part %d, %dx%d) -> Blender %s.%s" % (
                    name, part["index"], w, h, layer, pass_name)
                if pix is None:
                    problems.append("%s: the compositor gives no data" % where)
                elif pix.shape[:2] != (h, w):
                    block = padded_block(pix, slot, want)
                    if pix.shape[:2] == (part0["height"], part0["width"]) and block:
                        # Blender sizes every pass like part 0: a smaller part arrives padded,
                        # its values bit-identical in one corner block.
                        padded.append("%s: padded to part 0's %dx%d, the values identical in "
                                      "the %s %dx%d block, %s elsewhere"
                                      % (where, pix.shape[1], pix.shape[0], block[0], w, h,
                                         block[1]))
                        seen += 1
                        continue
                    extra = ""
                    if (h, w) != (part0["height"], part0["width"]):
                        extra = " (Blender sizes every pass like part 0, %dx%d)" % (
                            part0["width"], part0["height"])
                    problems.append("%s: Blender's pass is %dx%d%s"
                                    % (where, pix.shape[1], pix.shape[0], extra))
                elif slot >= pix.shape[2] or not same_values(pix[:, :, slot], want):
                    problems.append("%s: values differ" % where)
                else:
                    seen += 1
    if problems and log_path and os.path.exists(log_path):
        with open(log_path, errors="replace") as f:
            notes = sorted({line.strip() for line in f
                            if re.search(r"multilayer read|OpenEXR|can't|cannot|ERROR", line)})
        for line in notes[:12]:
            print("  blender said: %s" % line)
    for p in padded:
        print("  PADDED %s" % p)
    for p in problems:
        print("  FAIL %s" % p)
    print("%s: Blender sees %d of %d channel(s) with identical values%s: %s"
          % (path, seen, channels,
             " (%d of them padded to part 0's size)" % len(padded) if padded else "",
             "OK" if not problems else "FAIL"))
    return 0 if not problems and seen == channels else 1


def padded_block(pix, slot, want):
    """Where a smaller part's values sit in Blender's larger pass (as OpenImageIO reads Blender's
    output: top row first): ("top-left" or "bottom-left", what the rest holds), or None."""
    import numpy as np

    h, w = want.shape
    if slot >= pix.shape[2] or pix.shape[0] < h or pix.shape[1] < w:
        return None
    for corner, rows in (("top-left", slice(0, h)), ("bottom-left", slice(pix.shape[0] - h, None))):
        if same_values(pix[rows, :w, slot], want):
            rest = pix[:, :, slot].copy()
            rest[rows, :w] = 0.0
            return corner, "zeros" if not np.any(rest) else "non-zero values"
    return None


def read_blender_pass(path):
    import OpenImageIO as oiio

    if not os.path.exists(path):
        return None
    inp = oiio.ImageInput.open(path)
    if inp is None:
        return None
    spec = inp.spec()
    pixels = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    inp.close()
    if pixels is None:
        return None
    return pixels.reshape(spec.height, spec.width, spec.nchannels)


if __name__ == "__main__":
    if "--" in sys.argv:  # inside Blender
        args = sys.argv[sys.argv.index("--") + 1:]
        blender_main(args[0], args[1])
    elif len(sys.argv) >= 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3], sys.argv[4] if len(sys.argv) > 4 else None))
    else:
        sys.exit(__doc__)
