#!/usr/bin/env python3
"""glint side by side with POV-Ray (Debian's povray 3.7) on an NFF scene.

Converts the NFF file to POV-Ray's scene language with the camera, lights, Phong finish and
transmission glint derives from it (docs/SCENES.md, "NFF scenes"), renders it with povray and with glint in both
modes at the same size, without antialiasing, with the same number of threads, and prints wall
times, their ratios and the image difference. POV-Ray's start-up (everything but parsing,
bounding and tracing) is reported apart, as is glint's (load, GL context, shaders).

    python3 bench/povray_compare.py scenes/spd/balls-4.nff --size 1920x1080 --threads 2

Needs povray (`apt-get install povray`) and a built glint (`./glint build`). Runs are
repeated (--runs, default 3) alternately and the medians reported: the machine is shared.
"""
import argparse
import json
import math
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def tokens_of(path):
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0]
            yield from line.split()


def vec(v):
    return "<%s>" % ", ".join("%.9g" % x for x in v)


def nff_to_pov(path):
    """POV-Ray scene text for the NFF file, and its resolution."""
    t = tokens_of(path)
    num = lambda: float(next(t))
    out, lights, materials, mesh = [], [], {}, []
    current = None
    view = {}

    def flush():
        if mesh:
            out.append("mesh {\n%s  material { %s }\n}" % ("".join(mesh), current))
            mesh.clear()

    for word in t:
        if word == "v":
            for key in ("from", "at", "up"):
                assert next(t) == key
                view[key] = (num(), num(), num())
            assert next(t) == "angle"
            view["angle"] = num()
            assert next(t) == "hither"
            num()
            assert next(t) == "resolution"
            view["resolution"] = (int(num()), int(num()))
        elif word == "b":
            out.append("background { rgb %s }" % vec((num(), num(), num())))
        elif word == "l":
            p = (num(), num(), num())
            lights.append([p, None])
        elif word == "f":
            rgb = (num(), num(), num())
            kd, ks, shine, transmission, ior = num(), num(), num(), num(), num()
            key = (rgb, kd, ks, shine, transmission, ior)
            if key not in materials:
                name = "F%d" % len(materials)
                # As glint maps f: diffuse Kd·rgb, white Phong highlight Ks with exponent shine,
                # mirror reflection Ks, no ambient (NFF has none); transmission T with index ior.
                # POV-Ray's transmit scales the diffuse term by 1 − T, glint's does not
                # (docs/SCENES.md, "materials"): the diffuse weight is divided by 1 − T to match.
                # Its interior refracts (Snell, total internal reflection) as glint does.
                colour = "rgb %s" % vec(rgb)
                diffuse, interior = kd, ""
                if transmission > 0:
                    colour = "rgbt %s" % vec(rgb + (transmission,))
                    diffuse = kd / max(1 - transmission, 1e-6)
                    interior = " interior { ior %.9g }" % ior
                out.append("#declare %s = material { texture { pigment { %s } finish { ambient 0 "
                           "diffuse %.9g phong %.9g phong_size %.9g reflection { %.9g } } }%s }"
                           % (name, colour, diffuse, ks, shine, ks, interior))
                materials[key] = name
            if materials[key] != current:
                flush()
                current = materials[key]
        elif word == "s":
            flush()
            c, r = (num(), num(), num()), abs(num())
            out.append("sphere { %s, %.9g material { %s } }" % (vec(c), r, current))
        elif word == "c":
            flush()
            b, rb = (num(), num(), num()), abs(num())
            a, ra = (num(), num(), num()), abs(num())
            if rb == ra:
                out.append("cylinder { %s, %s, %.9g open material { %s } }"
                           % (vec(b), vec(a), rb, current))
            else:
                out.append("cone { %s, %.9g, %s, %.9g open material { %s } }"
                           % (vec(b), rb, vec(a), ra, current))
        elif word in ("p", "pp"):
            n = int(num())
            pts, normals = [], []
            for _ in range(n):
                pts.append((num(), num(), num()))
                if word == "pp":
                    normals.append((num(), num(), num()))
            if n == 3 or word == "pp":  # triangles (SPD's patches are all triangles): a mesh
                for i in range(1, n - 1):
                    if word == "pp":
                        mesh.append("  smooth_triangle { %s, %s, %s, %s, %s, %s }\n" % (
                            vec(pts[0]), vec(normals[0]), vec(pts[i]), vec(normals[i]),
                            vec(pts[i + 1]), vec(normals[i + 1])))
                    else:
                        mesh.append("  triangle { %s, %s, %s }\n"
                                    % (vec(pts[0]), vec(pts[i]), vec(pts[i + 1])))
            else:  # POV-Ray's polygon handles concave outlines (the gears)
                flush()
                out.append("polygon { %d, %s material { %s } }"
                           % (n + 1, ", ".join(vec(p) for p in pts + pts[:1]), current))
        else:
            sys.exit("%s: entity %r is not converted" % (path, word))
    flush()
    share = 1 / math.sqrt(max(1, len(lights)))
    light_text = ["light_source { %s color rgb %s }" % (vec(p), vec((share,) * 3))
                  for p, _ in lights]
    return view, light_text, out


