"""numpy's other dtypes (pupwave/dtypes.py): float64, wide and signed integers and bool round trip to
their own dtype on real photographs and wmag91, targets hold in the input's units, values that do
not fit are refused, and the recorded dtype leaves the stream readable by the CLI."""

import subprocess

import numpy as np
import pytest

import pupwave
from conftest import read_pnm


def psnr(reference, test, peak):
    err = np.asarray(test, np.float64) - np.asarray(reference, np.float64)
    return 10 * np.log10(peak**2 / np.mean(err**2))


@pytest.mark.parametrize("name,ext", [("camera", "pgm"), ("chelsea", "ppm")])
def test_float64_photograph_round_trip(real_image, name, ext):
    a = real_image(name, ext).astype(np.float64) / 255  # numpy's default dtype, values in [0, 1]
    for target in (30, 40):
        data = pupwave.compress(a, psnr=target)
        back = pupwave.decompress(data)
        assert back.dtype == np.float64 and back.shape == a.shape
        assert psnr(a, back, 1.0) >= target, target  # measured on the float64 values, peak 1
        assert 0 < np.abs(back - a).max() < 0.5
    assert pupwave.info(data)["dtype"] == "float64" and pupwave.info(data)["stored_dtype"] == "float32"
    # float64 goes through float32 exactly as a float32 array would, plus the recorded dtype.
    same = pupwave.decompress(pupwave.compress(a.astype(np.float32), psnr=40))
    assert np.array_equal(back.astype(np.float32), same)
    assert pupwave.decompress(data, level=1).dtype == np.float64


@pytest.mark.parametrize("dtype", [np.int32, np.int64, np.uint32, np.int16])
def test_integer_photograph_round_trip(real_image, dtype):
    a = real_image("chelsea", "ppm").astype(dtype)
    back = pupwave.decompress(pupwave.compress(a, lossless=True))
    assert back.dtype == dtype and back.shape == a.shape and np.array_equal(back, a)
    lossy = pupwave.decompress(pupwave.compress(a, psnr=38))
    assert lossy.dtype == dtype and psnr(a, lossy, 255) >= 38 - 0.05  # values 0..255: stored uint8, peak 255
    # The same samples code to the same stream as uint8, plus the recorded dtype.
    assert np.array_equal(lossy, pupwave.decompress(pupwave.compress(a.astype(np.uint8), psnr=38)))
    wide = (a.astype(np.int64) * 128 + 3).astype(dtype)  # 3..32643: stored uint16 (fits int16 too)
    data = pupwave.compress(wide, lossless=True)
    assert pupwave.info(data)["stored_dtype"] == "uint16" and pupwave.info(data)["dtype"] == np.dtype(dtype).name
    assert np.array_equal(pupwave.decompress(data), wide) and pupwave.decompress(data).dtype == dtype


