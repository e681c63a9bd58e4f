#!/usr/bin/env bash
# ctest python.install: a fresh venv at VENV with the package pip-installed from SOURCE_DIR, as
# users install it, for the Python tests to run against (they get no PYTHONPATH into the build).
#
#   install_venv.sh PYTHON VENV SOURCE_DIR BUILD_DIR
#
# The venv sees Debian's packages (numpy, pytest, Pillow, h5py, zarr, dask) and runs Debian's pip
# (--without-pip: copying pip into the venv takes longer than the install). setup.py builds in
# BUILD_DIR (PUPWAVE_CMAKE_BUILD_DIR: nothing is compiled when it is current); no index is read.
set -euo pipefail
python=$1 venv=$2 source_dir=$3 build_dir=$4
"$python" -m venv --clear --without-pip --system-site-packages "$venv"
PUPWAVE_CMAKE_BUILD_DIR="$build_dir" "$venv/bin/python" -m pip install --no-build-isolation --no-index \
  --disable-pip-version-check "$source_dir"
"$venv/bin/python" -c "import pupwave; print('installed pupwave', pupwave.__version__, 'at', pupwave.__file__)"
