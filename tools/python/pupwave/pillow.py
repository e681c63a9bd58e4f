"""Pillow plugin: after ``import pupwave``, ``PIL.Image.open`` reads .pw images and ``Image.save``
writes them (format "PUPWAVE", extension .pw, docs/api.md).

Modes, both ways: "L", "LA", "RGB", "RGBA" (uint8, 1..4 channels), "I;16" (uint16 grey), "F"
(float grey; float16 and float64 streams decode to these values exactly), "I" (int8..int32 grey)
and "1" (bool). Streams of other channel counts or sample types (16-bit colour, for one) have no
exact Pillow mode: opening them raises OSError naming the file; read them with pupwave.decompress.

Resolution levels: ``draft(mode, (w, h))`` before loading picks the smallest stored level 2^k
whose size is at least (w, h) (as JPEG's draft picks a DCT scale; the mode is not changed), and
``reduce(2^k)`` on an image not loaded yet decodes level k. Other factors, boxes, and images
already loaded (whose pixels may have been edited) take Pillow's own reduce.

Save keywords, at most one: bpp, psnr, lossless, quality (1..99: a PSNR target from 25 dB to
55 dB, linear; 100: lossless). None: pupwave's default, psnr 40. strict=True raises
pupwave.PupwaveTargetError (naming the file) where the target is missed, and writes nothing,
as pupwave.compress(strict=True) does; without it the miss is warned (PupwaveTargetWarning).
"""

import numbers
import os

import numpy as np
from PIL import Image, ImageFile

import pupwave  # the package importing this module; its functions are looked up when called

FORMAT = "PUPWAVE"
IMAGE_SIGNATURE = b"PUPW"
VOLUME_SIGNATURE = b"PUPV"

# Pillow mode -> (raw mode of the bytes handed to Pillow, numpy dtype of those bytes).
RAW = {
    "1": ("1;8", "u1"),
    "L": ("L", "u1"),
    "LA": ("LA", "u1"),
    "RGB": ("RGB", "u1"),
    "RGBA": ("RGBA", "u1"),
    "I;16": ("I;16", "<u2"),
    "I": ("I;32S", "<i4"),
    "F": ("F;32F", "<f4"),
}
UINT8_MODES = {1: "L", 2: "LA", 3: "RGB", 4: "RGBA"}
# One-channel dtypes (what pupwave.decompress gives) whose values a Pillow mode holds exactly.
GREY_MODES = {
    "bool": "1",
    "uint16": "I;16",
    "int8": "I",
    "int16": "I",
    "int32": "I",
    "float16": "F",
    "float32": "F",
    "float64": "F",  # an image's float64 samples are stored as float32
}
SAVE_DTYPES = {"1": np.bool_, "I;16": np.uint16, "I": np.int32, "F": np.float32}

QUALITY_PSNR_LOW, QUALITY_PSNR_HIGH = 25.0, 55.0  # dB at quality 1 and 99


def _accept(prefix):
    return prefix[:4] in (IMAGE_SIGNATURE, VOLUME_SIGNATURE)


def _name(fp, filename=None):
    """The user's path for messages (or a placeholder for an unnamed stream)."""
    try:
        return os.fsdecode(filename or getattr(fp, "name", None))
    except TypeError:  # no name, or a file descriptor's number
        return "<stream>"


def mode_for(header, name):
    """The Pillow mode for a stream described by pupwave.info, or OSError naming the file."""
    dtype, channels = header["dtype"], header["channels"]
    mode = UINT8_MODES.get(channels) if dtype == "uint8" else GREY_MODES.get(dtype) if channels == 1 else None
    if mode is None:
        raise OSError(f"{name}: a Pupwave image of {channels} channel(s) of {dtype} has no exact Pillow mode "
                      f"(Pillow reads uint8 with 1..4 channels and one channel of bool, int8..int32, uint16 or "
                      f"float); read it with pupwave.decompress")
    return mode


def level_size(size, level):
    """(width, height) of resolution level `level`: each level halves, rounding up."""
    width, height = size
    for _ in range(level):
        width, height = (width + 1) // 2, (height + 1) // 2
    return width, height


def raw_bytes(array, mode):
    """The decoded array as Pillow's raw bytes for `mode` (and the raw mode naming them)."""
    rawmode, dtype = RAW[mode]
    return np.ascontiguousarray(array, dtype=dtype).tobytes(), rawmode


