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
