"""``pupwave.numcodecs.Pupwave``: a numcodecs codec (Zarr v2, Dask) storing every chunk exactly as
the HDF5 filter does (docs/hdf5.md, "Chunk format"), through the plugin library's C entry points
``pupwave_chunk_encode`` / ``pupwave_chunk_decode`` (ctypes). Registered as ``"pupwave"`` on import.

The library is looked up in ``PUPWAVE_HDF5_PLUGIN`` (a file), then in each directory of
``HDF5_PLUGIN_PATH``, then in the package (``pupwave/hdf5_plugin/``, a pip install), then in the
install prefix (``P/lib/hdf5/plugins`` beside ``P/lib/python3/dist-packages/pupwave``), then in
the build tree (``build/lib/hdf5/plugins``).
"""

import ctypes
import math
import os
import threading

import numpy as np
from numcodecs.abc import Codec
from numcodecs.compat import ensure_contiguous_ndarray, ndarray_copy
from numcodecs.registry import register_codec

from pupwave.hdf5 import PLUGIN_NAME as _LIBRARY_NAME
from pupwave.hdf5 import filter_mode, packaged_plugin

_TYPE_CODES = {"u1": 1, "i1": 2, "u2": 3, "i2": 4, "f4": 5, "f8": 6}
_CODE_TYPES = {code: np.dtype(name) for name, code in _TYPE_CODES.items()}
_lib = None


def _candidates():
    if os.environ.get("PUPWAVE_HDF5_PLUGIN"):
        yield os.environ["PUPWAVE_HDF5_PLUGIN"]
    for folder in os.environ.get("HDF5_PLUGIN_PATH", "").split(":"):
        if folder:
            yield os.path.join(folder, _LIBRARY_NAME)
    if packaged_plugin():
        yield packaged_plugin()
    here = os.path.dirname(os.path.abspath(__file__))
    yield os.path.normpath(os.path.join(here, "..", "..", "..", "hdf5", "plugins", _LIBRARY_NAME))  # P/lib/python3/dist-packages
    yield os.path.normpath(os.path.join(here, "..", "..", "lib", "hdf5", "plugins", _LIBRARY_NAME))  # build/python


def _library():
    global _lib
    if _lib is None:
        path = next((p for p in _candidates() if os.path.isfile(p)), None)
        if path is None:
            raise OSError(f"pupwave: {_LIBRARY_NAME} not found (set HDF5_PLUGIN_PATH or PUPWAVE_HDF5_PLUGIN)")
        lib = ctypes.CDLL(path)
        size_p = ctypes.POINTER(ctypes.c_size_t)
        lib.pupwave_chunk_encode.argtypes = [ctypes.c_uint, ctypes.c_double, ctypes.c_uint, ctypes.c_uint,
                                             ctypes.POINTER(ctypes.c_ulonglong), ctypes.c_void_p, ctypes.c_size_t,
                                             ctypes.c_uint, ctypes.POINTER(ctypes.c_void_p), size_p, ctypes.c_char_p,
                                             ctypes.c_size_t]
        lib.pupwave_chunk_decode.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_uint,
                                             ctypes.POINTER(ctypes.c_void_p), size_p, ctypes.POINTER(ctypes.c_uint),
                                             ctypes.c_char_p, ctypes.c_size_t]
        lib.pupwave_chunk_free.argtypes = [ctypes.c_void_p]
        _lib = lib
    return _lib


