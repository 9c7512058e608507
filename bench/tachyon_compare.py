#!/usr/bin/env python3
"""glint side by side with Tachyon (Debian's tachyon 0.99) on SPD's NFF scenes.

Tachyon reads NFF itself, so both programs read the same file. What differs, and how the work
is made equal (measured with bench/tachyon_compare.py --keep, docs/PERFORMANCE.md):

- **The view.** Tachyon ignores NFF's `angle`: its image plane is 1 unit high at distance 1
  (a vertical field of view of 2·atan(0.5) = 53.13° whatever the file says), and it draws the
  scene mirrored left to right. glint renders a copy of the file whose angle gives that view
  (glint reads NFF's angle across the outermost pixel centres of the file's `resolution`), and
  its image is mirrored before the two are compared.
- **Shading.** Tachyon runs with `-shade_phong` (its default is Blinn's highlight), its
  default full shading (shadows), no antialiasing, its lights scaled by 1/√n as glint gives
  each of an NFF file's n lights (`-rescale_lights`), `-raydepth` one more than glint's depth for
  the file (Tachyon counts the camera ray), and glint's number of threads. Tachyon still adds
  an ambient term glint's NFF reading does not (NFF has none), so the images are compared by
  where each draws the background (the silhouettes agree when the camera and the objects
  agree) and by their mean difference where both draw an object.
- **Output.** Tachyon writes uncompressed PPM, glint PNG; both are in the wall time, and each
  program's own report of its write is printed apart.

Prints, per scene, both wall times (medians of --runs alternated runs), their ratio, and how
much the images agree.

    python3 bench/tachyon_compare.py scenes/spd/balls-4.nff --size 1920x1080 --threads 2
    python3 bench/tachyon_compare.py scenes/spd/{balls-4,teapot-12,tree-11,rings-7,sombrero-2}.nff --markdown

Needs tachyon (`apt-get install tachyon`) and a built glint (`./glint build`).
"""
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from povray_compare import peer_command_line, read_png, tokens_of, write_png  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def nff_view(path):
    """The file's resolution height, background colour (0–1) and number of lights."""
    tokens = list(tokens_of(path))
    height = int(tokens[tokens.index("resolution") + 2])
    background = [float(v) for v in tokens[tokens.index("b") + 1:tokens.index("b") + 4]] \
        if "b" in tokens else [0.0, 0.0, 0.0]
    lights = sum(1 for line in open(path) if line.split()[:1] == ["l"])
    return height, background, lights


def with_tachyons_view(path, out):
    """A copy of `path` whose angle gives glint Tachyon's vertical field of view, 2·atan(0.5),
    across the image's edges: the NFF angle spans the outermost pixel centres of height h."""
    height = nff_view(path)[0]
    half = 0.5 * (height - 1) / height if height > 1 else 0.5
    angle = 2 * math.degrees(math.atan(half))
    text = open(path).read()
    text, n = re.subn(r"(?m)^(\s*angle\s+)\S+", lambda m: "%s%.9g" % (m.group(1), angle), text,
                      count=1)
    if n != 1:
        sys.exit("%s: no 'angle' line in its view" % path)
    with open(out, "w") as f:
        f.write(text)


def read_ppm(path):
    """(width, height, RGB bytes) of a binary 8-bit PPM (P6), as Tachyon writes it."""
    data = open(path, "rb").read()
    fields, i = [], 0
    while len(fields) < 4:
        while data[i:i + 1].isspace():
            i += 1
        j = i
        while not data[j:j + 1].isspace():
            j += 1
        fields.append(data[i:j])
        i = j
    assert fields[0] == b"P6" and fields[3] == b"255", "8-bit P6 PPMs only"
    w, h = int(fields[1]), int(fields[2])
    return w, h, data[i + 1:i + 1 + 3 * w * h]


def mirrored(w, h, rgb):
    rows = (rgb[3 * w * j:3 * w * (j + 1)] for j in range(h))
    return b"".join(b"".join(row[3 * x:3 * x + 3] for x in range(w - 1, -1, -1)) for row in rows)


