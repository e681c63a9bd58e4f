"""Compresses a dask array into a Zarr v2 store with the Pupwave numcodecs codec on a
dask.distributed LocalCluster of worker processes, reads it back lazily and checks the bound
chunk by chunk. The field is made chunk by chunk (never whole in memory): a sum of separable
Fourier modes with a Kolmogorov-like k^(-5/6) amplitude (energy k^(-5/3)), continuous across
chunks. Used by ctest (small) and bench/hdf5_dask_bench.sh (>= 1 GiB).

    dask_zarr.py STORE --shape 256,256,128 --chunk 64 --workers 2 --max-error-rel 1e-3
"""
import argparse
import json
import shutil
import time

import dask.array as da
import numpy as np
from dask.distributed import Client, LocalCluster

MODES = 24


def modes(seed=7):
    rng = np.random.default_rng(seed)
    k = rng.integers(1, 12, size=(MODES, 3))
    phase = rng.uniform(0, 2 * np.pi, size=(MODES, 3))
    amp = np.linalg.norm(k, axis=1) ** (-5.0 / 6.0)
    return k, phase, amp


def field_block(period, block_info=None):
    """One chunk of the field at its global position (dask's block_info gives the location)."""
    k, phase, amp = modes()
    loc = block_info[None]["array-location"]
    axes = [2 * np.pi * np.arange(lo, hi) / period for lo, hi in loc]
    out = np.zeros(tuple(hi - lo for lo, hi in loc), dtype=np.float64)
    for m in range(MODES):
        z, y, x = (np.sin(k[m, i] * axes[i] + phase[m, i]) for i in range(3))
        out += amp[m] * z[:, None, None] * y[None, :, None] * x[None, None, :]
    return out.astype(np.float32)


def field(shape, chunk):
    """The lazy field; each task makes one chunk."""
    chunks = tuple(tuple(min(chunk, n - i) for i in range(0, n, chunk)) for n in shape)
    period = max(shape)
    return da.map_blocks(lambda block_info=None: field_block(period, block_info), dtype=np.float32, chunks=chunks)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("store")
    ap.add_argument("--shape", default="256,256,128")
    ap.add_argument("--chunk", type=int, default=64)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--max-error-rel", type=float, default=1e-3)
    args = ap.parse_args()
    shape = tuple(int(s) for s in args.shape.split(","))
    from pupwave.numcodecs import Pupwave
    amplitude = float(modes()[2].sum())  # |field| <= sum of amplitudes, so range <= 2 * that
    bound = args.max_error_rel * 2 * amplitude
    shutil.rmtree(args.store, ignore_errors=True)
    # Workers unpickle zarr arrays whose metadata names the codec: preload registers it there.
    with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, memory_limit="2GiB",
                      dashboard_address=None, preload=["pupwave.numcodecs"]) as cluster, Client(cluster):
        x = field(shape, args.chunk)
        t0 = time.perf_counter()
        da.to_zarr(x, args.store, compressor=Pupwave(max_error=bound), overwrite=True)
        t_write = time.perf_counter() - t0
        back = da.from_zarr(args.store)
        t0 = time.perf_counter()
        err = float(da.abs(back.astype(np.float64) - field(shape, args.chunk).astype(np.float64)).max().compute())
        t_check = time.perf_counter() - t0
    stored = sum(p.stat().st_size for p in __import__("pathlib").Path(args.store).rglob("*") if p.is_file())
    raw = int(np.prod(shape)) * 4
    result = dict(shape=shape, chunk=args.chunk, workers=args.workers, bound=bound, max_error=err,
                  ratio=raw / stored, raw_bytes=raw, write_s=t_write, write_mb_s=raw / 1e6 / t_write,
                  check_s=t_check)
    print(json.dumps(result))
    if not err <= bound:
        raise SystemExit(f"bound violated: {err} > {bound}")


if __name__ == "__main__":
    main()
