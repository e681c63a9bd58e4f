#!/usr/bin/env bash
# Sparse OpenVDB volumes side by side: file size of pupwave (--max-error) against the
# input .vdb (OpenVDB's zip/blosc) and vdb_tool's half-float output, and wall time / peak memory
# of compress, decompress and lod against vdb_lod and vdb_tool. Needs vdb_tool, vdb_lod and
# /usr/bin/time; writes a markdown table to stdout.
# Usage: bench/vdb_bench.sh [PUPWAVE] [RADIUS]   (RADIUS 250: ~3M active voxels in the level set)
set -euo pipefail
PW=${1:-build/tools/pupwave}
R=${2:-250}
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
vdb_tool -sphere radius=$R voxel=1 name=sphere -o "$DIR/ls.vdb" >/dev/null
vdb_tool -sphere radius=$((R / 2)) voxel=1 name=fog -ls2fog -o "$DIR/fog.vdb" >/dev/null

# "seconds peak_KB" of a command.
measure() { /usr/bin/time -f "%e %M" -o "$DIR/t" "$@" >/dev/null 2>&1 || true; tail -1 "$DIR/t"; }
size() { stat -c %s "$1"; }

echo "| volume | active voxels | input .vdb B | vdb_tool bits=16 B | pupwave 1e-3 of range B | compress s / MB | decompress s / MB | vdb_tool read + write bits=16 s / MB | pupwave lod 3 s / MB | vdb_lod 0-3 s / MB | pupwave lod 8 s / MB | vdb_lod 0-8 s / MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for v in ls fog; do
  in="$DIR/$v.vdb"
  active=$(vdb_print "$in" 2>/dev/null | grep -m1 -o "[0-9.]*[KM]Vox" || echo "?")
  h=$(measure vdb_tool -read "$in" -write bits=16 "$DIR/${v}_half.vdb")
  c=$(measure "$PW" compress "$in" "$DIR/$v.pw" --max-error-rel 1e-3)
  d=$(measure "$PW" decompress "$DIR/$v.pw" "$DIR/${v}_out.vdb")
  l3=$(measure "$PW" lod "$in" "$DIR/${v}_l3.vdb" --levels 3 || echo "fail -")
  v3=$(measure vdb_lod "$in" "$DIR/${v}_v3.vdb" -range 0-3)
  l8=$(measure "$PW" lod "$in" "$DIR/${v}_l8.vdb" --levels 8 || echo "fail -")
  v8=$(measure vdb_lod "$in" "$DIR/${v}_v8.vdb" -range 0-8)
  mb() { awk '{ if ($2 == "-") print $1; else printf "%s / %.0f", $1, $2 / 1024 }' <<<"$1"; }
  echo "| $v | $active | $(size "$in") | $(size "$DIR/${v}_half.vdb") | $(size "$DIR/$v.pw") | $(mb "$c") | $(mb "$d") | $(mb "$h") | $(mb "$l3") | $(mb "$v3") | $(mb "$l8") | $(mb "$v8") |"
done