def test_lossy_narrow_integers_are_clamped_not_wrapped(real_image):
    a = (real_image("camera", "pgm") // 2).astype(np.int8)  # 0..127
    assert a.max() == 127
    back = pupwave.decompress(pupwave.compress(a, psnr=25))
    assert back.dtype == np.int8 and back.min() >= 0 and back.max() == 127  # 128..255 would wrap negative
    assert psnr(a, back, 255) >= 25 - 0.05


def test_bool_mask_round_trip(real_image):
    mask = real_image("camera", "pgm") > 100
    back = pupwave.decompress(pupwave.compress(mask, lossless=True))
    assert back.dtype == np.bool_ and np.array_equal(back, mask)
    lossy = pupwave.decompress(pupwave.compress(mask, psnr=30))
    assert lossy.dtype == np.bool_ and np.mean(lossy != mask) < 0.01


def test_big_endian_round_trip(real_image):
    a = (real_image("camera", "pgm").astype(np.uint16) * 200).astype(">u2")
    back = pupwave.decompress(pupwave.compress(a, lossless=True))
    assert back.dtype == np.dtype(">u2") and np.array_equal(back, a)


def test_signed_photograph_is_coded_less_its_minimum(real_image):
    a = real_image("chelsea", "ppm")
    signed = a.astype(np.int16) - 128  # -128..127: stored as uint8 less -128
    data = pupwave.compress(signed, lossless=True)
    back = pupwave.decompress(data)
    assert back.dtype == np.int16 and np.array_equal(back, signed)
    assert pupwave.info(data)["stored_dtype"] == "uint8"
    assert pupwave.info(data)["attributes"] == {"pupwave:dtype": "<i2", "pupwave:offset": "-128"}
    # Lossy: the very samples of the uint8 photograph, shifted back.
    lossy = pupwave.decompress(pupwave.compress(signed, psnr=36))
    assert np.array_equal(lossy, pupwave.decompress(pupwave.compress(a, psnr=36)).astype(np.int16) - 128)
    far = a.astype(np.int64) + 2**40  # beyond 0..65535 and every 32-bit type
    assert np.array_equal(pupwave.decompress(pupwave.compress(far, lossless=True)), far)


def test_signed_volume_bound_in_its_units(wmag):
    ct = np.round(wmag * 50 - 1024).astype(np.int16)  # signed, like CT data: -1022..12241
    assert ct.min() < 0 and ct.max() > 255
    back = pupwave.decompress_volume(pupwave.compress_volume(ct))  # integers default to lossless
    assert back.dtype == np.int16 and np.array_equal(back, ct)
    for bound in (1, 4):
        back = pupwave.decompress_volume(pupwave.compress_volume(ct, max_error=bound))
        worst = np.abs(back.astype(np.int64) - ct).max()
        assert back.dtype == np.int16 and 0 < worst <= bound, bound


def test_values_that_do_not_fit_are_refused(real_image):
    a = real_image("camera", "pgm")
    big = a.astype(np.float64)
    big[10, 20] = 1e39  # finite in float64, infinite in float32
    with pytest.raises(ValueError, match=r"float64 image values must lie within \+-3.40.*e\+38.*1e\+39"):
        pupwave.compress(big)
    with pytest.raises(ValueError, match=r"int32 image values must span at most 65535 .*holds -5\.\.70000"):
        pupwave.compress(np.where(a > 200, 70000, a.astype(np.int32) - 5), lossless=True)
    with pytest.raises(ValueError, match=r"int64 image values must span at most 65535 .*holds 0\.\.70000"):
        pupwave.compress(np.where(a > 200, 70000, 0).astype(np.int64), psnr=30)
    with pytest.raises(TypeError, match="complex128"):
        pupwave.compress(a.astype(np.complex128))
    wide = np.full((4, 4, 4), -32768, np.int32)
    wide[1, 2, 3] = 32768
    with pytest.raises(ValueError, match=r"int32 volume values must span at most 65535 .*holds -32768\.\.32768"):
        pupwave.compress_volume(wide)
    with pytest.raises(ValueError):  # NaN is still refused by the codec, as for float32
        pupwave.compress(np.full((8, 8), np.nan))


def test_volume_dtypes(wmag):
    v = wmag[:24, :32, :40]
    ints = (v * 100).astype(np.int32)  # 0..~26000: stored uint16
    data = pupwave.compress_volume(ints)  # integers default to lossless
    back = pupwave.decompress_volume(data)
    assert back.dtype == np.int32 and np.array_equal(back, ints)
    assert pupwave.info(data)["dtype"] == "int32" and pupwave.info(data)["stored_dtype"] == "uint16"
    mask = v > np.median(v)
    assert np.array_equal(pupwave.decompress_volume(pupwave.compress_volume(mask)), mask)


def test_float64_volume_bound_in_float64(wmag):
    field = np.sqrt(wmag.astype(np.float64))  # float64 values float32 cannot hold
    for bound in (1e-3, 1e-4):
        back = pupwave.decompress_volume(pupwave.compress_volume(field, max_error=bound))
        assert back.dtype == np.float64 and 0 < np.abs(back - field).max() <= bound, bound


def test_float16_volume_bound_after_rounding_back(wmag):
    half = wmag.astype(np.float16)  # values up to ~256: float16 steps of up to 0.25
    for kwargs, bound in [({"max_error": 0.1}, 0.1), ({"max_error": 0.3}, 0.3),
                          ({}, 1e-3 * np.ptp(half.astype(np.float64)))]:
        data = pupwave.compress_volume(half, **kwargs)
        back = pupwave.decompress_volume(data)
        worst = np.abs(back.astype(np.float64) - half.astype(np.float64)).max()
        assert back.dtype == np.float16 and 0 < worst <= bound, kwargs
        assert pupwave.info(data)["max_error"] == pytest.approx(bound / 2)  # coded to half the bound


def test_streams_without_the_record_and_the_cli(cli, real_image, tmp_path):
    a = real_image("chelsea", "ppm")
    plain = pupwave.compress(a, bpp=1)
    assert pupwave.info(plain)["attributes"] == {} and pupwave.info(plain)["dtype"] == "uint8"
    data = pupwave.compress(a.astype(np.int64), lossless=True)
    assert pupwave.info(data)["attributes"] == {"pupwave:dtype": "<i8"}
    src = tmp_path / "int64.pw"
    src.write_bytes(data)
    out = tmp_path / "out.ppm"
    subprocess.run([cli, "decompress", str(src), str(out)], check=True, capture_output=True)
    assert np.array_equal(read_pnm(out), a)  # the CLI decodes the stored uint8 samples
    # A record this module does not write (here: float64 for uint8 samples) is refused.
    odd, _ = pupwave._pupwave.compress(a, lossless=True, attributes={"pupwave:dtype": "<f8"})
    with pytest.raises(ValueError, match="pupwave:dtype"):
        pupwave.decompress(odd)
