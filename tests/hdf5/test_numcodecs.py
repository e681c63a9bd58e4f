"""pupwave.numcodecs.Pupwave: numcodecs registration, config round trip, Zarr v2 arrays, and the
same chunk bytes as the HDF5 filter."""
import numcodecs
import numpy as np
import pytest
import zarr

import pupwave.numcodecs  # noqa: F401  (registers "pupwave")
from conftest import damaged_refusals, value_range
from pupwave.numcodecs import Pupwave


@pytest.mark.parametrize("kwargs", [dict(max_error=0.25), dict(bpv=3.0), dict(lossless=True)])
def test_config_round_trips_through_get_codec(kwargs):
    codec = Pupwave(**kwargs)
    config = codec.get_config()
    assert config["id"] == "pupwave"
    again = numcodecs.get_codec(config)
    assert isinstance(again, Pupwave) and again.get_config() == config


@pytest.mark.parametrize("kwargs", [dict(), dict(max_error=1.0, bpv=2.0), dict(max_error=0.0),
                                    dict(max_error=float("nan")), dict(bpv=-1.0)])
def test_bad_settings_raise_value_error(kwargs):
    with pytest.raises(ValueError):
        Pupwave(**kwargs)


def test_bad_dtypes_and_corrupt_bytes_raise():
    with pytest.raises(TypeError):
        Pupwave(max_error=1.0).encode(np.zeros((4, 4), dtype=np.int32))
    with pytest.raises(ValueError):
        Pupwave(lossless=True).encode(np.zeros((4, 4), dtype=np.float32))
    with pytest.raises(ValueError, match="cannot decode chunk"):
        Pupwave(max_error=1.0).decode(b"PW\x01\x05garbage")


def test_zarr_array_holds_the_bound(tmp_path, wmag91):
    bound = 1e-3 * value_range(wmag91)
    z = zarr.open(str(tmp_path / "w.zarr"), mode="w", shape=wmag91.shape, chunks=(48, 48, 48), dtype="f4",
                  compressor=Pupwave(max_error=bound))
    z[...] = wmag91
    again = zarr.open(str(tmp_path / "w.zarr"), mode="r")
    assert isinstance(again.compressor, Pupwave) and again.compressor.max_error == bound
    back = again[...]
    assert np.abs(back.astype(np.float64) - wmag91).max() <= bound
    assert again.nbytes_stored < wmag91.nbytes / 4


def test_zarr_lossless_u16_is_exact(tmp_path, wmag91):
    data = np.round((wmag91 - wmag91.min()) / value_range(wmag91) * 65535).astype(np.uint16)
    z = zarr.array(data, chunks=(32, 91, 91), compressor=Pupwave(lossless=True), store=str(tmp_path / "u.zarr"))
    assert np.array_equal(zarr.open(str(tmp_path / "u.zarr"), mode="r")[...], data)
    assert z.nbytes_stored < data.nbytes


def test_chunks_are_the_hdf5_filter_chunks(tmp_path, wmag91):
    h5py = pytest.importorskip("h5py")
    from pupwave.hdf5 import hdf5_filter
    data = wmag91[:64, :64, :64].copy()
    with h5py.File(tmp_path / "s.h5", "w") as f:
        f.create_dataset("x", data=data, chunks=data.shape, **hdf5_filter(max_error=0.01))
    with h5py.File(tmp_path / "s.h5", "r") as f:
        _, stored = f["x"].id.read_direct_chunk((0, 0, 0))
    assert bytes(stored) == Pupwave(max_error=0.01).encode(data)
    assert np.array_equal(Pupwave(max_error=0.01).decode(stored).reshape(data.shape), f_read(tmp_path / "s.h5"))


@pytest.mark.parametrize("dtype", ["f4", "f8", "u2"])
def test_unaligned_chunk_codes_as_the_aligned_one(wmag91, dtype):
    """An aligned chunk is coded in place through a typed view, an unaligned one from a copy
    widened to double: the two paths give the same bytes."""
    data = wmag91[:24, :28, :32].astype(dtype) if dtype != "u2" else np.round(wmag91[:24, :28, :32] * 100).astype("u2")
    codec = Pupwave(lossless=True) if dtype == "u2" else Pupwave(max_error=0.01)
    unaligned = np.frombuffer(b"\0" + data.tobytes(), dtype=data.dtype, offset=1).reshape(data.shape)
    assert not unaligned.flags.aligned
    assert codec.encode(unaligned) == codec.encode(data)


