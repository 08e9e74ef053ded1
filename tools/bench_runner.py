#!/usr/bin/python3
"""Times oceanref's working tree against a baseline build; run by tools/bench.sh.

Every figure is the wall time of a whole process (fork to exit, time.perf_counter) and its
peak resident set (os.wait4's ru_maxrss of that child alone), N runs per command, the commands
of one case alternating run by run (A B A B ..., so slow drift of the machine's load reaches
both alike). Medians, minima and maxima; ratios are ratios of medians. Writes OUT/bench.json
(everything, every run), OUT/bench.md (the tables, also printed on stdout) and OUT/bench.svg.
Standard library only.
"""

import argparse
import datetime
import json
import math
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

RENDER_THREADS = 2  # the setting for the fast render and the reference/fast ratio
SPP = 4

FULL = {"runs": 5, "fast": (1280, 720), "reference": (320, 180)}
QUICK = {"runs": 3, "fast": (640, 360), "reference": (96, 54)}

STARTED = time.monotonic()


def log(message):
    elapsed = int(time.monotonic() - STARTED + ARGS.elapsed_offset)
    print(f"[bench {elapsed:4d}s] {message}", file=sys.stderr, flush=True)


def fmt_s(seconds):
    if seconds >= 100:
        return f"{seconds:.0f} s"
    if seconds >= 10:
        return f"{seconds:.1f} s"
    return f"{seconds:.2f} s"


def fmt_ms(ms):
    return f"{ms:.1f} ms" if ms < 100 else f"{ms:.0f} ms"


def fmt_duration(seconds):
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds} s"
    return f"{seconds // 60} min {seconds % 60:02d} s"


def mib(n_bytes):
    return n_bytes / (1024 * 1024)


# ---------------------------------------------------------------------------------------------
# Running one command


def run_once(argv, work_dir):
    """Runs argv in work_dir; returns wall time, CPU time, peak RSS (bytes) and stdout."""
    out_path = work_dir / "stdout.txt"
    err_path = work_dir / "stderr.txt"
    with open(out_path, "wb") as out, open(err_path, "wb") as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen(argv, cwd=work_dir, stdin=subprocess.DEVNULL, stdout=out, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.stderr.write(err_path.read_text(errors="replace")[-4000:])
        how = (f"was killed by signal {-proc.returncode}" if proc.returncode < 0
               else f"exited {proc.returncode}")
        raise SystemExit(f"bench: `{' '.join(map(str, argv))}` {how}")
    return {
        "wall_s": wall,
        "cpu_s": usage.ru_utime + usage.ru_stime,
        "max_rss_bytes": usage.ru_maxrss * 1024,  # Linux: kilobytes
    }, out_path.read_text(errors="replace")


def summary(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values)}


# The parallelism (CPU time / wall time) of the bench's last run: the 1-minute load average seen
# before a run includes the bench's own previous runs (a 2-thread render keeps 2 cores busy), so
# the load of other work is the load average minus that. None before the first run (the builds'
# load is still in the average then).
LAST_PARALLELISM = [None]


def run_case(case, runs):
    """Runs every variant of case `runs` times, alternating; fills case['variants'][*]['runs']."""
    variants = case["variants"]
    names = list(variants)
    total = runs * len(names)
    done = 0
    case_start = time.monotonic()
    for i in range(runs):
        for name in names:
            v = variants[name]
            work = Path(v["work_dir"])
            for f in v.get("outputs", []):
                (work / f).unlink(missing_ok=True)
            load = os.getloadavg()[0]
            record, stdout = run_once(v["argv"], work)
            record["load_average_1min_before"] = load
            if LAST_PARALLELISM[0] is not None:
                record["other_load_before"] = max(0.0, load - LAST_PARALLELISM[0])
            LAST_PARALLELISM[0] = record["cpu_s"] / record["wall_s"] if record["wall_s"] > 0 else 0.0
            if v.get("parse"):
                record.update(v["parse"](stdout))
            if i == 0:
                v["stdout_first_run"] = stdout.splitlines()[:12]
            v["runs"].append(record)
            done += 1
            spent = time.monotonic() - case_start
            eta = spent / done * (total - done)
            extra = ""
            if "frame_ms" in record:
                extra = f", frame {fmt_ms(record['frame_ms'])}"
            log(f"{case['short']}: {name} run {i + 1}/{runs}: {fmt_s(record['wall_s'])}{extra}, "
                f"CPU {fmt_s(record['cpu_s'])}, peak {mib(record['max_rss_bytes']):.0f} MiB, load {load:.1f} "
                f"(case ETA {fmt_duration(eta)})")
    for v in variants.values():
        v["wall_s"] = summary([r["wall_s"] for r in v["runs"]])
        v["cpu_s"] = summary([r["cpu_s"] for r in v["runs"]])
        v["max_rss_bytes"] = max(r["max_rss_bytes"] for r in v["runs"])
        if v.get("pixels"):
            v["bytes_per_pixel"] = v["max_rss_bytes"] / v["pixels"]
        if "frame_ms" in v["runs"][0]:
            v["frame_ms"] = summary([r["frame_ms"] for r in v["runs"]])
        v.pop("parse", None)


