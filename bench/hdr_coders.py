#!/usr/bin/env python3
"""The image coders on real HDR photographs: Blender's eight studio-light environment maps
(Debian's blender-data, studiolights/world/*.exr, stored by Blender with DWAB), each resized to
512x256 half as testimages/forest_hdr.exr was made (testimages/README.md). For each map, the
default coder and `--entropy ebcot` code --bpp 0.5, 1, 2 and 4; the table gives each point's
log-PSNR (the domain pupwave codes float images in) and PSNR in linear light, and the
Bjontegaard rate difference in log-PSNR of the default against ebcot (cubic fit of log rate,
as bench/bd_vs.py). Fetches blender-data's .deb with `apt-get download` (no install).

    python3 bench/hdr_coders.py [path/to/pupwave] > /tmp/hdr_coders.md
"""
import glob
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PUPWAVE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build/tools/pupwave")
RATES = [0.5, 1, 2, 4]


def maps(tmp):
    subprocess.run(["apt-get", "download", "blender-data"], cwd=tmp, check=True, capture_output=True)
    deb = glob.glob(os.path.join(tmp, "blender-data_*.deb"))[0]
    subprocess.run(["dpkg", "-x", deb, os.path.join(tmp, "x")], check=True)
    out = []
    for src in sorted(glob.glob(os.path.join(tmp, "x/usr/share/blender/datafiles/studiolights/world/*.exr"))):
        dst = os.path.join(tmp, os.path.basename(src).replace(".exr", "_hdr.exr"))
        subprocess.run(["oiiotool", src, "--resize", "512x256", "--clamp:min=0", "-d", "half",
                        "--compression", "zip", "-o", dst], check=True)
        out.append(dst)
    return out


def point(image, coder, bpp, tmp):
    args = [PUPWAVE, "compress", image, os.path.join(tmp, "x.pw"), "--bpp", str(bpp), "--report-psnr"]
    if coder != "default":
        args += ["--entropy", coder]
    line = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    m = re.search(r"([0-9.]+) bpp, log-PSNR ([0-9.-]+) dB \(PSNR ([0-9.]+) dB\)", line)
    return float(m.group(1)), float(m.group(2)), float(m.group(3))


def bd_rate(anchor, test):
    """Mean rate difference (%) of `test` against `anchor` over their common quality range."""
    lo = max(min(q for _, q in anchor), min(q for _, q in test))
    hi = min(max(q for _, q in anchor), max(q for _, q in test))
    area = []
    for pts in (anchor, test):
        fit = np.polyint(np.polyfit([q for _, q in pts], [np.log(r) for r, _ in pts], 3))
        area.append(np.polyval(fit, hi) - np.polyval(fit, lo))
    return (np.exp((area[1] - area[0]) / (hi - lo)) - 1.0) * 100.0


def main():
    with tempfile.TemporaryDirectory() as tmp:
        print("| map | bpp | default: log-PSNR / PSNR (dB) | ebcot: log-PSNR / PSNR (dB) |")
        print("|---|---|---|---|")
        gains = {}
        for image in maps(tmp):
            name = os.path.basename(image)
            curves = {c: [point(image, c, b, tmp) for b in RATES] for c in ("default", "ebcot")}
            for i, b in enumerate(RATES):
                d, e = curves["default"][i], curves["ebcot"][i]
                print(f"| {name} | {b} | {d[1]:.2f} / {d[2]:.2f} | {e[1]:.2f} / {e[2]:.2f} |")
            gains[name] = bd_rate([(r, q) for r, q, _ in curves["ebcot"]], [(r, q) for r, q, _ in curves["default"]])
        print()
        print("| map | BD-rate of the default against ebcot (log-PSNR) |")
        print("|---|---|")
        for name, g in gains.items():
            print(f"| {name} | {g:+.1f}% |")
        print(f"| mean | {np.mean(list(gains.values())):+.1f}% |")


if __name__ == "__main__":
    main()
