"""Pupwave wavelet codec for numpy arrays (docs/python.md).

compress(array, bpp=None, psnr=None, step=None, lossless=False, transform=None, levels=None, effort=1,
         entropy="auto", threads=None, strict=False, tune="psnr") -> bytes
decompress(data, level=0, threads=None) -> numpy.ndarray
compress_volume(array3d, max_error=None, max_error_rel=None, bpv=None, psnr=None, step=None, lossless=False,
                transform=None, levels=None, brick=None, threads=None, strict=False, fill_value=None) -> bytes
decompress_volume(data, level=0, threads=None, box=None) -> numpy.ndarray
info(data) -> dict
hdf5_filter(max_error=None, bpv=None, lossless=False) -> dict of h5py create_dataset keywords (docs/hdf5.md);
    a pip-installed pupwave ships the HDF5 filter plugin, and importing pupwave registers it with h5py
PupwaveTargetWarning, PupwaveTargetError: a rate target the stream misses (warned, or raised with strict=True)
pupwave.numcodecs.Pupwave: the numcodecs codec "pupwave" for Zarr (import pupwave.numcodecs registers it)
pupwave.pillow: with Pillow installed, PIL.Image opens and saves .pw images (format "PUPWAVE")

Arrays of any bool, integer or float dtype are taken (pupwave.dtypes says how those the codec
does not store itself are coded) and decode to their own dtype. Bad arguments raise ValueError
or TypeError with the library's message. The GIL is released while coding, and independent calls
on different threads are safe. threads=None or 0 codes on all cores, 1 on the calling thread
only, n on at most n; the bytes never depend on it.
"""

import warnings

import numpy as np

from . import _pupwave, dtypes
from ._pupwave import __version__
from .hdf5 import hdf5_filter, register_plugin

register_plugin()  # h5py finds the packaged HDF5 filter (pip installs) with no HDF5_PLUGIN_PATH

try:
    from . import pillow  # registers the Pillow plugin
except ImportError as e:  # Pillow absent (or broken): pupwave works without the plugin
    if not (e.name or "").startswith("PIL"):
        raise

__all__ = ["compress", "decompress", "compress_volume", "decompress_volume", "info", "hdf5_filter",
           "PupwaveTargetWarning", "PupwaveTargetError", "__version__"]


class PupwaveTargetWarning(UserWarning):
    """A stream misses the rate target asked for (a bpp budget below a tiny image's header, a
    PSNR beyond what lossless reaches); the stream is complete. The text is that of the CLI's
    `warning:` line for the same input."""


class PupwaveTargetError(ValueError):
    """Raised by compress and compress_volume with strict=True where they would warn
    PupwaveTargetWarning (no bytes are returned); the message is the warning's text."""


def _checked(coded, strict):
    """The stream of (stream, miss) from _pupwave, after warning (or raising, with strict) for a miss."""
    stream, miss = coded
    if miss and strict:
        raise PupwaveTargetError(miss)
    if miss:
        warnings.warn(miss, PupwaveTargetWarning, stacklevel=3)
    return stream


def compress(array, bpp=None, psnr=None, step=None, lossless=False, transform=None, levels=None, effort=1,
             entropy="auto", threads=None, strict=False, tune="psnr"):
    """Compress an image to .pw bytes.

    array: 2-D (height, width) grey or 3-D (height, width, channels), 1..64 channels, of any
        bool, integer or float dtype (uint8, uint16, float16, float32 stored as they are).
    bpp, psnr, step, lossless: the rate; at most one (default psnr=40). bpp: bits per pixel;
        psnr: dB (log-PSNR for float images); step: the quantizer base step; lossless: bit exact.
    transform: a spec as the CLI's --transform; None: cdf97, or cdf53 for lossless.
    levels: decomposition levels; None: from the image size.
    effort: 2 (with entropy="ebcot") makes bpp targets search three base steps per band (about
        1% smaller, up to 1.9x slower).
    entropy: auto (pc for rate targets on images up to 4 Mpixel, else ebcot; lc for lossless),
        ebcot, pc, lc or ht (the CLI's --entropy names).
    threads: None or 0 all cores, 1 the calling thread, n at most n (the bytes do not depend on it).
    strict: raise PupwaveTargetError instead of warning when the bpp or psnr target is missed.
    tune: what lossy coding minimises (the CLI's --tune): "psnr" (default, the squared error) or
        "visual" (a contrast-sensitivity-weighted error, less weight on chroma: better butteraugli
        and MS-SSIM at a size, lower PSNR). bpp and psnr targets hold in both.

    Returns the stream (bytes). Warns PupwaveTargetWarning (the CLI's `warning:` text) when the
    stream misses its bpp or psnr target. Raises ValueError (bad arguments, the library's message),
    TypeError (not an array, unsupported dtype), PupwaveTargetError (strict=True and a miss).
    """
    stored, attributes = dtypes.to_stored(array, dtypes.IMAGE)
    return _checked(_pupwave.compress(stored, bpp, psnr, step, lossless, transform, levels, effort, entropy,
                                      tune, attributes, threads), strict)


def decompress(data, level=0, threads=None):
    """Decode .pw image bytes (any bytes-like object).

    level: 0 full size, n 1/2^n of it (rounded up per halving), reading only that data.
    threads: None or 0 all cores, 1 the calling thread, n at most n.

    Returns a numpy array of the original dtype and shape (halved per level). Raises ValueError
    for bytes that are not a Pupwave image stream (the reason), TypeError for a non-bytes-like.
    """
    array, attributes = _pupwave.decompress(data, level, threads)
    return dtypes.from_stored(array, attributes, dtypes.IMAGE)


