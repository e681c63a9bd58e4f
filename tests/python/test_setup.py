"""setup.py's refusals of a PUPWAVE_CMAKE_BUILD_DIR it cannot build the package from: a message
naming the folder and the reason, a non-zero exit, before anything is built."""

import os
import subprocess
import sys

from conftest import ROOT


def build_ext(build_dir):
    env = {**os.environ, "PUPWAVE_CMAKE_BUILD_DIR": str(build_dir)}
    return subprocess.run([sys.executable, "setup.py", "-q", "build_ext"], cwd=ROOT, env=env, capture_output=True,
                          text=True)


def test_a_folder_that_is_not_configured_is_refused(tmp_path):
    done = build_ext(tmp_path)
    assert done.returncode != 0
    assert f"PUPWAVE_CMAKE_BUILD_DIR={tmp_path}: no CMakeCache.txt there" in done.stderr


def test_a_build_without_the_hdf5_plugin_is_refused(tmp_path):
    (tmp_path / "CMakeCache.txt").write_text("PUPWAVE_BUILD_PYTHON:BOOL=ON\nPUPWAVE_BUILD_HDF5:BOOL=OFF\n")
    done = build_ext(tmp_path)
    assert done.returncode != 0
    assert f"PUPWAVE_CMAKE_BUILD_DIR={tmp_path}: configured with PUPWAVE_BUILD_HDF5=OFF" in done.stderr
