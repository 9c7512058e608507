#!/usr/bin/env python3
"""One frame on 1 rank x 1 thread, 1 rank x 2 threads and N ranks x 1 thread (mpirun), run
alternately so that all meet the same machine conditions; prints each configuration's median
wall time (the whole command: load, structures, GL, trace, exchange, write), the speed-ups over
1 x 1, and the distributed run's efficiency against the threaded one, then rank 0's per-rank
lines from the last distributed run (docs/DISTRIBUTED.md). With --before OLD_GLINT, the old
build's 1 x 2 and N x 1 runs are interleaved with the new one's, for a change's before and after.

    python3 bench/distributed.py build/app/glint SCENE [--size 1920x1080] [--runs 3]
        [--ranks 2] [--flags "--mode ray"] [--before OLD_GLINT] [--no-single]
"""
import argparse
import os
import re
import shlex
import statistics
import subprocess
import tempfile
import time


def run(cmd, env):
    start = time.perf_counter()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    return time.perf_counter() - start, out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("glint")
    p.add_argument("scene")
    p.add_argument("--size", default="1920x1080")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--flags", default="")
    p.add_argument("--before", help="an older glint, measured beside")
    p.add_argument("--no-single", action="store_true", help="leave out 1 x 1")
    a = p.parse_args()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out_dir = tempfile.mkdtemp()
    base = [a.glint, "render", a.scene, "--size", a.size, "-o", os.path.join(out_dir, "o.png")]
    base += shlex.split(a.flags)
    def pair(glint, label=""):
        cmd = [glint] + base[1:]
        return {
            f"1 x 2{label}": cmd + ["--threads", "2"],
            f"{a.ranks} x 1{label}": ["mpirun", "-np", str(a.ranks), "--bind-to", "core"] + cmd
            + ["--threads", "1"],
        }
    configs = {} if a.no_single else {"1 x 1": base + ["--threads", "1"]}
    configs.update(pair(a.glint))
    if a.before:
        configs.update(pair(a.before, " (before)"))
    times = {name: [] for name in configs}
    last = ""
    for _ in range(a.runs):
        for name, cmd in configs.items():
            seconds, out = run(cmd, env)
            times[name].append(seconds)
            if name == f"{a.ranks} x 1":
                last = out
    med = {name: statistics.median(t) for name, t in times.items()}
    print(f"{a.scene} at {a.size} {a.flags}, {a.runs} runs each, alternated; median wall time:")
    for name, t in med.items():
        print(f"  {name}: {t:6.2f} s  (runs {', '.join(f'{x:.2f}' for x in times[name])})"
              + (f"; speed-up over 1 x 1: {med['1 x 1'] / t:.2f}" if "1 x 1" in med else ""))
    for label in [""] + ([" (before)"] if a.before else []):
        dist = f"{a.ranks} x 1{label}"
        print(f"{dist} against 1 x 2{label}: {100 * med['1 x 2' + label] / med[dist]:.0f}% "
              f"(the efficiency of the distributed run against the threaded one when both use "
              f"{a.ranks} cores)")
    print("last distributed run, per rank:")
    print("".join(line + "\n" for line in last.splitlines() if re.match(r"^(ranks:|  rank )", line)),
          end="")


if __name__ == "__main__":
    main()
