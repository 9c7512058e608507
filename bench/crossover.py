#!/usr/bin/env python3
"""Where does the item buffer pay off? Runs `glint compare` on generated scenes of N random
spheres and boxes over a floor, at several resolutions and settings, and prints a markdown
table of the hybrid/ray time ratios (below 1: hybrid is faster).

    python3 bench/crossover.py [--glint build/app/glint] [--counts 10,100,1000] [--sizes 800x600]
    python3 bench/crossover.py --scenes scenes/*.json --sizes 800x600

Timings are ratios measured side by side in one `glint compare` run (machines here are shared
and noisy); the absolute seconds are printed for context only.
"""
import argparse
import json
import random
import subprocess
import tempfile
from pathlib import Path


def scene(count: int, seed: int = 1) -> dict:
    rng = random.Random(seed)
    objects = [{"shape": "plane", "material": "floor"}]
    for i in range(count):
        size = rng.uniform(0.08, 0.25)
        objects.append({
            "shape": "sphere" if i % 2 else "box",
            "material": ["red", "blue", "mirror"][i % 3],
            "transform": [{"scale": size},
                          {"rotate": {"axis": [rng.uniform(-1, 1), 1, rng.uniform(-1, 1)],
                                      "degrees": rng.uniform(0, 180)}},
                          {"translate": [rng.uniform(-4, 4), size + rng.uniform(0, 2), rng.uniform(-4, 4)]}],
        })
    return {
        "description": f"{count} random spheres and boxes over a floor (bench/crossover.py)",
        "camera": {"eye": [0, 4, 9], "look_at": [0, 0.6, 0], "fov_y": 50},
        "ambient": [0.1, 0.1, 0.1],
        "lights": [{"position": [5, 8, 6]}, {"position": [-6, 5, 3], "color": [0.3, 0.3, 0.4]}],
        "materials": {
            "floor": {"diffuse": [0.5, 0.5, 0.5], "reflectivity": 0.2},
            "red": {"diffuse": [0.8, 0.2, 0.1], "specular": [0.5, 0.5, 0.5], "shininess": 40},
            "blue": {"diffuse": [0.2, 0.3, 0.9], "specular": [0.5, 0.5, 0.5], "shininess": 40},
            "mirror": {"diffuse": [0.05, 0.05, 0.05], "specular": [0.8, 0.8, 0.8], "shininess": 200,
                       "reflectivity": 0.7},
        },
        "objects": objects,
        "render": {"max_depth": 2},
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--glint", default="build/app/glint")
    parser.add_argument("--counts", default="10,30,100,300,1000")
    parser.add_argument("--sizes", default="400x300,800x600,1920x1080")
    parser.add_argument("--settings", default="mesh:exact,mesh:trust,proxy:exact,proxy:trust")
    parser.add_argument("--scenes", nargs="*", help="scene files to use instead of generated ones")
    parser.add_argument("--accel", default="auto", help="acceleration structure for both modes")
    args = parser.parse_args()
    print("| scene | objects | size | raster | resolve | ray s | hybrid s | primary visibility hybrid/ray |"
          " whole frame hybrid/ray | id agreement | pixels > 1/255 |")
    print("|---|---:|---|---|---|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        if args.scenes:
            runs = [(Path(p), len(json.loads(Path(p).read_text()).get("objects", []))) for p in args.scenes]
        else:
            runs = []
            for count in (int(c) for c in args.counts.split(",")):
                path = Path(tmp) / f"random-{count}.json"
                path.write_text(json.dumps(scene(count)))
                runs.append((path, count + 1))  # the floor too
        for path, count in runs:
            for size in args.sizes.split(","):
                for setting in args.settings.split(","):
                    raster, resolve = setting.split(":")
                    out = Path(tmp) / "compare.json"
                    subprocess.run([args.glint, "compare", str(path), "--size", size, "--raster", raster,
                                    "--resolve", resolve, "--accel", args.accel, "--json", str(out)], check=True, stdout=subprocess.DEVNULL)
                    d = json.loads(out.read_text())
                    print(f"| {path.stem} | {count} | {size} | {raster} | {resolve} | {d['ray']['seconds']:.3f} |"
                          f" {d['hybrid']['seconds']:.3f} | {d['primary_ratio']:.2f} | {d['frame_ratio']:.2f} |"
                          f" {100 * d['id_agreement']:.3f}% | {100 * d['fraction_over_1_255']:.4f}% |", flush=True)


if __name__ == "__main__":
    main()
