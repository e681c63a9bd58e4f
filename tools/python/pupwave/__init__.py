"""Pupwave wavelet codec for numpy arrays (docs/api.md).

compress(array, bpp=None, psnr=None, step=None, lossless=False, transform="cdf97", levels=None, effort=1,
         entropy="default") -> bytes
decompress(data, level=0) -> numpy.ndarray
compress_volume(array3d, max_error=None, max_error_rel=None, bpv=None, lossless=False) -> bytes
decompress_volume(data, level=0) -> numpy.ndarray
info(data) -> dict
hdf5_filter(max_error=None, bpv=None, lossless=False) -> dict of h5py create_dataset keywords (docs/hdf5.md)
pupwave.numcodecs.Pupwave: the numcodecs codec "pupwave" for Zarr (import pupwave.numcodecs registers it)

Bad arguments raise ValueError or TypeError with the library's message. The GIL is released
while coding, and independent calls on different threads are safe.
"""

from ._pupwave import compress, compress_volume, decompress, decompress_volume, info, __version__
from .hdf5 import hdf5_filter

__all__ = ["compress", "decompress", "compress_volume", "decompress_volume", "info", "hdf5_filter", "__version__"]
