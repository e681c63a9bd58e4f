"""A chunk holding a whole array is coded by the HDF5 filter and by numcodecs to the stream the
CLI (and with it every library front door, tests/api/volume_front_doors_test.cpp) writes for the
same array and options: their options are resolved by the library's one rule
(codec/api/api_volume_options.h). A coded chunk is the 4-byte header 'P' 'W' kind type, then, for
kind 1, the volume stream (tools/hdf5/chunk_format.h), whose grid is named "chunk"; the CLI names a
raw file's grid by its stem, so the CLI codes a file named chunk.<dtype>."""
import os
import subprocess

import numpy as np
import pytest

from conftest import h5_write, value_range
from pupwave.hdf5 import hdf5_filter
from pupwave.numcodecs import Pupwave

VOLUME_CHUNK = b"PW\x01"  # header of a chunk holding a volume stream (kind 1), before the type byte


def cli_stream(tmp_path, array, dtype, flags):
    raw = tmp_path / f"chunk.{dtype}"
    array.tofile(raw)
    out = tmp_path / "cli.pw"
    z, y, x = array.shape
    subprocess.run([os.environ["PUPWAVE_CLI"], "compress", str(raw), str(out), "-q", "--dims", f"{x},{y},{z}",
                    "--dtype", dtype, *flags], check=True, capture_output=True)
    return out.read_bytes()


def h5_chunk(tmp_path, array, **kwargs):
    """The stored bytes of the one chunk of `array` written with the filter."""
    import h5py

    h5_write(tmp_path / "c.h5", array, array.shape, **hdf5_filter(**kwargs))
    with h5py.File(tmp_path / "c.h5", "r") as f:
        return f["x"].id.read_direct_chunk((0, 0, 0))[1]


def settings(wmag91):
    """(array, CLI dtype, CLI flags, the filter's and the codec's keywords) per rate mode."""
    u16 = np.round(wmag91.astype(np.float64) * 100).astype(np.uint16)
    bound = 1e-3 * value_range(wmag91)
    return [
        (wmag91, "f32", ["--max-error", repr(bound)], {"max_error": bound}),
        (wmag91, "f32", ["--bpv", "1.5"], {"bpv": 1.5}),
        (u16, "u16", ["--lossless"], {"lossless": True}),
    ]


@pytest.mark.parametrize("case", range(3), ids=["max_error", "bpv", "lossless"])
def test_whole_array_chunk_is_the_cli_stream(tmp_path, wmag91, case):
    array, dtype, flags, kwargs = settings(wmag91)[case]
    expected = cli_stream(tmp_path, array, dtype, flags)
    from_numcodecs = Pupwave(**kwargs).encode(array)
    from_hdf5 = h5_chunk(tmp_path, array, **kwargs)
    assert from_numcodecs[:3] == VOLUME_CHUNK and from_numcodecs[4:] == expected
    assert from_hdf5 == from_numcodecs