class PupwaveImageFile(ImageFile.ImageFile):
    """A .pw image opened by PIL.Image.open (format "PUPWAVE"); draft() and reduce() decode only
    the stored resolution level they need."""

    format = FORMAT
    format_description = "Pupwave wavelet image"

    def _open(self):
        name = _name(self.fp, self.filename)
        data = self.fp.read()
        if data[:4] == VOLUME_SIGNATURE:
            raise OSError(f"{name}: a Pupwave volume stream, not an image (read it with "
                          f"pupwave.decompress_volume)")
        try:
            header = pupwave.info(data)
        except ValueError as e:
            raise OSError(f"{name}: not a readable Pupwave image: {e}") from e
        self.mode = mode_for(header, name)
        self._full_size = (header["width"], header["height"])
        self._levels = header["levels"]
        self._set_level(0)

    def _set_level(self, level):
        """Decode at resolution level `level` (the size halves per level) when loaded."""
        self._level = level
        self._size = level_size(self._full_size, level)
        self.tile = [(FORMAT, (0, 0) + self.size, 0, (level, _name(self.fp, self.filename)))]

    def draft(self, mode, size):
        """Pick the smallest stored level at least `size`; returns (mode, box of the full image in the
        drafted one), or None when loaded already or no size is asked for."""
        if not self.tile or not size:
            return None
        scale = int(min(self._full_size[0] // size[0], self._full_size[1] // size[1]))  # thumbnail asks in floats
        level = min(max(scale, 1).bit_length() - 1, self._levels)
        self._set_level(level)
        return self.mode, (0, 0, self._full_size[0] / 2**level, self._full_size[1] / 2**level)

    def _reduced_level(self, factor, box):
        """The stored level that reduce(factor, box) decodes, or None: loaded already (the pixels may
        have been edited), a box, a factor other than 2^k (k >= 1) or too few levels."""
        fx, fy = factor if isinstance(factor, (list, tuple)) else (factor, factor)
        whole = box is None or tuple(box) == (0, 0) + self.size
        if not self.tile or not whole or fx != fy or not isinstance(fx, int) or fx < 2 or fx & (fx - 1):
            return None
        level = self._level + fx.bit_length() - 1
        return level if level <= self._levels else None

    def reduce(self, factor, box=None):
        """A stored resolution level where _reduced_level finds one; Pillow's reduce otherwise."""
        level = self._reduced_level(factor, box)
        if level is None:
            return super().reduce(factor, box)
        self.fp.seek(0)
        data, rawmode = raw_bytes(decode(self.fp.read(), level, _name(self.fp, self.filename)), self.mode)
        reduced = Image.frombytes(self.mode, level_size(self._full_size, level), data, "raw", rawmode)
        reduced.info = self.info.copy()
        return reduced


def decode(data, level, name):
    """pupwave.decompress at `level`, its errors as OSError naming the file."""
    try:
        return pupwave.decompress(data, level=level)
    except ValueError as e:
        raise OSError(f"{name}: cannot decode the Pupwave image: {e}") from e


class PupwaveDecoder(ImageFile.PyDecoder):
    """Pillow's decoder "PUPWAVE": decodes the whole stream at the tile's level."""

    _pulls_fd = True  # the codec decodes the whole stream at once

    def decode(self, buffer):
        """Reads the whole file (``buffer`` is unused: the decoder pulls the file) and sets the pixels."""
        level, name = self.args
        data, rawmode = raw_bytes(decode(self.fd.read(), level, name), self.mode)
        self.set_as_raw(data, rawmode)
        return -1, 0


def quality_target(quality):
    """pupwave.compress keywords for save's quality: 1..99 a PSNR target, linear from 25 dB at 1 to
    55 dB at 99; 100 lossless."""
    if isinstance(quality, bool) or not isinstance(quality, numbers.Integral) or not 1 <= quality <= 100:
        raise ValueError(f"pupwave: quality must be an integer 1..100, not {quality!r}")
    if quality == 100:
        return {"lossless": True}
    return {"psnr": QUALITY_PSNR_LOW + (QUALITY_PSNR_HIGH - QUALITY_PSNR_LOW) * (quality - 1) / 98}


def target(encoderinfo):
    """pupwave.compress keywords for save's bpp, psnr, lossless or quality (at most one)."""
    given = {k: encoderinfo[k] for k in ("bpp", "psnr", "quality") if encoderinfo.get(k) is not None}
    if encoderinfo.get("lossless"):
        given["lossless"] = True
    if len(given) > 1:
        raise ValueError(f"pupwave: give at most one of bpp, psnr, lossless, quality (got {', '.join(given)})")
    return quality_target(given["quality"]) if "quality" in given else given


def _save(im, fp, filename):
    name = _name(fp, filename)
    if im.mode not in RAW:
        raise OSError(f"{name}: cannot write mode {im.mode} as {FORMAT} (convert it to one of {', '.join(RAW)})")
    array = np.asarray(im, dtype=SAVE_DTYPES.get(im.mode))
    try:
        data = pupwave.compress(array, strict=bool(im.encoderinfo.get("strict")), **target(im.encoderinfo))
    except pupwave.PupwaveTargetError as e:
        raise pupwave.PupwaveTargetError(f"{name}: {e}") from e
    except ValueError as e:
        raise ValueError(f"{name}: {e}") from e
    fp.write(data)


Image.register_open(FORMAT, PupwaveImageFile, _accept)
Image.register_save(FORMAT, _save)
Image.register_extension(FORMAT, ".pw")
Image.register_mime(FORMAT, "image/x-pupwave")
Image.register_decoder(FORMAT, PupwaveDecoder)
