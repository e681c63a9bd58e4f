"""The numpy dtypes the codec does not store itself, coded as one it does and given back.

The codec stores images as uint8, uint16, float16 or float32 and volumes as uint8, uint16,
float32 or float64. Any other bool, integer or float array is converted to one of these, and the
original dtype is recorded in the stream as the text attribute ``pupwave:dtype`` (its
``numpy.dtype.str``, e.g. ``<f8``), so that decoding gives it back:

- integers (int8 ... int64, uint32, uint64): values 0..255 are stored as uint8, values up to 65535
  as uint16, exactly. An array with a value outside 0..65535 is stored less its minimum, recorded
  as the text attribute ``pupwave:offset``, when its values span at most 65535 (signed data such
  as -1024..3071); a wider span is refused (ValueError naming the dtype, the span and the values
  found), never wrapped. A rate target's peak is that of the stored type (255 or 65535).
- bool: stored as uint8 0 and 255 (so a rate target's peak is the two values' distance); decodes
  as stored value >= 128.
- floats: an image's float64 (or wider) samples are rounded to float32; a volume's float16
  samples are widened to float32 and wider-than-float64 ones rounded to float64. A finite value
  beyond the stored type's range is refused (ValueError); targets are in the input's units. A
  float16 volume is coded to half its max_error (halves_bound), so that the decoded values,
  rounded back to float16, keep within it.
- non-native byte order: swapped to native first, then as above.

A stream without the attribute decodes to its stored dtype.
"""

import numpy as np

DTYPE_ATTRIBUTE = "pupwave:dtype"
OFFSET_ATTRIBUTE = "pupwave:offset"


class Storage:
    """What one kind of stream (images or volumes) stores natively."""

    def __init__(self, noun, native, floats):
        self.noun = noun
        self.native = tuple(np.dtype(t) for t in native)
        self.floats = tuple(np.dtype(t) for t in floats)  # the stored float dtypes, narrowest first

    def float_storage(self, dtype):
        """The stored float dtype for float `dtype`: the narrowest at least as wide, else the widest."""
        return next((f for f in self.floats if f.itemsize >= dtype.itemsize), self.floats[-1])


IMAGE = Storage("image", ("uint8", "uint16", "float16", "float32"), ("float16", "float32"))
VOLUME = Storage("volume", ("uint8", "uint16", "float32", "float64"), ("float32", "float64"))


def _value_range(array):
    return (array.min(), array.max()) if array.size else (0, 0)


def _integers(array, dtype, storage):
    """(uint8 or uint16 array, attributes): the values less an offset, the minimum when they do
    not lie in 0..65535 (0 otherwise, so that 0..255 data codes as the same uint8 samples)."""
    lo, hi = (int(v) for v in _value_range(array))
    offset = 0 if lo >= 0 and hi <= 65535 else lo
    if hi - offset > 65535:
        raise ValueError(f"pupwave: {dtype} {storage.noun} values must span at most 65535 (max - min) to be coded "
                         f"exactly as uint16 (less their minimum); this one holds {lo}..{hi}")
    wide = array if dtype == np.uint64 else array.astype(np.int64)  # no wrap while shifting
    stored = (wide - wide.dtype.type(offset)).astype(np.uint8 if hi - offset <= 255 else np.uint16)
    return stored, ({OFFSET_ATTRIBUTE: str(offset)} if offset else {})


def _floats(array, dtype, storage):
    stored = storage.float_storage(dtype)
    if stored.itemsize < dtype.itemsize:  # narrowing: refuse what would become infinite
        largest = np.finfo(stored).max
        magnitude = np.abs(array[np.isfinite(array)])
        if magnitude.size and magnitude.max() > largest:
            raise ValueError(f"pupwave: {dtype} {storage.noun} values must lie within +-{largest} (stored as "
                             f"{stored}); this one holds {magnitude.max()}")
    return array.astype(stored)


def to_stored(array, storage):
    """(array of a stored dtype, attributes recording the original dtype). Non-arrays and stored
    dtypes pass unchanged (no copy); other dtypes raise TypeError."""
    if not isinstance(array, np.ndarray) or array.dtype in storage.native and array.dtype.isnative:
        return array, {}
    dtype = array.dtype
    if dtype.kind not in "biuf":
        raise TypeError(f"pupwave: unsupported {storage.noun} dtype {dtype}; expected bool, an integer or a float "
                        f"dtype")
    native = array.astype(dtype.newbyteorder("=")) if not dtype.isnative else array
    extra = {}
    if dtype.kind == "b":
        stored = native.astype(np.uint8) * np.uint8(255)
    elif dtype.kind == "f":
        stored = _floats(native, native.dtype, storage)
    else:
        stored, extra = _integers(native, native.dtype, storage)
    return stored, {DTYPE_ATTRIBUTE: dtype.str, **extra}


def halves_bound(array):
    """Whether a volume `array` is coded to half the point-wise bound asked for: float16 ones,
    since rounding a decoded value to the nearest float16 moves it at most as far as the original
    is (the original being a float16), which can double the error."""
    return isinstance(array, np.ndarray) and array.dtype.kind == "f" and array.dtype.itemsize == 2


def _stored_dtypes(dtype, storage):
    """The dtypes to_stored may store a `dtype` array as."""
    if dtype.kind == "b":
        return (np.dtype(np.uint8),)
    if dtype.kind in "iu":
        return (np.dtype(np.uint8), np.dtype(np.uint16))
    if dtype.kind == "f":
        return (storage.float_storage(dtype),)
    return ()


def recorded_dtype(attributes, stored, storage):
    """The dtype `attributes` record for samples stored as `stored`, or None. Raises ValueError
    for a record this module does not write (a stream from elsewhere, or damaged)."""
    if DTYPE_ATTRIBUTE not in attributes:
        return None
    text = attributes[DTYPE_ATTRIBUTE]
    try:
        dtype = np.dtype(text)
    except (TypeError, ValueError):
        dtype = None
    if dtype is None or stored not in _stored_dtypes(dtype, storage):
        raise ValueError(f"pupwave: the stream records {DTYPE_ATTRIBUTE}={text!r} for {stored} samples, which this "
                         f"module does not write; pupwave._pupwave decodes the stored samples")
    return dtype


def _recorded_offset(attributes, dtype):
    """The offset `attributes` record for `dtype` values (0 when none). Raises ValueError for one
    this module does not write."""
    text = attributes.get(OFFSET_ATTRIBUTE)
    if text is None:
        return 0
    try:
        offset = int(text)
    except ValueError:
        offset = None
    limits = np.iinfo(dtype) if dtype.kind in "iu" else None
    if offset is None or limits is None or not limits.min <= offset <= limits.max:
        raise ValueError(f"pupwave: the stream records {OFFSET_ATTRIBUTE}={text!r} for {dtype} values, which this "
                         f"module does not write; pupwave._pupwave decodes the stored samples")
    return offset


def from_stored(array, attributes, storage):
    """The decoded `array` in the dtype `attributes` record (unchanged when they record none)."""
    dtype = recorded_dtype(attributes, array.dtype, storage)
    if dtype is None:
        return array
    offset = _recorded_offset(attributes, dtype)
    if dtype.kind == "b":
        return array >= 128
    if dtype.kind in "iu":  # lossy values may pass the original type's top (int8: 127): clamp, never wrap
        top = min(int(np.iinfo(dtype).max) - offset, int(np.iinfo(array.dtype).max))
        wide = np.minimum(array, array.dtype.type(top)).astype(np.uint64 if dtype == np.uint64 else np.int64)
        return (wide + wide.dtype.type(offset)).astype(dtype)
    return array.astype(dtype)
