#!/usr/bin/env python3
"""The same crop of one photograph from every codec of a `pupwave bench rd` run at one target
rate, side by side in one PNG (the original first), so a reader can see the difference.

Each codec is run again with the setting the harness kept (results.csv's `setting` column: the
same file size), so nothing of the run's own files is needed.

usage: crop_grid.py RESULTS.CSV IMAGE.png BPP X,Y,W,H OUT.png [PUPWAVE]
Needs python3-pil and the tools of the codecs in the CSV (pupwave, opj_*, avifenc/avifdec,
cjxl/djxl) in PATH.
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw


def decoded(row, src_png, src_ppm, work, pupwave):
    """The decoded image of `row`'s codec at its kept setting, as a PIL image."""
    codec, setting = row["codec"], row["setting"]
    out = os.path.join(work, codec + ".png")
    if row["kind"] == "pupwave":
        flags = re.sub(r"\s*\(.*\)$", "", setting).split()
        subprocess.run([pupwave, "compress", "-q", src_png, work + "/a.pw", *flags], check=True)
        subprocess.run([pupwave, "decompress", "-q", work + "/a.pw", out], check=True)
    elif codec == "openjpeg":
        subprocess.run(["opj_compress", "-i", src_ppm, "-o", work + "/a.j2k", *setting.split()], check=True,
                       capture_output=True)
        subprocess.run(["opj_decompress", "-i", work + "/a.j2k", "-o", out], check=True, capture_output=True)
    elif codec.startswith("avif"):
        m = re.match(r"-s (\d+) -y (\d+) --min/--max (\d+)", setting)
        s, y, q = m.groups()
        subprocess.run(["avifenc", "-s", s, "-y", y, "--min", q, "--max", q, src_png, work + "/a.avif"], check=True,
                       capture_output=True)
        subprocess.run(["avifdec", work + "/a.avif", out], check=True, capture_output=True)
    elif codec == "jxl":
        d = re.match(r"-d ([0-9.]+)", setting).group(1)
        subprocess.run(["cjxl", "-d", d, src_png, work + "/a.jxl"], check=True, capture_output=True)
        subprocess.run(["djxl", work + "/a.jxl", out], check=True, capture_output=True)
    else:
        raise SystemExit(f"crop_grid.py: no way to run codec {codec}")
    return Image.open(out).convert("RGB")


def main():
    if len(sys.argv) not in (6, 7):
        raise SystemExit(__doc__)
    results, src_png, bpp, box, out = sys.argv[1:6]
    pupwave = sys.argv[6] if len(sys.argv) == 7 else "pupwave"
    x, y, w, h = (int(v) for v in box.split(","))
    stem = os.path.splitext(os.path.basename(src_png))[0]
    with open(results, newline="") as f:
        rows = [r for r in csv.DictReader(f)
                if r["image"] == stem and float(r["target_bpp"]) == float(bpp) and r["status"] == "ok"]
    if not rows:
        raise SystemExit(f"crop_grid.py: no ok rows for {stem} at {bpp} bpp in {results}")
    original = Image.open(src_png).convert("RGB")
    tiles = [("original", original)]
    with tempfile.TemporaryDirectory() as work:
        src_ppm = os.path.join(work, "src.ppm")
        original.save(src_ppm)
        for r in rows:
            label = f"{r['codec']} {float(r['bpp']):.3f} bpp"
            if r.get("butteraugli"):
                label += f", BA {float(r['butteraugli']):.2f}"
            tiles.append((label, decoded(r, src_png, src_ppm, work, pupwave)))
    label_h = 16
    grid = Image.new("RGB", (w * len(tiles), h + label_h), "white")
    draw = ImageDraw.Draw(grid)
    for i, (label, img) in enumerate(tiles):
        grid.paste(img.crop((x, y, x + w, y + h)), (i * w, label_h))
        draw.text((i * w + 3, 2), label, fill="black")
    grid.save(out, optimize=True)


if __name__ == "__main__":
    main()
