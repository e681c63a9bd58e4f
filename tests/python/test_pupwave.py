"""The Python module: round trips of every dtype, bit-exact lossless, the max-error bound on a
real volume, bytes identical to the CLI's, levels, info, threads, and bad input."""

import subprocess
import threading

import numpy as np
import pytest

import pupwave
from conftest import write_pnm


def smooth(shape, dtype, scale):
    y, x = np.mgrid[0 : shape[0], 0 : shape[1]]
    base = 0.5 + 0.4 * np.sin(x / 7.0) * np.cos(y / 5.0)
    planes = [base * (0.8 + 0.1 * c) for c in range(shape[2])] if len(shape) == 3 else [base]
    a = np.stack(planes, axis=-1) if len(shape) == 3 else base
    return (a * scale).astype(dtype)


@pytest.mark.parametrize("dtype,scale", [("uint8", 255), ("uint16", 65535), ("float16", 1.0), ("float32", 1.0)])
@pytest.mark.parametrize("shape", [(37, 50), (40, 33, 3), (24, 31, 4), (20, 22, 2)])
def test_round_trip_every_dtype(dtype, scale, shape):
    a = smooth(shape, dtype, scale)
    data = pupwave.compress(a, psnr=50)
    assert isinstance(data, bytes)
    b = pupwave.decompress(data)
    assert b.dtype == a.dtype and b.shape == a.shape
    err = np.abs(b.astype(np.float64) - a.astype(np.float64)).max()
    assert 0 <= err < 0.05 * scale
    info = pupwave.info(data)
    assert info["kind"] == "image" and info["dtype"] == dtype and info["shape"] == a.shape


@pytest.mark.parametrize("name,ext", [("camera", "pgm"), ("chelsea", "ppm")])
def test_lossless_is_bit_exact_on_real_images(real_image, name, ext):
    a = real_image(name, ext)
    data = pupwave.compress(a, lossless=True)
    assert len(data) < a.nbytes
    assert np.array_equal(pupwave.decompress(data), a)
    assert pupwave.info(data)["lossless"]
    wide = a.astype(np.uint16) * 257 + 3
    assert np.array_equal(pupwave.decompress(pupwave.compress(wide, lossless=True)), wide)