def parse_bench_synthesis(stdout):
    """The KissFFT row of `oceanref bench synthesis`: the median frame time of 20 frames."""
    lines = stdout.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("fft,frame_ms_median"):
            columns = line.split(",")
            for row in lines[i + 1:]:
                cells = row.split(",")
                if cells[0] == "kissfft":
                    return {"frame_ms": float(cells[columns.index("frame_ms_median")])}
    raise SystemExit("bench: `oceanref bench synthesis` printed no kissfft,frame_ms_median row")


# ---------------------------------------------------------------------------------------------
# Scenes


def git(*args, check=True):
    result = subprocess.run(["git", *args], capture_output=True, text=True, check=False)
    if check and result.returncode != 0:
        raise SystemExit(f"bench: git {' '.join(args)}: {result.stderr.strip()}")
    return result.stdout.strip() if result.returncode == 0 else None


def knows_accuracy(scene, schema_text):
    """Whether a revision has shading.accuracy (reference vs fast lighting)."""
    if "accuracy" in scene.get("shading", {}):
        return True
    if schema_text:
        try:
            schema = json.loads(schema_text)
            return "accuracy" in schema["properties"]["shading"]["properties"]
        except (ValueError, KeyError):
            return False
    return False


def render_scene(base, accuracy, width, height):
    """The default scene at the given size and SPP; accuracy None leaves the lighting as is
    (a revision without shading.accuracy, whose fixed-order rules are its fast mode)."""
    scene = json.loads(json.dumps(base))
    shading = scene.setdefault("shading", {})
    if accuracy == "fast":
        shading["accuracy"] = "fast"
        shading.pop("tolerance", None)
    elif accuracy == "reference":
        shading["accuracy"] = "reference"
        shading.pop("sky_order", None)
        shading.pop("sun_order", None)
    render = scene.setdefault("render", {})
    render["width"], render["height"], render["samples_per_pixel"] = width, height, SPP
    return scene


def write_json(path, value):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(value, indent=2) + "\n")
    return path


# ---------------------------------------------------------------------------------------------
# Machine and builds


def machine_info():
    info = {"cores": os.cpu_count(), "kernel": platform.release(), "arch": platform.machine()}
    model = None
    if shutil.which("lscpu"):
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=False).stdout
        for line in out.splitlines():
            key, _, value = line.partition(":")
            if key.strip() == "Model name" and model is None:
                model = value.strip()
            if key.strip() == "Core(s) per socket":
                info["cores_per_socket"] = int(value.strip())
            if key.strip() == "Thread(s) per core":
                info["threads_per_core"] = int(value.strip())
    if model is None and Path("/proc/cpuinfo").exists():
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.partition(":")[2].strip()
                break
    info["cpu_model"] = model or "unknown"
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal:"):
                info["memory_bytes"] = int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        for line in Path("/etc/os-release").read_text().splitlines():
            if line.startswith("PRETTY_NAME="):
                info["os"] = line.partition("=")[2].strip('"')
    except OSError:
        pass
    return info


