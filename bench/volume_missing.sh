#!/usr/bin/env bash
# Missing values: wmag91 (testimages/) with a land mask (every voxel below 8, about a fifth, set
# to NaN, and a 31 x 24 x 20 corner block set to the fill value -999), coded at an absolute bound
# E of 1e-3 / 1e-2 of the valid voxels' range, against the same field without the mask (every
# voxel valid, the masked ones holding their original values) and against the masked voxels set to
# 0 (what a coder without missing values needs: the zeros are coded as data). Peer: zfp (fixed
# accuracy E) on the same two unmasked inputs; zfp does not keep NaN. Each Pupwave stream is
# decoded and checked: missing voxels bit for bit, the rest within E.
# Usage: bench/volume_missing.sh [path/to/pupwave] > T.md  (the table for bench/results/volumes.md)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
pupwave=$(realpath "${1:-$here/../build/tools/pupwave}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$pupwave" "$work" "$here/../testimages/wmag91.float" <<'PY'
import shutil, subprocess, sys
import numpy as np
pupwave, work, source = sys.argv[1:4]
v = np.fromfile(source, '<f4').reshape(91, 91, 91)
masked = v.copy()
masked[masked < 8] = np.nan
masked[:20, :24, 60:] = -999.0
missing = np.isnan(masked) | (masked == -999.0)
zeroed = np.where(missing, 0, v).astype('<f4')
valid = v[~missing]
span = float(valid.max() - valid.min())
for name, a in (("masked", masked), ("original", v), ("zeroed", zeroed)):
    a.astype('<f4').tofile(f"{work}/{name}.f32")
zfp = shutil.which("zfp")
print(f"wmag91, {missing.sum()} of {v.size} voxels missing ({100 * missing.mean():.1f}%); "
      f"valid range {span:.6g}; sizes in bytes\n")
print("| E / valid range | Pupwave, NaN + fill mask | Pupwave, no mask (original values) | "
      "Pupwave, missing set to 0 | zfp, no mask | zfp, missing set to 0 |")
print("|---|---|---|---|---|---|")
for rel in (1e-2, 1e-3):
    e = rel * span
    sizes = []
    for name in ("masked", "original", "zeroed"):
        out = f"{work}/{name}.pw"
        extra = ["--fill-value", "-999"] if name == "masked" else []
        subprocess.run([pupwave, "compress", f"{work}/{name}.f32", out, "--dims", "91,91,91",
                        "--dtype", "f32", "--max-error", repr(e), "-q", *extra], check=True)
        subprocess.run([pupwave, "decompress", out, f"{work}/{name}.raw", "-q"], check=True)
        back = np.fromfile(f"{work}/{name}.raw", '<f4').reshape(v.shape)
        if name == "masked":
            assert np.array_equal(back.view('<u4')[missing], masked.view('<u4')[missing])
            assert np.abs(back[~missing].astype(float) - masked[~missing]).max() <= e
        sizes.append(str(len(open(out, 'rb').read())))
    for name in ("original", "zeroed"):
        if zfp is None:
            sizes.append("-")
            continue
        subprocess.run([zfp, "-f", "-3", "91", "91", "91", "-a", repr(e), "-i", f"{work}/{name}.f32",
                        "-z", f"{work}/{name}.zfp"], check=True, stderr=subprocess.DEVNULL)
        sizes.append(str(len(open(f"{work}/{name}.zfp", 'rb').read())))
    print(f"| {rel:g} | " + " | ".join(sizes) + " |")
PY
