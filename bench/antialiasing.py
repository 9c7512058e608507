#!/usr/bin/env python3
"""Adaptive antialiasing against the uniform grid it stands for (docs/ANTIALIASING.md).

For each scene, side by side in one run (alternately, `--runs` times, medians kept): hybrid
uniform NxN, hybrid adaptive NxN and ray adaptive NxN, all with glint's defaults otherwise.
Prints, per scene, the render times and their ratio to uniform, the pixels adaptive refined,
and the share of pixels within 2/255 of the uniform image, as a markdown table.

    python3 bench/antialiasing.py --size 1920x1080 --samples 4
    python3 bench/antialiasing.py --pictures docs/antialiasing

With --pictures DIR it renders scenes/default.json at 800x600 instead, with one sample, adaptive
4x4 and uniform 4x4, and writes a crop of an edge from each (enlarged 4x, nearest neighbour),
the adaptive render's map of refined pixels (--aa-map), and that map's crop.

Default scenes: every shipped scene and SPD's balls-4, lattice-4 and tree-11 (scenes/spd).
Needs a built glint (`./glint build`).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from povray_compare import read_png, write_png  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPD = os.path.join(ROOT, "scenes", "spd")


def default_scenes():
    shipped = ["default", "mirrors", "transforms", "shadows", "primitives", "instances", "whitted",
               "glass"]
    scenes = [os.path.join(ROOT, "scenes", name + ".json") for name in shipped]
    return scenes + [os.path.join(SPD, name + ".nff") for name in ("balls-4", "lattice-4", "tree-11")]


def render(glint, scene, out, size, samples, aa, mode, threshold):
    stats = out + ".json"
    command = [glint, "render", scene, "-o", out, "--size", size, "--samples", str(samples),
               "--aa", aa, "--mode", mode, "--stats", stats]
    if threshold is not None:
        command += ["--aa-threshold", str(threshold)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(stats) as f:
        s = json.load(f)
    return s["seconds"]["total"], s.get("refined_pixels")


def within(a, b, limit=2):
    """Share of pixels whose every channel is within `limit`/255."""
    (w, h, x), (_, _, y) = read_png(a), read_png(b)
    good = sum(1 for p in range(0, len(x), 3)
               if max(abs(x[p] - y[p]), abs(x[p + 1] - y[p + 1]), abs(x[p + 2] - y[p + 2])) <= limit)
    return good / (w * h)


def crop(path, out, x0, y0, w, h, scale):
    width, _, rgb = read_png(path)
    pixels = bytearray()
    for y in range(h * scale):
        for x in range(w * scale):
            p = 3 * ((y0 + y // scale) * width + x0 + x // scale)
            pixels += rgb[p:p + 3]
    write_png(out, w * scale, h * scale, pixels)


def pictures(glint, directory):
    """The edge crops and the map of docs/ANTIALIASING.md."""
    os.makedirs(directory, exist_ok=True)
    scene = os.path.join(ROOT, "scenes", "default.json")
    runs = {"one": ["--samples", "1"], "adaptive": ["--samples", "4", "--aa", "adaptive",
                                                    "--aa-map", os.path.join(directory, "map.png")],
            "uniform": ["--samples", "4", "--aa", "uniform"]}
    with tempfile.TemporaryDirectory() as tmp:
        for name, flags in runs.items():
            full = os.path.join(tmp, name + ".png")
            subprocess.run([glint, "render", scene, "--size", "800x600", "-o", full] + flags,
                           check=True, stdout=subprocess.DEVNULL)
            crop(full, os.path.join(directory, name + "-crop.png"), 230, 300, 120, 90, 4)
    crop(os.path.join(directory, "map.png"), os.path.join(directory, "map-crop.png"),
         230, 300, 120, 90, 4)
    print("wrote", ", ".join(sorted(os.listdir(directory))), "in", directory)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scenes", nargs="*")
    parser.add_argument("--glint", default=os.path.join(ROOT, "build", "app", "glint"))
    parser.add_argument("--size", default="1920x1080")
    parser.add_argument("--samples", type=int, default=4)
    parser.add_argument("--threshold", type=float, default=None, help="default: glint's")
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--pictures", metavar="DIR")
    args = parser.parse_args()
    if args.pictures:
        pictures(args.glint, args.pictures)
        return
    width, height = map(int, args.size.split("x"))
    print(f"| scene | uniform {args.samples}×{args.samples} hybrid (s) | adaptive hybrid (s) | "
          "ratio | refined | within 2/255 of uniform | adaptive ray (s) | ratio to uniform hybrid | "
          "ray within 2/255 |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes or default_scenes():
            name = os.path.splitext(os.path.basename(scene))[0]
            runs = {"uniform": [], "hybrid": [], "ray": []}
            refined = None
            for _ in range(args.runs):
                for key, aa, mode in (("uniform", "uniform", "hybrid"), ("hybrid", "adaptive", "hybrid"),
                                      ("ray", "adaptive", "ray")):
                    seconds, count = render(args.glint, scene, os.path.join(tmp, key + ".png"),
                                            args.size, args.samples, aa, mode, args.threshold)
                    runs[key].append(seconds)
                    if key == "hybrid":
                        refined = count
            t = {k: statistics.median(v) for k, v in runs.items()}
            uniform = os.path.join(tmp, "uniform.png")
            good = within(uniform, os.path.join(tmp, "hybrid.png"))
            good_ray = within(uniform, os.path.join(tmp, "ray.png"))
            print(f"| {name} | {t['uniform']:.2f} | {t['hybrid']:.2f} | {t['hybrid'] / t['uniform']:.2f} | "
                  f"{100 * refined / (width * height):.1f}% | {100 * good:.2f}% | {t['ray']:.2f} | "
                  f"{t['ray'] / t['uniform']:.2f} | {100 * good_ray:.2f}% |", flush=True)


if __name__ == "__main__":
    main()
