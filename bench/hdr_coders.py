#!/usr/bin/env python3
"""The default coder against the bit-plane coder on real HDR photographs and their 16-bit
conversions: Blender's eight studio-light environment maps (Debian's blender-data,
studiolights/world/*.exr, stored by Blender with DWAB), each resized to 512x256 half as
testimages/forest_hdr.exr was made, and each tone-mapped to 16-bit RGB as
testimages/courtyard16.png was (testimages/README.md: exposure to a mean of 0.18, clipped at 1,
gamma 1/2.2). For each image the default coder and `--entropy ebcot` code --bpp 0.5, 1, 2 and 4;
the tables give each point's quality and the Bjontegaard rate difference of the default against
ebcot (cubic fit of log rate, as bench/bd_vs.py): in log-PSNR for the float maps (the domain
pupwave codes float images in; PSNR in linear light is listed beside it), in PSNR for the 16-bit
ones. Fetches blender-data's .deb with `apt-get download` (no install).

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
        mean = subprocess.run(["oiiotool", "--stats", dst], check=True, capture_output=True, text=True).stdout
        avg = [float(v) for v in re.search(r"Stats Avg: ([0-9.e+-]+) ([0-9.e+-]+) ([0-9.e+-]+)", mean).groups()]
        tone = dst.replace("_hdr.exr", "16.png")
        subprocess.run(["oiiotool", dst, "--mulc", str(0.18 / (sum(avg) / 3.0)), "--clamp:min=0:max=1",
                        "--powc", "0.4545", "-d", "uint16", "-o", tone], check=True)
        out.append(dst)
        out.append(tone)
    return out


def point(image, coder, bpp, tmp):
    args = [PUPWAVE, "compress", image, os.path.join(tmp, "x.pw"), "--bpp", str(bpp), "--report-psnr"]
    if coder != "default":
        args += ["--entropy", coder]
    line = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    m = re.search(r"([0-9.]+) bpp, log-PSNR ([0-9.-]+) dB \(PSNR ([0-9.]+) dB\)", line)
    if m:
        return float(m.group(1)), float(m.group(2)), float(m.group(3))
    m = re.search(r"([0-9.]+) bpp, PSNR ([0-9.]+) dB", line)  # an integer image: PSNR only
    return float(m.group(1)), float(m.group(2)), float(m.group(2))


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
        print("| image | bpp | default: log-PSNR / PSNR (dB) | ebcot: log-PSNR / PSNR (dB) |")
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
        print("| image | BD-rate of the default against ebcot (log-PSNR for the EXR maps, PSNR for 16-bit) |")
        print("|---|---|")
        for name, g in gains.items():
            print(f"| {name} | {g:+.1f}% |")
        for kind, suffix in (("float", ".exr"), ("16-bit", ".png")):
            mean = np.mean([g for n, g in gains.items() if n.endswith(suffix)])
            print(f"| mean, {kind} | {mean:+.1f}% |")


if __name__ == "__main__":
    main()
