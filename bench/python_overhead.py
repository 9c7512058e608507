#!/usr/bin/env python3
"""What glint's Python module costs over the command line, same settings, side by side.

For each scene and mode, alternately and --runs times (medians reported):
  cli      `glint render SCENE --mode M --size WxH --stats S -o x.png`: the whole process, and its
           work without the PNG's write (--stats "total" less "write": load, prepare, frame);
  python   `python3 -c "import glint; glint.load(SCENE).render(mode=M, size=(W, H))"`: the whole
           process (interpreter, NumPy, the module), and the render call alone;
  again    in one Python process, the scene loaded once: render() called again, three times, the
           median (what a notebook pays for the next render), with the arrays .rgb and .image
           taken (no copy).
Python's stats always count the structure's traversals, as `--stats` does, so the CLI runs with
--stats too.

    ./glint python bench/python_overhead.py [--runs 5] [--size 800x600] [SCENES…]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GLINT = os.path.join(ROOT, "build", "app", "glint")

IN_PROCESS = """
import sys, time
t0 = time.perf_counter()
import glint
scene = glint.load(sys.argv[1])
t1 = time.perf_counter()
frame = scene.render(mode=sys.argv[2], size=(int(sys.argv[3]), int(sys.argv[4])))
t2 = time.perf_counter()
agains = []
for _ in range(3):
    t3 = time.perf_counter()
    again = scene.render(mode=sys.argv[2], size=(int(sys.argv[3]), int(sys.argv[4])))
    rgb, image = again.rgb, again.image
    agains.append(time.perf_counter() - t3)
print(t1 - t0, t2 - t1, sorted(agains)[1], sum(agains))
"""


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed:\n{done.stderr}")
    return time.perf_counter() - start, done.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="*", default=["scenes/default.json", "scenes/spd/balls-4.nff"])
    parser.add_argument("--size", default="800x600")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--modes", default="ray,hybrid")
    args = parser.parse_args()
    width, height = args.size.split("x")
    print(f"| scene | mode | CLI process | its work, no write | Python process | render() | "
          f"render() again | again / CLI work |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as scratch:
        stats = os.path.join(scratch, "stats.json")
        for scene in args.scenes:
            for mode in args.modes.split(","):
                cli, cli_frame, py, py_render, py_again = [], [], [], [], []
                for _ in range(args.runs):
                    seconds, _ = timed([GLINT, "render", scene, "--mode", mode, "--size", args.size,
                                        "--stats", stats, "-o", os.path.join(scratch, "x.png")])
                    cli.append(seconds)
                    seconds_of = json.load(open(stats))["seconds"]
                    cli_frame.append(seconds_of["total"] - seconds_of["write"])
                    seconds, out = timed([sys.executable, "-c", IN_PROCESS, scene, mode, width,
                                          height])
                    _, render, again, agains = (float(v) for v in out.split())
                    py.append(seconds - agains)  # the process as if it had rendered once
                    py_render.append(render)
                    py_again.append(again)
                m = statistics.median
                print(f"| {os.path.basename(scene)} | {mode} | {m(cli):.3f} s | {m(cli_frame):.3f} s "
                      f"| {m(py):.3f} s | {m(py_render):.3f} s | {m(py_again):.3f} s "
                      f"| {m(py_again) / m(cli_frame):.3f} |", flush=True)


if __name__ == "__main__":
    main()
