"""Shared fixtures: the CLI (PUPWAVE_CLI), testimages/ and real images read through the CLI's
PNM conversion (no imaging package needed in Python), the pip-installed distribution and new
interpreters that see only it."""

import os
import pathlib
import subprocess
import sys

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


# Variables that point Python or the codec into a build tree: unset where only the install may count.
BUILD_TREE_VARIABLES = ("PYTHONPATH", "HDF5_PLUGIN_PATH", "PUPWAVE_HDF5_PLUGIN")


def run_python(code, *args):
    """Runs `code` in a new interpreter (this one's, so the venv of ctest's run) without
    BUILD_TREE_VARIABLES: it sees the installed package only. Returns its stdout; fails on a
    non-zero exit."""
    env = {k: v for k, v in os.environ.items() if k not in BUILD_TREE_VARIABLES}
    done = subprocess.run([sys.executable, "-c", code, *map(str, args)], capture_output=True, text=True, env=env)
    assert done.returncode == 0, f"exit {done.returncode}\n{done.stdout}\n{done.stderr}"
    return done.stdout


@pytest.fixture(scope="session")
def installed():
    """The pip-installed distribution pupwave is imported from (entry points exist only in an
    installed dist). ctest's python.pytest runs in the venv python.install made and sets
    PUPWAVE_REQUIRE_INSTALLED, so there a missing install fails; elsewhere (PYTHONPATH=build/python)
    the tests that need it are skipped."""
    import importlib.metadata

    import pupwave

    try:
        dist = importlib.metadata.distribution("pupwave")
    except importlib.metadata.PackageNotFoundError:
        dist = None
    if dist is None or pathlib.Path(dist.locate_file("pupwave/__init__.py")).resolve() != pathlib.Path(
            pupwave.__file__).resolve():
        message = f"pupwave is imported from {pupwave.__file__}, not from a pip-installed distribution"
        if os.environ.get("PUPWAVE_REQUIRE_INSTALLED"):
            pytest.fail(message)
        pytest.skip(message)
    return dist
