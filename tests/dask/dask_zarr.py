"""Compresses a dask array into a Zarr v2 store with the Pupwave numcodecs codec on a
dask.distributed LocalCluster of worker processes, reads it back lazily and checks the bound
chunk by chunk. The field is made chunk by chunk (never whole in memory): a sum of separable
Fourier modes with a Kolmogorov-like k^(-5/6) amplitude (energy k^(-5/3)), continuous across
chunks. Used by ctest (small) and bench/hdf5_dask_bench.sh (>= 1 GiB).

    dask_zarr.py STORE --shape 256,256,128 --chunk 64 --workers 2 --max-error-rel 1e-3
"""
import argparse
import json
import os
import shutil
import time

import dask
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


def field_block(period, chunks, block_id):
    """One chunk of the field at its global position. The sum of separable modes is a rank-MODES
    tensor, so it is one matrix product ((z*y) x MODES) @ (MODES x x) instead of MODES passes over
    the chunk: 3x less CPU and memory traffic per chunk, leaving the workers' time to the codec."""
    k, phase, amp = modes()
    loc = [(sum(c[:b]), sum(c[: b + 1])) for c, b in zip(chunks, block_id)]
    # s[i][n, m] = sin(k_mi * t_n + phase_mi) along axis i (z, y, x) of this chunk.
    s = [np.sin(np.outer(2 * np.pi * np.arange(lo, hi) / period, k[:, i]) + phase[:, i]) for i, (lo, hi) in enumerate(loc)]
    zy = (s[0][:, None, :] * s[1][None, :, :] * amp).reshape(-1, MODES)
    return (zy @ s[2].T).reshape(tuple(hi - lo for lo, hi in loc)).astype(np.float32)


def field(shape, chunk):
    """The lazy field; each task makes one chunk (block_id, not block_info: no extra task per chunk)."""
    chunks = tuple(tuple(min(chunk, n - i) for i in range(0, n, chunk)) for n in shape)
    period = max(shape)
    return da.map_blocks(lambda block_id=None: field_block(period, chunks, block_id), dtype=np.float32, chunks=chunks)


def worker_environ():
    """dask's default worker environment less MALLOC_TRIM_THRESHOLD_: setting it (dask sets 64 KiB)
    turns off glibc's dynamic mmap threshold, so every chunk-sized buffer (the field, the codec's
    copy of the chunk) is mmapped, page-faulted and zeroed afresh: 4.6x the page faults, 20-50%
    more CPU per chunk, and munmap's TLB shootdowns interrupt the other worker's core."""
    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
    environ.pop("MALLOC_TRIM_THRESHOLD_", None)
    return environ


# dask's housekeeping on every process (an event-loop health tick every 20 ms, system and memory
# monitors, a statistical profiler sampling the running task every 10 ms) takes 12% of a core
# when idle, on event-loop threads that run beside the task on the other core: free for one
# worker, taken from the second worker on a 2-core machine. Slower housekeeping cuts that to 2%.
QUIET = {"distributed.admin.tick.interval": "500ms", "distributed.admin.system-monitor.interval": "2s",
         "distributed.worker.memory.monitor-interval": "1s", "distributed.worker.profile.enabled": False}


def cpu_seconds(client):
    """CPU seconds used so far by the workers (each process, all its threads), this process (the
    client and the LocalCluster's scheduler and nannies) and the whole machine (busy, from
    /proc/stat), to tell what a run's processes used from what other jobs took."""
    workers = sum(client.run(time.process_time).values())
    with open("/proc/stat") as f:
        ticks = [int(v) for v in f.readline().split()[1:]]
    busy = (sum(ticks) - ticks[3] - ticks[4]) / os.sysconf("SC_CLK_TCK")  # all but idle and iowait
    return workers, time.process_time(), busy


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
    config = {**QUIET, "distributed.nanny.pre-spawn-environ": worker_environ()}
    with dask.config.set(config), LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                               memory_limit="2GiB", dashboard_address=None,
                                               preload=["pupwave.numcodecs"]) as cluster, Client(cluster) as client:
        x = field(shape, args.chunk)
        cpu0, t0 = cpu_seconds(client), time.perf_counter()
        da.to_zarr(x, args.store, compressor=Pupwave(max_error=bound), overwrite=True)
        t_write = time.perf_counter() - t0
        cpu = [b - a for a, b in zip(cpu0, cpu_seconds(client))]
        back = da.from_zarr(args.store)
        t0 = time.perf_counter()
        err = float(da.abs(back.astype(np.float64) - field(shape, args.chunk).astype(np.float64)).max().compute())
        t_check = time.perf_counter() - t0
    stored = sum(p.stat().st_size for p in __import__("pathlib").Path(args.store).rglob("*") if p.is_file())
    raw = int(np.prod(shape)) * 4
    result = dict(shape=shape, chunk=args.chunk, workers=args.workers, bound=bound, max_error=err,
                  ratio=raw / stored, raw_bytes=raw, write_s=t_write, write_mb_s=raw / 1e6 / t_write,
                  check_s=t_check, write_cpu_workers_s=cpu[0], write_cpu_client_s=cpu[1],
                  write_cpu_others_s=cpu[2] - cpu[0] - cpu[1], cores=os.cpu_count())
    print(json.dumps(result))
    if not err <= bound:
        raise SystemExit(f"bound violated: {err} > {bound}")


if __name__ == "__main__":
    main()
