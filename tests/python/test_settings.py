"""Every setting of every call, by keyword: a bad value raises ValueError naming the setting, with
the command line's own message; an unknown keyword raises TypeError naming it."""
import pytest

from conftest import SANITIZED

# One value each setting's check refuses, with a part of the message it gives. A setting added to
# a command without a line here fails test_every_setting_has_a_bad_value.
BAD = {
    "camera": (-1, "camera"),
    "size": ((0, 5), "each side must be 1 to 16384"),
    "time": (-1.0, "must be 0 or more seconds"),
    "animation": (-2, "must be 0 or more"),
    "framing": ("sideways", "sideways not in"),
    "environment": ("sky.png", "an environment is an equirectangular .hdr or .exr file"),
    "accel": ("octree", "octree not in"),
    "max_depth": (65, "not in range 0 to 64"),
    "min_reflectivity": (1.5, "Value 1.5 not in range"),
    "samples": (0, "not in range 1 to 16"),
    "aa": ("stochastic", "stochastic not in"),
    "aa_threshold": (-0.1, "Value -0.1 not in range"),
    "packet_levels": (99, "not in range 0 to 64"),
    "mode": ("raster", "raster not in {hybrid,ray}"),
    "gl": ("vulkan", "vulkan not in"),
    "raster": ("wire", "wire not in"),
    "tess": (2, "not in range 3 to 1024"),
    "resolve": ("guess", "guess not in"),
    "threads": (0, "not in range 1 to 1024"),
    "aa_sample_ids": ("yes", "takes True or False"),
    "aovs": (["albedo"], "not an AOV"),
    "colour": ("cmyk", "cmyk not in"),
    "sample": ((9, 9), "outside the pixel's"),
    "against": ("--max-depth 99", "not in range 0 to 64"),
}
CALLS = ["load", "render", "explain", "compare"]


def invoke(glint, call, **settings):
    if call == "load":
        return glint.load("scenes/default.json", **settings)
    scene = glint.load("scenes/default.json")
    if call == "render":
        return scene.render(**{"mode": "ray", "size": (8, 6), **settings})
    if call == "explain":
        return scene.explain(0, 0, **settings)
    return scene.compare(a={"mode": "ray"}, b={"mode": "ray", "max_depth": 1}, **settings)


@pytest.mark.parametrize("call", CALLS)
def test_every_setting_has_a_bad_value(glint_module, call):
    assert set(glint_module.keywords(call)) <= set(BAD), call


@pytest.mark.parametrize("call", CALLS)
def test_each_bad_value_raises_value_error_naming_the_setting(glint_module, call):
    keywords = glint_module.keywords(call) + (["sample"] if call == "explain" else [])
    for name in keywords:
        value, message = BAD[name]
        with pytest.raises(ValueError) as raised:
            invoke(glint_module, call, **{name: value})
        text = str(raised.value)
        assert message in text, (call, name, text)
        assert name in text or name in ("sample", "against"), (call, name, text)


@pytest.mark.parametrize("call", CALLS)
def test_an_unknown_keyword_raises_type_error(glint_module, call):
    with pytest.raises(TypeError, match="unexpected keyword argument 'max_dpeth'"):
        invoke(glint_module, call, max_dpeth=2)


def test_what_a_call_does_not_take_is_unknown(glint_module):
    scene = glint_module.load("scenes/default.json")
    with pytest.raises(TypeError, match="'output'"):
        scene.render(output="x.png")  # render returns arrays; it writes no file
    with pytest.raises(TypeError, match="'json'"):
        scene.explain(0, 0, json="x.json")
    with pytest.raises(TypeError, match="'aovs'"):
        scene.explain(0, 0, aovs=["depth"])  # refused by `glint explain` too
    with pytest.raises(TypeError, match="'samples'"):
        glint_module.load("scenes/default.json", samples=2)  # a render's, not a load's


def test_none_is_not_given(glint_module):
    frame = glint_module.load("scenes/default.json", camera=None).render(
        mode="ray", size=(8, 6), samples=None)
    assert frame.stats["samples"] == 3  # the scene's own


def test_a_setting_of_the_wrong_type(glint_module):
    with pytest.raises(ValueError, match="samples: a dict is not a value"):
        glint_module.load("scenes/default.json").render(samples={})


def test_scene_errors_carry_the_file_and_the_place(glint_module, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"camera": {"width": -1}}')
    with pytest.raises(glint_module.SceneError) as raised:
        glint_module.load(str(bad))
    e = raised.value
    assert (e.file, e.place) == (str(bad), "/camera/width")
    assert "must be between 1 and 16384" in e.detail and str(bad) in str(e)
    nff = tmp_path / "bad.nff"
    nff.write_text("b 0 0 0\nv\nfrom x\n")
    with pytest.raises(glint_module.SceneError) as raised:
        glint_module.load(str(nff))
    assert (raised.value.file, raised.value.place) == (str(nff), "line 3")
    with pytest.raises(glint_module.SceneError) as raised:
        glint_module.load(str(tmp_path / "missing.json"))
    assert raised.value.place is None and "cannot open" in raised.value.detail


@pytest.mark.skipif(SANITIZED, reason="hybrid mode draws with GL: not under the sanitizers")
def test_bad_memory_or_grid_is_a_value_error(glint_module):
    with pytest.raises(ValueError, match="beyond the largest GL draws"):
        glint_module.load("scenes/default.json").render(size=(16000, 100), samples=4)


def test_numpy_scalars_are_numbers(glint_module):
    import numpy as np
    scene = glint_module.load("scenes/default.json")
    frame = scene.render(mode="ray", size=(np.int64(8), np.int32(6)), max_depth=np.int64(2),
                         min_reflectivity=np.float32(0.25))
    stats = frame.stats
    assert (stats["width"], stats["height"], stats["max_depth"]) == (8, 6, 2)
    assert stats["min_reflectivity"] == 0.25
