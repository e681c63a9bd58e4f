#!/usr/bin/env bash
# Installs the Debian 12 packages pupwave needs to build, test and benchmark.
# Runs apt-get only for packages that are missing, so it is quick on a prepared machine.
set -euo pipefail

packages=(
  # build
  build-essential cmake ninja-build pkg-config clang-format
  # libraries found by CMake with find_package
  libeigen3-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev python3-imath libopenvdb-dev
  libboost-iostreams-dev libzstd-dev libcli11-dev nlohmann-json3-dev libpng-dev libtiff-dev libjpeg-dev
  # found by CMake with pkg-config
  libexif-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # anchors and helpers for the rate-distortion harness and volume comparisons
  libopenjp2-tools libjxl-tools zfp libopenvdb-tools gnuplot-nox
  # the butteraugli distance column of `pupwave bench rd`
  butteraugli
  # the modern anchors of `pupwave bench rd`: AVIF (libaom), HEVC intra (ffmpeg + libx265), WebP
  libavif-bin ffmpeg webp
  # bench/codec_speed.sh only: Grok and OpenJPH (HTJ2K) as speed peers
  grokj2k-tools openjph-tools
  # bench/encode_instructions.sh only: instruction counts that a loaded machine does not disturb
  valgrind
  # sqrt(3) meshes: OpenMesh for the subdivision cross-check test, Draco and the CGAL sample
  # meshes for bench/mesh_vs_draco.py
  libopenmesh-dev draco libcgal-demo
  # the Python module, its Pillow plugin and their tests (docs/api.md)
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest python3-pil
  # pip install of the package (pyproject.toml, setup.py) into a venv, with no package index
  python3-venv python3-pip python3-setuptools python3-wheel python3-build
  # the HDF5 filter plugin, numcodecs codec and their MPI/Dask tests and bench (docs/hdf5.md)
  libhdf5-dev libhdf5-openmpi-dev hdf5-tools python3-h5py python3-h5py-mpi openmpi-bin python3-mpi4py
  python3-zarr python3-numcodecs python3-dask python3-distributed hdf5-filter-plugin-zfp-serial
  # fuzzing and sanitizers (scripts/sanitize.sh, docs/fuzzing.md): clang with libFuzzer
  clang libclang-rt-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=""
  [[ $(id -u) -ne 0 ]] && sudo_cmd="sudo"
  $sudo_cmd apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y --no-install-recommends "${missing[@]}"
fi
