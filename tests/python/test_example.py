"""examples/depth_error.py runs headless (Matplotlib's Agg back end) and writes its figure, and
what it measures holds together: more depth, less error, down to the exact image's."""
import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT, SANITIZED, png_size


@pytest.mark.skipif(SANITIZED, reason="Matplotlib is not glint's code: Release tree only")
def test_the_depth_error_example_draws_its_figure(tmp_path):
    figure = tmp_path / "depth-error.png"
    environment = dict(os.environ, MPLBACKEND="Agg")
    environment.pop("DISPLAY", None)
    done = subprocess.run(
        [sys.executable, os.path.join(ROOT, "examples", "depth_error.py"), "-o", str(figure),
         "--size", "120x90", "--depths", "0,1,2,4,8"],
        cwd=ROOT, env=environment, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    rows = re.findall(r"^\s*(\d+)\s+([\d.]+)\s+([\d.]+|inf)\s+(\d+)", done.stdout, re.M)
    assert [int(r[0]) for r in rows] == [0, 1, 2, 4, 8]
    psnr = [float(r[2]) for r in rows]
    differing = [int(r[3]) for r in rows]
    assert psnr == sorted(psnr) and differing == sorted(differing, reverse=True)
    width, height = png_size(figure)
    assert (width, height) == (1100, 420)  # 11 × 4.2 inches at 100 dpi
    assert "wrote " + str(figure) in done.stdout