def test_rate_modes_and_levels(real_image):
    a = real_image("chelsea", "ppm")
    low, high = pupwave.compress(a, bpp=0.25), pupwave.compress(a, bpp=2)
    assert len(low) * 8 <= 0.25 * a.shape[0] * a.shape[1] + 64 < len(high) * 8
    assert len(pupwave.compress(a, step=4.0)) > len(pupwave.compress(a, step=16.0))
    err = pupwave.decompress(pupwave.compress(a, psnr=38)).astype(float) - a
    assert 10 * np.log10(255**2 / np.mean(err**2)) >= 38 - 0.05
    half = pupwave.decompress(high, level=1)
    assert half.shape == ((a.shape[0] + 1) // 2, (a.shape[1] + 1) // 2, 3)
    assert half.dtype == np.uint8
    assert pupwave.compress(a, bpp=1, transform="cdf53", levels=3) != pupwave.compress(a, bpp=1)
    assert pupwave.info(pupwave.compress(a, bpp=1, levels=3))["levels"] == 3
    # The default coder of a photograph this size is pc; effort 2 is the bit-plane coder's search.
    coder = 5 + 8 + 15  # the entropy coder's byte in the header (docs/bitstream.md): 4 pc, 0 ebcot
    assert pupwave.compress(a, bpp=1)[coder] == 4
    assert pupwave.compress(a, bpp=1) == pupwave.compress(a, bpp=1, entropy="pc")
    slow = pupwave.compress(a, bpp=1, effort=2, entropy="ebcot")
    assert len(slow) * 8 <= a.shape[0] * a.shape[1] + 64 and slow != pupwave.compress(a, bpp=1, entropy="ebcot")
    assert slow[coder] == 0
    with pytest.raises(ValueError, match="ebcot"):
        pupwave.compress(a, bpp=1, effort=2)
    with pytest.raises(ValueError, match="entropy"):
        pupwave.compress(a, bpp=1, entropy="jpeg")
    with pytest.raises(ValueError, match="effort"):
        pupwave.compress(a, bpp=1, effort=3, entropy="ebcot")
    visual = pupwave.compress(a, bpp=1, tune="visual")
    assert len(visual) * 8 <= a.shape[0] * a.shape[1] and visual != pupwave.compress(a, bpp=1)
    with pytest.raises(ValueError, match="tune"):
        pupwave.compress(a, bpp=1, tune="sharp")


def test_image_bytes_identical_to_cli(cli, real_image, tmp_path):
    a = real_image("chelsea", "ppm")
    src = tmp_path / "in.ppm"
    write_pnm(src, a)
    for flags, kwargs in [(["--bpp", "1"], {
  "bpp" : 1}), (["--lossless"], {
  "lossless" : True}),
                          (["--psnr", "36", "--levels", "4"], {
  "psnr" : 36, "levels" : 4})]:
        out = tmp_path / "cli.pw"
        subprocess.run([cli, "compress", str(src), str(out), *flags], check=True, capture_output=True)
        assert out.read_bytes() == pupwave.compress(a, **kwargs), flags


def test_volume_max_error_on_wmag91(wmag):
    for bound in (0.5,):
        data = pupwave.compress_volume(wmag, max_error=bound)
        back = pupwave.decompress_volume(data)
        assert back.dtype == np.float32 and back.shape == wmag.shape
        worst = np.abs(back.astype(np.float64) - wmag).max()
        assert 0 < worst <= bound
        assert len(data) < wmag.nbytes / 4
    rel = pupwave.compress_volume(wmag, max_error_rel=1e-3)
    bound = 1e-3 * float(wmag.max() - wmag.min())
    assert np.abs(pupwave.decompress_volume(rel).astype(np.float64) - wmag).max() <= bound
    info = pupwave.info(rel)
    assert info["kind"] == "volume" and info["shape"] == (91, 91, 91) and info["max_error"] == pytest.approx(bound)


def test_volume_dtypes_bpv_levels(wmag):
    wmag = wmag[:40, :50, :60]  # a non-cubic crop keeps the test fast and checks the axis order
    d = wmag.astype(np.float64)
    back = pupwave.decompress_volume(pupwave.compress_volume(d, max_error=0.01))
    assert back.dtype == np.float64 and np.abs(back - d).max() <= 0.01
    u16 = (wmag * 200).astype(np.uint16)
    assert np.array_equal(pupwave.decompress_volume(pupwave.compress_volume(u16, lossless=True)), u16)
    u8 = (wmag / 2).astype(np.uint8)
    assert np.array_equal(pupwave.decompress_volume(pupwave.compress_volume(u8)), u8)  # default lossless
    small = pupwave.compress_volume(wmag, bpv=0.5)
    assert len(small) * 8 <= 0.5 * wmag.size + 64
    assert pupwave.decompress_volume(small, level=1).shape == (20, 25, 30)


def test_volume_bytes_identical_to_cli(cli, wmag, tmp_path):
    wmag = np.ascontiguousarray(wmag[:48, :64, :80])  # (z, y, x): --dims 80,64,48
    raw = tmp_path / "volume.raw"  # the CLI names a raw grid after the file; the API calls it "volume"
    wmag.astype("<f4").tofile(raw)
    for flags, kwargs in [(["--max-error", "0.5"], {
  "max_error" : 0.5}),
                          (["--max-error-rel", "0.001"], {
  "max_error_rel" : 1e-3}), (["--bpv", "1"], {
  "bpv" : 1})]:
        out = tmp_path / "cli.pw"
        subprocess.run([cli, "compress", str(raw), str(out), "--dims", "80,64,48", "--dtype", "f32", *flags],
                       check=True, capture_output=True)
        assert out.read_bytes() == pupwave.compress_volume(wmag, **kwargs), flags


def test_non_contiguous_arrays_are_handled(real_image, wmag):
    a = real_image("chelsea", "ppm")
    view = a[::2, 1::3]
    assert not view.flags.c_contiguous
    assert pupwave.compress(view, bpp=1) == pupwave.compress(np.ascontiguousarray(view), bpp=1)
    planar = np.ascontiguousarray(a.transpose(2, 0, 1)).transpose(1, 2, 0)  # planar memory, HxWxC view
    assert pupwave.compress(planar, lossless=True) == pupwave.compress(a, lossless=True)
    flipped = a[::-1]
    assert np.array_equal(pupwave.decompress(pupwave.compress(flipped, lossless=True)), flipped)
    vol = wmag[:50, ::2, ::3]
    assert pupwave.compress_volume(vol, max_error=1) == pupwave.compress_volume(np.ascontiguousarray(vol), max_error=1)
    crop = wmag[:30, :40, :50]
    fortran = np.asfortranarray(crop)
    assert pupwave.compress_volume(fortran, max_error=1) == pupwave.compress_volume(crop, max_error=1)
    backwards = wmag[::-1, :40, ::-2]  # negative strides, read in place like the others
    assert pupwave.compress_volume(backwards, max_error=1) == pupwave.compress_volume(
        np.ascontiguousarray(backwards), max_error=1)


def test_two_threads_give_serial_results(real_image, wmag):
    a = real_image("chelsea", "ppm")
    wmag = wmag[:48, :48, :48]
    expected = [pupwave.compress(a, bpp=1), pupwave.compress_volume(wmag, max_error=0.5)]
    results = [None, None]

    def work(i):
        for _ in range(2):
            results[i] = pupwave.compress(a, bpp=1) if i == 0 else pupwave.compress_volume(wmag, max_error=0.5)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == expected


def test_bad_arguments_raise(wmag):
    good = np.zeros((16, 16), np.uint8)
    with pytest.raises(TypeError, match="dtype"):
        pupwave.compress(np.zeros((8, 8), np.complex64))
    with pytest.raises(TypeError, match="dtype"):
        pupwave.compress(np.zeros((8, 8), "datetime64[s]"))
    with pytest.raises(TypeError, match="numpy"):
        pupwave.compress([[1, 2], [3, 4]])
    with pytest.raises(ValueError, match="4-D"):
        pupwave.compress(np.zeros((4, 4, 3, 2), np.uint8))
    with pytest.raises(ValueError):
        pupwave.compress(np.zeros((0, 5), np.uint8))
    with pytest.raises(ValueError, match="channel"):
        pupwave.compress(np.zeros((8, 8, 65), np.uint8))  # at most 64 channels
    with pytest.raises(ValueError, match="at most one"):
        pupwave.compress(good, bpp=1, psnr=30)
    for kwargs in [{"bpp": -1}, {"psnr": 0}, {"step": float("nan")}, {"bpp": float("inf")}, {"levels": 99},
                   {"levels": -5}, {"transform": "nonsense"}]:
        with pytest.raises(ValueError):
            pupwave.compress(good, **kwargs)
    with pytest.raises(ValueError, match="lossless|integer|float"):
        pupwave.compress(np.zeros((8, 8), np.float32), lossless=True)
    with pytest.raises(TypeError, match="dtype"):
        pupwave.compress_volume(np.zeros((4, 4, 4), np.complex64))
    with pytest.raises(ValueError, match="3-D"):
        pupwave.compress_volume(np.zeros((4, 4), np.float32))
    with pytest.raises(ValueError, match="3-D"):
        pupwave.compress_volume(np.zeros((2, 4, 4, 4), np.float32))
    with pytest.raises(ValueError):
        pupwave.compress_volume(np.zeros((0, 4, 4), np.float32))
    with pytest.raises(ValueError):
        pupwave.compress_volume(wmag, max_error=-1)
    with pytest.raises(ValueError):
        pupwave.compress_volume(wmag, lossless=True)  # float data cannot be lossless
    with pytest.raises(ValueError):
        pupwave.compress_volume(wmag, fill_value=float("nan"))  # NaN is always missing; a fill value is finite


def test_volume_missing_values_come_back_exactly(wmag):
    masked = np.array(wmag[:40, :40, :40], np.float32)
    masked[masked < 40] = np.nan
    masked[:8, :8, :8] = -999.0
    stream = pupwave.compress_volume(masked, max_error_rel=1e-3, fill_value=-999.0)
    out = pupwave.decompress_volume(stream)
    missing = np.isnan(masked) | (masked == -999.0)
    assert 0 < missing.sum() < masked.size
    assert np.array_equal(out.view(np.uint32)[missing], masked.view(np.uint32)[missing])
    valid = masked[~missing]
    bound = 1e-3 * float(valid.max() - valid.min())
    assert np.abs(out[~missing].astype(np.float64) - valid).max() <= bound
    everything = pupwave.decompress_volume(pupwave.compress_volume(np.full((4, 4, 4), np.nan, np.float32)))
    assert np.isnan(everything).all()


def test_corrupted_bytes_raise(real_image, wmag):
    image = pupwave.compress(real_image("camera", "pgm"), bpp=1)
    volume = pupwave.compress_volume(wmag[:40, :40, :40], max_error=0.5)
    rng = np.random.default_rng(7)
    for data, decode in [(image, pupwave.decompress), (volume, pupwave.decompress_volume)]:
        for cut in (0, 3, 10, len(data) // 2, len(data) - 1):
            with pytest.raises(ValueError):
                decode(data[:cut])
        for _ in range(20):
            bad = bytearray(data)
            pos = int(rng.integers(0, len(bad)))
            bad[pos] ^= 1 << int(rng.integers(0, 8))
            with pytest.raises(ValueError):
                decode(bytes(bad))
            with pytest.raises(ValueError):
                pupwave.info(bytes(bad))
        with pytest.raises(ValueError):
            decode(data, level=99)
        with pytest.raises(ValueError):
            decode(data, level=-1)
    with pytest.raises(ValueError):
        pupwave.decompress(volume)  # a volume stream is not an image
    with pytest.raises(ValueError):
        pupwave.decompress_volume(image)
    with pytest.raises(ValueError):
        pupwave.decompress(rng.integers(0, 256, 5000, dtype=np.uint8).tobytes())
    with pytest.raises(TypeError):
        pupwave.decompress(12345)
    assert np.array_equal(pupwave.decompress(memoryview(bytearray(image))), pupwave.decompress(image))


def test_absurd_parameters_give_a_stream_or_value_error(wmag):
    """Extreme targets either code (and decode) or raise ValueError; never crash or hang."""
    a = (np.random.default_rng(3).random((48, 40, 3)) * 255).astype(np.uint8)
    for kwargs in [{"psnr": 1e6}, {"psnr": 1e-9}, {"step": 1e-30}, {"step": 1e30}, {"bpp": 1e-9},
                   {"bpp": 1e300}, {"levels": 32}, {"levels": 0}]:
        try:
            data = pupwave.compress(a, **kwargs)
        except ValueError:
            continue
        assert pupwave.decompress(data).shape == a.shape, kwargs
    v = np.ascontiguousarray(wmag[:16, :16, :16])
    for kwargs in [{"max_error": 1e-30}, {"max_error": 1e30}, {"bpv": 1e-9}, {"bpv": 1e9},
                   {"max_error_rel": 1e-300}, {"max_error_rel": 1e9}]:
        try:
            data = pupwave.compress_volume(v, **kwargs)
        except ValueError:
            continue
        back = pupwave.decompress_volume(data)
        assert back.shape == v.shape, kwargs
        if "max_error" in kwargs:
            assert np.abs(back.astype(np.float64) - v).max() <= kwargs["max_error"]
