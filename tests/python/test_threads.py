"""The GIL is released while glint renders: Ctrl-C stops a render between tiles and raises
KeyboardInterrupt, leaking nothing; two Python threads render at once and get what one thread
rendering both after each other gets."""
import os
import re
import subprocess
import sys
import threading
import _thread

import numpy as np
import pytest

from conftest import ROOT, SANITIZED

MODES = ["ray"] if SANITIZED else ["ray", "hybrid"]
# A render far too long to finish before the interrupt (minutes): it must be stopped, not waited
# for. Were it not interruptible, the test would run on to ctest's timeout and fail.
LONG = dict(mode="ray", size=(4000, 3000), samples=8, aa="uniform")


def test_ctrl_c_stops_a_render_and_raises_keyboard_interrupt(glint_module):
    scene = glint_module.load("scenes/default.json")
    before = scene.render(mode="ray", size=(64, 48)).rgb.copy()
    timer = threading.Timer(0.5, _thread.interrupt_main)  # what Ctrl-C does: SIGINT's flag
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(**LONG)
    timer.join()
    # The scene renders again afterwards, the same image.
    assert np.array_equal(scene.render(mode="ray", size=(64, 48)).rgb, before)


def test_ctrl_c_stops_a_comparison(glint_module):
    scene = glint_module.load("scenes/default.json")
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.compare(a={"mode": "ray"}, b={"mode": "ray", "samples": 8, "aa": "uniform"},
                      size=(4000, 3000))
    timer.join()


@pytest.mark.parametrize("mode", MODES)
def test_two_threads_render_what_one_thread_renders(glint_module, mode):
    scenes = [glint_module.load("scenes/default.json"), glint_module.load("scenes/mirrors.json")]
    settings = dict(mode=mode, size=(100, 75) if SANITIZED else (200, 150))
    alone = [s.render(**settings) for s in scenes]
    results = [[], []]

    def render(k):
        for _ in range(3):
            results[k].append(scenes[k].render(**settings))

    threads = [threading.Thread(target=render, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in range(2):
        assert len(results[k]) == 3
        for frame in results[k]:
            assert np.array_equal(frame.rgb, alone[k].rgb)
            assert np.array_equal(frame.image, alone[k].image)


# The leak check: a process with the sanitizers' runtime preloaded interrupts a render, renders
# again and exits; LeakSanitizer's report is read for leaks that glint's code allocated (a frame in
# the module or in the repository's sources). Python's own allocations left at exit are not
# glint's: their stacks hold none of its frames.
LEAK_SCRIPT = """
import threading, _thread, glint
scene = glint.load("scenes/default.json")
threading.Timer(0.5, _thread.interrupt_main).start()
try:
    scene.render(mode="ray", size=(4000, 3000), samples=8, aa="uniform")
    raise SystemExit("not interrupted")
except KeyboardInterrupt:
    pass
frame = scene.render(mode="ray", size=(64, 48), aovs=["depth"])
c = scene.compare(a={"mode": "ray"}, b={"mode": "ray", "max_depth": 1}, size=(64, 48))
print("interrupted", frame.depth.shape, c["causes"].shape)
"""


def glints_leaks(report):
    """The leak blocks of a LeakSanitizer report with a frame in glint's code."""
    blocks = re.split(r"\n(?=(?:Direct|Indirect) leak of)", report)
    ours = re.compile(r"glint\.cpython|" + re.escape(ROOT) + r"/(?!build/)|\bglint::")
    return [b for b in blocks if re.match(r"(Direct|Indirect) leak of", b) and ours.search(b)]


def test_the_leak_filter_finds_a_leak_in_glints_code():
    report = ("Direct leak of 8 byte(s) in 1 object(s) allocated from:\n"
              "    #0 0x1 in malloc\n    #1 0x2 in _PyObject_Malloc (/usr/bin/python3.11+0x1)\n\n"
              "Direct leak of 16 byte(s) in 1 object(s) allocated from:\n"
              f"    #0 0x1 in operator new\n    #1 0x2 in glint::World::World {ROOT}/trace/world.cpp:1\n")
    assert len(glints_leaks(report)) == 1


@pytest.mark.skipif(not SANITIZED, reason="needs the sanitizer build (AddressSanitizer)")
def test_an_interrupted_render_leaks_nothing():
    environment = dict(os.environ)
    environment["ASAN_OPTIONS"] = environment.get("ASAN_OPTIONS", "") + ":detect_leaks=1"
    environment["LSAN_OPTIONS"] = environment.get("LSAN_OPTIONS", "") + ":exitcode=0"
    environment["PYTHONMALLOC"] = "malloc"  # Python objects too, so that a reference kept shows
    done = subprocess.run([sys.executable, "-c", LEAK_SCRIPT], cwd=ROOT, env=environment,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and "interrupted" in done.stdout, done.stderr[-3000:]
    leaks = glints_leaks(done.stderr)
    assert not leaks, "\n".join(leaks)[:5000]
