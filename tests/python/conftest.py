"""What the Python module's tests share: where glint is, how to run its command line, and two
readers written here from the formats' specifications (PNG, and OpenEXR's scan-line files with
ZIP compression), so that the module is held to the files the command line writes, not to glint's
own decoders."""
import os
import struct
import subprocess
import zlib

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# Set by ctest (tests/CMakeLists.txt); the Release tree's binary when run by hand.
GLINT = os.environ.get("GLINT_BINARY", os.path.join(ROOT, "build", "app", "glint"))
# The sanitizer run (ASan preloaded into python3): no GL, no Matplotlib (tests/CMakeLists.txt).
SANITIZED = os.environ.get("GLINT_SANITIZED") == "1"


def run_glint(*args, check=True):
    """Runs the command line from the repository's root; returns the completed process. Not with
    the sanitizers' shared runtime that python3 has preloaded: the program links its own."""
    environment = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    done = subprocess.run([GLINT, *args], cwd=ROOT, capture_output=True, text=True,
                          env=environment)
    if check and done.returncode != 0:
        raise AssertionError(f"glint {' '.join(args)} exited {done.returncode}:\n{done.stderr}")
    return done


def read_png(path):
    """An 8-bit RGB, non-interlaced PNG (what glint writes) as a uint8 H×W×3 array."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    at, idat, header = 8, b"", None
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert (depth, colour, interlace) == (8, 2, 0), f"{path}: not 8-bit RGB, non-interlaced"
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(height, 1 + 3 * width)
    out = np.zeros((height, 3 * width), np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        up = out[y - 1] if y > 0 else np.zeros(3 * width, np.int32)
        if kind == 0:
            out[y] = line
        elif kind == 2:
            out[y] = (line + up) & 255
        else:  # 1 (sub), 3 (average), 4 (Paeth): each byte depends on the one to its left
            row = np.zeros(3 * width, np.int32)
            for i in range(3 * width):
                left = row[i - 3] if i >= 3 else 0
                corner = up[i - 3] if i >= 3 else 0
                if kind == 1:
                    predicted = left
                elif kind == 3:
                    predicted = (left + up[i]) // 2
                else:
                    p = left + up[i] - corner
                    pa, pb, pc = abs(p - left), abs(p - up[i]), abs(p - corner)
                    predicted = left if pa <= pb and pa <= pc else up[i] if pb <= pc else corner
                row[i] = (line[i] + predicted) & 255
            out[y] = row
    return out.astype(np.uint8).reshape(height, width, 3)


def png_size(path):
    """A PNG's width and height, from its header."""
    with open(path, "rb") as f:
        data = f.read(24)
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR", f"{path}: not a PNG"
    return struct.unpack(">II", data[16:24])


def read_exr(path):
    """A scan-line OpenEXR file (no, ZIPS or ZIP compression; 32-bit FLOAT and UINT channels) as
    {channel name: H×W array}, bit for bit as stored."""
    with open(path, "rb") as f:
        data = f.read()
    assert struct.unpack("<I", data[:4])[0] == 20000630, f"{path}: not an OpenEXR file"
    at, attributes = 8, {}
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack("<i", data[type_end + 1:type_end + 5])[0]
        attributes[data[at:name_end].decode()] = data[type_end + 5:type_end + 5 + size]
        at = type_end + 5 + size
    at += 1
    channels, c = [], 0
    chlist = attributes["channels"]
    while chlist[c] != 0:
        end = chlist.index(b"\0", c)
        kind = struct.unpack("<i", chlist[end + 1:end + 5])[0]
        channels.append((chlist[c:end].decode(), kind))
        c = end + 17
    x0, y0, x1, y1 = struct.unpack("<iiii", attributes["dataWindow"])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    compression = attributes["compression"][0]
    lines = {0: 1, 2: 1, 3: 16}[compression]
    chunks = (height + lines - 1) // lines
    offsets = struct.unpack(f"<{chunks}Q", data[at:at + 8 * chunks])
    planes = {name: np.zeros((height, width), np.uint32) for name, _ in channels}
    for offset in offsets:
        y, size = struct.unpack("<ii", data[offset:offset + 8])
        block = data[offset + 8:offset + 8 + size]
        rows = min(lines, y1 + 1 - y)
        expected = rows * width * 4 * len(channels)
        if size < expected:  # compressed: zlib, then the predictor, then the two halves merged
            t = np.frombuffer(zlib.decompress(block), np.uint8).astype(np.int64)
            t[1:] -= 128
            t = np.cumsum(t) & 255
            half = (len(t) + 1) // 2
            merged = np.empty(len(t), np.uint8)
            merged[0::2], merged[1::2] = t[:half], t[half:]
            block = merged.tobytes()
        words = np.frombuffer(block, "<u4").reshape(rows, len(channels), width)
        for k, (name, _) in enumerate(channels):
            planes[name][y - y0:y - y0 + rows] = words[:, k, :]
    return {name: planes[name].view(np.float32) if kind == 2 else planes[name]
            for name, kind in channels}


@pytest.fixture(scope="session")
def glint_module():
    import glint
    return glint


@pytest.fixture(autouse=True)
def in_the_repository(monkeypatch):
    """Scenes are named as the documentation names them, from the repository's root."""
    monkeypatch.chdir(ROOT)
