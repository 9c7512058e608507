#!/usr/bin/env python3
"""A sequence's phases (issue 73): how much of `glint render MODEL --frames N` goes to posing the
model (its node matrices, skins and morph targets) and to its structures (the moved meshes' BVHs
built again, the top level over the objects) against tracing, read from the sequence's last line.
Each figure is the median of the runs with its spread (min–max).

    python3 bench/sequence.py [GLINT] [--model models/khronos/Fox/glTF/Fox.gltf] [--runs 9]
        [--flags "--frames 48 --fps 24 --size 640x480 --mode ray"]
"""
import argparse
import os
import re
import shlex
import statistics
import subprocess
import tempfile

LINE = re.compile(r"in ([0-9.]+) s \(pose ([0-9.]+) s, structures ([0-9.]+) s, render ([0-9.]+) s\)")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("glint", nargs="?", default="build/app/glint")
    parser.add_argument("--model", default="models/khronos/Fox/glTF/Fox.gltf")
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--flags", default="--frames 48 --fps 24 --size 640x480 --mode ray")
    args = parser.parse_args()
    out = os.path.join(tempfile.mkdtemp(prefix="glint_sequence_"), "f-%04d.png")
    phases = {"total": [], "pose": [], "structures": [], "render": [], "share": []}
    for _ in range(args.runs):
        r = subprocess.run([args.glint, "render", args.model, "-o", out] + shlex.split(args.flags),
                           capture_output=True, text=True, check=True)
        total, pose, structures, render = map(float, LINE.search(r.stdout).groups())
        for name, value in zip(["total", "pose", "structures", "render"], [total, pose, structures, render]):
            phases[name].append(value)
        phases["share"].append((pose + structures) / total)
    print(f"{args.model} {args.flags}, {args.runs} runs")
    for name, values in phases.items():
        unit = "" if name == "share" else " s"
        scale = 100 if name == "share" else 1
        print(f"{name:<11} {statistics.median(values) * scale:8.3f}{unit or ' %'} "
              f"({min(values) * scale:.3f}–{max(values) * scale:.3f})")


if __name__ == "__main__":
    main()