def build_info(binary):
    """Compiler and flags from the build's CMakeCache.txt, and `oceanref --version` if it has it."""
    build_dir = Path(binary).resolve().parent.parent
    cache = {}
    cache_file = build_dir / "CMakeCache.txt"
    if cache_file.exists():
        for line in cache_file.read_text(errors="replace").splitlines():
            m = re.match(r"^([A-Za-z0-9_]+):[A-Z]+=(.*)$", line)
            if m:
                cache[m.group(1)] = m.group(2)
    info = {"binary": str(binary), "build_dir": str(build_dir),
            "build_type": cache.get("CMAKE_BUILD_TYPE"), "cxx_flags": None}
    # The flags that reached the compiler (a revision may set CMAKE_CXX_FLAGS_RELEASE in its
    # CMakeLists, which the cache does not show): the renderer's compile command.
    commands_file = build_dir / "compile_commands.json"
    if commands_file.exists():
        commands = json.loads(commands_file.read_text())
        chosen = next((c for c in commands if c["file"].endswith("raster/renderer.cpp")),
                      next((c for c in commands if "/src/" in c["file"]), None))
        if chosen:
            words = chosen["command"].split()
            keep = [w for w in words[1:] if re.match(r"^-(O|f|m|g$|DNDEBUG|std=)", w)]
            info["cxx_flags"] = " ".join(keep)
            info["flags_of"] = chosen["file"]
    compiler = cache.get("CMAKE_CXX_COMPILER")
    if compiler:
        out = subprocess.run([compiler, "--version"], capture_output=True, text=True, check=False)
        info["compiler"] = out.stdout.splitlines()[0] if out.stdout else compiler
    version = subprocess.run([str(binary), "--version"], capture_output=True, text=True,
                             check=False)
    info["version"] = version.stdout.strip() if version.returncode == 0 else None
    return info


# ---------------------------------------------------------------------------------------------
# Report


def spread(s, unit=fmt_s):
    return f"{unit(s['median'])} [{unit(s['min'])} – {unit(s['max'])}]"


def ratio_text(r):
    if r <= 0:
        return "—"
    if r < 1:
        return f"{r:.3f} ({1 / r:.2f}× faster)"
    return f"{r:.3f} ({r:.2f}× slower)"


def flags(revision):
    value = revision["build"].get("cxx_flags")
    return f"`{value}`" if value else "flags unknown"


