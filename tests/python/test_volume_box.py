"""pupwave.decompress_volume(..., box=...) on the real float field testimages/wmag91.float and on
the same field in hundredths as uint16 (lossless): a box, given in the array's (z, y, x) order, is
the slice of the whole decode at levels 0, 1 and 2, and the CLI's --box (x, y, z order) gives the
same voxels; bad boxes raise ValueError."""

import subprocess

import numpy as np
import pytest

import pupwave

# (z0, z1), (y0, y1), (x0, x1): inside one 32^3 brick, straddling bricks, at the far edges, one voxel.
BOXES = [((1, 9), (5, 30), (3, 20)), ((10, 80), (30, 40), (20, 70)), ((85, 91), (60, 91), (0, 91)),
         ((90, 91), (0, 1), (45, 46))]


def level_slice(box, level):
    """The level-`level` indices whose footprint meets the box, as slices."""
    return tuple(slice(lo >> level, ((hi - 1) >> level) + 1) for lo, hi in box)


@pytest.fixture(scope="module")
def streams(wmag):
    return {"max_error": pupwave.compress_volume(wmag, max_error=0.05, brick=32, levels=2),
            "lossless": pupwave.compress_volume(np.round(wmag * 100).astype(np.uint16), lossless=True, brick=32,
                                                levels=2)}


@pytest.mark.parametrize("kind", ["max_error", "lossless"])
def test_box_is_the_slice_of_the_whole_decode(streams, kind):
    stream = streams[kind]
    for level in (0, 1, 2):
        whole = pupwave.decompress_volume(stream, level=level)
        for box in BOXES:
            part = pupwave.decompress_volume(stream, level=level, box=box)
            assert part.dtype == whole.dtype
            np.testing.assert_array_equal(part, whole[level_slice(box, level)], err_msg=f"{kind} {level} {box}")


def test_cli_box_gives_the_same_voxels(streams, cli, tmp_path):
    path = tmp_path / "v.pw"
    path.write_bytes(streams["max_error"])
    (z0, z1), (y0, y1), (x0, x1) = box = BOXES[1]
    subprocess.run([cli, "decompress", str(path), str(tmp_path / "b.raw"), "--level", "1", "-q", "--box",
                    f"{x0},{y0},{z0}:{x1},{y1},{z1}"], check=True)
    part = pupwave.decompress_volume(streams["max_error"], level=1, box=box)
    raw = np.fromfile(tmp_path / "b.raw", dtype="<f4").reshape(part.shape)
    np.testing.assert_array_equal(raw, part)


@pytest.mark.parametrize("box, message", [
    (((0, 91), (0, 92), (0, 91)), "box [0,91) x [0,92) x [0,91) is empty, inverted or outside grid"),
    (((5, 5), (0, 1), (0, 1)), "[5,5)"),
    (((0, 1), (0, 1)), "box must be ((z0, z1), (y0, y1), (x0, x1))"),
    (((0, 1), (0, 1), (-1, 1)), "box bounds must be >= 0"),
])
def test_bad_boxes_are_refused(streams, box, message):
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("(", r"\(").replace(")", r"\)")):
        pupwave.decompress_volume(streams["max_error"], box=box)
