#!/usr/bin/env python3
"""Issue 19's figures: does the item buffer earn its keep? Runs `glint compare` (ray mode, then
hybrid, in one process: each ratio compares two renders made side by side) on scene files, at
one size and raster setting, and prints a markdown table and the largest ratios.

    python3 bench/item_buffer.py [--glint build/app/glint] [--size 1920x1080] [--raster auto]
                                 [--gl osmesa|egl] [--samples N] SCENE...

Columns: raster and resolve seconds of the hybrid frame; primary = ray mode's primary rays;
primary visibility = (raster + resolve) / primary; resolve share = resolve / primary; whole
frame = hybrid total / ray total (one-time GL set-up included); same = the images are identical.
"""
import argparse
import json
import subprocess
import tempfile
from pathlib import Path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--glint", default="build/app/glint")
    parser.add_argument("--size", default="1920x1080")
    parser.add_argument("--raster", default="auto")
    parser.add_argument("--gl", default="osmesa", choices=["osmesa", "egl"])
    parser.add_argument("--samples", help="override the scenes' samples per pixel")
    parser.add_argument("scenes", nargs="+")
    args = parser.parse_args()
    print(f"`glint compare --size {args.size} --raster {args.raster} --gl {args.gl}`"
          + (f" `--samples {args.samples}`" if args.samples else "") + ", each scene's other settings\n")
    print("| scene | proxies | tessellations | raster s | resolve s | primary s | primary visibility | resolve share |"
          " whole frame | same |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    worst = {"primary_ratio": (0, ""), "resolve_ratio": (0, ""), "frame_ratio": (0, "")}
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "compare.json"
        for scene in args.scenes:
            command = [args.glint, "compare", scene, "--size", args.size, "--raster", args.raster,
                       "--gl", args.gl, "--json", str(out)]
            if args.samples:
                command += ["--samples", args.samples]
            subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
            d = json.loads(out.read_text())
            h, r = d["hybrid"]["phases"], d["ray"]["phases"]
            same = d["psnr_db"] is None
            name = Path(scene).stem
            print(f"| {name} | {d['proxy_objects']} | {d['tessellated_objects']} | {h['raster']:.3f} |"
                  f" {h['primary']:.3f} | {r['primary']:.3f} | {d['primary_ratio']:.2f} |"
                  f" {d['resolve_ratio']:.2f} | {d['frame_ratio']:.2f} | {'yes' if same else 'NO'} |", flush=True)
            for key in worst:
                if d[key] > worst[key][0]:
                    worst[key] = (d[key], name)
    print()
    for key, (value, name) in worst.items():
        print(f"largest {key}: {value:.2f} ({name})")


if __name__ == "__main__":
    main()