def _take(lib, out, size, dtype=np.dtype(np.uint8)):
    """Copies a buffer the library allocated into a new (writable) array and frees it."""
    try:
        arr = np.empty(size.value // dtype.itemsize, dtype=dtype)
        ctypes.memmove(arr.ctypes.data, out, size.value)
        return arr
    finally:
        lib.pupwave_chunk_free(out)


def _range_bound(max_error_rel, psnr, value_range):
    """The absolute bound on every value that keeps max_error_rel * (hi - lo), or a PSNR of at least
    psnr dB with peak hi - lo (every error within E gives a mean squared error within E^2)."""
    if value_range is None:
        name = "max_error_rel" if max_error_rel is not None else "psnr"
        raise ValueError(f"pupwave: {name} needs value_range=(lo, hi), the value range of the whole array "
                         f"(a codec sees one chunk at a time)")
    lo, hi = (float(v) for v in value_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
        raise ValueError(f"pupwave: value_range must be two finite numbers lo < hi, got {tuple(value_range)!r}")
    if max_error_rel is not None:
        rel = float(max_error_rel)
        if not (math.isfinite(rel) and rel > 0.0):
            raise ValueError(f"pupwave: max_error_rel must be a finite positive number, got {max_error_rel!r}")
        return rel * (hi - lo)
    db = float(psnr)
    if not (math.isfinite(db) and db > 0.0):
        raise ValueError(f"pupwave: psnr must be a finite positive number of dB, got {psnr!r}")
    return (hi - lo) * 10.0 ** (-db / 20.0)


class Pupwave(Codec):
    """Error-bounded wavelet coding of float32/float64 chunks of 1 to 3 dimensions (larger ranks
    are fine when at most 3 dimensions exceed 1), or lossless 8/16-bit integers. Give exactly one
    of:

    - ``max_error``: every value within this (absolute) of its original;
    - ``max_error_rel`` with ``value_range=(lo, hi)``: every value within max_error_rel * (hi - lo);
    - ``psnr`` with ``value_range=(lo, hi)``: every chunk, and so the whole array, reaches at least
      this PSNR in dB with peak hi - lo;
    - ``bpv``: at most this many bits per value in each chunk (plus its headers);
    - ``lossless=True``: bit exact (8/16-bit integers).

    ``value_range`` is the range of the whole array, given by the user (``(float(a.min()),
    float(a.max()))``, or the range the data can take): a codec sees one chunk at a time, and a
    bound taken from each chunk's own range would promise something different in every chunk.
    ``max_error_rel`` and ``psnr`` are coded as the absolute bound they imply (for ``psnr``,
    (hi - lo) * 10^(-psnr/20), which guarantees the PSNR; the PSNR reached is typically about
    7 dB above it, at a rate a PSNR-targeting coder would spend on that higher PSNR), so chunks
    are stored exactly as with ``max_error`` (docs/hdf5.md, "Chunk format"). The config
    (``get_config``) holds the options given; it is JSON."""

    codec_id = "pupwave"

    def __init__(self, max_error=None, bpv=None, lossless=False, max_error_rel=None, psnr=None, value_range=None,
                 threads=None):
        """``threads``: threads coding one chunk (0 all cores, 1 the calling thread). None, the
        default, follows numcodecs' Blosc: all cores when called from the main thread, else 1, so
        that Dask workers and threaded Zarr writes do not oversubscribe the cores. It is a runtime
        choice, not part of the codec's config (the stored bytes never depend on it)."""
        if threads is not None and (not isinstance(threads, int) or threads < 0):
            raise ValueError(f"pupwave: threads must be None or an integer >= 0, got {threads!r}")
        self._threads = threads
        relative = max_error_rel is not None or psnr is not None
        if max_error_rel is not None and psnr is not None:
            raise ValueError("pupwave: give exactly one of max_error, max_error_rel, psnr, bpv or lossless=True")
        if relative and (max_error is not None or bpv is not None or lossless):
            raise ValueError("pupwave: give exactly one of max_error, max_error_rel, psnr, bpv or lossless=True")
        if value_range is not None and not relative:
            raise ValueError("pupwave: value_range goes with max_error_rel or psnr only")
        bound = _range_bound(max_error_rel, psnr, value_range) if relative else None
        self._mode, self._bound = filter_mode(bound if relative else max_error, bpv, lossless)
        self.max_error = None if max_error is None else float(max_error)
        self.bpv = None if bpv is None else float(bpv)
        self.lossless = bool(lossless)
        self._relative = {}  # the options that exist only with value_range, kept in the config when given
        if max_error_rel is not None:
            self._relative["max_error_rel"] = float(max_error_rel)
        if psnr is not None:
            self._relative["psnr"] = float(psnr)
        if relative:
            self._relative["value_range"] = [float(v) for v in value_range]

    def get_config(self):
        """The codec's id and options, JSON-clean; max_error_rel, psnr and value_range only when
        given (so that the configs of arrays written without them stay as they were)."""
        return {"id": self.codec_id, "max_error": self.max_error, "bpv": self.bpv, "lossless": self.lossless,
                **self._relative}

    def encode(self, buf):
        """One chunk (any array-like of the codec's dtypes) to its stored bytes; ValueError or
        TypeError with the reason when the chunk or the options cannot be coded."""
        arr = np.ascontiguousarray(buf)
        if arr.dtype.byteorder == ">":
            raise ValueError(f"pupwave: big-endian arrays are not supported ({arr.dtype})")
        code = _TYPE_CODES.get(arr.dtype.kind + str(arr.dtype.itemsize))
        if code is None:
            raise TypeError(f"pupwave: dtype must be float32, float64 or an 8/16-bit integer, got {arr.dtype}")
        shape = arr.shape if arr.ndim > 0 else (1,)
        dims = (ctypes.c_ulonglong * len(shape))(*shape)
        lib, out, size, err = _library(), ctypes.c_void_p(), ctypes.c_size_t(), ctypes.create_string_buffer(512)
        rc = lib.pupwave_chunk_encode(self._mode, self._bound, code, len(shape), dims, arr.ctypes.data, arr.nbytes,
                                      self._thread_count(), ctypes.byref(out), ctypes.byref(size), err, len(err))
        if rc != 0:
            raise ValueError("pupwave: " + err.value.decode(errors="replace"))
        return _take(lib, out, size).tobytes()

    def decode(self, buf, out=None):
        """Stored bytes to the chunk as a flat array of its dtype (copied into ``out`` when given);
        ValueError with the reason for bytes that are not a Pupwave chunk."""
        data = ensure_contiguous_ndarray(buf).view(np.uint8)
        lib, res, size, code = _library(), ctypes.c_void_p(), ctypes.c_size_t(), ctypes.c_uint()
        err = ctypes.create_string_buffer(512)
        rc = lib.pupwave_chunk_decode(data.ctypes.data, data.nbytes, self._thread_count(), ctypes.byref(res), ctypes.byref(size),
                                      ctypes.byref(code), err, len(err))
        if rc != 0:
            raise ValueError("pupwave: cannot decode chunk: " + err.value.decode(errors="replace"))
        arr = _take(lib, res, size, _CODE_TYPES[code.value])
        return ndarray_copy(arr, out) if out is not None else arr

    def _thread_count(self):
        if self._threads is not None:
            return self._threads
        return 0 if threading.current_thread() is threading.main_thread() else 1

    def __repr__(self):
        options = ", ".join(f"{k}={v!r}" for k, v in self.get_config().items() if k != "id")
        return f"Pupwave({options})"


register_codec(Pupwave)
