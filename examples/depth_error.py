#!/usr/bin/env python3
"""Depth against error: the default scene rendered at each maximum reflection depth, each image
measured against the exact one (ray traced in double precision, depth 64, no cut-off), as
`glint compare --a exact --b "--max-depth D"` measures it. Prints the table and draws a figure:
frame time against PSNR, one point per depth, and the per-pixel error of depth 2.

    ./glint python examples/depth_error.py [SCENE] [-o out/depth-error.png] [--size 400x300]

Headless: Matplotlib's Agg back end writes the PNG; no display is needed (docs/PYTHON.md).
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the back end is chosen)
import numpy as np  # noqa: E402

import glint  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default="scenes/default.json")
    parser.add_argument("-o", "--output", default="out/depth-error.png")
    parser.add_argument("--size", default="400x300", help="WIDTHxHEIGHT")
    parser.add_argument("--depths", default="0,1,2,3,4,5", help="the depths, comma-separated")
    parser.add_argument("--shown", type=int, default=2, help="the depth whose error is drawn")
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    depths = [int(d) for d in args.depths.split(",")]

    scene = glint.load(args.scene)
    rows, shown = [], None
    print(f"{'depth':>5} {'seconds':>9} {'PSNR dB':>8} {'differing':>10} {'largest':>9}")
    for depth in depths:
        c = scene.compare(a={"exact": True}, b={"mode": "ray", "max_depth": depth}, size=size)
        m = c["measures"]
        psnr = m["psnr_db"]  # None: identical bytes
        rows.append((depth, m["b"]["seconds"], psnr))
        print(f"{depth:>5} {m['b']['seconds']:>9.4f} "
              f"{'inf' if psnr is None else f'{psnr:.2f}':>8} {m['differing_pixels']:>10} "
              f"{m['max_error_radiance']:>9.4f}")
        if depth == args.shown:
            shown = c["error"]

    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    finite = [(d, t, p) for d, t, p in rows if p is not None]
    left.plot([t for _, t, _ in finite], [p for _, _, p in finite], "o-", color="tab:blue")
    for d, t, p in finite:
        left.annotate(f"depth {d}", (t, p), textcoords="offset points", xytext=(6, -10))
    left.set_xlabel("frame time (s), ray mode")
    left.set_ylabel("PSNR against the exact image (dB)")
    left.set_title(f"{os.path.basename(args.scene)}, {size[0]}x{size[1]}: time against error")
    left.grid(alpha=0.3)
    if shown is not None:
        # The scale's top at the 99th percentile of the differing pixels, as glint's heat map
        # sets it, so that a few bright pixels do not leave the rest black.
        differing = shown[shown > 0]
        top = float(np.percentile(differing, 99)) if differing.size else 1e-6
        image = right.imshow(shown, cmap="magma", vmin=0, vmax=max(top, 1e-6))
        figure.colorbar(image, ax=right, extend="max",
                        label="largest channel error (linear radiance)")
        right.set_title(f"depth {args.shown}: where it differs from the exact image")
    right.set_axis_off()
    figure.tight_layout()
    os.makedirs(os.path.dirname(args.output) or ".", exist_ok=True)
    figure.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
