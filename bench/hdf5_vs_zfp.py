#!/usr/bin/python3
"""Pupwave's HDF5 filter against H5Z-ZFP (Debian hdf5-filter-plugin-zfp-serial), side by side in one
run, on the same chunked datasets: wmag91 (91^3) and a 256^3 turbulence field from
`pupwave generate-volume`, chunks 64^3 and 128^3 (clipped to the dataset), bounds 1e-2/1e-3/1e-4 of
the value range. Reports ratio, max error over every value, write and read throughput, and the
ratio lost to chunking against `pupwave compress` of the whole volume. Writes a markdown table.

    HDF5_PLUGIN_PATH=build/lib/hdf5/plugins:/usr/lib/x86_64-linux-gnu/hdf5/serial/plugins \
      PYTHONPATH=build/python /usr/bin/python3 bench/hdf5_vs_zfp.py --cli build/tools/pupwave \
      --out T.md   (tables for bench/results/hdf5-zarr.md)

`--volumes wmag91` (or `turbulence`) runs one volume only.
"""
import argparse
import os
import struct
import subprocess
import tempfile
import time

import h5py
import numpy as np

from pupwave.hdf5 import hdf5_filter

ZFP_ID = 32013
ZFP_MODE_ACCURACY = 3


def zfp_filter(tolerance):
    low, high = struct.unpack("<II", struct.pack("<d", tolerance))
    return {"compression": ZFP_ID, "compression_opts": (ZFP_MODE_ACCURACY, 0, low, high)}


def timed_write(path, data, chunks, kwargs):
    t0 = time.perf_counter()
    with h5py.File(path, "w") as f:
        d = f.create_dataset("x", data=data, chunks=chunks, **kwargs)
        f.flush()
        stored = d.id.get_storage_size()
    return stored, time.perf_counter() - t0


def timed_read(path):
    t0 = time.perf_counter()
    with h5py.File(path, "r") as f:
        back = f["x"][...]
    return back, time.perf_counter() - t0


def whole_volume_bytes(cli, raw_path, shape, bound, tmp):
    out = os.path.join(tmp, "whole.pw")
    dims = ",".join(str(n) for n in reversed(shape))  # x fastest
    subprocess.run([cli, "compress", raw_path, out, "--dims", dims, "--dtype", "f32", "--max-error", repr(bound)],
                   check=True, capture_output=True)
    return os.path.getsize(out)


def volumes(cli, tmp, images, which):
    if "wmag91" in which:
        yield "wmag91", os.path.join(images, "wmag91.float"), (91, 91, 91)
    if "turbulence" not in which:
        return
    turb = os.path.join(tmp, "turbulence256.raw")
    subprocess.run([cli, "generate-volume", "--kind", "turbulence", "--size", "256", turb], check=True,
                   capture_output=True)
    yield "turbulence 256^3", turb, (256, 256, 256)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--images", default=os.path.join(here, "..", "testimages"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--volumes", default="wmag91,turbulence", help="comma-separated: wmag91, turbulence")
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, raw_path, shape in volumes(args.cli, tmp, args.images, args.volumes.split(",")):
            data = np.fromfile(raw_path, dtype="<f4").reshape(shape)
            vrange = float(data.max()) - float(data.min())
            mb = data.nbytes / 1e6
            for rel in (1e-2, 1e-3, 1e-4):
                bound = rel * vrange
                whole = whole_volume_bytes(args.cli, raw_path, shape, bound, tmp)
                for edge in (64, 128):
                    chunks = tuple(min(edge, n) for n in shape)
                    row = dict(volume=name, chunks="x".join(map(str, chunks)), rel=rel, whole_ratio=data.nbytes / whole)
                    for codec, kwargs in (("pupwave", hdf5_filter(max_error=bound)), ("zfp", zfp_filter(bound))):
                        path = os.path.join(tmp, codec + ".h5")
                        stored, tw = timed_write(path, data, chunks, kwargs)
                        back, tr = timed_read(path)
                        row[codec] = dict(ratio=data.nbytes / stored, err=float(np.abs(back.astype(np.float64) - data).max()) / bound,
                                          write=mb / tw, read=mb / tr)
                    rows.append(row)
                    p, z = row["pupwave"], row["zfp"]
                    print(f"{name} {row['chunks']} {rel:g}: pupwave {p['ratio']:.1f} zfp {z['ratio']:.1f} "
                          f"({p['ratio'] / z['ratio']:.2f}x) whole {row['whole_ratio']:.1f}", flush=True)
    write_table(args.out, rows)


def write_table(path, rows):
    lines = ["| volume | chunks | bound / range | pupwave ratio | zfp ratio | pupwave / zfp | pupwave max err / bound |"
             " zfp max err / bound | pupwave write MB/s | zfp write MB/s | pupwave read MB/s | zfp read MB/s |"
             " whole-volume ratio | loss from chunking |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        p, z = r["pupwave"], r["zfp"]
        loss = 1.0 - p["ratio"] / r["whole_ratio"]
        lines.append(f"| {r['volume']} | {r['chunks']} | {r['rel']:g} | {p['ratio']:.2f} | {z['ratio']:.2f} |"
                     f" {p['ratio'] / z['ratio']:.2f}x | {p['err']:.3f} | {z['err']:.3f} | {p['write']:.1f} |"
                     f" {z['write']:.1f} | {p['read']:.1f} | {z['read']:.1f} | {r['whole_ratio']:.2f} | {100 * loss:.1f}% |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
