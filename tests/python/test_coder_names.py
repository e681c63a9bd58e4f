"""One set of entropy-coder names: Python's entropy=, the CLI's --entropy (and the C API's
PUPWAVE_CODER_*, tests/api/c_api_test.c) name the same coders, and the same name gives the same
bytes from Python as from the CLI on a real photograph."""

import subprocess

import pytest

import pupwave
from conftest import TESTIMAGES


@pytest.mark.parametrize("name,rate", [("auto", ["--bpp", "1"]), ("ebcot", ["--bpp", "1"]), ("pc", ["--bpp", "1"]),
                                       ("ht", ["--bpp", "1"]), ("lc", ["--lossless"]),
                                       ("auto", ["--lossless"])])
def test_same_name_same_bytes_as_the_cli(cli, real_image, tmp_path, name, rate):
    out = tmp_path / "camera.pw"
    subprocess.run([cli, "compress", str(TESTIMAGES / "camera.png"), str(out), "--entropy", name, "-q", *rate],
                   check=True, capture_output=True)
    kwargs = {"lossless": True} if rate == ["--lossless"] else {"bpp": 1}
    assert pupwave.compress(real_image("camera", "pgm"), entropy=name, **kwargs) == out.read_bytes()


def test_names_are_case_blind_and_unknown_ones_are_listed(cli, real_image, tmp_path):
    a = real_image("camera", "pgm")
    assert pupwave.compress(a, bpp=1, entropy="PC") == pupwave.compress(a, bpp=1, entropy="pc")
    with pytest.raises(ValueError, match="auto, ebcot, pc, lc, ht"):
        pupwave.compress(a, bpp=1, entropy="jpeg")
    with pytest.raises(ValueError, match="auto, ebcot, pc, lc, ht, got zstd"):  # a retired coder
        pupwave.compress(a, bpp=1, entropy="zstd")
    r = subprocess.run([cli, "compress", str(TESTIMAGES / "camera.png"), str(tmp_path / "x.pw"), "--entropy", "jpeg"],
                       capture_output=True, text=True)
    assert r.returncode != 0 and "auto, ebcot, pc, lc, ht" in r.stderr
    assert not (tmp_path / "x.pw").exists()
