"""The pip-installed package (pyproject.toml, setup.py): its metadata, and the numcodecs entry
point through which Zarr and Dask find the codec "pupwave" in processes that never import
pupwave. Every test needs the installed distribution (the `installed` fixture)."""

import json
import pathlib
import re

import numpy as np
import pytest

from conftest import ROOT, TESTIMAGES, run_python

numcodecs = pytest.importorskip("numcodecs")
zarr = pytest.importorskip("zarr")

# One codec config per rate option of pupwave.numcodecs.Pupwave (a bound in wmag91's units).
MAX_ERROR, BPV = 0.01, 2.0
CONFIGS = [
    {"id": "pupwave", "max_error": MAX_ERROR, "bpv": None, "lossless": False},
    {"id": "pupwave", "max_error": None, "bpv": BPV, "lossless": False},
    {"id": "pupwave", "max_error": None, "bpv": None, "lossless": True},
]
CHUNKS = (48, 48, 48)
# Stored bytes of a chunk beyond bpv bits per value: the chunk and stream headers.
HEADER_BYTES = 64


@pytest.fixture(scope="module")
def wmag91():
    """The 91^3 float32 wind-magnitude field (testimages/README.md), (z, y, x)."""
    return np.fromfile(TESTIMAGES / "wmag91.float", dtype="<f4").reshape(91, 91, 91)


def data_for(config, wmag91):
    """wmag91 for the lossy modes; for lossless (integers only), its values scaled to uint16."""
    if not config["lossless"]:
        return wmag91
    scaled = (wmag91 - wmag91.min()) / (wmag91.max() - wmag91.min()) * 65535
    return np.round(scaled).astype(np.uint16)


def check_rate(config, data, back, store):
    """The rate option's promise: max_error on every value, bpv on every stored chunk, lossless exact."""
    if config["max_error"] is not None:
        assert np.abs(back.astype(np.float64) - data).max() <= config["max_error"]
    elif config["bpv"] is not None:
        chunk_files = [f for f in pathlib.Path(store).iterdir() if re.fullmatch(r"\d+\.\d+\.\d+", f.name)]
        assert len(chunk_files) == 8
        budget = config["bpv"] * np.prod(CHUNKS) / 8 + HEADER_BYTES
        assert max(f.stat().st_size for f in chunk_files) <= budget
        assert np.abs(back.astype(np.float64) - data).max() < 0.1 * (data.max() - data.min())
    else:
        assert np.array_equal(back, data)


