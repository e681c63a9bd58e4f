"""Shared fixtures of the HDF5 filter and numcodecs tests (run by ctest, see CMakeLists.txt)."""
import os

import numpy as np
import pytest

TESTIMAGES = os.environ.get("PUPWAVE_TESTIMAGES_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "testimages"))


@pytest.fixture(scope="session")
def wmag91():
    """The 91^3 float32 wind-magnitude field (testimages/README.md), C order (z, y, x)."""
    return np.fromfile(os.path.join(TESTIMAGES, "wmag91.float"), dtype="<f4").reshape(91, 91, 91)


def value_range(a):
    return float(a.max()) - float(a.min())


def damaged_refusals(codec, stored, seed, trials=150):
    """Decodes `trials` copies of a stored chunk with 1-3 random bytes flipped (every fifth also
    cut short); returns how many were refused with the codec's message (none may crash)."""
    rng = np.random.default_rng(seed)
    refused = 0
    for i in range(trials):
        damaged = bytearray(stored)
        for _ in range(int(rng.integers(1, 4))):
            damaged[int(rng.integers(0, len(damaged)))] ^= int(rng.integers(1, 256))
        if i % 5 == 0:
            damaged = damaged[: int(rng.integers(0, len(damaged)))]
        try:
            codec.decode(bytes(damaged))
        except ValueError as e:
            assert "cannot decode chunk" in str(e)
            refused += 1
    return refused


def h5_write(path, data, chunks, **kwargs):
    """Writes `data` as dataset "x" with these chunks and filter arguments; returns its stored bytes."""
    import h5py  # here, not at the top: the numcodecs tests share this file without needing h5py

    with h5py.File(path, "w") as f:
        return f.create_dataset("x", data=data, chunks=chunks, **kwargs).id.get_storage_size()


def h5_read(path):
    """Dataset "x" of the file, whole."""
    import h5py

    with h5py.File(path, "r") as f:
        return f["x"][...]
