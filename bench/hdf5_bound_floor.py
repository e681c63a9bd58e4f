#!/usr/bin/python3
"""Where the bits go at tight bounds, beside zfp: for wmag91 and the 256^3 turbulence field at
bounds 1e-2/1e-3/1e-4 of range, Pupwave's bits per value (`pupwave compress --max-error`, whole
volume), the share of them spent on outlier corrections (`pupwave info`), its PSNR against the
PSNR of an error spread evenly over [-E, E]; H5Z-ZFP's bits per value in 128^3 chunks; and the
rate of a prediction coder that meets the bound with no outliers (indices round(x / 2E), 3-D
Lorenzo prediction of the indices, zeroth-order entropy of the residuals, as SZ does), a floor
for how far spending bits differently could go. Writes a markdown table.

    HDF5_PLUGIN_PATH=/usr/lib/x86_64-linux-gnu/hdf5/serial/plugins PYTHONPATH=build/python \
      /usr/bin/python3 bench/hdf5_bound_floor.py --cli build/tools/pupwave --out T.md
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hdf5_vs_zfp import timed_write, volumes, zfp_filter  # noqa: E402


def entropy_bits(values):
    """Zeroth-order entropy, bits per value."""
    _, counts = np.unique(values, return_counts=True)
    p = counts / counts.sum()
    return float(-(p * np.log2(p)).sum())


def lorenzo_residual(q):
    """q minus its 3-D Lorenzo prediction from the (already coded) lower neighbours, zero outside."""
    z = np.pad(q, ((1, 0), (1, 0), (1, 0)))
    pred = (z[:-1, 1:, 1:] + z[1:, :-1, 1:] + z[1:, 1:, :-1] - z[:-1, :-1, 1:] - z[:-1, 1:, :-1] - z[1:, :-1, :-1] +
            z[:-1, :-1, :-1])
    return q - pred


def pupwave_stats(cli, raw_path, shape, bound, tmp):
    """Bits per value, outlier bytes / stream bytes, PSNR of `pupwave compress` of the whole volume."""
    out = os.path.join(tmp, "whole.pw")
    dims = ",".join(str(n) for n in reversed(shape))
    run = subprocess.run([cli, "compress", raw_path, out, "--dims", dims, "--dtype", "f32", "--max-error", repr(bound),
                          "--threads", "1"], check=True, capture_output=True, text=True)
    psnr = float(re.search(r"PSNR ([0-9.]+) dB", run.stdout + run.stderr).group(1))
    info = subprocess.run([cli, "info", out], check=True, capture_output=True, text=True).stdout
    found = re.search(r"outliers\s+(\d+) bytes", info)
    size = os.path.getsize(out)
    return 8.0 * size / math.prod(shape), (int(found.group(1)) if found else 0) / size, psnr


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--images", default=os.path.join(here, "..", "testimages"))
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    lines = ["| volume | bound / range | pupwave bpv | outlier share | pupwave PSNR dB | even-error PSNR dB |"
             " zfp bpv (128^3 chunks) | bpv for 2x zfp | Lorenzo floor bpv |", "|---|---|---|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        for name, raw_path, shape in volumes(args.cli, tmp, args.images):
            data = np.fromfile(raw_path, dtype="<f4").reshape(shape)
            x = data.astype(np.float64)
            vrange = float(x.max() - x.min())
            for rel in (1e-2, 1e-3, 1e-4):
                bound = rel * vrange
                bpv, outlier_share, psnr = pupwave_stats(args.cli, raw_path, shape, bound, tmp)
                stored, _ = timed_write(os.path.join(tmp, "zfp.h5"), data, tuple(min(128, n) for n in shape),
                                        zfp_filter(bound))
                zfp_bpv = 8.0 * stored / data.size
                floor = entropy_bits(lorenzo_residual(np.round(x / (2 * bound)).astype(np.int64)))
                even_psnr = 20 * math.log10(vrange / (bound / math.sqrt(3)))  # rms of uniform [-E, E]
                lines.append(f"| {name} | {rel:g} | {bpv:.2f} | {100 * outlier_share:.1f}% | {psnr:.1f} | {even_psnr:.1f} |"
                             f" {zfp_bpv:.2f} | {zfp_bpv / 2:.2f} | {floor:.2f} |")
                print(lines[-1], flush=True)
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