def compress_volume(array3d, max_error=None, max_error_rel=None, bpv=None, psnr=None, step=None, lossless=False,
                    transform=None, levels=None, brick=None, threads=None, strict=False, fill_value=None):
    """Compress a volume to .pw bytes.

    array3d: 3-D (z, y, x) array of any bool, integer or float dtype (uint8, uint16, float32,
        float64 stored as they are).
    max_error, max_error_rel, bpv, psnr, step, lossless: the rate; at most one (the CLI's
        --max-error, --max-error-rel, --bpv, --psnr, --step, --lossless). max_error: every value
        within this of its original (guaranteed); max_error_rel: the same with bound
        max_error_rel * (max - min) of the array; bpv: bits per value; psnr: dB, peak = the value
        range (estimated); step: the quantizer base step; lossless: bit exact (integers).
        Default: lossless for integers, for floats the library's relative bound
        (_pupwave.DEFAULT_MAX_ERROR_REL, 1e-3). A float16 volume is coded to half its bound,
        given or default (its decoded values, rounded back to float16, keep within the bound).
    transform: a spec as the CLI's --transform; None: the rate's default (pups:cinpact-interp-vm4
        for error bounds, cdf53 for lossless, else cdf97).
    levels: decomposition levels per brick; None: the default.
    brick: brick edge, a power of two 8..256; None: 64.
    threads: None or 0 all cores, 1 the calling thread, n at most n (the bytes do not depend on it).
    strict: raise PupwaveTargetError instead of warning when the target is missed.
    fill_value: values equal to it are missing (as NaN and infinities always are): decoded bit
        for bit, outside the bound, the value range and the statistics (the CLI's --fill-value).

    Returns the stream (bytes), the CLI's bytes for the same settings. Warns PupwaveTargetWarning
    (the CLI's `warning:` text) when the stream misses its bpv budget, psnr target or error bound.
    Raises ValueError, TypeError or PupwaveTargetError as compress does.
    """
    stored, attributes = dtypes.to_stored(array3d, dtypes.VOLUME)
    if dtypes.halves_bound(array3d):
        max_error, max_error_rel = _halved_bounds(max_error, max_error_rel, bpv, psnr, step, lossless)
    return _checked(_pupwave.compress_volume(stored, max_error, max_error_rel, bpv, psnr, step, lossless, transform,
                                             levels, brick, attributes, threads, fill_value), strict)


def _halved_bounds(max_error, max_error_rel, bpv, psnr, step, lossless):
    """(max_error, max_error_rel) halved for a float16 volume; with no rate given, the library's
    default relative bound, made explicit to be halved."""
    if all(r is None for r in (max_error, max_error_rel, bpv, psnr, step)) and not lossless:
        max_error_rel = _pupwave.DEFAULT_MAX_ERROR_REL
    return (max_error / 2 if max_error is not None else None,
            max_error_rel / 2 if max_error_rel is not None else None)


def decompress_volume(data, level=0, threads=None, box=None):
    """Decode .pw volume bytes (any bytes-like object) holding one grid.

    level: 0 full size, n 1/2^n of it per axis.
    threads: None or 0 all cores, 1 the calling thread, n at most n.
    box: None for the whole grid, or ((z0, z1), (y0, y1), (x0, x1)), the axes in the order of the
        returned array, in full-resolution voxels, each upper bound excluded (as array[z0:z1,
        y0:y1, x0:x1]): only the bricks the box touches are decoded. At a level n > 0 the array
        holds the level-n voxels whose footprint meets the box, indices z0 // 2^n to
        (z1 - 1) // 2^n along z (and likewise y, x): the same voxels as slicing the whole
        decode at that level.

    Returns a (z, y, x) numpy array of the original dtype. Raises ValueError for bytes that are
    not a single-grid Pupwave volume stream (the reason) or a box that is empty, inverted or
    outside the grid (the library's message names it as [x0,x1) x [y0,y1) x [z0,z1) and the
    grid's dims as x by y by z), TypeError for a non-bytes-like.
    """
    array, attributes = _pupwave.decompress_volume(data, level, threads, _xyz_box(box))
    return dtypes.from_stored(array, attributes, dtypes.VOLUME)


def _xyz_box(box):
    """box ((z0, z1), (y0, y1), (x0, x1)) as _pupwave takes it: (x0, y0, z0, x1, y1, z1); None stays."""
    if box is None:
        return None
    try:
        (z0, z1), (y0, y1), (x0, x1) = box
        bounds = [int(v) for v in (x0, y0, z0, x1, y1, z1)]
    except (TypeError, ValueError):
        raise ValueError(f"box must be ((z0, z1), (y0, y1), (x0, x1)) with integer bounds, got {box!r}") from None
    if min(bounds) < 0:
        raise ValueError(f"box bounds must be >= 0, got {box!r}")
    return tuple(bounds)


def info(data):
    """Describe .pw bytes (every checksum verified).

    Returns a dict: "kind" ("image" or "volume"), "shape", "dtype" (what decompress gives),
    "stored_dtype" (what the stream holds), "levels", "transform", "lossless", "bytes",
    "description" (the CLI's `pupwave info` text), "attributes" (the stream's text attributes),
    and for images "width", "height", "channels", for volumes "grids", "max_error", "sparse".
    Raises ValueError for bytes that are not a Pupwave stream.
    """
    d = _pupwave.info(data)
    d["stored_dtype"] = d["dtype"]
    storage = dtypes.VOLUME if d["kind"] == "volume" else dtypes.IMAGE
    recorded = dtypes.recorded_dtype(d["attributes"], np.dtype(d["stored_dtype"]), storage)
    if recorded is not None:
        d["dtype"] = str(recorded)
    return d
