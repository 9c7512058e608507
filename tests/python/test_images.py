"""Frame.image is the PNG's pixels and Frame.rgb the EXR's R, G, B, bit for bit, on every shipped
scene in both modes, against the command line's files for the same settings."""
import glob
import os

import numpy as np
import pytest

from conftest import ROOT, SANITIZED, read_exr, read_png, run_glint

SCENES = sorted(
    os.path.relpath(p, ROOT)
    for pattern in ("scenes/*.json", "scenes/meshes/*.obj", "scenes/spd/*.nff")
    for p in glob.glob(os.path.join(ROOT, pattern)))
# Under the sanitizers, one scene of each format and the glass scene: the module's path is the
# same for every scene, and the Release run holds every scene to the files.
if SANITIZED:
    SCENES = ["scenes/default.json", "scenes/glass.json", "scenes/meshes/geosphere.obj",
              "scenes/spd/balls-1.nff"]
# Small, so that the whole set stays a few seconds; the scene's own antialiasing and depth.
SIZE = (64, 48)
MODES = ["ray"] if SANITIZED else ["ray", "hybrid"]  # no GL under the sanitizers


@pytest.mark.skipif(SANITIZED, reason="a subset under the sanitizers")
def test_every_shipped_scene_is_here():
    assert len(SCENES) >= 30 and "scenes/default.json" in SCENES


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("scene", SCENES)
def test_arrays_are_the_command_lines_files(glint_module, tmp_path, scene, mode):
    frame = glint_module.load(scene).render(mode=mode, size=SIZE)
    flags = [scene, "--mode", mode, "--size", f"{SIZE[0]}x{SIZE[1]}"]
    run_glint("render", *flags, "-o", str(tmp_path / "x.png"))
    run_glint("render", *flags, "-o", str(tmp_path / "x.exr"))
    png = read_png(tmp_path / "x.png")
    exr = read_exr(tmp_path / "x.exr")
    assert frame.image.shape == png.shape == (SIZE[1], SIZE[0], 3)
    assert np.array_equal(frame.image, png)
    rgb = np.stack([exr["R"], exr["G"], exr["B"]], axis=-1)
    assert frame.rgb.dtype == np.float32
    assert np.array_equal(frame.rgb.view(np.uint32), rgb.view(np.uint32))  # bit for bit


def test_aovs_are_the_exrs_channels(glint_module, tmp_path):
    scene = "scenes/default.json"
    frame = glint_module.load(scene).render(mode="ray", size=SIZE,
                                            aovs=["depth", "normal", "id", "cutoff"])
    run_glint("render", scene, "--mode", "ray", "--size", "64x48", "--aov",
              "depth,normal,id,cutoff", "-o", str(tmp_path / "x.exr"))
    exr = read_exr(tmp_path / "x.exr")
    same = lambda a, b: np.array_equal(np.asarray(a).view(np.uint32), np.asarray(b).view(np.uint32))
    assert same(frame.depth, exr["Z"])
    assert same(frame.normal, np.stack([exr["N.X"], exr["N.Y"], exr["N.Z"]], axis=-1))
    assert np.array_equal(frame.id, exr["id"])
    assert same(frame.cutoff, exr["cutoff"])
    assert np.isinf(frame.depth).any() and frame.id.max() > 0  # background and objects both


def test_arrays_share_the_frames_memory_and_outlive_it(glint_module):
    frame = glint_module.load("scenes/default.json").render(mode="ray", size=SIZE)
    rgb, again = frame.rgb, frame.rgb
    assert np.shares_memory(rgb, again) and not rgb.flags.writeable
    copy = np.array(rgb)
    del frame  # the arrays keep the frame alive
    assert np.array_equal(rgb, copy)


def test_a_layer_not_asked_for_says_how_to_ask(glint_module):
    frame = glint_module.load("scenes/default.json").render(mode="ray", size=SIZE)
    with pytest.raises(AttributeError, match=r"aovs=\['depth'\]"):
        frame.depth


def test_stats_are_the_command_lines(glint_module, tmp_path):
    import json
    scene = "scenes/mirrors.json"
    frame = glint_module.load(scene).render(mode="ray", size=SIZE)
    run_glint("render", scene, "--mode", "ray", "--size", "64x48", "-o", str(tmp_path / "x.png"),
              "--stats", str(tmp_path / "stats.json"))
    cli = json.load(open(tmp_path / "stats.json"))
    ours = frame.stats
    assert ours["output"] is None and set(ours) == set(cli)
    for key in ("width", "height", "mode", "max_depth", "samples", "rays", "cutoff"):
        assert ours[key] == cli[key], key
    assert ours["accel"]["nodes_visited_per_ray"] == cli["accel"]["nodes_visited_per_ray"]


def test_a_skinned_model_is_posed_at_time_as_the_command_line_poses_it(glint_module, tmp_path):
    """time= poses a glTF skin (DESIGN §14): the array is the command line's file at that time,
    and another time gives another image."""
    model = "models/khronos/RiggedSimple/glTF/RiggedSimple.gltf"
    at_one = glint_module.load(model, time=1.0).render(mode="ray", size=SIZE)
    run_glint("render", model, "--time", "1", "--mode", "ray", "--size", "64x48",
              "-o", str(tmp_path / "x.png"))
    assert np.array_equal(at_one.image, read_png(tmp_path / "x.png"))
    at_zero = glint_module.load(model, time=0.0).render(mode="ray", size=SIZE)
    assert not np.array_equal(at_one.image, at_zero.image)
