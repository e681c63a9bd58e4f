# Types of the compiled extension pupwave._pupwave (tools/python/module.cpp), for type checkers.
# Users call the package's functions (pupwave/__init__.py), which take any dtype and return arrays
# and bytes; these take the stored dtypes and return (result, text) pairs.
from typing import Any, Dict, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
DEFAULT_MAX_ERROR_REL: float

def compress(
    array: npt.NDArray[Any],
    bpp: Optional[float] = None,
    psnr: Optional[float] = None,
    step: Optional[float] = None,
    lossless: bool = False,
    transform: Optional[str] = None,
    levels: Optional[int] = None,
    effort: int = 1,
    entropy: str = "auto",
    tune: str = "psnr",
    attributes: Dict[str, str] = {},
    threads: Optional[int] = None,
) -> Tuple[bytes, str]:
    """(stream, miss): miss is the CLI's warning text for a missed bpp or psnr target, "" when met."""

def decompress(data: Any, level: int = 0, threads: Optional[int] = None) -> Tuple[np.ndarray, Dict[str, str]]:
    """(array of the stored dtype, the stream's text attributes)."""

def compress_volume(
    array3d: npt.NDArray[Any],
    max_error: Optional[float] = None,
    max_error_rel: Optional[float] = None,
    bpv: Optional[float] = None,
    psnr: Optional[float] = None,
    step: Optional[float] = None,
    lossless: bool = False,
    transform: Optional[str] = None,
    levels: Optional[int] = None,
    brick: Optional[int] = None,
    attributes: Dict[str, str] = {},
    threads: Optional[int] = None,
    fill_value: Optional[float] = None,
) -> Tuple[bytes, str]:
    """(stream, miss) as compress."""

def decompress_volume(
    data: Any,
    level: int = 0,
    threads: Optional[int] = None,
    box: Optional[Tuple[int, int, int, int, int, int]] = None,
) -> Tuple[np.ndarray, Dict[str, str]]:
    """(array of the stored dtype, the grid's text attributes); box: (x0, y0, z0, x1, y1, z1)."""

def info(data: Any) -> Dict[str, Any]:
    """The stream described as a dict (pupwave.info adds the decoded dtype)."""