def markdown(result):
    m = result["machine"]
    cur, base = result["current"], result["baseline"]
    load = result["load_average"]
    lines = []
    lines.append(f"Measured {result['date']} with `tools/bench.sh{' --quick' if result['settings']['quick'] else ''}` "
                 f"on {m['cpu_model']}, {m['cores']} cores, {mib(m.get('memory_bytes', 0)) / 1024:.0f} GiB, "
                 f"Linux {m['kernel']}, {cur['build'].get('compiler', '?')}; load average "
                 f"{load['start'][0]:.2f} at the start, {load['end'][0]:.2f} at the end.")
    lines.append(f"Baseline `{base['rev']}` = {base['sha'][:12]} ({base['build'].get('build_type')}, "
                 f"{flags(base)}); current = {cur['describe']} "
                 f"({cur['build'].get('build_type')}, {flags(cur)}). "
                 f"Wall time of the whole process, median [min – max] of {result['settings']['runs']} runs, "
                 f"the commands of each row alternating run by run; ratio = current/baseline of the medians "
                 f"(CPU time: user + system of the process, all its threads).")
    runs_ = [r for case in result["cases"] for v in case["variants"].values() for r in v["runs"]]
    if any("other_load_before" in r for r in runs_):
        # The load beyond the bench's own processes (see LAST_PARALLELISM).
        busiest = max(r.get("other_load_before", 0.0) for r in runs_)
        what = "1-minute load average beyond the bench's own processes"
    else:  # a bench.json from before that field: the raw load average
        busiest = max([load["start"][0], load["end"][0]] +
                      [r.get("load_average_1min_before", 0) for r in runs_])
        what = "1-minute load average"
    if busiest > 0.5 * m["cores"]:
        lines.append("")
        lines.append(f"**The machine was busy** ({what} up to {busiest:.1f} on "
                     f"{m['cores']} cores, other work beside the bench): wall times, their ratios and the "
                     f"thread scaling are spoilt by it; the CPU-time ratios less so. Quote a run on an "
                     f"idle machine.")
    else:
        lines.append("")
        lines.append(f"The machine was otherwise idle ({what}: at most {busiest:.1f} on "
                     f"{m['cores']} cores).")
    lines.append("")
    lines.append("| case | baseline | current | current/baseline | CPU time current/baseline | goal |")
    lines.append("|---|---|---|---|---|---|")
    for case in result["cases"]:
        if case["kind"] != "versus":
            continue
        b, c = case["variants"]["baseline"], case["variants"]["current"]
        if "frame_ms" in c:
            bs, cs = spread(b["frame_ms"], fmt_ms), spread(c["frame_ms"], fmt_ms)
        else:
            bs, cs = spread(b["wall_s"]), spread(c["wall_s"])
        # The in-process frame timer has no CPU time of its own (the process does more).
        cpu = "—" if "frame_ms" in c else f"{c['cpu_s']['median'] / b['cpu_s']['median']:.3f}"
        lines.append(f"| {case['title']} | {bs} | {cs} | {ratio_text(case['ratio'])} | "
                     f"{cpu} | {case.get('goal_text', '—')} |")
    ref = next((c for c in result["cases"] if c["kind"] == "reference"), None)
    if ref:
        lines.append("")
        lines.append(f"| {ref['title']} | fast | reference | reference/fast | goal |")
        lines.append("|---|---|---|---|---|")
        for name in ("current", "baseline"):
            if name not in ref["ratios"]:
                continue
            f, r = ref["variants"][f"{name} fast"], ref["variants"][f"{name} reference"]
            lines.append(f"| {name} | {spread(f['wall_s'])} | {spread(r['wall_s'])} | "
                         f"{ref['ratios'][name]:.1f} | {ref.get('goal_text', '—')} |")
    scaling = next((c for c in result["cases"] if c["kind"] == "scaling"), None)
    if scaling:
        lines.append("")
        lines.append(f"| {scaling['title']}: threads | wall | CPU | speedup over 1 thread | goal |")
        lines.append("|---|---|---|---|---|")
        for name, v in scaling["variants"].items():
            t = v["threads"]
            goal = scaling.get("goal_text", "—") if t == 2 else ""
            lines.append(f"| {t} | {spread(v['wall_s'])} | {fmt_s(v['cpu_s']['median'])} | "
                         f"{scaling['speedup'][name]:.2f}× | {goal} |")
    lines.append("")
    lines.append("| peak RSS (largest of the runs) | baseline | current | current bytes/pixel |")
    lines.append("|---|---|---|---|")
    for case in result["cases"]:
        if case["kind"] == "scaling":
            continue
        roles = {}
        for v in case["variants"].values():
            roles.setdefault(v["role"], {})[v["binary"]] = v
        for role, by_rev in roles.items():
            cells = [f"{mib(by_rev[r]['max_rss_bytes']):.0f} MiB" if r in by_rev else "—"
                     for r in ("baseline", "current")]
            c = by_rev.get("current", {})
            bpp = f"{c['bytes_per_pixel']:.0f}" if "bytes_per_pixel" in c else "—"
            lines.append(f"| {role} | {cells[0]} | {cells[1]} | {bpp} |")
    lines.append("")
    return "\n".join(lines)


