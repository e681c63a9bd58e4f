"""Shared fixtures: the CLI (PUPWAVE_CLI), testimages/ and real images read through the CLI's
PNM conversion (no imaging package needed in Python)."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TESTIMAGES = pathlib.Path(os.environ.get("PUPWAVE_TESTIMAGES_DIR", ROOT / "testimages"))


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("PUPWAVE_CLI", str(ROOT / "build" / "tools" / "pupwave"))
    assert os.path.exists(path), f"pupwave CLI not found at {path} (set PUPWAVE_CLI)"
    return path


def read_pnm(path):
    """Binary PGM/PPM (P5/P6, maxval 255 or 65535) as a (H, W) or (H, W, 3) array."""
    data = pathlib.Path(path).read_bytes()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos : pos + 1].isspace():
            pos += 1
        if data[pos : pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end : end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    pos += 1
    magic, width, height, maxval = fields[0], int(fields[1]), int(fields[2]), int(fields[3])
    dtype = np.dtype(">u2") if maxval > 255 else np.dtype("u1")
    channels = 3 if magic == b"P6" else 1
    a = np.frombuffer(data, dtype=dtype, count=width * height * channels, offset=pos)
    a = a.reshape((height, width, channels) if channels == 3 else (height, width))
    return a.astype(dtype.newbyteorder("=")) if dtype.itemsize > 1 else a.copy()


def write_pnm(path, a):
    """Writes a (H, W) or (H, W, 3) uint8/uint16 array as binary PGM/PPM."""
    magic = b"P6" if a.ndim == 3 else b"P5"
    maxval = 65535 if a.dtype == np.uint16 else 255
    header = b"%s\n%d %d\n%d\n" % (magic, a.shape[1], a.shape[0], maxval)
    body = a.astype(">u2").tobytes() if a.dtype == np.uint16 else a.tobytes()
    pathlib.Path(path).write_bytes(header + body)


@pytest.fixture(scope="session")
def real_image(cli, tmp_path_factory):
    """testimages/<name>.png as a numpy array (via `pupwave convert` to PNM)."""
    cache = {}
    folder = tmp_path_factory.mktemp("pnm")

    def load(name, ext):
        if name not in cache:
            out = folder / f"{name}.{ext}"
            subprocess.run([cli, "convert", str(TESTIMAGES / f"{name}.png"), str(out)], check=True,
                           capture_output=True)
            cache[name] = read_pnm(out)
        return cache[name]

    return load


@pytest.fixture(scope="session")
def wmag():
    """testimages/wmag91.float: 91^3 float32 (x fastest) as a (z, y, x) array."""
    return np.fromfile(TESTIMAGES / "wmag91.float", dtype="<f4").reshape(91, 91, 91)
