"""Trimmed chunks (kind 2, docs/hdf5.md "Chunk format"): HDF5 and Zarr pad edge chunks with the fill
value; the chunk codec codes only the box holding the data and restores the padding bit for bit."""
import os
import re
import struct
import subprocess

import h5py
import numpy as np
import pytest
import zarr

from conftest import damaged_refusals, h5_read, h5_write, value_range
from pupwave.hdf5 import hdf5_filter
from pupwave.numcodecs import Pupwave

TRIMMED = 2


def head(chunk):
    """(chunk extent, box extent) of a trimmed chunk, x fastest."""
    dims = struct.unpack_from("<6I", chunk, 4)
    return dims[:3], dims[3:]


def h5_chunks(path):
    """Offset -> stored bytes of every chunk."""
    with h5py.File(path, "r") as f:
        d = f["x"].id
        return {d.get_chunk_info(i).chunk_offset: d.read_direct_chunk(d.get_chunk_info(i).chunk_offset)[1]
                for i in range(d.get_num_chunks())}


@pytest.mark.parametrize("rel", [1e-2, 1e-3, 1e-4])
def test_hdf5_edge_chunks_of_wmag91_are_trimmed(tmp_path, wmag91, rel):
    bound = rel * value_range(wmag91)
    stored = h5_write(tmp_path / "w.h5", wmag91, (64, 64, 64), **hdf5_filter(max_error=bound))
    back = h5_read(tmp_path / "w.h5")
    assert np.abs(back.astype(np.float64) - wmag91).max() <= bound
    chunks = h5_chunks(tmp_path / "w.h5")
    for offset, chunk in chunks.items():
        if offset == (0, 0, 0):
            assert chunk[2] == 1  # no padding: a plain volume chunk
            continue
        assert chunk[2] == TRIMMED
        box = tuple(min(64, 91 - o) for o in reversed(offset))  # x fastest; 27 where HDF5 padded
        assert head(chunk) == ((64, 64, 64), box)
    # One 91^3 chunk has no padding: padded 64^3 chunks are 14-17% larger, trimmed ones within 5%.
    whole = h5_write(tmp_path / "one.h5", wmag91, wmag91.shape, **hdf5_filter(max_error=bound))
    assert stored < 1.05 * whole


@pytest.mark.parametrize("dtype", ["u1", "i1", "u2", "i2"])
def test_hdf5_trimmed_integer_chunks_are_lossless(tmp_path, wmag91, dtype):
    info = np.iinfo(dtype)
    scaled = (wmag91 - wmag91.min()) / value_range(wmag91) * (float(info.max) - info.min) + info.min
    data = np.round(scaled).astype(dtype)
    h5_write(tmp_path / "i.h5", data, (64, 64, 64), **hdf5_filter(lossless=True))
    assert np.array_equal(h5_read(tmp_path / "i.h5"), data)
    kinds = [c[2] for c in h5_chunks(tmp_path / "i.h5").values()]
    assert kinds.count(TRIMMED) == 7


def test_hdf5_trimmed_chunk_keeps_the_bits_per_value_of_the_chunk(tmp_path, wmag91):
    """bpv counts bits per value of the whole chunk: the box gets the padded chunk's budget."""
    data = wmag91[:, :64, :64].copy()  # HDF5 pads the second chunk from 27 to 64 planes
    stored = h5_write(tmp_path / "b.h5", data, (64, 64, 64), **hdf5_filter(bpv=1.0))
    chunk = h5_chunks(tmp_path / "b.h5")[(64, 0, 0)]
    assert chunk[2] == TRIMMED and head(chunk)[1] == (64, 64, 27)
    budget = 64 ** 3 * 1.0 / 8
    assert 0.6 * budget < len(chunk) <= budget + 200  # the box alone would get 27/64 of it
    assert stored <= 2 * (budget + 200)
    err = (h5_read(tmp_path / "b.h5").astype(np.float64) - data) ** 2
    assert np.sqrt(err[64:].mean()) < 0.8 * np.sqrt(err[:64].mean())  # 2.4x the bits per data value


@pytest.mark.parametrize("fill", [0.0, np.nan])
def test_zarr_edge_chunks_are_trimmed_whatever_the_fill_value(tmp_path, wmag91, fill):
    """Zarr v2 pads edge chunks with fill_value (a NaN fill made them raw before: NaN cannot be coded)."""
    data = wmag91[:, :80, :70].copy()
    bound = 1e-3 * value_range(data)
    z = zarr.open(str(tmp_path / "w.zarr"), mode="w", shape=data.shape, chunks=(48, 48, 48), dtype="f4",
                  fill_value=fill, compressor=Pupwave(max_error=bound))
    z[...] = data
    back = zarr.open(str(tmp_path / "w.zarr"), mode="r")[...]
    assert np.abs(back.astype(np.float64) - data).max() <= bound
    for key in ("1.1.1", "0.0.1", "1.0.0"):  # padded on 3, 1 and 1 axes
        chunk = z.store[key]
        assert chunk[2] == TRIMMED
        offset = [48 * int(i) for i in reversed(key.split("."))]
        assert head(chunk)[1] == tuple(min(48, n - o) for n, o in zip(reversed(data.shape), offset))
    one = zarr.open(str(tmp_path / "one.zarr"), mode="w", shape=data.shape, chunks=data.shape, dtype="f4",
                    fill_value=fill, compressor=Pupwave(max_error=bound))
    one[...] = data
    assert z.nbytes_stored < 1.1 * one.nbytes_stored


