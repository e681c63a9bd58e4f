"""The HDF5 filter through h5py (serial HDF5) and HDF5's own tools (h5dump, h5ls), on real data."""
import os
import re
import subprocess

import h5py
import numpy as np
import pytest

from conftest import h5_read, h5_write, value_range
from pupwave.hdf5 import FILTER_ID, filter_cd_values, hdf5_filter

CHUNK_HEADER = 4  # bytes added to a chunk stored raw (docs/hdf5.md)


@pytest.mark.parametrize("rel", [1e-2, 1e-3, 1e-4])
def test_max_error_holds_on_every_value_of_wmag91(tmp_path, wmag91, rel):
    bound = rel * value_range(wmag91)
    stored = h5_write(tmp_path / "w.h5", wmag91, (48, 91, 91), **hdf5_filter(max_error=bound))
    back = h5_read(tmp_path / "w.h5")
    assert back.dtype == np.float32 and back.shape == wmag91.shape
    assert np.abs(back.astype(np.float64) - wmag91).max() <= bound
    assert stored < wmag91.nbytes / 3  # compresses (two chunks, the second padded by HDF5)


def test_float64_1d_and_2d_chunks(tmp_path, wmag91):
    plane = wmag91[40].astype(np.float64)
    bound = 1e-3 * value_range(plane)
    h5_write(tmp_path / "p.h5", plane, (32, 91), **hdf5_filter(max_error=bound))
    assert np.abs(h5_read(tmp_path / "p.h5") - plane).max() <= bound
    line = plane.ravel()
    h5_write(tmp_path / "l.h5", line, (1000,), **hdf5_filter(max_error=bound))
    assert np.abs(h5_read(tmp_path / "l.h5") - line).max() <= bound


def test_bits_per_value_sets_the_size(tmp_path, wmag91):
    data = wmag91[:64, :64, :64].copy()
    stored = h5_write(tmp_path / "b.h5", data, data.shape, **hdf5_filter(bpv=2.0))
    assert stored <= data.size * 2.0 / 8 + 200  # a 200-byte stream header at most
    assert stored > data.size * 1.0 / 8
    assert np.abs(h5_read(tmp_path / "b.h5") - data).max() < 0.1 * value_range(data)


@pytest.mark.parametrize("dtype", ["u1", "i1", "u2", "i2"])
def test_lossless_integers_are_bit_exact(tmp_path, wmag91, dtype):
    info = np.iinfo(dtype)
    scaled = (wmag91 - wmag91.min()) / value_range(wmag91) * (float(info.max) - info.min) + info.min
    data = np.round(scaled).astype(dtype)
    stored = h5_write(tmp_path / "i.h5", data, (48, 48, 48), **hdf5_filter(lossless=True))
    assert np.array_equal(h5_read(tmp_path / "i.h5"), data)
    assert stored < data.nbytes


def test_incompressible_chunks_are_stored_raw_and_nan_chunks_keep_their_missing_values(tmp_path, wmag91):
    noise = np.random.default_rng(1).standard_normal((64, 64, 64)).astype(np.float32)
    stored = h5_write(tmp_path / "n.h5", noise, (32, 32, 32), **hdf5_filter(max_error=1e-7))
    assert stored <= noise.nbytes + 8 * CHUNK_HEADER
    assert np.abs(h5_read(tmp_path / "n.h5") - noise).max() <= 1e-7
    data = wmag91[:32, :32, :32].copy()
    data[3, 4, 5] = np.nan
    data[6, 7, 8] = np.inf
    stored = h5_write(tmp_path / "nan.h5", data, data.shape, **hdf5_filter(max_error=1e-3))
    assert stored < data.nbytes  # coded: NaN and infinities are missing values, kept exactly
    back = h5_read(tmp_path / "nan.h5")
    missing = ~np.isfinite(data)
    assert np.array_equal(back.view(np.uint32)[missing], data.view(np.uint32)[missing])
    assert np.abs(back[~missing].astype(np.float64) - data[~missing]).max() <= 1e-3


@pytest.mark.parametrize("opts, message", [
    ((1, 0, 0), "max_error must be a finite positive number"),
    ((9, 0, 0), "unknown mode 9"),
    (filter_cd_values(bpv=40.0), "bits per value must be in"),
    (filter_cd_values(lossless=True), "lossless mode needs 8- or 16-bit integers"),
])
def test_absurd_cd_values_are_refused_at_creation(tmp_path, opts, message):
    with h5py.File(tmp_path / "bad.h5", "w") as f:
        with pytest.raises(ValueError, match="pupwave filter: " + message):
            f.create_dataset("x", shape=(64, 64), dtype="f4", chunks=(32, 32), compression=FILTER_ID,
                             compression_opts=opts)
        assert "x" not in f