def pov_scene(path, width, height):
    view, lights, objects = nff_to_pov(path)
    h0 = view["resolution"][1]
    # glint: fov_y from NFF's angle between outer pixel centres (docs/SCENES.md); POV-Ray's
    # angle is the horizontal one to the image edges.
    half = math.tan(math.radians(view["angle"]) / 2) * (h0 / (h0 - 1) if h0 > 1 else 1)
    horizontal = 2 * math.degrees(math.atan(half * width / height))
    # NFF is right-handed, POV-Ray left-handed: a negative right vector mirrors the view back.
    camera = ("camera { perspective location %s look_at %s sky %s right -x*%.9g up y angle %.9g }"
              % (vec(view["from"]), vec(view["at"]), vec(view["up"]), width / height, horizontal))
    # SPD's rules, as glint reads NFF: a ray tree 5 deep counting the eye ray, no adaptive
    # cut-off; no ambient light.
    settings = ("#version 3.7;\nglobal_settings { assumed_gamma 1.0 max_trace_level 5 "
                "adc_bailout 0 ambient_light rgb 0 }")
    return "\n".join([settings, camera] + lights + objects) + "\n"


def read_png(path):
    """(width, height, RGB bytes) of an 8-bit RGB or RGBA PNG."""
    data = open(path, "rb").read()
    i, idat = 8, b""
    while i < len(data):
        n, kind = struct.unpack(">I4s", data[i:i + 8])
        chunk = data[i + 8:i + 8 + n]
        i += 12 + n
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", chunk[:10])
            assert depth == 8 and colour in (2, 6), "8-bit RGB(A) PNGs only"
        elif kind == b"IDAT":
            idat += chunk
    raw, bpp = zlib.decompress(idat), 3 if colour == 2 else 4
    stride, rows, prev, k = w * bpp, [], bytearray(w * bpp), 0
    for _ in range(h):
        f, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
        k += 1 + stride
        if f == 1:
            for x in range(bpp, stride):
                line[x] = (line[x] + line[x - bpp]) & 255
        elif f == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif f == 3:
            for x in range(stride):
                left = line[x - bpp] if x >= bpp else 0
                line[x] = (line[x] + (left + prev[x]) // 2) & 255
        elif f == 4:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                b, c = prev[x], prev[x - bpp] if x >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if bpp == 3 else bytes(
            v for j, v in enumerate(line) if j % 4 != 3))
        prev = line
    return w, h, b"".join(rows)


def difference(a, b):
    """Mean absolute difference (0–255) and the share of pixels off by more than 8/255."""
    (w, h, x), (_, _, y) = read_png(a), read_png(b)
    total, off = 0, 0
    for p in range(0, len(x), 3):
        d = max(abs(x[p] - y[p]), abs(x[p + 1] - y[p + 1]), abs(x[p + 2] - y[p + 2]))
        total += abs(x[p] - y[p]) + abs(x[p + 1] - y[p + 1]) + abs(x[p + 2] - y[p + 2])
        off += d > 8
    return total / len(x), off / (w * h)


def write_png(path, w, h, rgb):
    """An 8-bit RGB PNG of `rgb` (3 bytes a pixel, rows top first)."""
    rows = bytearray()
    for j in range(h):
        rows.append(0)  # filter type: none
        rows += rgb[3 * w * j:3 * w * (j + 1)]

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(bytes(rows))) + chunk(b"IEND", b""))