def svg_escape(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def svg(result):
    """Two panels: time ratios (log scale, with the goals) and thread scaling."""
    width, height = 900, 420
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
             f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">',
             f'<rect width="{width}" height="{height}" fill="white"/>']
    m = result["machine"]
    title = (f"oceanref bench {result['date'][:10]}: {result['current']['describe']} vs "
             f"{result['baseline']['rev']} ({m['cpu_model']}, {m['cores']} cores)")
    parts.append(f'<text x="{width / 2}" y="20" text-anchor="middle" font-size="14">'
                 f'{svg_escape(title)}</text>')

    # Left panel: ratios on a log axis from 1/8 to 64.
    bars = []
    for case in result["cases"]:
        if case["kind"] == "versus":
            b, c = case["variants"]["baseline"], case["variants"]["current"]
            key = "frame_ms" if "frame_ms" in c else "wall_s"
            lo, hi = c[key]["min"] / b[key]["max"], c[key]["max"] / b[key]["min"]
            bars.append((case["short"], "current/baseline", case["ratio"], lo, hi, case.get("goal")))
        elif case["kind"] == "reference":
            for name, r in case["ratios"].items():
                f, rr = case["variants"][f"{name} fast"], case["variants"][f"{name} reference"]
                lo = rr["wall_s"]["min"] / f["wall_s"]["max"]
                hi = rr["wall_s"]["max"] / f["wall_s"]["min"]
                bars.append((f"{name} {case['short']}", "reference/fast", r, lo, hi, case.get("goal")))
    x0, x1, y0, y1 = 70, 470, 50, 340
    values = [v for bar in bars for v in bar[2:5]] + [bar[5] for bar in bars if bar[5]]
    lmin = math.log(2) * min(-3, math.floor(math.log2(min(values))))
    lmax = math.log(2) * max(3, math.ceil(math.log2(max(values))))

    def ypos(v):
        v = min(max(v, math.exp(lmin)), math.exp(lmax))
        return y1 - (math.log(v) - lmin) / (lmax - lmin) * (y1 - y0)

    parts.append(f'<text x="{(x0 + x1) / 2}" y="40" text-anchor="middle">time ratio (log scale; '
                 f'lines: goals; whiskers: min/max over max/min)</text>')
    for e in range(round(lmin / math.log(2)), round(lmax / math.log(2)) + 1):
        tick = 2.0 ** e
        y = ypos(tick)
        parts.append(f'<line x1="{x0}" x2="{x1}" y1="{y:.1f}" y2="{y:.1f}" stroke="#ddd"/>')
        label = f"{tick:g}" if tick >= 1 else f"1/{1 / tick:g}"
        parts.append(f'<text x="{x0 - 6}" y="{y + 4:.1f}" text-anchor="end">{label}</text>')
    y = ypos(1)
    parts.append(f'<line x1="{x0}" x2="{x1}" y1="{y:.1f}" y2="{y:.1f}" stroke="black"/>')
    slot = (x1 - x0) / max(len(bars), 1)
    for i, (label, sublabel, r, lo, hi, goal) in enumerate(bars):
        cx = x0 + slot * (i + 0.5)
        w = slot * 0.5
        top, base_y = min(ypos(r), ypos(1)), max(ypos(r), ypos(1))
        colour = "#4a7ab5" if r <= 1 else "#c0504d"
        parts.append(f'<rect x="{cx - w / 2:.1f}" y="{top:.1f}" width="{w:.1f}" '
                     f'height="{max(base_y - top, 1):.1f}" fill="{colour}"/>')
        parts.append(f'<line x1="{cx:.1f}" x2="{cx:.1f}" y1="{ypos(lo):.1f}" y2="{ypos(hi):.1f}" '
                     f'stroke="black"/>')
        if goal:
            gy = ypos(goal)
            parts.append(f'<line x1="{cx - w * 0.8:.1f}" x2="{cx + w * 0.8:.1f}" y1="{gy:.1f}" '
                         f'y2="{gy:.1f}" stroke="#2a9d3a" stroke-width="2" stroke-dasharray="5,3"/>')
        parts.append(f'<text x="{cx + w / 2 + 3:.1f}" y="{ypos(r) + 4:.1f}">{r:.2f}</text>')
        parts.append(f'<text x="{cx:.1f}" y="{y1 + 16}" text-anchor="middle" font-size="11">'
                     f'{svg_escape(label)}<tspan x="{cx:.1f}" dy="13" font-size="9" fill="#555">'
                     f'{svg_escape(sublabel)}</tspan></text>')

    # Right panel: speedup over one thread against threads.
    scaling = next((c for c in result["cases"] if c["kind"] == "scaling"), None)
    if scaling:
        sx0, sx1, sy0, sy1 = 560, 870, 50, 340
        points = sorted((v["threads"], scaling["speedup"][n]) for n, v in scaling["variants"].items())
        tmax = max(t for t, _ in points)
        smax = max(tmax, max(s for _, s in points), 2) * 1.1
        parts.append(f'<text x="{(sx0 + sx1) / 2}" y="40" text-anchor="middle">'
                     f'{svg_escape(scaling["title"])}: speedup over 1 thread</text>')

        def sx(t):
            return sx0 + (t - 1) / max(tmax - 1, 1) * (sx1 - sx0)

        def sy(s):
            return sy1 - s / smax * (sy1 - sy0)

        for k in range(0, int(smax) + 1):
            parts.append(f'<line x1="{sx0}" x2="{sx1}" y1="{sy(k):.1f}" y2="{sy(k):.1f}" stroke="#ddd"/>')
            parts.append(f'<text x="{sx0 - 6}" y="{sy(k) + 4:.1f}" text-anchor="end">{k}</text>')
        for t, _ in points:
            parts.append(f'<text x="{sx(t):.1f}" y="{sy1 + 16}" text-anchor="middle">{t}</text>')
        parts.append(f'<text x="{(sx0 + sx1) / 2}" y="{sy1 + 32}" text-anchor="middle">threads</text>')
        parts.append(f'<line x1="{sx(1):.1f}" y1="{sy(1):.1f}" x2="{sx(tmax):.1f}" y2="{sy(tmax):.1f}" '
                     f'stroke="#999" stroke-dasharray="4,3"/>')
        parts.append(f'<text x="{sx(tmax) - 4:.1f}" y="{sy(tmax) - 6:.1f}" text-anchor="end" '
                     f'fill="#999">ideal</text>')
        if tmax >= 2 and scaling.get("goal"):
            parts.append(f'<circle cx="{sx(2):.1f}" cy="{sy(scaling["goal"]):.1f}" r="6" fill="none" '
                         f'stroke="#2a9d3a" stroke-width="2"/>')
            parts.append(f'<text x="{sx(2) - 10:.1f}" y="{sy(scaling["goal"]) + 4:.1f}" text-anchor="end" '
                         f'fill="#2a9d3a">goal {scaling["goal"]}×</text>')
        path = " ".join(f"{'M' if i == 0 else 'L'}{sx(t):.1f},{sy(s):.1f}" for i, (t, s) in enumerate(points))
        parts.append(f'<path d="{path}" fill="none" stroke="#4a7ab5" stroke-width="2"/>')
        for t, s in points:
            parts.append(f'<circle cx="{sx(t):.1f}" cy="{sy(s):.1f}" r="3.5" fill="#4a7ab5"/>')
            anchor = "end" if t == tmax and tmax > 1 else "start"
            dx = -6 if anchor == "end" else 6
            parts.append(f'<text x="{sx(t) + dx:.1f}" y="{sy(s) + 16:.1f}" text-anchor="{anchor}">'
                         f'{s:.2f}×</text>')
    note = ("bars: current/baseline of median wall times (below 1: faster); ref/fast: reference "
            "mode over fast mode; green: the goals of issue 16")
    parts.append(f'<text x="10" y="{height - 10}" font-size="10" fill="#555">{svg_escape(note)}</text>')
    parts.append("</svg>")
    return "\n".join(parts) + "\n"