@pytest.mark.parametrize("dtype, shape, chunks, message", [
    ("i4", (64, 64), (32, 32), "datatype must be float32, float64 or an 8/16-bit integer"),
    (">f4", (64, 64), (32, 32), "only little-endian datatypes"),
    ("f4", (4, 4, 4, 4), (2, 2, 2, 2), "chunks with more than 3 dimensions larger than 1"),
])
def test_unsupported_datasets_are_refused(tmp_path, dtype, shape, chunks, message):
    with h5py.File(tmp_path / "bad.h5", "w") as f:
        with pytest.raises(ValueError, match="pupwave filter: " + message):
            f.create_dataset("x", shape=shape, dtype=dtype, chunks=chunks, **hdf5_filter(max_error=1.0))


def test_unit_dimensions_are_dropped(tmp_path, wmag91):
    data = wmag91[:32, :32, :32].reshape(1, 32, 32, 32).copy()
    h5_write(tmp_path / "u.h5", data, data.shape, **hdf5_filter(max_error=0.05))
    assert np.abs(h5_read(tmp_path / "u.h5") - data).max() <= 0.05


def corrupt_first_chunk(path, position):
    with h5py.File(path, "r") as f:
        info = f["x"].id.get_chunk_info(0)
    with open(path, "r+b") as fh:
        fh.seek(info.byte_offset + position(info.size))
        byte = fh.read(1)
        fh.seek(-1, os.SEEK_CUR)
        fh.write(bytes([byte[0] ^ 0x5A]))


@pytest.mark.parametrize("where", ["signature", "stream header", "middle"])
def test_corrupted_chunk_fails_the_read_with_the_filter_named(tmp_path, wmag91, where):
    path = tmp_path / "c.h5"
    data = wmag91[:64, :64, :64].copy()
    h5_write(path, data, data.shape, **hdf5_filter(max_error=1e-3 * value_range(data)))
    position = {"signature": lambda n: 0, "stream header": lambda n: 9, "middle": lambda n: n // 2}[where]
    corrupt_first_chunk(path, position)
    with pytest.raises(OSError):
        h5_read(path)
    run = subprocess.run(["h5dump", "--enable-error-stack", "-d", "/x", str(path)], capture_output=True, text=True,
                         env=os.environ, timeout=60)
    assert run.returncode != 0
    assert "pupwave filter: cannot decode chunk" in run.stdout + run.stderr


def test_h5dump_and_h5ls_show_and_decode_the_filter(tmp_path, wmag91):
    path = tmp_path / "d.h5"
    data = wmag91[:8, :8, :8].copy()
    h5_write(path, data, (8, 8, 8), **hdf5_filter(max_error=1e-2))
    header = subprocess.run(["h5dump", "-p", "-H", str(path)], capture_output=True, text=True, check=True,
                            env=os.environ, timeout=60).stdout
    assert f"FILTER_ID {FILTER_ID}" in header and "pupwave" in header
    values = subprocess.run(["h5dump", "-d", "/x", "-m", "%.9g", str(path)], capture_output=True, text=True,
                            check=True, env=os.environ, timeout=60).stdout
    body = re.sub(r"\(\d+(,\d+)*\):", " ", values.split("DATA {")[1].split("}")[0])  # drop "(z,y,x):"
    dumped = np.array([float(v) for v in body.replace(",", " ").split()])
    assert dumped.size == data.size and np.abs(dumped - data.ravel()).max() <= 1e-2
    listing = subprocess.run(["h5ls", "-v", str(path) + "/x"], capture_output=True, text=True, check=True,
                             env=os.environ, timeout=60).stdout
    assert "pupwave" in listing and "Filter-0" in listing


def test_max_error_chunks_use_the_cli_default_bank(tmp_path, wmag91):
    """Max-error chunks carry the bank `pupwave compress --max-error` uses (one default everywhere)."""
    import pupwave
    bound = 1e-3 * value_range(wmag91)
    h5_write(tmp_path / "t.h5", wmag91, (64, 64, 64), **hdf5_filter(max_error=bound))
    with h5py.File(tmp_path / "t.h5", "r") as f:
        _, chunk = f["x"].id.read_direct_chunk((0, 0, 0))
    assert chunk[:2] == b"PW" and chunk[2] == 1  # a coded chunk (docs/hdf5.md, "Chunk format")
    assert pupwave.info(chunk[4:])["transform"] == pupwave.info(pupwave.compress_volume(wmag91, max_error=bound))[
        "transform"] == "pups:cinpact-interp-vm4"


def test_hdf5_filter_is_on_the_package():
    import pupwave

    assert pupwave.hdf5_filter is hdf5_filter
    assert pupwave.hdf5_filter(max_error=0.5)["compression"] == FILTER_ID