def write_difference_map(a, b, path):
    """A PNG of image b at a third of its brightness, red where it differs from a by > 8/255."""
    (w, h, x), (_, _, y) = read_png(a), read_png(b)
    out = bytearray()
    for p in range(0, 3 * w * h, 3):
        if max(abs(x[p + c] - y[p + c]) for c in range(3)) > 8:
            out += b"\xff\x00\x00"
        else:
            out += bytes(v // 3 for v in y[p:p + 3])
    write_png(path, w, h, out)


def pov_seconds(log, name):
    for line in log.splitlines():
        if line.strip().startswith(name) and "(" in line:
            return float(line.rsplit("(", 1)[1].split()[0])
    return 0.0


def run_povray(pov, png, width, height, threads):
    start = time.monotonic()
    r = subprocess.run(["povray", "+I" + pov, "+O" + png, "+W%d" % width, "+H%d" % height,
                        "-A", "+WT%d" % threads, "-D", "+FN8", "File_Gamma=1.0", "-V", "+STP0"],
                       capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        sys.exit("povray failed:\n" + r.stderr[-2000:])
    parse = pov_seconds(r.stderr, "Parse Time") + pov_seconds(r.stderr, "Bounding Time")
    trace = pov_seconds(r.stderr, "Trace Time")
    return {"wall": wall, "parse": parse, "trace": trace, "startup": wall - parse - trace}


def run_glint(glint, nff, png, width, height, threads, mode):
    stats = png + ".json"
    start = time.monotonic()
    r = subprocess.run([glint, "render", nff, "--size", "%dx%d" % (width, height), "--threads",
                        str(threads), "--mode", mode, "-o", png, "--stats", stats],
                       capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        sys.exit("glint failed:\n" + r.stderr)
    s = json.load(open(stats))["seconds"]
    startup = s["load"] + s["prepare"] + s.get("context", 0) + s.get("compile", 0)
    return {"wall": wall, "startup": startup, "trace": wall - startup}


def peer_command_line(doc, peer, keep_help):
    """The command line of a comparison with another renderer (this one, bench/tachyon_compare.py):
    NFF files, --size, --threads, --runs, --glint, --keep, --markdown; checked that `peer` and
    glint are there. Returns the arguments, the width and height, and the working directory."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("nff", nargs="+")
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--glint", default=os.path.join(ROOT, "build", "app", "glint"))
    ap.add_argument("--keep", help=keep_help)
    ap.add_argument("--markdown", action="store_true", help="print one table row per scene")
    args = ap.parse_args()
    if not shutil.which(peer):
        sys.exit("%s is not installed: apt-get install %s" % (peer, peer))
    if not os.access(args.glint, os.X_OK):
        sys.exit("%s is not built: ./glint build" % args.glint)
    width, height = (int(v) for v in args.size.split("x"))
    work = args.keep or tempfile.mkdtemp(prefix="glint-%s-" % peer)
    os.makedirs(work, exist_ok=True)
    return args, width, height, work


def main():
    args, width, height, work = peer_command_line(
        __doc__, "povray", "keep the .pov files and images in this directory, and a map of where "
        "glint's ray-mode image differs from POV-Ray's by > 8/255")
    for nff in args.nff:
        name = os.path.splitext(os.path.basename(nff))[0]
        pov = os.path.join(work, name + ".pov")
        with open(pov, "w") as f:
            f.write(pov_scene(nff, width, height))
        runs = {"povray": [], "hybrid": [], "ray": []}
        images = {k: os.path.join(work, "%s-%s.png" % (name, k)) for k in runs}
        for _ in range(args.runs):  # alternately, so that drifting load hits all three alike
            runs["povray"].append(run_povray(pov, images["povray"], width, height, args.threads))
            for mode in ("hybrid", "ray"):
                runs[mode].append(run_glint(args.glint, nff, images[mode], width, height,
                                            args.threads, mode))
        med = {k: {f: statistics.median(r[f] for r in v) for f in v[0]} for k, v in runs.items()}
        p = med["povray"]
        diffs = {m: difference(images["povray"], images[m]) for m in ("hybrid", "ray")}
        if args.keep:
            write_difference_map(images["povray"], images["ray"],
                                 os.path.join(work, name + "-difference.png"))
        if args.markdown:
            print("| %s | %dx%d | %.2f (%.2f + %.2f) | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f%% |" % (
                name, width, height, p["wall"], p["startup"], p["parse"] + p["trace"],
                med["hybrid"]["wall"], med["ray"]["wall"], med["hybrid"]["wall"] / p["wall"],
                med["ray"]["wall"] / p["wall"], med["ray"]["trace"] / p["trace"],
                100 * diffs["ray"][1]))
            continue
        print("%s at %dx%d, %d threads, median of %d runs:" % (name, width, height, args.threads,
                                                               args.runs))
        print("  povray        %6.2f s wall = %.2f start-up + %.2f parse/bounding + %.2f trace"
              % (p["wall"], p["startup"], p["parse"], p["trace"]))
        for mode in ("hybrid", "ray"):
            g = med[mode]
            print("  glint %-6s  %6.2f s wall = %.2f start-up + %.2f the rest;  %.2fx POV-Ray's "
                  "wall, %.2fx without either's start-up;  differs from POV-Ray: mean %.3f/255, "
                  "%.1f%% of pixels by > 8/255" % (mode, g["wall"], g["startup"], g["trace"],
                                                  g["wall"] / p["wall"],
                                                  g["trace"] / (p["parse"] + p["trace"]),
                                                  diffs[mode][0], 100 * diffs[mode][1]))
    if not args.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
