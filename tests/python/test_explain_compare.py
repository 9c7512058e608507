"""Scene.explain is `glint explain --json`, and Scene.compare is `glint compare --json` with the
per-pixel maps as arrays."""
import json

import numpy as np
import pytest

from conftest import SANITIZED, read_png, run_glint

MODES = ["ray"] if SANITIZED else ["ray", "hybrid"]


def cli_explain(tmp_path, *args):
    run_glint("explain", *args, "--json", str(tmp_path / "e.json"))
    return json.load(open(tmp_path / "e.json"))


# At 120x90: with adaptive antialiasing, explain renders the whole frame first (whether a pixel
# is refined depends on its neighbours).
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("scene, x, y", [("scenes/default.json", 60, 45),
                                         ("scenes/glass.json", 54, 42),
                                         ("scenes/spd/balls-1.nff", 60, 60)])
def test_explain_is_the_command_lines_json(glint_module, tmp_path, scene, x, y, mode):
    ours = glint_module.load(scene).explain(x, y, mode=mode, size=(120, 90))
    assert ours == cli_explain(tmp_path, scene, str(x), str(y), "--mode", mode, "--size",
                               "120x90")
    assert ours["schema"] == "glint-explain/1"


def test_explain_with_a_sample_and_settings(glint_module, tmp_path):
    scene = "scenes/mirrors.json"
    ours = glint_module.load(scene).explain(50, 40, sample=(0, 2), mode="ray", max_depth=2,
                                            samples=3, size=(160, 120))
    cli = cli_explain(tmp_path, scene, "50", "40", "--sample", "0,2", "--mode", "ray",
                      "--max-depth", "2", "--samples", "3", "--size", "160x120")
    assert ours == cli


def test_explain_against(glint_module, tmp_path):
    scene = "scenes/default.json"
    ours = glint_module.load(scene).explain(60, 45, mode="ray", size=(120, 90),
                                            against="--max-depth 1")
    assert ours == cli_explain(tmp_path, scene, "60", "45", "--mode", "ray", "--size", "120x90",
                               "--against", "--max-depth 1")


def test_explain_refuses_a_pixel_outside_the_image(glint_module):
    with pytest.raises(ValueError, match="outside the 800x600 image"):
        glint_module.load("scenes/default.json").explain(800, 0)


def test_compare_is_the_command_lines(glint_module, tmp_path):
    scene = "scenes/default.json"
    c = glint_module.load(scene).compare(a={"exact": True}, b={"max_depth": 2, "mode": "ray"},
                                         size=(120, 90))
    run_glint("compare", scene, "--size", "120x90", "--a", "exact", "--b",
              "--max-depth 2 --mode ray", "-o", str(tmp_path / "c"), "--json",
              str(tmp_path / "c.json"))
    cli = json.load(open(tmp_path / "c.json"))
    for key in ("differing_pixels", "psnr_db", "rmse_radiance", "max_error_radiance", "causes"):
        assert c["measures"][key] == cli[key], key
    assert np.array_equal(c["heat_map"], read_png(tmp_path / "c-heat.png"))
    assert np.array_equal(c["cause_map"], read_png(tmp_path / "c-causes.png"))
    assert np.array_equal(c["a"].image, read_png(tmp_path / "c-a.png"))
    assert np.array_equal(c["b"].image, read_png(tmp_path / "c-b.png"))
    causes, names = c["causes"], c["cause_names"]
    assert causes.shape == (90, 120) and names[0] == "none"
    # Per cause, its pixels in the array are the count the measures give.
    for k, name in enumerate(names[1:], 1):
        assert np.count_nonzero(causes == k) == cli["causes"][name]["pixels"], name
    assert np.count_nonzero(causes) == cli["differing_pixels"] > 0
    # The per-pixel error's largest is the measures' largest radiance error (float32 against
    # double: to a float's precision).
    assert c["error"].shape == (90, 120)
    assert c["error"].max() == pytest.approx(cli["max_error_radiance"], rel=1e-6)


@pytest.mark.skipif(SANITIZED, reason="hybrid mode draws with GL: not under the sanitizers")
def test_compare_without_sides_is_ray_against_hybrid(glint_module):
    c = glint_module.load("scenes/default.json").compare(size=(160, 120))
    assert c["measures"]["a"]["settings"].startswith("ray")
    assert c["measures"]["b"]["settings"].startswith("hybrid")
    assert c["measures"]["differing_pixels"] == 0  # the exact resolve: the same image


def test_a_sides_bad_flag_names_the_side(glint_module):
    with pytest.raises(ValueError, match='--a "--max-depth 99"'):
        glint_module.load("scenes/default.json").compare(a={"max_depth": 99})
    with pytest.raises(ValueError, match="b: a dict of settings"):
        glint_module.load("scenes/default.json").compare(b=3)
