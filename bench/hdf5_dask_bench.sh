#!/usr/bin/env bash
# Dask scale-out bench: a 1024 x 1024 x 256 float32 field (1 GiB, made chunk by chunk) compressed
# into a Zarr store with the Pupwave codec by a LocalCluster of 1 and of 2 worker processes (the
# same program, tests/dask/dask_zarr.py), read back lazily and checked chunk by chunk. Runs are
# interleaved (1, 2, 1, 2, ...) so that load from other jobs hits both alike; prints one JSON line
# per run, then the medians and the 2-worker / 1-worker throughput ratios.
#   bash bench/hdf5_dask_bench.sh [BUILD_DIR] [WORK_DIR] [SHAPE] [REPEATS]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build=${1:-$root/build} work=${2:-$(mktemp -d)} shape=${3:-1024,1024,256} repeats=${4:-3}
export HDF5_PLUGIN_PATH=$build/lib/hdf5/plugins PYTHONPATH=$build/python
mkdir -p "$work"
log="$work/dask_bench.jsonl"
: >"$log"
for ((r = 0; r < repeats; r++)); do
  for workers in 1 2; do
    /usr/bin/python3 "$root/tests/dask/dask_zarr.py" "$work/bench.zarr" --shape "$shape" --chunk 128 \
      --workers "$workers" --max-error-rel 1e-3 2>/dev/null | tee -a "$log"
  done
done
rm -rf "$work/bench.zarr"
/usr/bin/python3 - "$log" <<'PY'
import json, statistics, sys
runs = [json.loads(line) for line in open(sys.argv[1])]
med = {w: {k: statistics.median(r[k] for r in runs if r["workers"] == w) for k in
           ("write_s", "check_s", "write_cpu_workers_s", "write_cpu_client_s", "write_cpu_others_s")} for w in (1, 2)}
for w, m in med.items():
    print(f"median of {sum(r['workers'] == w for r in runs)}, {w} worker(s): " + ", ".join(f"{k} {v:.2f}" for k, v in m.items()))
print(f"2 workers / 1 worker: write {med[1]['write_s'] / med[2]['write_s']:.2f}x, "
      f"check {med[1]['check_s'] / med[2]['check_s']:.2f}x")
PY