def test_metadata_is_the_projects(installed):
    import pupwave

    cmake_version = re.search(r"project\(pupwave VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)
    assert installed.version == cmake_version == pupwave.__version__
    assert installed.metadata["Name"] == "pupwave"
    assert "wavelet codec" in installed.metadata["Summary"].lower()
    assert installed.metadata["License"]
    assert "numpy" in installed.requires


@pytest.mark.parametrize("config", CONFIGS, ids=["max_error", "bpv", "lossless"])
def test_get_codec_finds_the_entry_point_in_a_new_process(installed, config):
    out = run_python("import json, sys, numcodecs\n"
                     "assert 'pupwave' not in sys.modules\n"
                     "codec = numcodecs.get_codec(json.loads(sys.argv[1]))\n"
                     "print(type(codec).__module__, type(codec).__name__)\n"
                     "print(json.dumps(codec.get_config()))", json.dumps(config))
    name, config_back = out.splitlines()
    assert name == "pupwave.numcodecs Pupwave"
    assert json.loads(config_back) == config


@pytest.mark.parametrize("config", CONFIGS, ids=["max_error", "bpv", "lossless"])
def test_config_round_trips_through_json(installed, config):
    from pupwave.numcodecs import Pupwave

    codec = Pupwave(**{k: v for k, v in config.items() if k != "id"})
    again = numcodecs.get_codec(json.loads(json.dumps(codec.get_config())))
    assert isinstance(again, Pupwave) and again.get_config() == codec.get_config() == config


@pytest.mark.parametrize("config", CONFIGS, ids=["max_error", "bpv", "lossless"])
def test_zarr_array_reads_back_in_a_process_that_never_imports_pupwave(installed, config, wmag91, tmp_path):
    data = data_for(config, wmag91)
    store = tmp_path / "w.zarr"
    z = zarr.open(str(store), mode="w", shape=data.shape, chunks=CHUNKS, dtype=data.dtype,
                  compressor=numcodecs.get_codec(config))
    z[...] = data
    run_python("import sys, numpy as np, zarr\n"
               "assert 'pupwave' not in sys.modules\n"
               "z = zarr.open(sys.argv[1], mode='r')\n"
               "np.save(sys.argv[2], z[...])\n"
               "assert type(z.compressor).__module__ == 'pupwave.numcodecs'", store, tmp_path / "back.npy")
    back = np.load(tmp_path / "back.npy")
    assert back.dtype == data.dtype and back.shape == data.shape
    check_rate(config, data, back, store)


def test_dask_processes_write_and_read_zarr_through_the_entry_point(installed, wmag91, tmp_path):
    """da.to_zarr on a LocalCluster of two worker processes: the client names the codec by its
    config only, the workers rebuild it from .zarray (the entry point), and da.from_zarr reads it
    back within the bound."""
    pytest.importorskip("distributed")
    np.save(tmp_path / "in.npy", wmag91)
    out = run_python(
        "import sys, json, numpy as np, numcodecs, dask.array as da\n"
        "from distributed import Client, LocalCluster\n"
        "if __name__ == '__main__':\n"
        "    assert 'pupwave' not in sys.modules\n"
        "    data, store, config = np.load(sys.argv[1]), sys.argv[2], json.loads(sys.argv[3])\n"
        "    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \\\n"
        "            Client(cluster) as client:\n"
        "        da.to_zarr(da.from_array(data, chunks=48), store, compressor=numcodecs.get_codec(config))\n"
        "        back = da.from_zarr(store).compute()\n"
        "        loaded = client.run(lambda: 'pupwave.numcodecs' in sys.modules)\n"
        "    print(float(np.abs(back.astype(np.float64) - data).max()), sorted(loaded.values()))",
        tmp_path / "in.npy", tmp_path / "d.zarr", json.dumps(CONFIGS[0]))
    error, loaded = out.split(" ", 1)
    assert float(error) <= MAX_ERROR
    assert loaded.strip() == "[True, True]"
    assert zarr.open(str(tmp_path / "d.zarr"), mode="r").nbytes_stored < wmag91.nbytes / 2


def value_range(data):
    return [float(data.min()), float(data.max())]


def relative_configs(data):
    """The codec's max_error_rel and psnr configs for `data` (its whole range as value_range)."""
    base = {"id": "pupwave", "max_error": None, "bpv": None, "lossless": False, "value_range": value_range(data)}
    return {"max_error_rel": {**base, "max_error_rel": 1e-3}, "psnr": {**base, "psnr": 60.0}}


def chunk_slices(shape, chunks):
    """The slices of every chunk of an array of `shape` cut in `chunks`."""
    import itertools

    starts = itertools.product(*(range(0, n, c) for n, c in zip(shape, chunks)))
    return [tuple(slice(s, min(s + c, n)) for s, c, n in zip(start, chunks, shape)) for start in starts]


def psnr(reference, test, peak):
    mse = np.mean((test.astype(np.float64) - reference) ** 2)
    return np.inf if mse == 0 else 10 * np.log10(peak**2 / mse)


def check_relative(option, config, data, back, chunks):
    """max_error_rel: every value within max_error_rel * (hi - lo); psnr: every chunk at or above it."""
    lo, hi = config["value_range"]
    for part in chunk_slices(data.shape, chunks):
        if option == "max_error_rel":
            assert np.abs(back[part].astype(np.float64) - data[part]).max() <= config["max_error_rel"] * (hi - lo)
        else:
            assert psnr(data[part], back[part], hi - lo) >= config["psnr"]
    if option == "psnr":  # the bound is guaranteed, not a waste: the array lands within 10 dB of it
        assert psnr(data, back, hi - lo) < config["psnr"] + 10


@pytest.fixture(scope="module")
def camera_float(real_image):
    """testimages/camera.png (a photograph, 512x512 grey) as float32 in 0..1: an image for the codec."""
    return real_image("camera", "pgm").astype(np.float32) / 255


@pytest.mark.parametrize("option", ["max_error_rel", "psnr"])
@pytest.mark.parametrize("kind", ["volume", "image"])
def test_range_options_hold_on_every_chunk_read_in_a_new_process(installed, option, kind, wmag91, camera_float,
                                                                 tmp_path):
    data, chunks = (wmag91, CHUNKS) if kind == "volume" else (camera_float, (200, 200))
    config = relative_configs(data)[option]
    store = tmp_path / "r.zarr"
    z = zarr.open(str(store), mode="w", shape=data.shape, chunks=chunks, dtype=data.dtype,
                  compressor=numcodecs.get_codec(config))
    z[...] = data
    out = run_python("import sys, json, numpy as np, zarr\n"
                     "assert 'pupwave' not in sys.modules\n"
                     "z = zarr.open(sys.argv[1], mode='r')\n"
                     "np.save(sys.argv[2], z[...])\n"
                     "print(json.dumps(z.compressor.get_config()))", store, tmp_path / "back.npy")
    assert json.loads(out) == config  # the stored config, JSON, as given
    back = np.load(tmp_path / "back.npy")
    assert back.dtype == data.dtype and back.shape == data.shape
    check_relative(option, config, data, back, chunks)
    assert z.nbytes_stored < data.nbytes / 2


def test_range_options_need_a_value_range_and_one_rate(installed):
    from pupwave.numcodecs import Pupwave

    for kwargs, message in [({"max_error_rel": 1e-3}, "max_error_rel needs value_range"),
                            ({"psnr": 50}, "psnr needs value_range"),
                            ({"psnr": 50, "value_range": (1, 1)}, "lo < hi"),
                            ({"psnr": 50, "value_range": (0, float("nan"))}, "lo < hi"),
                            ({"max_error_rel": -1, "value_range": (0, 1)}, "finite positive"),
                            ({"psnr": 50, "max_error_rel": 1e-3, "value_range": (0, 1)}, "exactly one"),
                            ({"psnr": 50, "max_error": 0.1, "value_range": (0, 1)}, "exactly one"),
                            ({"max_error": 0.1, "value_range": (0, 1)}, "value_range goes with")]:
        with pytest.raises(ValueError, match=message):
            Pupwave(**kwargs)


def test_range_configs_round_trip_and_old_configs_stay(installed, wmag91):
    from pupwave.numcodecs import Pupwave

    for config in relative_configs(wmag91).values():
        codec = numcodecs.get_codec(json.loads(json.dumps(config)))
        assert isinstance(codec, Pupwave) and codec.get_config() == config
    assert Pupwave(max_error=0.5).get_config() == {"id": "pupwave", "max_error": 0.5, "bpv": None, "lossless": False}
