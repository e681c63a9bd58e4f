"""The Pillow plugin (pupwave.pillow): Image.open reads .pw files made by the CLI and by save,
every mode round trips losslessly, draft and reduce decode stored resolution levels, save's
rate keywords (quality's PSNR mapping), and bad files and arguments."""

import io
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

import pupwave
from conftest import TESTIMAGES


def png(name):
    with Image.open(TESTIMAGES / f"{name}.png") as im:
        im.load()
        return im


def psnr(a, b, peak=255.0):
    mse = np.mean((np.asarray(a, np.float64) - np.asarray(b, np.float64)) ** 2)
    return 10 * np.log10(peak**2 / mse)


def saved(im, **kwargs):
    buffer = io.BytesIO()
    im.save(buffer, format="PUPWAVE", **kwargs)
    return buffer.getvalue()


def test_import_registers_the_format():
    assert Image.registered_extensions()[".pw"] == "PUPWAVE"
    assert Image.MIME["PUPWAVE"] == "image/x-pupwave"
    assert "PUPWAVE" in Image.OPEN and "PUPWAVE" in Image.SAVE


def test_opens_a_cli_lossless_file_with_the_png_pixels(cli, tmp_path):
    path = tmp_path / "astronaut.pw"
    subprocess.run([cli, "compress", "--lossless", "-q", str(TESTIMAGES / "astronaut.png"), str(path)], check=True)
    reference = png("astronaut")
    with Image.open(path) as im:
        assert im.format == "PUPWAVE" and im.get_format_mimetype() == "image/x-pupwave"
        assert im.mode == "RGB" and im.size == (512, 512)
        assert np.array_equal(np.asarray(im), np.asarray(reference))


def modes():
    """An image of every mode, from the real photographs (alpha and low bits from other ones)."""
    astronaut, camera = png("astronaut"), png("camera")  # both 512 x 512
    grey, red = np.asarray(camera), np.asarray(astronaut)[:, :, 0]
    return {
        "L": camera,
        "LA": Image.merge("LA", (camera, astronaut.getchannel("G"))),
        "RGB": astronaut,
        "RGBA": Image.merge("RGBA", (*astronaut.split(), camera)),
        "I;16": Image.fromarray(grey.astype(np.uint16) * 256 + red, "I;16"),
        "I": Image.fromarray(grey.astype(np.int32) * 100 - 20000, "I"),
        "1": camera.convert("1"),
    }


@pytest.mark.parametrize("mode", ["L", "LA", "RGB", "RGBA", "I;16", "I", "1"])
def test_lossless_save_and_open_keep_every_pixel(mode, tmp_path):
    im = modes()[mode]
    assert im.mode == mode
    path = tmp_path / "out.pw"  # format from the extension
    im.save(path, lossless=True)
    assert pupwave.info(path.read_bytes())["lossless"]
    with Image.open(path) as back:
        assert back.mode == mode and back.size == im.size
        assert np.array_equal(np.asarray(back), np.asarray(im))


def test_float_images_open_as_mode_f():
    camera = np.asarray(png("camera"), np.float32) / 255
    data = saved(Image.fromarray(camera, "F"), psnr=60)
    with Image.open(io.BytesIO(data)) as back:
        assert back.mode == "F"
        pixels = np.asarray(back)
    assert np.array_equal(pixels, pupwave.decompress(data))
    assert 0 < np.abs(pixels - camera).max() < 0.05
    half = pupwave.compress(camera.astype(np.float16), psnr=60)
    with Image.open(io.BytesIO(half)) as back:  # float16 samples are float32 values exactly
        assert back.mode == "F" and np.array_equal(np.asarray(back), pupwave.decompress(half).astype(np.float32))


