"""One volume and one set of options give the same .pw bytes from Python as from the CLI, on the
real float field testimages/wmag91.float and on the same field in hundredths as uint16 (the C and
C++ APIs: tests/api/volume_front_doors_test.cpp). With no rate argument both code integer volumes
lossless and float ones within 1e-3 of the value range."""

import subprocess

import numpy as np
import pytest

import pupwave
from conftest import TESTIMAGES

# (CLI flags, the same as pupwave.compress_volume keywords): every rate mode, and a transform,
# levels and brick edge that are not the defaults.
RATE_SETS = [
    ([], {}),
    (["--max-error", "0.5"], {"max_error": 0.5}),
    (["--max-error-rel", "1e-4"], {"max_error_rel": 1e-4}),
    (["--bpv", "1.5"], {"bpv": 1.5}),
    (["--psnr", "55"], {"psnr": 55}),
    (["--step", "0.25"], {"step": 0.25}),
    (["--bpv", "1.5", "--transform", "cdf53", "--levels", "2", "--brick", "32"],
     {"bpv": 1.5, "transform": "cdf53", "levels": 2, "brick": 32}),
]


def wmag91():
    return np.fromfile(TESTIMAGES / "wmag91.float", dtype="<f4").reshape(91, 91, 91)


@pytest.mark.parametrize("dtype", ["f32", "u16"])
def test_same_options_same_bytes_as_the_cli(cli, tmp_path, dtype):
    field = wmag91() if dtype == "f32" else np.round(wmag91().astype(np.float64) * 100).astype(np.uint16)
    sets = RATE_SETS + ([(["--lossless"], {"lossless": True})] if dtype == "u16" else [])
    raw = tmp_path / f"volume.{dtype}"  # the CLI names the grid by the stem, as the library: "volume"
    field.tofile(raw)
    out = tmp_path / "cli.pw"
    for flags, kwargs in sets:
        subprocess.run([cli, "compress", str(raw), str(out), "-q", "--dims", "91,91,91", "--dtype", dtype, *flags],
                       check=True, capture_output=True)
        assert pupwave.compress_volume(field, **kwargs) == out.read_bytes(), (dtype, flags)


def test_the_default_is_lossless_for_integers():
    field = np.round(wmag91().astype(np.float64) * 100).astype(np.uint16)
    assert pupwave.info(pupwave.compress_volume(field))["lossless"]
    assert not pupwave.info(pupwave.compress_volume(wmag91()))["lossless"]


def test_the_float_default_is_the_librarys_relative_bound():
    field = wmag91()
    assert pupwave.compress_volume(field) == pupwave.compress_volume(
        field, max_error_rel=pupwave._pupwave.DEFAULT_MAX_ERROR_REL)
    bound = pupwave.info(pupwave.compress_volume(field))["max_error"]
    assert bound == pytest.approx(1e-3 * np.ptp(field.astype(np.float64)))


def test_rate_options_change_the_stream_as_asked():
    field = wmag91()
    fine, coarse = pupwave.compress_volume(field, step=0.05), pupwave.compress_volume(field, step=0.5)
    assert len(fine) > len(coarse)
    back = pupwave.decompress_volume(pupwave.compress_volume(field, psnr=55))
    peak = np.ptp(field.astype(np.float64))
    assert 10 * np.log10(peak**2 / np.mean((back.astype(np.float64) - field) ** 2)) > 54
    described = pupwave.info(pupwave.compress_volume(field, bpv=1.5, transform="cdf53", levels=2, brick=32))
    assert described["transform"] == "cdf53" and described["levels"] == 2
    with pytest.raises(ValueError, match="at most one of max_error, max_error_rel, bpv, psnr, step and lossless"):
        pupwave.compress_volume(field, psnr=50, step=1)
    with pytest.raises(ValueError, match="brick"):
        pupwave.compress_volume(field, brick=12)
