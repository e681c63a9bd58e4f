"""Arrays as users have them: C- or Fortran-ordered, strided, transposed or reversed views of
every dtype the module takes code to the same bytes as their np.ascontiguousarray copy, for
images and volumes, through pupwave.compress, pupwave.compress_volume and the numcodecs codec."""

import numpy as np
import pytest

import pupwave

# name -> view of a C-contiguous array: the layouts numpy users hand over.
LAYOUTS = {
    "fortran": np.asfortranarray,
    "strided": lambda a: a[::2, ::3],
    "transposed": lambda a: a.swapaxes(0, 1),
    "reversed": lambda a: a[::-1, ::-2],
}
IMAGE_DTYPES = ["uint8", "uint16", "float16", "float32", "float64", "int8", "int16", "int32", "uint32", "bool"]
VOLUME_DTYPES = ["uint8", "uint16", "float16", "float32", "float64", "int16", "int32", "bool"]


def as_dtype(unit, dtype):
    """`unit` (values in [0, 1]) as `dtype` values spanning that type's usual range: floats as
    they are, integers to 0..255 (0..65535 for uint16), signed ones shifted to hold negatives
    (the offset path of pupwave.dtypes), bools thresholded."""
    dtype = np.dtype(dtype)
    if dtype.kind == "f":
        return unit.astype(dtype)
    if dtype.kind == "b":
        return unit > 0.5
    top = 65535 if dtype == np.uint16 else 255
    values = np.round(unit * top).astype(np.int64)
    return (values - 128 if dtype.kind == "i" else values).astype(dtype)


@pytest.fixture(scope="module")
def photo_unit(real_image):
    """An RGB crop of testimages/astronaut.png with values in [0, 1]."""
    return real_image("astronaut", "ppm")[100:196, 140:260].astype(np.float64) / 255


@pytest.fixture(scope="module")
def field_unit(wmag):
    """A 40^3 crop of testimages/wmag91.float, values in [0, 1]."""
    crop = wmag[20:60, 30:70, 10:50].astype(np.float64)
    return (crop - crop.min()) / (crop.max() - crop.min())


def layouts_of(array):
    return [(name, make(array)) for name, make in LAYOUTS.items()]


@pytest.mark.parametrize("channels", [1, 3])
@pytest.mark.parametrize("dtype", IMAGE_DTYPES)
def test_image_layouts_code_as_their_contiguous_copy(photo_unit, dtype, channels):
    image = as_dtype(photo_unit if channels == 3 else photo_unit[..., 1], dtype)
    for name, view in layouts_of(image):
        assert not view.flags.c_contiguous, name
        assert pupwave.compress(view) == pupwave.compress(np.ascontiguousarray(view)), name
        if dtype in ("uint8", "uint16"):
            lossless = pupwave.compress(view, lossless=True)
            assert lossless == pupwave.compress(np.ascontiguousarray(view), lossless=True), name
            assert np.array_equal(pupwave.decompress(lossless), view.squeeze()), name


def record_field(array):
    """`array`'s values as a field of a record array: strides that are not whole elements."""
    records = np.zeros(array.shape, dtype=[("tag", "u1"), ("value", array.dtype)])
    records["value"] = array
    return records["value"]


@pytest.mark.parametrize("dtype", ["uint8", "uint16", "float16", "float32"])
def test_image_record_fields_and_broadcasts_code_as_their_contiguous_copy(photo_unit, dtype):
    """Views the library cannot read in place (a record's field, a row or a grey plane repeated
    by np.broadcast_to) are copied once, not refused."""
    image = as_dtype(photo_unit, dtype)
    views = {"record field": record_field(image), "broadcast rows": np.broadcast_to(image[5, :, 0], (40, 120)),
             "broadcast channels": np.broadcast_to(image[..., :1], image.shape)}
    for name, view in views.items():
        assert pupwave.compress(view) == pupwave.compress(np.ascontiguousarray(view)), name


@pytest.mark.parametrize("dtype", ["uint8", "uint16", "float32", "float64"])
def test_volume_record_fields_and_broadcasts_code_as_their_contiguous_copy(field_unit, dtype):
    volume = as_dtype(field_unit, dtype)
    for name, view in {"record field": record_field(volume), "broadcast": np.broadcast_to(volume[:1], volume.shape)}.items():
        assert pupwave.compress_volume(view) == pupwave.compress_volume(np.ascontiguousarray(view)), name


@pytest.mark.parametrize("dtype", VOLUME_DTYPES)
def test_volume_layouts_code_as_their_contiguous_copy(field_unit, dtype):
    volume = as_dtype(field_unit, dtype)
    for name, view in layouts_of(volume) + [("axes rolled", volume.transpose(2, 0, 1)[:, 1:, ::-1])]:
        assert not view.flags.c_contiguous, name
        coded = pupwave.compress_volume(view)
        assert coded == pupwave.compress_volume(np.ascontiguousarray(view)), name
        if dtype in ("float32", "float64"):
            bounded = pupwave.compress_volume(view, max_error=1e-3)
            assert bounded == pupwave.compress_volume(np.ascontiguousarray(view), max_error=1e-3), name
            assert np.abs(pupwave.decompress_volume(bounded).astype(np.float64) - view).max() <= 1e-3, name


@pytest.mark.parametrize("dtype", ["uint8", "int8", "uint16", "int16", "float32", "float64"])
def test_numcodecs_layouts_code_as_their_contiguous_copy(field_unit, dtype):
    codecs = pytest.importorskip("pupwave.numcodecs")
    codec = codecs.Pupwave(max_error=1e-3) if dtype.startswith("float") else codecs.Pupwave(lossless=True)
    volume = as_dtype(field_unit, dtype)
    for name, view in layouts_of(volume) + layouts_of(volume[7]):  # chunks of 3 and 2 dimensions
        assert not view.flags.c_contiguous, name
        coded = codec.encode(view)
        assert coded == codec.encode(np.ascontiguousarray(view)), name
        back = codec.decode(coded).reshape(view.shape)
        assert np.abs(back.astype(np.float64) - view).max() <= (1e-3 if dtype.startswith("float") else 0), name
