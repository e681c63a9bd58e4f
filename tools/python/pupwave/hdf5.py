"""Keyword arguments for h5py's ``create_dataset`` that select the Pupwave HDF5 filter.

The filter itself is the plugin ``libh5pupwave.so`` (tools/hdf5/, docs/hdf5.md). A pip install
ships it in the package (``pupwave/hdf5_plugin/``), and ``import pupwave`` adds that folder to
h5py's plugin search path (register_plugin); otherwise HDF5 finds it through ``HDF5_PLUGIN_PATH``
(installed into ``P/lib/hdf5/plugins`` by CMake)::

    f.create_dataset("t", data=a, chunks=(64, 64, 64), **pupwave.hdf5.hdf5_filter(max_error=1e-3))
"""

import importlib.util
import math
import os
import struct

FILTER_ID = 402  # HDF5 testing range 256-511; a registered id must be requested before a release
MODE_MAX_ERROR = 1
MODE_BPV = 2
MODE_LOSSLESS = 3
PLUGIN_NAME = "libh5pupwave.so"
# The folder of the plugin in a pip-installed package (setup.py puts it there).
PACKAGED_PLUGIN_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hdf5_plugin")


def packaged_plugin():
    """The path of the plugin shipped in the package, or None (a CMake build or install)."""
    path = os.path.join(PACKAGED_PLUGIN_DIR, PLUGIN_NAME)
    return path if os.path.isfile(path) else None


def register_plugin():
    """Appends the packaged plugin's folder to h5py's plugin search path (h5py.h5pl), as hdf5plugin
    does, so that h5py reads and writes filter 402 with no HDF5_PLUGIN_PATH. Returns the folder, or
    None when there is no packaged plugin or h5py is not installed. Called by ``import pupwave``;
    registering twice adds the folder once."""
    if packaged_plugin() is None or importlib.util.find_spec("h5py") is None:
        return None
    from h5py import h5pl  # imported only here: pupwave needs no h5py

    folder = os.fsencode(PACKAGED_PLUGIN_DIR)
    if folder not in (h5pl.get(i) for i in range(h5pl.size())):
        h5pl.append(folder)
    return PACKAGED_PLUGIN_DIR


def filter_mode(max_error=None, bpv=None, lossless=False):
    """(mode, bound) for exactly one of max_error (absolute), bpv (bits per value) or lossless."""
    chosen = [max_error is not None, bpv is not None, bool(lossless)]
    if sum(chosen) != 1:
        raise ValueError("pupwave: give exactly one of max_error, bpv or lossless=True")
    if lossless:
        return MODE_LOSSLESS, 0.0
    value = float(max_error if max_error is not None else bpv)
    name = "max_error" if max_error is not None else "bpv"
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"pupwave: {name} must be a finite positive number, got {value!r}")
    if bpv is not None and value > 64.0:
        raise ValueError(f"pupwave: bpv must be at most 64 bits per value, got {value!r}")
    return (MODE_MAX_ERROR if max_error is not None else MODE_BPV), value


def filter_cd_values(max_error=None, bpv=None, lossless=False):
    """The 3 user cd_values: mode, then the bound as a double split into low and high 32-bit words."""
    mode, bound = filter_mode(max_error, bpv, lossless)
    low, high = struct.unpack("<II", struct.pack("<d", bound))
    return (mode, low, high)


def hdf5_filter(max_error=None, bpv=None, lossless=False):
    """``dict(compression=402, compression_opts=(mode, low, high))`` for ``create_dataset``
    (as ``hdf5plugin.Zfp(accuracy=...)`` does); chunks must be given by the caller."""
    return {"compression": FILTER_ID, "compression_opts": filter_cd_values(max_error, bpv, lossless)}