# ---------------------------------------------------------------------------------------------


def main():
    global ARGS
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--baseline-bin")
    p.add_argument("--current-bin")
    p.add_argument("--baseline-scenes", help="the baseline's reference/scenes copy")
    p.add_argument("--current-scenes")
    p.add_argument("--baseline-rev")
    p.add_argument("--baseline-sha")
    p.add_argument("--work", help="scratch directory (scenes, outputs)")
    p.add_argument("--out", required=True)
    p.add_argument("--report", metavar="BENCH_JSON",
                   help="only write bench.md and bench.svg into --out from an earlier bench.json")
    p.add_argument("--runs", type=int)
    p.add_argument("--threads", help="thread counts of the scaling case (default 1,2,nproc)")
    p.add_argument("--reference-size", help="WxH of the reference/fast case")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--elapsed-offset", type=float, default=0.0)
    ARGS = p.parse_args()
    if ARGS.report:
        write_report(json.loads(Path(ARGS.report).read_text()), Path(ARGS.out).resolve(), False)
        return
    missing = [a for a in ("baseline_bin", "current_bin", "baseline_scenes", "current_scenes",
                           "baseline_rev", "baseline_sha", "work") if getattr(ARGS, a) is None]
    if missing:
        p.error("missing " + ", ".join("--" + a.replace("_", "-") for a in missing))

    preset = QUICK if ARGS.quick else FULL
    runs = ARGS.runs or preset["runs"]
    nproc = os.cpu_count() or 1
    if ARGS.threads:
        thread_counts = sorted({1} | {int(t) for t in ARGS.threads.split(",")})
    else:
        thread_counts = sorted({1, 2, nproc})
    fast_w, fast_h = preset["fast"]
    ref_w, ref_h = preset["reference"]
    if ARGS.reference_size:
        m = re.fullmatch(r"([1-9][0-9]*)x([1-9][0-9]*)", ARGS.reference_size)
        if not m:
            raise SystemExit(f"bench: --reference-size: expected WxH, got '{ARGS.reference_size}'")
        ref_w, ref_h = int(m.group(1)), int(m.group(2))

    bins = {"baseline": Path(ARGS.baseline_bin).resolve(), "current": Path(ARGS.current_bin).resolve()}
    scene_dirs = {"baseline": Path(ARGS.baseline_scenes), "current": Path(ARGS.current_scenes)}
    schema_text = {
        "baseline": git("show", f"{ARGS.baseline_sha}:reference/scene.schema.json", check=False),
        "current": (Path("reference/scene.schema.json").read_text()
                    if Path("reference/scene.schema.json").exists() else None),
    }
    work = Path(ARGS.work).resolve()
    out_dir = Path(ARGS.out).resolve()
    work.mkdir(parents=True, exist_ok=True)
    out_dir.mkdir(parents=True, exist_ok=True)

    head = git("rev-parse", "HEAD")
    dirty = bool(git("status", "--porcelain", "--untracked-files=no", check=False))
    result = {
        "schema": "oceanref-bench/1",
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "machine": machine_info(),
        "load_average": {"start": list(os.getloadavg())},
        "baseline": {"rev": ARGS.baseline_rev, "sha": ARGS.baseline_sha,
                     "build": build_info(bins["baseline"])},
        "current": {"sha": head, "dirty": dirty,
                    "describe": f"{head[:12]}{' + uncommitted changes' if dirty else ''}",
                    "build": build_info(bins["current"])},
        "settings": {"runs": runs, "quick": ARGS.quick, "render_threads": RENDER_THREADS,
                     "spp": SPP, "fast_size": [fast_w, fast_h], "reference_size": [ref_w, ref_h],
                     "scaling_threads": thread_counts,
                     "method": "wall time of the whole process (fork to exit), peak RSS by "
                               "wait4 ru_maxrss of that process; commands of a case alternate "
                               "run by run; ratios of medians"},
        "cases": [],
    }
    log(f"{runs} runs per command; machine: {result['machine']['cpu_model']}, "
        f"{result['machine']['cores']} cores, load {os.getloadavg()[0]:.2f}")

    base_scene = {name: json.loads((scene_dirs[name] / "default.json").read_text()) for name in bins}
    has_accuracy = {name: knows_accuracy(base_scene[name], schema_text[name]) for name in bins}
    if not has_accuracy["current"]:
        raise SystemExit("bench: the working tree's scenes have no shading.accuracy")

    def variant(name, role, argv, tag, pixels=None, outputs=(), parse=None, **extra):
        d = work / tag
        d.mkdir(parents=True, exist_ok=True)
        v = {"binary": name, "role": role, "argv": [str(a) for a in argv], "work_dir": str(d),
             "outputs": list(outputs), "runs": [], **extra}
        if pixels:
            v["pixels"] = pixels
        if parse:
            v["parse"] = parse
        return v

    def fast_render(name, w, h, threads, tag):
        scene = render_scene(base_scene[name], "fast" if has_accuracy[name] else None, w, h)
        path = write_json(work / tag / "scene.json", scene)
        role = f"fast render {w}×{h}, {SPP} spp, {threads} threads"
        return variant(name, role, [bins[name], "render", path, "-o", "out.exr", "--threads", threads],
                       tag, pixels=w * h, outputs=["out.exr"], scene=scene, threads=threads)

    # 1. Synthesis: `fields` (whole process) and bench synthesis's in-process KissFFT frame.
    cases = result["cases"]
    cases.append({"id": "synthesis_fields", "kind": "versus", "short": "fields",
                  "title": f"synthesis: `oceanref fields waves_default.json -o X.exr --threads {RENDER_THREADS}`",
                  "variants": {name: variant(name, "`fields waves_default.json`", [bins[name], "fields",
                                                    scene_dirs[name] / "waves_default.json", "-o",
                                                    "fields.exr", "--threads", RENDER_THREADS],
                                             f"{name}-fields", outputs=["fields.exr"])
                               for name in bins}})
    cases.append({"id": "synthesis_frame", "kind": "versus", "short": "synth frame",
                  "title": f"synthesis frame: `oceanref bench synthesis --threads {RENDER_THREADS}`, "
                           "its KissFFT median of 20 frames (in-process timer)",
                  "variants": {name: variant(name, "`bench synthesis`", [bins[name], "bench", "synthesis", "--threads",
                                                    RENDER_THREADS],
                                             f"{name}-synthesis", parse=parse_bench_synthesis)
                               for name in bins}})
    # 2. The fast render of each revision's default scene.
    cases.append({"id": "fast_render", "kind": "versus", "short": "fast render",
                  "title": f"fast render: default scene {fast_w}×{fast_h}, {SPP} spp, {RENDER_THREADS} threads",
                  "goal": 0.25, "goal_text": "≥ 4× faster (issue 16, at 1280×720)",
                  "variants": {name: fast_render(name, fast_w, fast_h, RENDER_THREADS, f"{name}-fast")
                               for name in bins}})
    # 3. Reference vs fast mode at a size the reference finishes in.
    ref_variants = {}
    for name in ("current", "baseline"):
        if not has_accuracy[name]:
            continue
        ref_variants[f"{name} fast"] = fast_render(name, ref_w, ref_h, RENDER_THREADS, f"{name}-small-fast")
        scene = render_scene(base_scene[name], "reference", ref_w, ref_h)
        path = write_json(work / f"{name}-reference" / "scene.json", scene)
        ref_variants[f"{name} reference"] = variant(
            name, f"reference render {ref_w}×{ref_h}, {SPP} spp, {RENDER_THREADS} threads", [bins[name], "render", path, "-o", "out.exr", "--threads", RENDER_THREADS],
            f"{name}-reference", pixels=ref_w * ref_h, outputs=["out.exr"], scene=scene,
            threads=RENDER_THREADS)
    cases.append({"id": "reference_vs_fast", "kind": "reference", "short": "ref/fast",
                  "title": f"default scene {ref_w}×{ref_h}, {SPP} spp, {RENDER_THREADS} threads",
                  "goal": 3.0, "goal_text": "≤ 3 (issue 16)", "variants": ref_variants})
    # 4. Thread scaling of the current fast render.
    cases.append({"id": "thread_scaling", "kind": "scaling", "short": "scaling",
                  "title": f"current fast render {fast_w}×{fast_h}, {SPP} spp",
                  "goal": 1.85, "goal_text": "≥ 1.85× on 2 cores (issue 16)",
                  "variants": {f"{t} thread{'s' if t > 1 else ''}": fast_render("current", fast_w, fast_h, t, f"scaling-{t}")
                               for t in thread_counts}})
    if not has_accuracy["baseline"]:
        log("the baseline has no shading.accuracy: its default scene's fixed-order lighting is its "
            "fast mode, and it has no reference mode to time")

    for case in cases:
        log(f"case: {case['title']}")
        run_case(case, runs)
        if case["kind"] == "versus":
            b, c = case["variants"]["baseline"], case["variants"]["current"]
            key = "frame_ms" if "frame_ms" in c else "wall_s"
            case["ratio"] = c[key]["median"] / b[key]["median"]
        elif case["kind"] == "reference":
            case["ratios"] = {name: case["variants"][f"{name} reference"]["wall_s"]["median"]
                              / case["variants"][f"{name} fast"]["wall_s"]["median"]
                              for name in ("current", "baseline") if f"{name} fast" in case["variants"]}
        elif case["kind"] == "scaling":
            one = next(v for v in case["variants"].values() if v["threads"] == 1)
            case["speedup"] = {n: one["wall_s"]["median"] / v["wall_s"]["median"]
                               for n, v in case["variants"].items()}
    result["load_average"]["end"] = list(os.getloadavg())
    result["elapsed_s"] = time.monotonic() - STARTED + ARGS.elapsed_offset

    write_report(result, out_dir, True)
    log(f"wrote {out_dir}/bench.json, bench.md, bench.svg (whole run {fmt_duration(result['elapsed_s'])})")


def write_report(result, out_dir, with_json):
    out_dir.mkdir(parents=True, exist_ok=True)
    table = markdown(result)
    if with_json:
        write_json(out_dir / "bench.json", result)
    (out_dir / "bench.md").write_text(table)
    (out_dir / "bench.svg").write_text(svg(result))
    print(table, end="")


ARGS = None

if __name__ == "__main__":
    main()