def agreement(glint_png, tachyon_ppm, background):
    """Share of pixels both draw as background or both as an object (their silhouettes), and
    the mean absolute difference (0–255) where both draw an object, Tachyon's image mirrored."""
    w, h, g = read_png(glint_png)
    tw, th, t = read_ppm(tachyon_ppm)
    assert (w, h) == (tw, th), "the two images differ in size"
    t = mirrored(w, h, t)
    bg = [round(255 * min(max(c, 0.0), 1.0)) for c in background]

    def is_background(img, p):
        return all(abs(img[p + c] - bg[c]) <= 2 for c in range(3))

    same, both, total = 0, 0, 0
    for p in range(0, 3 * w * h, 3):
        a, b = is_background(g, p), is_background(t, p)
        same += a == b
        if not a and not b:
            both += 1
            total += sum(abs(g[p + c] - t[p + c]) for c in range(3)) / 3
    return same / (w * h), (total / both if both else 0.0), t


def seconds(log, name):
    m = re.search(r"%s:\s+([0-9.]+) seconds" % re.escape(name), log)
    return float(m.group(1)) if m else 0.0


def run_tachyon(nff, ppm, width, height, threads, depth, lights):
    start = time.monotonic()
    r = subprocess.run(["tachyon", nff, "-res", str(width), str(height), "-numthreads",
                        str(threads), "-raydepth", str(depth + 1), "-shade_phong", "-aasamples",
                        "0", "-rescale_lights", "%.9g" % (1 / math.sqrt(max(lights, 1))),
                        "-format", "PPM", "-o", ppm, "+V"], capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        sys.exit("tachyon failed:\n" + (r.stderr or r.stdout)[-2000:])
    log = r.stdout + r.stderr
    return {"wall": wall, "trace": seconds(log, "Ray Tracing Time"),
            "write": seconds(log, "Image I/O Time")}


def run_glint(glint, nff, png, width, height, threads):
    stats = png + ".json"
    start = time.monotonic()
    r = subprocess.run([glint, "render", nff, "--size", "%dx%d" % (width, height), "--threads",
                        str(threads), "--mode", "ray", "-o", png, "--stats", stats],
                       capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        sys.exit("glint failed:\n" + r.stderr)
    s = json.load(open(stats))
    return {"wall": wall, "trace": s["seconds"]["frame"], "write": s["seconds"]["write"],
            "depth": s["max_depth"]}


def main():
    args, width, height, work = peer_command_line(
        __doc__, "tachyon", "keep the scenes and images in this directory (Tachyon's as a "
        "mirrored PNG)")
    if args.markdown:
        print("| scene | Tachyon wall (s) | glint ray wall (s) | glint / Tachyon | Tachyon trace (s) "
              "| glint frame (s) | silhouettes agree | mean difference inside |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for nff in args.nff:
        name = os.path.splitext(os.path.basename(nff))[0]
        viewed = os.path.join(work, name + "-tachyon-view.nff")
        with_tachyons_view(nff, viewed)
        png, ppm = os.path.join(work, name + "-glint.png"), os.path.join(work, name + "-tachyon.ppm")
        runs = {"tachyon": [], "glint": []}
        for _ in range(args.runs):  # alternately, so that drifting load hits both alike
            runs["glint"].append(run_glint(args.glint, viewed, png, width, height, args.threads))
            depth = runs["glint"][-1]["depth"]
            runs["tachyon"].append(run_tachyon(nff, ppm, width, height, args.threads, depth,
                                               nff_view(nff)[2]))
        med = {k: {f: statistics.median(r[f] for r in v) for f in v[0]} for k, v in runs.items()}
        same, inside, tachyon_rgb = agreement(png, ppm, nff_view(nff)[1])
        if args.keep:
            write_png(os.path.join(work, name + "-tachyon-mirrored.png"), width, height,
                      tachyon_rgb)
        t, g = med["tachyon"], med["glint"]
        if args.markdown:
            print("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f%% | %.1f/255 |" % (
                name, t["wall"], g["wall"], g["wall"] / t["wall"], t["trace"], g["trace"],
                100 * same, inside))
            continue
        print("%s at %dx%d, %d threads, median of %d alternated runs:" % (
            name, width, height, args.threads, args.runs))
        print("  tachyon  %6.2f s wall (ray tracing %.2f, write %.3f)" % (t["wall"], t["trace"],
                                                                         t["write"]))
        print("  glint    %6.2f s wall (frame %.2f, write %.3f): %.2fx Tachyon's wall" % (
            g["wall"], g["trace"], g["write"], g["wall"] / t["wall"]))
        print("  images: %.2f%% of pixels agree on background or object; where both draw an "
              "object, mean difference %.1f/255" % (100 * same, inside))
    if not args.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
