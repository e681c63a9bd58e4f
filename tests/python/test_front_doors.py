"""One image and one set of options give the same .pw bytes from Python as from the CLI, on the
test photographs (the C and C++ APIs: tests/api/front_doors_test.cpp). Python's defaults are the
library's: no transform given means cdf97, or cdf53 for lossless, as the CLI."""

import subprocess

import pytest

import pupwave
from conftest import TESTIMAGES

# (CLI flags, the same as pupwave.compress keywords)
OPTION_SETS = [
    ([], {}),
    (["--bpp", "1"], {"bpp": 1}),
    (["--bpp", "0.5", "--entropy", "ebcot", "--effort", "2"], {"bpp": 0.5, "entropy": "ebcot", "effort": 2}),
    (["--lossless"], {"lossless": True}),
    (["--lossless", "--entropy", "ebcot"], {"lossless": True, "entropy": "ebcot"}),
    (["--psnr", "35", "--transform", "cdf53"], {"psnr": 35, "transform": "cdf53"}),
    (["--levels", "3", "--bpp", "1"], {"levels": 3, "bpp": 1}),
    (["--entropy", "ht", "--bpp", "1"], {"entropy": "ht", "bpp": 1}),
    (["--bpp", "0.5", "--tune", "visual"], {"bpp": 0.5, "tune": "visual"}),
    (["--psnr", "33", "--entropy", "ebcot", "--tune", "visual"], {"psnr": 33, "entropy": "ebcot", "tune": "visual"}),
]
PHOTOGRAPHS = [("camera", "pgm"), ("astronaut", "ppm"), ("chelsea", "ppm"), ("coffee", "ppm")]


@pytest.mark.parametrize("name,ext", PHOTOGRAPHS)
def test_same_options_same_bytes_as_the_cli(cli, real_image, tmp_path, name, ext):
    image = real_image(name, ext)
    out = tmp_path / f"{name}.pw"
    for flags, kwargs in OPTION_SETS:
        subprocess.run([cli, "compress", str(TESTIMAGES / f"{name}.png"), str(out), "-q", *flags], check=True,
                       capture_output=True)
        assert pupwave.compress(image, **kwargs) == out.read_bytes(), flags


def test_an_irreversible_transform_for_lossless_is_refused_as_by_the_cli(cli, real_image, tmp_path):
    out = tmp_path / "camera.pw"
    r = subprocess.run([cli, "compress", str(TESTIMAGES / "camera.png"), str(out), "--lossless", "--transform",
                        "cdf97"], capture_output=True, text=True)
    assert r.returncode != 0 and "reversible" in r.stderr and not out.exists()
    with pytest.raises(ValueError, match="reversible"):
        pupwave.compress(real_image("camera", "pgm"), lossless=True, transform="cdf97")
