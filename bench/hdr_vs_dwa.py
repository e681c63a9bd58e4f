#!/usr/bin/env python3
"""Pupwave against OpenEXR's lossy DWAA and DWAB at DWA's own sizes, JPEG XL beside, on real
HDR images: the eight environment maps of Debian's blender-data (studiolights/world/*.exr,
stored by Blender with DWAB, resized to 512x256 half as bench/hdr_coders.py makes them; one of
them is testimages/forest_hdr.exr). For each image and each Q in 45, 100, 200, 400, oiiotool writes
`--compression dwaa:Q` and `dwab:Q`; each Pupwave transfer (--transfer NAME) and cjxl (on PFM,
as bench/hdr_compare.sh) give the largest file not above that size (a search over --bpp; for
cjxl, the largest of 16 distances from 0.04 to 6 spaced evenly in log). Each decode is measured against the input: log-PSNR (peak 1 stop over
log2(1 + |x|/2^-14), codec/image/transfer.h) and linear-light PSNR (peak = the input's largest
sample, all channels).

    python3 bench/hdr_vs_dwa.py [path/to/pupwave] [--transfers log,adaptive] > /tmp/hdr_vs_dwa.md
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import hdr_coders  # noqa: E402  (the eight maps, prepared one way for every HDR benchmark)
import tiff_to_pfm  # noqa: E402

QUALITIES = [45, 100, 200, 400]
LOG_OFFSET = 2.0**-14


def read_float(path, tmp):
    """An image file's samples as float64 (height, width, channels), through oiiotool."""
    tif, pfm = os.path.join(tmp, "r.tif"), os.path.join(tmp, "r.pfm")
    subprocess.run(["oiiotool", path, "-d", "float", "--compression", "none", "--attrib", "tiff:RowsPerStrip",
                    "100000", "-o", tif], check=True)
    tiff_to_pfm.main(tif, pfm)
    return read_pfm(pfm)


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    channels = 3 if kind == b"PF" else 1
    return data.reshape(height, width, channels)[::-1].astype(np.float64)


def metrics(ref, test):
    """(log-PSNR, linear-light PSNR) of `test` against `ref`."""
    t = lambda x: np.sign(x) * np.log2(1.0 + np.abs(x) / LOG_OFFSET)  # noqa: E731
    log_mse = np.mean((t(ref) - t(test)) ** 2)
    lin_mse = np.mean((ref - test) ** 2)
    return 10 * np.log10(1.0 / log_mse), 10 * np.log10(ref.max() ** 2 / lin_mse)


def pupwave_fit(pw, image, budget, pixels, transfer, tmp):
    """The largest Pupwave file not above `budget` bytes: (bytes, decoded path), or None."""
    coded, out = os.path.join(tmp, "p.pw"), os.path.join(tmp, "p.exr")
    best, lo, hi = None, 0.0, None
    bpp = 8.0 * budget / pixels
    for _ in range(8):
        subprocess.run([pw, "compress", image, coded, "--bpp", f"{bpp:.6f}", "--transfer", transfer],
                       check=True, capture_output=True)
        size = os.path.getsize(coded)
        if size <= budget:
            if best is None or size > best:
                best = size
                subprocess.run([pw, "decompress", coded, out], check=True, capture_output=True)
            if size >= 0.995 * budget:
                break
            lo = bpp
        else:
            hi = bpp
        bpp = (lo + hi) / 2 if hi is not None else bpp * budget / size
        if hi is None and size <= budget:
            bpp = min(bpp, lo * 1.2)
    return (best, out) if best is not None else None


def jxl_ladder(pfm, tmp):
    """cjxl (on the PFM, declared linear sRGB) at a ladder of distances: [(bytes, decoded)]."""
    jxl, dec = os.path.join(tmp, "j.jxl"), os.path.join(tmp, "j.pfm")
    hint = "--dec-hints=color_space=RGB_D65_SRG_Rel_Lin"
    out = []
    for d in np.geomspace(0.04, 6.0, 16):
        subprocess.run(["cjxl", pfm, jxl, "-d", f"{d:.4f}", hint], check=True, capture_output=True)
        subprocess.run(["djxl", jxl, dec, "--color_space=RGB_D65_SRG_Rel_Lin"], check=True, capture_output=True)
        out.append((os.path.getsize(jxl), read_pfm(dec)))
    return out


def jxl_fit(ladder, budget):
    """The largest file of the ladder not above `budget` bytes, or None."""
    fits = [r for r in ladder if r[0] <= budget]
    return max(fits, key=lambda r: r[0]) if fits else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("pupwave", nargs="?", default=os.path.join(ROOT, "build/tools/pupwave"))
    ap.add_argument("--transfers", default="log,adaptive", help="comma list of --transfer values")
    ap.add_argument("--images", default="", help="comma list of image names to keep (default: all)")
    ap.add_argument("--no-jxl", action="store_true")
    args = ap.parse_args()
    transfers = args.transfers.split(",")
    head = ["image", "Q", "DWA bytes", "DWA log / lin"]
    head += [f"pupwave {t}: bytes, log / lin" for t in transfers] + ([] if args.no_jxl else ["JPEG XL bytes, log / lin"])
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    wins = {t: [0, 0] for t in transfers}
    with tempfile.TemporaryDirectory() as tmp:
        # blender-data's forest.exr made this way is testimages/forest_hdr.exr, sample for sample.
        images = [p for p in hdr_coders.maps(tmp) if p.endswith(".exr")]
        if args.images:
            images = [p for p in images if os.path.basename(p) in args.images.split(",")]
        for image in images:
            name = os.path.basename(image)
            ref = read_float(image, tmp)
            pixels = ref.shape[0] * ref.shape[1]
            tif, pfm = os.path.join(tmp, "in.tif"), os.path.join(tmp, "in.pfm")
            subprocess.run(["oiiotool", image, "-d", "float", "--compression", "none", "--attrib",
                            "tiff:RowsPerStrip", "100000", "-o", tif], check=True)
            tiff_to_pfm.main(tif, pfm)
            ladder = [] if args.no_jxl else jxl_ladder(pfm, tmp)
            for q in QUALITIES:
                for codec in ("dwaa", "dwab"):
                    dwa = os.path.join(tmp, "d.exr")
                    subprocess.run(["oiiotool", image, "--compression", f"{codec}:{q}", "-o", dwa], check=True)
                    budget = os.path.getsize(dwa)
                    d_log, d_lin = metrics(ref, read_float(dwa, tmp))
                    row = [name, f"{codec}:{q}", str(budget), f"{d_log:.2f} / {d_lin:.2f}"]
                    for t in transfers:
                        fit = pupwave_fit(args.pupwave, image, budget, pixels, t, tmp)
                        if fit is None:
                            row.append("none fits")
                            continue
                        p_log, p_lin = metrics(ref, read_float(fit[1], tmp))
                        won = p_log > d_log and p_lin > d_lin
                        wins[t][0] += won
                        wins[t][1] += 1
                        mark = "" if won else " (not both)"
                        row.append(f"{fit[0]}, {p_log:.2f} / {p_lin:.2f}{mark}")
                    if not args.no_jxl:
                        j = jxl_fit(ladder, budget)
                        if j is None:
                            row.append("none fits")
                        else:
                            j_log, j_lin = metrics(ref, j[1])
                            row.append(f"{j[0]}, {j_log:.2f} / {j_lin:.2f}")
                    print("| " + " | ".join(row) + " |", flush=True)
    print()
    for t, (won, n) in wins.items():
        print(f"pupwave --transfer {t}: ahead of DWA in both measures at {won} of {n} points")


if __name__ == "__main__":
    main()
