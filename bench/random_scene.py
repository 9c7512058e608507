#!/usr/bin/env python3
"""Writes bench/crossover.py's scene of N random spheres and boxes over a floor as JSON, for
measurements that need one large scene (docs/PREVIEW.md's camera-move restarts).

    python3 bench/random_scene.py 100000 --spheres-only -o /tmp/spheres-100k.json
"""
import argparse
import json

from crossover import scene


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("count", type=int)
    parser.add_argument("--spheres-only", action="store_true", help="every object a sphere")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("-o", "--output", required=True)
    args = parser.parse_args()
    s = scene(args.count, args.seed)
    if args.spheres_only:
        for o in s["objects"][1:]:
            o["shape"] = "sphere"
        s["description"] = f"{args.count} random spheres over a floor (bench/random_scene.py)"
    with open(args.output, "w") as f:
        json.dump(s, f)


if __name__ == "__main__":
    main()
