#!/usr/bin/env bash
# Dask scale-out bench: a 1024 x 1024 x 256 float32 field (1 GiB, made chunk by chunk) compressed
# into a Zarr store with the Pupwave codec by a LocalCluster of 1, then 2 worker processes, read
# back lazily and checked chunk by chunk (tests/dask/dask_zarr.py). Prints one JSON line per run.
#   bash bench/hdf5_dask_bench.sh [BUILD_DIR] [WORK_DIR] [SHAPE]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build=${1:-$root/build} work=${2:-$(mktemp -d)} shape=${3:-1024,1024,256}
export HDF5_PLUGIN_PATH=$build/lib/hdf5/plugins PYTHONPATH=$build/python
for workers in 1 2; do
  /usr/bin/python3 "$root/tests/dask/dask_zarr.py" "$work/bench.zarr" --shape "$shape" --chunk 128 \
    --workers "$workers" --max-error-rel 1e-3
done
rm -rf "$work/bench.zarr"
