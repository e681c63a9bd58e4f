"""Pupwave wavelet codec for numpy arrays (docs/api.md).

compress(array, bpp=None, psnr=None, step=None, lossless=False, transform=None, levels=None, effort=1,
         entropy="auto") -> bytes
decompress(data, level=0) -> numpy.ndarray
compress_volume(array3d, max_error=None, max_error_rel=None, bpv=None, lossless=False) -> bytes
decompress_volume(data, level=0) -> numpy.ndarray
info(data) -> dict
hdf5_filter(max_error=None, bpv=None, lossless=False) -> dict of h5py create_dataset keywords (docs/hdf5.md);
    a pip-installed pupwave ships the HDF5 filter plugin, and importing pupwave registers it with h5py
pupwave.numcodecs.Pupwave: the numcodecs codec "pupwave" for Zarr (import pupwave.numcodecs registers it)
pupwave.pillow: with Pillow installed, PIL.Image opens and saves .pw images (format "PUPWAVE")

Arrays of any bool, integer or float dtype are taken (pupwave.dtypes says how those the codec
does not store itself are coded) and decode to their own dtype. Bad arguments raise ValueError
or TypeError with the library's message. The GIL is released while coding, and independent calls
on different threads are safe.
"""

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

__all__ = ["compress", "decompress", "compress_volume", "decompress_volume", "info", "hdf5_filter", "__version__"]


def compress(array, bpp=None, psnr=None, step=None, lossless=False, transform=None, levels=None, effort=1,
             entropy="auto"):
    """Compress a 2-D (grey) or HxWxC (C 1..64) array to .pw bytes. At most one of bpp, psnr, step,
    lossless (default psnr=40). transform: a spec as the CLI's --transform; None: cdf97, or cdf53 for
    lossless (the library's default). entropy: auto (pc for rate targets on images up to 4 Mpixel,
    else ebcot; lc for lossless), ebcot, pc, lc, ht or zstd (the CLI's --entropy names). effort=2 (with entropy='ebcot'):
    bpp targets search three base steps per band (about 1% smaller, up to 1.9x slower)."""
    stored, attributes = dtypes.to_stored(array, dtypes.IMAGE)
    return _pupwave.compress(stored, bpp, psnr, step, lossless, transform, levels, effort, entropy, attributes)


def decompress(data, level=0):
    """Decode .pw image bytes to an array of the original dtype and shape (halved per level)."""
    array, attributes = _pupwave.decompress(data, level)
    return dtypes.from_stored(array, attributes, dtypes.IMAGE)


def compress_volume(array3d, max_error=None, max_error_rel=None, bpv=None, lossless=False):
    """Compress a (z, y, x) array to .pw volume bytes. Default: lossless for integers,
    max_error_rel=1e-3 for floats. A float16 volume is coded to half the bound (its decoded
    values, rounded back to float16, keep within the bound asked for)."""
    stored, attributes = dtypes.to_stored(array3d, dtypes.VOLUME)
    if dtypes.halves_bound(array3d):
        if max_error is None and max_error_rel is None and bpv is None and not lossless:
            max_error_rel = 1e-3  # the floats' default, made explicit to be halved
        max_error = max_error / 2 if max_error is not None else None
        max_error_rel = max_error_rel / 2 if max_error_rel is not None else None
    return _pupwave.compress_volume(stored, max_error, max_error_rel, bpv, lossless, attributes)


def decompress_volume(data, level=0):
    """Decode .pw volume bytes to a (z, y, x) array of the original dtype (halved per level)."""
    array, attributes = _pupwave.decompress_volume(data, level)
    return dtypes.from_stored(array, attributes, dtypes.VOLUME)


def info(data):
    """Describe .pw bytes (every checksum verified) as a dict. "dtype" is what decompress gives,
    "stored_dtype" what the stream holds, "attributes" the stream's text attributes."""
    d = _pupwave.info(data)
    d["stored_dtype"] = d["dtype"]
    storage = dtypes.VOLUME if d["kind"] == "volume" else dtypes.IMAGE
    recorded = dtypes.recorded_dtype(d["attributes"], np.dtype(d["stored_dtype"]), storage)
    if recorded is not None:
        d["dtype"] = str(recorded)
    return d