def test_thread_count_never_changes_the_bytes(wmag91):
    """threads (None: all cores on the main thread, 1 elsewhere, as numcodecs' Blosc) is a
    runtime choice: the same bytes for any count, from any thread, and not in the config."""
    import concurrent.futures
    data = wmag91[:64, :64, :64].copy()
    reference = Pupwave(max_error=0.01, threads=0).encode(data)
    assert Pupwave(max_error=0.01, threads=1).encode(data) == reference
    assert "threads" not in Pupwave(max_error=0.01, threads=1).get_config()
    with concurrent.futures.ThreadPoolExecutor(2) as pool:  # worker threads take the 1-thread path
        coded = list(pool.map(lambda _: Pupwave(max_error=0.01).encode(data), range(2)))
        decoded = list(pool.map(lambda c: Pupwave(max_error=0.01).decode(c), coded))
    assert coded == [reference, reference]
    assert all(np.array_equal(d.reshape(data.shape), Pupwave(max_error=0.01).decode(reference).reshape(data.shape))
               for d in decoded)
    with pytest.raises(ValueError, match="threads"):
        Pupwave(max_error=0.01, threads=-1)


def f_read(path):
    import h5py
    with h5py.File(path, "r") as f:
        return f["x"][...]


def test_chunk_payload_is_the_pupwave_volume_stream(wmag91):
    """After the 4-byte header a coded chunk is a plain volume stream: the library's Python module
    (pupwave.decompress_volume, docs/api.md) decodes it to the codec's values."""
    import pupwave
    data = wmag91[:40, :50, :60].copy()
    stored = Pupwave(max_error=0.01).encode(data)
    assert stored[:4] == b"PW\x01\x05"  # kind 1 (volume stream), type 5 (float32)
    assert pupwave.info(stored[4:])["shape"] == data.shape
    assert np.array_equal(pupwave.decompress_volume(stored[4:]), Pupwave(max_error=0.01).decode(stored).reshape(data.shape))


@pytest.mark.parametrize("kwargs,dtype", [(dict(max_error=0.01), "f4"), (dict(bpv=2.0), "f4"), (dict(lossless=True), "u2")])
def test_chunk_payload_is_the_library_stream_but_for_the_grid_name(wmag91, kwargs, dtype):
    """The codec resolves max_error, bpv and lossless as the library's compress_volume does
    (transform, levels, bricks, bound): its payload is that stream but for the grid's name, 'chunk'
    (the library's is 'volume', one byte longer), so the coded grid has the same bytes count and
    decodes to the same values."""
    import re

    import pupwave
    data = wmag91[:40, :50, :60].copy()
    data = data if dtype == "f4" else (data * 1000).astype(dtype)
    payload = Pupwave(**kwargs).encode(data)[4:]
    stream = pupwave.compress_volume(data, **kwargs)
    assert len(stream) - len(payload) == len("volume") - len("chunk")
    ours, theirs = pupwave.info(payload), pupwave.info(stream)
    for key in ("transform", "levels", "lossless", "max_error", "shape", "dtype"):
        assert ours[key] == theirs[key], key
    grid_bytes = re.compile(r"; (\d+) bytes \(")  # the grid line's coded size, in `pupwave info`'s words
    assert grid_bytes.findall(ours["description"]) == grid_bytes.findall(theirs["description"])
    assert np.array_equal(pupwave.decompress_volume(payload), pupwave.decompress_volume(stream))


def test_damaged_chunks_are_refused_not_crashing(wmag91):
    """Flipped bytes and truncations anywhere in a chunk: a clean ValueError naming the chunk,
    never a crash (the stream's checks catch nearly all; a flip of the kind byte to "raw" cannot
    be caught here, the HDF5 filter then refuses the size, Zarr the shape)."""
    data = wmag91[:32, :32, :32].copy()
    codec = Pupwave(max_error=0.01)
    stored = codec.encode(data)
    refused = damaged_refusals(codec, stored, seed=3)
    assert refused >= 140
