"""Per-pixel differences between two renders of the same scene, for the tools that compare
renderers and grids (tools/grid_convergence.sh, tools/surface_truth.sh). Reads the EXRs with
oceanref's own Python module (build/python on PYTHONPATH)."""
import numpy as np
import oceanref


def channels(path):
    """Every channel of a render (all parts), by name, as float64 H×W arrays."""
    out = {}
    for part in oceanref.read_exr(path):
        out.update({k: v.astype(np.float64) for k, v in part["channels"].items()})
    return out


def layer(chans, name=""):
    """The H×W×3 R, G, B of a layer of channels(): the radiance, or e.g. "pixel_error"."""
    return np.stack([chans[(name + "." if name else "") + c] for c in "RGB"], axis=2)


def read(path):
    """R, G, B (H×W×3), coverage and view depth (H×W) of a render written with --aov."""
    channels = {}
    for part in oceanref.read_exr(path):
        channels.update(part["channels"])
    rgb = np.stack([channels[c].astype(np.float64) for c in "RGB"], axis=2)
    return rgb, channels["coverage"], channels["depth"].astype(np.float64)


def differences(test, truth):
    """The difference of `test` from `truth` (both as read()): per pixel the largest over R, G, B
    of |c − f|/s, s = max(|f|, 0.01·RMS of f's channel) as `oceanref compare` scales it (so
    near-black pixels do not dominate), at p50 and p99; the relative RMS over the image
    √Σ|c − f|² / √Σ|f|²; the RMS of the relative difference of the view depth over the pixels
    that see the sea in both; the pixels whose sea coverage differs."""
    rgb, coverage, depth = test
    f, f_coverage, f_depth = truth
    diff = np.abs(rgb - f)
    scale = np.maximum(np.abs(f), 0.01 * np.sqrt((f ** 2).mean(axis=(0, 1))))
    per_pixel = (diff / scale).max(axis=2).ravel()
    both = (depth > 0) & (f_depth > 0)
    return {
        "p50": np.percentile(per_pixel, 50),
        "p99": np.percentile(per_pixel, 99),
        "rms": np.sqrt((diff ** 2).sum()) / np.sqrt((f ** 2).sum()),
        "depth_rms": np.sqrt(np.mean(((depth[both] - f_depth[both]) / f_depth[both]) ** 2))
        if both.any() else 0.0,
        "coverage": int((coverage != f_coverage).sum()),
    }
