"""Rate targets the stream misses (PupwaveTargetWarning with the CLI's `warning:` text, or
PupwaveTargetError with strict=True) and the `threads` argument (bytes independent of it, the GIL
released while coding), on real data."""

import subprocess
import threading
import time
import warnings

import numpy as np
import pytest

import pupwave
from conftest import write_pnm


@pytest.fixture(scope="module")
def tiny(real_image):
    """A 2x2 crop of chelsea (uint8 RGB): its header alone exceeds a 1 bpp budget."""
    return np.ascontiguousarray(real_image("chelsea", "ppm")[100:102, 200:202])


def write_pfm(path, a):
    """A float32 (H, W, 3) array as a colour PFM (little endian, rows bottom to top)."""
    path.write_bytes(b"PF\n%d %d\n-1.0\n" % (a.shape[1], a.shape[0]) + a[::-1].astype("<f4").tobytes())


def cli_warning(cli, source, flags):
    """The CLI's `warning:` line for `pupwave compress SOURCE - FLAGS`, without the prefix."""
    done = subprocess.run([cli, "compress", str(source), "-", *flags], capture_output=True, check=True)
    lines = [line for line in done.stderr.decode().splitlines() if line.startswith("warning: ")]
    assert len(lines) == 1, done.stderr
    return lines[0][len("warning: "):]


def test_bpp_below_the_header_warns_the_clis_text(cli, tiny, tmp_path):
    write_pnm(tmp_path / "tiny.ppm", tiny)
    expected = cli_warning(cli, tmp_path / "tiny.ppm", ["--bpp", "1"])
    assert "its header and chunk framing alone take" in expected
    with pytest.warns(pupwave.PupwaveTargetWarning) as caught:
        data = pupwave.compress(tiny, bpp=1)
    assert [str(w.message) for w in caught] == [expected]
    assert caught[0].filename == __file__  # the warning names the caller's line, not the package's
    assert pupwave.decompress(data).shape == tiny.shape  # over budget, complete


def test_psnr_beyond_a_float_images_reach_warns_the_clis_text(cli, tiny, tmp_path):
    floats = tiny.astype(np.float32) / 255
    write_pfm(tmp_path / "tiny.pfm", floats)
    expected = cli_warning(cli, tmp_path / "tiny.pfm", ["--psnr", "120"])
    with pytest.warns(pupwave.PupwaveTargetWarning) as caught:
        pupwave.compress(floats, psnr=120)
    assert [str(w.message) for w in caught] == [expected]
    assert expected.startswith("--psnr 120 not met: the stream reaches log-PSNR ")


def test_volume_psnr_beyond_reach_warns_the_clis_text(cli, wmag, tmp_path):
    block = np.ascontiguousarray(wmag[40:44, 40:44, 40:44])  # 4x4x4 real values: 150 dB is out of reach
    block.tofile(tmp_path / "block.f32")
    expected = cli_warning(cli, tmp_path / "block.f32", ["--dims", "4,4,4", "--dtype", "f32", "--psnr", "150"])
    with pytest.warns(pupwave.PupwaveTargetWarning) as caught:
        pupwave.compress_volume(block, psnr=150)
    assert [str(w.message) for w in caught] == [expected]
    assert expected.startswith("--psnr 150 not met: the stream reaches PSNR ")


def test_strict_raises_the_warnings_text_instead(tiny, wmag):
    with pytest.raises(pupwave.PupwaveTargetError, match=r"^--bpp 1 not met: the stream is \d+ bytes"):
        pupwave.compress(tiny, bpp=1, strict=True)
    with pytest.raises(pupwave.PupwaveTargetError, match=r"^--psnr 120 not met"):
        pupwave.compress(tiny.astype(np.float32) / 255, psnr=120, strict=True)
    with pytest.raises(pupwave.PupwaveTargetError, match=r"^--bpv 1 not met: the stream is \d+ bytes"):
        pupwave.compress_volume(np.ascontiguousarray(wmag[40:42, 40:42, 40:42]), bpv=1, strict=True)
    assert issubclass(pupwave.PupwaveTargetError, ValueError)
    assert issubclass(pupwave.PupwaveTargetWarning, UserWarning)


def test_met_targets_say_nothing(real_image, wmag):
    a = real_image("chelsea", "ppm")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pupwave.compress(a, bpp=1, strict=True)
        pupwave.compress(a, psnr=35)
        pupwave.compress(a[:2, :2], psnr=200)  # beyond lossy reach: coded lossless, which reaches it
        pupwave.compress_volume(wmag, bpv=2, strict=True)


def test_thread_counts_give_identical_bytes(real_image, wmag):
    a = real_image("chelsea", "ppm")
    v = wmag[:64, :64, :64]
    images = {t: pupwave.compress(a, bpp=1, threads=t) for t in (1, 4, None, 0)}
    volumes = {t: pupwave.compress_volume(v, max_error=0.05, threads=t) for t in (1, 4, None, 0)}
    assert len(set(images.values())) == 1 and len(set(volumes.values())) == 1
    for t in (1, 4):
        assert np.array_equal(pupwave.decompress(images[1], threads=t), pupwave.decompress(images[4]))
        assert np.array_equal(pupwave.decompress_volume(volumes[1], threads=t), pupwave.decompress_volume(volumes[4]))


@pytest.mark.parametrize("threads", [-1, 1.5, "2"])
def test_bad_thread_counts_raise(real_image, threads):
    with pytest.raises((ValueError, TypeError), match="threads|incompatible"):
        pupwave.compress(real_image("camera", "pgm"), threads=threads)


def longest_pause_during(call):
    """(longest pause between turns of a Python loop on this thread while `call` runs on another,
    the call's duration). The loop needs the GIL at every turn: a call holding it pauses the loop
    for its whole duration; one releasing it, for about a switch interval (5 ms) at most."""
    done, took = threading.Event(), []

    def work():
        start = time.perf_counter()
        call()
        took.append(time.perf_counter() - start)
        done.set()

    worker = threading.Thread(target=work)
    longest, last = 0.0, time.perf_counter()
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
    worker.join()
    return longest, took[0]


@pytest.mark.parametrize("what", ["compress", "decompress", "compress_volume", "decompress_volume"])
def test_every_coding_call_releases_the_gil(real_image, wmag, what):
    a = np.tile(real_image("chelsea", "ppm"), (2, 2, 1))
    v = np.ascontiguousarray(wmag)
    stream = {"decompress": pupwave.compress(a, lossless=True), "decompress_volume": pupwave.compress_volume(v)}
    call = {"compress": lambda: pupwave.compress(a, lossless=True, threads=1),
            "decompress": lambda: pupwave.decompress(stream["decompress"], threads=1),
            "compress_volume": lambda: pupwave.compress_volume(v, threads=1),
            "decompress_volume": lambda: pupwave.decompress_volume(stream["decompress_volume"], threads=1)}[what]
    longest, took = longest_pause_during(call)
    assert took > 0.04 and longest < 0.5 * took, (longest, took)