def test_draft_and_reduce_decode_stored_levels():
    chelsea = png("chelsea")  # 451 x 300: odd sizes round up per level
    data = saved(chelsea, bpp=2)
    levels = pupwave.info(data)["levels"]
    assert levels >= 3
    for k, factor in [(1, 2), (2, 4)]:
        stored = pupwave.decompress(data, level=k)
        with Image.open(io.BytesIO(data)) as im:
            reduced = im.reduce(factor)
            assert reduced.mode == "RGB" and np.array_equal(np.asarray(reduced), stored)
            assert im.size == (451, 300)  # reduce leaves the opened image as it was
            wanted = (451 // factor, 300 // factor)
            assert im.draft("RGB", wanted) == ("RGB", (0, 0, 451 / factor, 300 / factor))
            assert im.size == (stored.shape[1], stored.shape[0]) and im.size >= wanted
            assert np.array_equal(np.asarray(im), stored)
    with Image.open(io.BytesIO(data)) as im:
        im.draft("RGB", (225, 150))
        assert np.array_equal(np.asarray(im.reduce(2)), pupwave.decompress(data, level=2))  # levels add up
    with Image.open(io.BytesIO(data)) as im:
        im.draft("RGB", (300, 200))  # 1.5x smaller: no level is that small and still as large
        assert im.size == (451, 300)
    with Image.open(io.BytesIO(data)) as im:
        assert im.draft(None, (100.0, 100.0)) == ("RGB", (0, 0, 451 / 2, 300 / 2))  # floats, as thumbnail asks
    with Image.open(io.BytesIO(data)) as im:
        im.thumbnail((50, 50))  # drafts at twice the size (Pillow's reducing gap), then resizes
        assert im.size == (50, 33)


def test_reduce_falls_back_to_pillow_where_no_level_matches():
    data = saved(png("camera"), bpp=2)
    with Image.open(io.BytesIO(data)) as im:
        im.load()
        assert im.draft("L", (64, 64)) is None and im.size == (512, 512)  # too late once loaded
        loaded = im.copy()
        pillow = Image.Image.reduce(loaded, 2)
        assert np.array_equal(np.asarray(im.reduce(2)), np.asarray(pillow))  # loaded pixels may be edited
    assert not np.array_equal(np.asarray(pillow), pupwave.decompress(data, level=1))
    with Image.open(io.BytesIO(data)) as im:
        assert np.array_equal(np.asarray(im.reduce(3)), np.asarray(Image.Image.reduce(loaded, 3)))
    lossless = saved(png("camera"), lossless=True)
    assert pupwave.info(lossless)["levels"] == 0  # no stored level to serve 1/2
    with Image.open(io.BytesIO(lossless)) as im:
        assert np.array_equal(np.asarray(im.reduce(2)), np.asarray(png("camera").reduce(2)))
    with Image.open(io.BytesIO(lossless)) as im:
        im.draft("L", (64, 64))
        assert im.size == (512, 512)


def test_save_rate_keywords():
    astronaut = png("astronaut")
    pixels = np.asarray(astronaut)
    data = saved(astronaut, bpp=1)
    assert len(data) * 8 <= 512 * 512
    with Image.open(io.BytesIO(data)) as im:
        assert im.size == (512, 512) and psnr(im, pixels) > 25
    assert saved(astronaut, psnr=36) == pupwave.compress(pixels, psnr=36)
    assert saved(astronaut) == pupwave.compress(pixels)  # pupwave's default, psnr 40
    sizes = [len(saved(astronaut, quality=q)) for q in (10, 30, 50, 70, 90)]
    assert sizes == sorted(sizes) and len(set(sizes)) == len(sizes)
    middle = saved(astronaut, quality=50)  # 25 + 30 * 49 / 98 = 40 dB
    assert middle == pupwave.compress(pixels, psnr=40)
    top = saved(astronaut, quality=100)
    assert pupwave.info(top)["lossless"] and np.array_equal(pupwave.decompress(top), pixels)


def test_missed_target_warns_and_writes():
    tiny = png("chelsea").crop((200, 100, 202, 102))  # 2x2: the header alone exceeds 1 bpp
    with pytest.warns(pupwave.PupwaveTargetWarning, match="--bpp 1 not met"):
        data = saved(tiny, bpp=1)
    assert pupwave.decompress(data).shape == (2, 2, 3)


def test_strict_save_raises_the_miss_naming_the_file_and_writes_nothing(tmp_path):
    tiny = png("chelsea").crop((200, 100, 202, 102))
    path = tmp_path / "tiny.pw"
    with pytest.raises(pupwave.PupwaveTargetError, match=r"tiny\.pw: --bpp 1 not met: the stream is \d+ bytes"):
        tiny.save(path, bpp=1, strict=True)
    assert not path.exists()
    astronaut = png("astronaut")  # a target met: strict changes nothing
    assert saved(astronaut, bpp=1, strict=True) == pupwave.compress(np.asarray(astronaut), bpp=1)


def test_bad_save_arguments_name_the_file(tmp_path):
    camera = png("camera")
    path = tmp_path / "bad.pw"
    for kwargs, message in [({"bpp": 1, "quality": 50}, "at most one of bpp, psnr, lossless, quality"),
                            ({"psnr": 40, "lossless": True}, "at most one"), ({"quality": 0}, "1..100"),
                            ({"quality": 101}, "1..100"), ({"quality": "high"}, "1..100"),
                            ({"bpp": -1}, "rate target")]:
        with pytest.raises(ValueError, match=message) as error:
            camera.save(path, **kwargs)
        assert str(path) in str(error.value) and not path.exists()
    with pytest.raises(OSError, match=r"bad\.pw: cannot write mode P as PUPWAVE"):
        camera.convert("P").save(path)
    with pytest.raises(ValueError, match="lossless"):
        Image.fromarray(np.ones((8, 8), np.float32), "F").save(path, lossless=True)


def test_bad_files_raise_naming_the_file_and_problem(tmp_path):
    data = saved(png("camera"), bpp=1)
    cases = {
        "flipped.pw": (data[:60] + bytes([data[60] ^ 4]) + data[61:], "checksum mismatch"),
        "truncated.pw": (data[: len(data) // 2], "truncated"),
        "volume.pw": (pupwave.compress_volume(np.zeros((8, 8, 8), np.float32)), "volume stream, not an image"),
        "colour16.pw": (pupwave.compress(np.zeros((8, 8, 3), np.uint16), lossless=True),
                        r"3 channel\(s\) of uint16 has no exact Pillow mode"),
        "five.pw": (pupwave.compress(np.zeros((8, 8, 5), np.uint8), lossless=True), "5 channel"),
    }
    for name, (content, message) in cases.items():
        path = tmp_path / name
        path.write_bytes(content)
        with pytest.raises(OSError, match=message) as error:
            Image.open(path)
        assert str(error.value).startswith(f"{path}: ")
    with pytest.raises(OSError, match=r"^<stream>: .*truncated"):
        Image.open(io.BytesIO(data[:20]))


def test_pupwave_imports_without_pillow():
    script = ("import sys; sys.modules['PIL'] = None\n"  # makes `import PIL` fail as if absent
              "import numpy as np, pupwave\n"
              "assert 'pupwave.pillow' not in sys.modules\n"
              "assert pupwave.decompress(pupwave.compress(np.eye(8, dtype=np.uint8), lossless=True)).sum() == 8\n")
    subprocess.run([sys.executable, "-c", script], check=True)
