#!/usr/bin/env python3
"""Two glint binaries (or two sets of flags) rendering the same scenes, alternated run by run, so
that both meet the same machine conditions; prints each phase's median, the new/old ratio of the
medians, and the spread of the run-by-run ratios (each new run over the old run beside it: the
smallest and the largest). Machines here are shared and noisy: a ratio of medians over alternated
runs, with its spread, is the figure to quote, not either time alone.

    python3 bench/side_by_side.py OLD_GLINT NEW_GLINT SCENE... [--runs 5] [--flags "--mode ray"]
    python3 bench/side_by_side.py build/app/glint build/app/glint balls-4.nff \\
        --old-flags "--accel bvh2" --new-flags "--accel bvh"
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import tempfile

PHASES = ["primary", "shading", "total"]


def render(binary, scene, flags, out_dir):
    stats = os.path.join(out_dir, "stats.json")
    cmd = [binary, "render", scene, "-o", os.path.join(out_dir, "out.png"), "--stats", stats] + flags
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    seconds = json.load(open(stats))["seconds"]
    return {p: seconds[p] for p in PHASES}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--flags", default="--mode ray --size 1920x1080", help="for both")
    parser.add_argument("--old-flags", default="", help="for the old one only")
    parser.add_argument("--new-flags", default="", help="for the new one only")
    args = parser.parse_args()
    common = shlex.split(args.flags)
    print(f"| scene | phase | old median (s) | new median (s) | new / old | run ratios (min–max) |")
    print(f"|---|---|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as out_dir:
        for scene in args.scenes:
            runs = {"old": [], "new": []}
            for _ in range(args.runs):
                runs["old"].append(render(args.old, scene, common + shlex.split(args.old_flags), out_dir))
                runs["new"].append(render(args.new, scene, common + shlex.split(args.new_flags), out_dir))
            name = os.path.splitext(os.path.basename(scene))[0]
            for phase in PHASES:
                old = statistics.median(r[phase] for r in runs["old"])
                new = statistics.median(r[phase] for r in runs["new"])
                ratios = [n[phase] / o[phase] for o, n in zip(runs["old"], runs["new"]) if o[phase] > 0]
                spread = f"{min(ratios):.2f}–{max(ratios):.2f}" if ratios else "n/a"
                print(f"| {name} | {phase} | {old:.3f} | {new:.3f} | {new / old:.2f} | {spread} |",
                      flush=True)


if __name__ == "__main__":
    main()
