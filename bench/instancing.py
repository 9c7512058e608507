#!/usr/bin/env python3
"""Instancing's cost (issue 73): 10^4 instances of a 10^5-triangle mesh (EXT_mesh_gpu_instancing)
against the mesh alone (peak RSS: what each instance adds), and their frame against 10^4 plain
boxes at the same places (the top level's share: the same count of objects, each a unit shape);
and each run's whole wall time, loading included.
The three are alternated run by run; each figure is the median of the runs with its spread.

    python3 bench/instancing.py [GLINT] [--runs 9] [--count 10000] [--size 640x480]
"""
import argparse
import base64
import json
import math
import os
import re
import statistics
import struct
import subprocess
import tempfile
import time

EYE, LOOK_AT = (50.0, 45.0, 125.0), (50.0, 0.0, 45.0)


def sphere(segments):
    """A UV sphere of radius 0.4: 2·segments·(segments − 1) triangles."""
    xyz, tris = [], []
    for i in range(segments + 1):
        theta = math.pi * i / segments
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            xyz += [0.4 * math.sin(theta) * math.cos(phi), 0.4 * math.cos(theta),
                    0.4 * math.sin(theta) * math.sin(phi)]
    for i in range(segments):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            if i > 0:
                tris += [a, b, c]
            if i < segments - 1:
                tris += [b, d, c]
    return xyz, tris


def look_rotation(eye, at):
    """The unit quaternion (x, y, z, w) that turns a glTF camera (looking down −Z, +Y up) to look
    from `eye` at `at`."""
    f = [a - e for a, e in zip(at, eye)]
    n = math.sqrt(sum(v * v for v in f))
    back = [-v / n for v in f]
    right = [back[2], 0.0, -back[0]]  # up (0, 1, 0) × back
    n = math.sqrt(sum(v * v for v in right))
    right = [v / n for v in right]
    up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
          back[0] * right[1] - back[1] * right[0]]
    m = [[right[0], up[0], back[0]], [right[1], up[1], back[1]], [right[2], up[2], back[2]]]
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w),
            (m[1][0] - m[0][1]) / (4 * w), w]


def places(count):
    side = int(math.ceil(math.sqrt(count)))
    return [(float(k % side), 0.0, float(k // side)) for k in range(count)]


def gltf(path, count, segments):
    """The mesh, and `count` instances of it (none: the mesh alone, placed once)."""
    xyz, tris = sphere(segments)
    buf = struct.pack(f"<{len(xyz)}f", *xyz) + struct.pack(f"<{len(tris)}I", *tris)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 4 * len(xyz)},
             {"buffer": 0, "byteOffset": 4 * len(xyz), "byteLength": 4 * len(tris)}]
    lo = [min(xyz[k::3]) for k in range(3)]
    hi = [max(xyz[k::3]) for k in range(3)]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(xyz) // 3, "type": "VEC3",
                  "min": lo, "max": hi},
                 {"bufferView": 1, "componentType": 5125, "count": len(tris), "type": "SCALAR"}]
    node = {"mesh": 0}
    used = []
    if count:
        offset = len(buf)
        flat = [v for p in places(count) for v in p]
        buf += struct.pack(f"<{len(flat)}f", *flat)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": 4 * len(flat)})
        accessors.append({"bufferView": 2, "componentType": 5126, "count": count, "type": "VEC3"})
        node["extensions"] = {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 2}}}
        used = ["EXT_mesh_gpu_instancing"]
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
           "nodes": [node, {"camera": 0, "translation": list(EYE), "rotation": look_rotation(EYE, LOOK_AT)}],
           "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(buf),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}]}
    if used:
        doc["extensionsUsed"] = used
    with open(path, "w") as f:
        json.dump(doc, f)
    return len(tris) // 3


def boxes(path, count):
    """`count` unit boxes scaled to the sphere's size, at the instances' places, seen alike."""
    scene = {"camera": {"eye": list(EYE), "look_at": list(LOOK_AT), "fov_y": math.degrees(0.8),
                        "width": 640, "height": 480},
             "lights": [{"position": [50, 100, 150]}],
             "materials": {"m": {"diffuse": [0.8, 0.8, 0.8]}},
             "objects": [{"shape": "box", "material": "m",
                          "transform": [{"scale": 0.4}, {"translate": list(p)}]} for p in places(count)]}
    with open(path, "w") as f:
        json.dump(scene, f)


def run(glint, scene, size, out):
    cmd = ["/usr/bin/time", "-f", "peak %M", glint, "render", scene, "--mode", "ray", "--size", size,
           "-o", out]
    started = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, check=True)
    wall = time.monotonic() - started
    text = r.stdout + r.stderr
    render = float(re.search(r"\(render ([0-9.]+) s\)", text).group(1))
    peak_mb = int(re.search(r"peak (\d+)", text).group(1)) / 1024
    return render, peak_mb, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("glint", nargs="?", default="build/app/glint")
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--count", type=int, default=10000)
    parser.add_argument("--segments", type=int, default=224, help="224: 99,904 triangles")
    parser.add_argument("--size", default="640x480")
    args = parser.parse_args()
    d = tempfile.mkdtemp(prefix="glint_instancing_")
    files = {"mesh alone": os.path.join(d, "single.gltf"),
             f"{args.count} instances": os.path.join(d, "instances.gltf"),
             f"{args.count} boxes": os.path.join(d, "boxes.json")}
    triangles = gltf(files["mesh alone"], 0, args.segments)
    gltf(files[f"{args.count} instances"], args.count, args.segments)
    boxes(files[f"{args.count} boxes"], args.count)
    runs = {name: [] for name in files}
    for _ in range(args.runs):  # interleaved: each round runs all three
        for name, scene in files.items():
            runs[name].append(run(args.glint, scene, args.size, os.path.join(d, "out.png")))
    print(f"{triangles} triangles a mesh, {args.runs} interleaved runs, ray mode, {args.size}")
    print(f"{'scene':<18} {'frame s (median, min–max)':<30} {'peak RSS MB (median, min–max)':<32}"
          f"wall s (median, min–max)")
    med = {}
    for name, rs in runs.items():
        t = [r[0] for r in rs]
        m = [r[1] for r in rs]
        w = [r[2] for r in rs]
        med[name] = (statistics.median(t), statistics.median(m))
        print(f"{name:<18} {med[name][0]:.3f} ({min(t):.3f}–{max(t):.3f}){'':<10} "
              f"{med[name][1]:.1f} ({min(m):.1f}–{max(m):.1f}){'':<13} "
              f"{statistics.median(w):.2f} ({min(w):.2f}–{max(w):.2f})")
    inst, alone, box = (med[f"{args.count} instances"], med["mesh alone"], med[f"{args.count} boxes"])
    ratios = [a[0] / b[0] for a, b in zip(runs[f"{args.count} instances"], runs[f"{args.count} boxes"])]
    print(f"instances' peak RSS over the mesh alone: +{inst[1] - alone[1]:.1f} MB "
          f"({(inst[1] - alone[1]) * 1024 / args.count:.2f} KB an instance)")
    print(f"instances' frame over the boxes': {inst[0] / box[0]:.2f}× "
          f"(run by run {min(ratios):.2f}–{max(ratios):.2f})")


if __name__ == "__main__":
    main()
