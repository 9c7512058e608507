#!/usr/bin/env python3
"""Turns `glint bench` JSON into the tables and plot of docs/PERFORMANCE.md.

    ./glint bench --benchmark_out=bench.json --benchmark_out_format=json
    python3 bench/performance_report.py bench.json --svg docs/performance/primary.svg > tables.md
"""
import argparse
import json
import math
from collections import defaultdict

NAMES = ["list", "bvh", "spheres", "grid", "kd", "bvh2"]
COLOURS = {"list": "#888888", "bvh": "#d62728", "bvh2": "#ff7f0e", "spheres": "#1f77b4", "grid": "#2ca02c", "kd": "#9467bd"}


def load(path):
    # With --benchmark_repetitions, the medians; otherwise the single runs.
    out = {}
    for b in json.load(open(path))["benchmarks"]:
        if b.get("aggregate_name") == "median":
            out[b["run_name"]] = b
        elif b.get("run_type", "iteration") == "iteration":
            out.setdefault(b["run_name"] if "run_name" in b else b["name"], b)
    return out


def ms(b):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    return b["real_time"] * scale


def table(title, header, rows):
    out = [f"**{title}**", "", "| " + " | ".join(header) + " |", "|" + "---:|" * len(header)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out) + "\n"


def per_structure(runs, prefix, value, fmt):
    counts = [100, 1000, 10000, 100000, 1000000]
    rows = []
    for k, name in enumerate(NAMES):
        row = [name]
        for n in counts:
            b = runs.get(f"{prefix}/{k}/{n}")
            row.append(fmt(value(b)) if b else "–")
        rows.append(row)
    return ["structure"] + [f"{n:,}" for n in counts], rows


def svg_plot(runs, path):
    """Time for one 256×256 frame of primary rays (1 thread) against the number of spheres."""
    width, height, left, bottom, top, right = 640, 400, 70, 50, 20, 110
    series = defaultdict(list)
    for k, name in enumerate(NAMES):
        for n in [100, 1000, 10000, 100000, 1000000]:
            b = runs.get(f"PrimaryRays/{k}/{n}")
            if b:
                series[name].append((n, 65536 / b["items_per_second"] * 1e3))
    xs = [math.log10(n) for s in series.values() for n, _ in s]
    ys = [math.log10(t) for s in series.values() for _, t in s]
    x0, x1 = min(xs), max(xs)
    y0, y1 = math.floor(min(ys)), math.ceil(max(ys))
    px = lambda x: left + (math.log10(x) - x0) / (x1 - x0) * (width - left - right)
    py = lambda y: height - bottom - (math.log10(y) - y0) / (y1 - y0) * (height - top - bottom)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">',
             f'<rect width="{width}" height="{height}" fill="white"/>']
    for e in range(int(x0), int(x1) + 1):
        x = px(10 ** e)
        parts.append(f'<line x1="{x}" y1="{top}" x2="{x}" y2="{height - bottom}" stroke="#ddd"/>')
        parts.append(f'<text x="{x}" y="{height - bottom + 16}" text-anchor="middle">10^{e}</text>')
    for e in range(y0, y1 + 1):
        y = py(10 ** e)
        parts.append(f'<line x1="{left}" y1="{y}" x2="{width - right}" y2="{y}" stroke="#ddd"/>')
        parts.append(f'<text x="{left - 6}" y="{y + 4}" text-anchor="end">{10 ** e:g} ms</text>')
    parts.append(f'<text x="{(left + width - right) / 2}" y="{height - 12}" text-anchor="middle">spheres in the scene</text>')
    for i, (name, points) in enumerate(series.items()):
        path_d = " ".join(("M" if j == 0 else "L") + f"{px(n):.1f},{py(t):.1f}" for j, (n, t) in enumerate(points))
        parts.append(f'<path d="{path_d}" fill="none" stroke="{COLOURS[name]}" stroke-width="2"/>')
        for n, t in points:
            parts.append(f'<circle cx="{px(n):.1f}" cy="{py(t):.1f}" r="3" fill="{COLOURS[name]}"/>')
        parts.append(f'<text x="{width - right + 10}" y="{top + 20 + 18 * i}" fill="{COLOURS[name]}">{name}</text>')
    parts.append("</svg>")
    open(path, "w").write("\n".join(parts) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json")
    parser.add_argument("--svg")
    args = parser.parse_args()
    runs = load(args.json)
    header, rows = per_structure(runs, "Build", ms, lambda v: f"{v:.2f}")
    print(table("Build time of the structure alone (ms, 2 cores)", header, rows))
    for kind in ["PrimaryRays", "ShadowRays", "ReflectionRays"]:
        header, rows = per_structure(runs, kind, lambda b: b["items_per_second"], lambda v: f"{v / 1e6:.2f}")
        print(table(f"{kind}: million rays/s, 1 thread", header, rows))
    frame_rows = []
    for n in [1000, 10000, 100000, 1000000]:
        one = runs.get(f"Frame/spheres:{n}/threads:1/real_time")
        two = runs.get(f"Frame/spheres:{n}/threads:2/real_time")
        if one and two:
            frame_rows.append([f"{n:,}", f"{ms(one):.1f}", f"{ms(two):.1f}", f"{ms(one) / (2 * ms(two)) * 100:.0f}%"])
    print(table("Frame 256×256 with shadows and one reflection, BVH (ms)",
                ["spheres", "1 thread", "2 threads", "parallel efficiency"], frame_rows))
    # Peers: glint against Embree on the same rays (bench/accel_bench.cpp, "Peers").
    pairs = [("closest hit, single rays", "GlintClosest", "EmbreeIntersect1"),
             ("camera rays, one at a time", "GlintCameraSingle", "EmbreeCameraIntersect1"),
             ("camera rays, packets (glint 16; Embree rtcIntersect16)", "GlintPackets", "EmbreeIntersect16"),
             ("camera rays, packets (glint 16; Embree rtcIntersect8)", "GlintPackets", "EmbreeIntersect8"),
             ("shadow rays, any hit, single rays", "GlintShadow", "EmbreeOccluded1"),
             ("shadow rays, any hit, glint's packets of 16", "GlintShadowPackets", "EmbreeOccluded1")]
    for scene, balls in [("10⁶-triangle terrain", 0), ("balls-4 (7,381 spheres)", 1)]:
        rows = []
        for what, ours, theirs in pairs:
            for threads, flag in [("1 thread", 0), ("2 threads", 1)]:
                key = f"/balls:{balls}/all:{flag}/real_time"
                g, e = runs.get(ours + key), runs.get(theirs + key)
                if g and e:
                    rows.append([what, threads, f"{g['items_per_second'] / 1e6:.2f}",
                                 f"{e['items_per_second'] / 1e6:.2f}",
                                 f"{e['items_per_second'] / g['items_per_second']:.2f}×"])
        if rows:
            print(table(f"{scene}: glint against Embree, million rays/s",
                        ["rays", "threads", "glint", "Embree", "glint / Embree time"], rows))
    build = runs.get("MeshBuild")
    if build:
        print(f"BVH build over the terrain's triangles: {ms(build):.0f} ms ({build.get('label', '')}).\n")
    if args.svg:
        svg_plot(runs, args.svg)


if __name__ == "__main__":
    main()
