#!/usr/bin/env bash
# Box decode benchmark: a generated 256^3 turbulence field coded at --max-error-rel 1e-3 (64^3
# bricks), then `pupwave decompress --box` of cubes of edge 16, 32, 64, 128 and 256 at the
# volume's origin corner, at levels 0 and 2, against the whole decode. CPU seconds (user + system,
# /usr/bin/time) of the whole process (reading and checking the stream included), median of 3,
# one thread. Each box output is checked against the same box cut out of the whole decode.
# Usage: bench/volume_box.sh [path/to/pupwave] > T.md  (the table for bench/results/volumes.md)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
pupwave=$(realpath "${1:-$here/../build/tools/pupwave}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$pupwave" generate-volume --kind turbulence --size 256 "$work/turb.raw" > /dev/null
"$pupwave" compress "$work/turb.raw" "$work/turb.pw" --dims 256,256,256 --dtype f32 --max-error-rel 1e-3 -q
python3 - "$pupwave" "$work" <<'PY'
import os, statistics, subprocess, sys
pupwave, work = sys.argv[1], sys.argv[2]
stream = f"{work}/turb.pw"
N, BRICK = 256, 64

def cpu(cmd):
    """CPU seconds (user + system) of one whole process."""
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S"] + cmd, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    user, system = p.stderr.strip().splitlines()[-1].split()
    return float(user) + float(system)

def median_cpu(cmd):
    return statistics.median(cpu(cmd) for _ in range(3))

def decode(out, level, box=None):
    cmd = [pupwave, "decompress", stream, out, "--level", str(level), "--threads", "1", "-q"]
    return cmd + (["--box", box] if box else [])

def crop_matches(whole, part, edge, level):
    """Whether `part` is the level-`level` crop [0, edge) of `whole` (float32 raw files)."""
    n, e = -(-N // 2**level), -(-edge // 2**level)
    with open(whole, "rb") as f:
        w = f.read()
    with open(part, "rb") as f:
        p = f.read()
    rows = [w[4 * n * (y + n * z): 4 * (n * (y + n * z) + e)] for z in range(e) for y in range(e)]
    return b"".join(rows) == p

size = os.path.getsize(stream)
print(f"256^3 turbulence, max-error-rel 1e-3, 64^3 bricks ({size / 2**20:.1f} MiB stream); "
      "CPU s, median of 3, --threads 1\n")
print("| box edge | voxels | bricks decoded | level 0 CPU s | level 2 CPU s |")
print("|---:|---:|---:|---:|---:|")
wholes = {}
for level in (0, 2):
    wholes[level] = f"{work}/whole{level}.raw"
    subprocess.run(decode(wholes[level], level), check=True)
for edge in (16, 32, 64, 128, 256):
    box = f"0,0,0:{edge},{edge},{edge}"
    times = []
    for level in (0, 2):
        out = f"{work}/box{level}.raw"
        times.append(median_cpu(decode(out, level, box)))
        assert crop_matches(wholes[level], out, edge, level), (edge, level)
    bricks = (-(-edge // BRICK)) ** 3
    print(f"| {edge} | {edge**3} | {bricks} | {times[0]:.2f} | {times[1]:.2f} |")
print(f"| whole decode (no --box) | {N**3} | {(N // BRICK)**3} | {median_cpu(decode(wholes[0], 0)):.2f} | "
      f"{median_cpu(decode(wholes[2], 2)):.2f} |")
PY
