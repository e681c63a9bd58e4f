"""Every ```python example of docs/python.md runs, in a fresh interpreter that sees only the
pip-installed package, from a temporary folder holding a link to testimages/ (the examples read
testimages/... as from the repository root and write beside it). The examples assert what they
promise (bounds, shapes, bytes), so a broken promise fails here."""

import os
import re
import subprocess
import sys

import pytest

from conftest import BUILD_TREE_VARIABLES, ROOT, TESTIMAGES

PAGE = ROOT / "docs" / "python.md"


def examples():
    """(heading, code, line) of each ```python block of the page, under the ## heading above it."""
    found, heading = [], None
    text = PAGE.read_text()
    for match in re.finditer(r"^## ([^\n]+)$|^```python\n(.*?)^```$", text, re.MULTILINE | re.DOTALL):
        if match.group(1):
            heading = match.group(1)
        else:
            found.append((heading, match.group(2), text.count("\n", 0, match.start()) + 1))
    return found


EXAMPLES = examples()


def test_the_page_has_an_example_for_each_subject():
    assert [h for h, _, _ in EXAMPLES] == ["Images", "Volumes", "Threads and the GIL", "Rate targets that cannot be met",
                                           "Zarr (numcodecs)", "h5py (the HDF5 filter)", "Dask", "Pillow"]


@pytest.mark.parametrize("heading, code, line", EXAMPLES, ids=[h for h, _, _ in EXAMPLES])
def test_example_runs_against_the_installed_package(installed, heading, code, line, tmp_path):
    for module in re.findall(r"^(?:import|from) (\w+)", code, re.MULTILINE):
        pytest.importorskip(module)
    (tmp_path / "testimages").symlink_to(TESTIMAGES)
    env = {k: v for k, v in os.environ.items() if k not in BUILD_TREE_VARIABLES}
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, f"docs/python.md:{line} ({heading}):\n{done.stderr}"