def test_zarr_lossless_i16_edge_chunks_are_exact(tmp_path, wmag91):
    data = np.round((wmag91 - wmag91.min()) / value_range(wmag91) * 60000 - 30000).astype(np.int16)
    z = zarr.array(data, chunks=(64, 64, 64), fill_value=-7, compressor=Pupwave(lossless=True),
                   store=str(tmp_path / "i.zarr"))
    assert np.array_equal(zarr.open(str(tmp_path / "i.zarr"), mode="r")[...], data)
    assert z.store["1.1.1"][2] == TRIMMED


def test_trimmed_padding_comes_back_bit_identical():
    """The trimmed planes hold c bit for bit (a NaN payload, -0.0), whatever the bound."""
    codec = Pupwave(max_error=0.5)
    rng = np.random.default_rng(5)
    data = np.full((20, 24, 28), np.float32(-0.0))
    data[:13, :17, :19] = rng.standard_normal((13, 17, 19)).astype(np.float32).cumsum(axis=2)
    stored = codec.encode(data)
    assert stored[2] == TRIMMED and head(stored) == ((28, 24, 20), (19, 17, 13))
    back = codec.decode(stored).reshape(data.shape)
    assert np.array_equal(back[13:].view(np.uint32), data[13:].view(np.uint32))
    assert np.abs(back - data).max() <= 0.5
    odd_nan = np.frombuffer(struct.pack("<I", 0x7FC01234), dtype="<f4")[0]
    data[:, :, 19:] = odd_nan
    back = codec.decode(codec.encode(data)).reshape(data.shape)
    assert np.array_equal(back[:, :, 19:].view(np.uint32), data[:, :, 19:].view(np.uint32))


def test_all_constant_chunk_has_no_stream():
    stored = Pupwave(max_error=1e-3).encode(np.full((64, 64, 64), 3.25, dtype=np.float32))
    assert stored[2] == TRIMMED and len(stored) == 4 + 24 + 4
    assert head(stored) == ((64, 64, 64), (0, 0, 0))
    assert np.all(Pupwave(max_error=1e-3).decode(stored) == np.float32(3.25))
    tiny = Pupwave(max_error=1e-3).encode(np.zeros(3, dtype=np.float32))
    assert tiny[2] == 0  # a head larger than the raw bytes: stored raw


def trimmed(chunk_dims, box_dims, c=b"\0\0\0\0", stream=b""):
    return b"PW\x02\x05" + struct.pack("<6I", *chunk_dims, *box_dims) + c + stream


@pytest.mark.parametrize("name", ["box larger", "box on some axes", "box is the chunk", "empty extent",
                                  "over the limit", "truncated head", "c truncated", "stream missing",
                                  "stream for no box", "stream of another box", "stream garbage"])
def test_hostile_trimmed_chunks_are_refused(wmag91, name):
    codec = Pupwave(max_error=0.01)
    good = codec.encode(np.pad(wmag91[:20, :20, :20], ((0, 4), (0, 4), (0, 4))))
    assert good[2] == TRIMMED and head(good) == ((24, 24, 24), (20, 20, 20))
    stream = good[4 + 24 + 4:]
    bad = {
        "box larger": trimmed((24, 24, 24), (20, 25, 20), stream=stream),
        "box on some axes": trimmed((24, 24, 24), (20, 0, 20), stream=stream),
        "box is the chunk": trimmed((20, 20, 20), (20, 20, 20), stream=stream),
        "empty extent": trimmed((24, 0, 24), (0, 0, 0)),
        "over the limit": trimmed((65535, 65535, 65535), (0, 0, 0)),
        "truncated head": good[:4 + 17],
        "c truncated": good[:4 + 24 + 2],
        "stream missing": trimmed((24, 24, 24), (20, 20, 20)),
        "stream for no box": trimmed((24, 24, 24), (0, 0, 0), stream=stream),
        "stream of another box": trimmed((24, 24, 24), (20, 20, 19), stream=stream),
        "stream garbage": trimmed((24, 24, 24), (20, 20, 20), stream=b"PUPV" + bytes(40)),
    }[name]
    with pytest.raises(ValueError, match="cannot decode chunk"):
        codec.decode(bad)


def test_damaged_trimmed_chunks_are_refused_not_crashing(wmag91):
    codec = Pupwave(max_error=0.01)
    stored = codec.encode(np.pad(wmag91[:30, :30, :30], ((0, 2), (0, 2), (0, 2))))
    assert stored[2] == TRIMMED
    refused = damaged_refusals(codec, stored, seed=11)
    assert refused >= 135  # flips of c or of the kind byte to "raw" decode without complaint


def test_corrupted_trimmed_chunk_fails_the_hdf5_read(tmp_path, wmag91):
    path = tmp_path / "c.h5"
    data = wmag91[:, :64, :64].copy()
    h5_write(path, data, (64, 64, 64), **hdf5_filter(max_error=0.01))
    with h5py.File(path, "r") as f:
        info = f["x"].id.get_chunk_info_by_coord((64, 0, 0))
    with open(path, "r+b") as fh:  # the box's z extent (27) becomes 65
        fh.seek(info.byte_offset + 4 + 12 + 8)
        fh.write(struct.pack("<I", 65))
    with pytest.raises(OSError):
        h5_read(path)
    run = subprocess.run(["h5dump", "--enable-error-stack", "-d", "/x", str(path)], capture_output=True, text=True,
                         env=os.environ, timeout=60)
    assert run.returncode != 0
    assert re.search("pupwave filter: cannot decode chunk: .*trimmed chunk's box is larger than the chunk",
                     run.stdout + run.stderr)
