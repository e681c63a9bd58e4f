#!/usr/bin/env bash
# Peak memory of `pupwave compress` / `decompress` on raw volumes (against the memory targets):
# the 256^3 turbulence field as u8, u16 and f32 (`generate-volume --kind turbulence --size 256`,
# the integer versions scaled to the full type range), and a 1024x1024x512 float volume (2 GiB,
# the 256^3 field tiled 4x4x2) that must compress within 3 GiB resident. Peak resident memory
# is /usr/bin/time's maximum RSS of the whole process, which includes the pages of the raw file
# mapped read-only (counted once touched) and the program's own libraries (the RSS of
# `pupwave --help`, reported as the baseline). The u8/u16/f32 inputs at 1e-3 of the range
# (max-error; the integer ones also lossless, their CLI default; u8 also at 1e-2, its lossy path).
# Usage: bench/volume_memory.sh [BUILD_DIR] [OLD_PUPWAVE]   (SKIP_BIG=1: no 2 GiB case)
# OLD_PUPWAVE: another build of the CLI measured on the same inputs, for comparison (BIG_OLD=1:
# on the 2 GiB case too).
# Writes $OUT (default /tmp/volume_memory.md); its tables go into bench/results/volumes.md. Needs ~5 GiB free in $TMPDIR for the 2 GiB case.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
old=${2:-}
pw=$build/tools/pupwave
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${OUT:-/tmp/volume_memory.md}
mib() { awk -v k="$1" 'BEGIN {printf "%.1f", k / 1024}'; }

# Runs a command once; prints "cpu_seconds max_rss_KiB" (user + system: wall time means little
# on a shared machine).
measure() {
  /usr/bin/time -f "%U %S %M" -o "$work/time" "$@" >/dev/null 2>"$work/err" || {
    cat "$work/err" >&2
    return 1
  }
  awk '{ printf "%.2f %s\n", $1 + $2, $3 }' "$work/time"
}

"$pw" generate-volume --kind turbulence --size 256 "$work/t_f32.raw" >/dev/null
# Integer versions: [min, max] mapped linearly to [0, 255] / [0, 65535], rounded.
python3 - "$work" <<'EOF'
import array, sys
w = sys.argv[1]
a = array.array('f'); a.frombytes(open(w + '/t_f32.raw', 'rb').read())
lo, hi = min(a), max(a)
for name, code, top in (('u8', 'B', 255), ('u16', 'H', 65535)):
    out = array.array(code, (int((v - lo) * (top / (hi - lo)) + 0.5) for v in a))
    if sys.byteorder != 'little': out.byteswap()
    open(w + '/t_' + name + '.raw', 'wb').write(out.tobytes())
EOF

read -r _ base < <(measure "$pw" --help)
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo "+changes")
load=$(cut -d' ' -f1-3 /proc/loadavg)
{
  echo "# Volume memory (raw input, whole process)"
  echo
  echo "Produced by \`bench/volume_memory.sh\` on $(date -u '+%Y-%m-%d %H:%M UTC') at commit $commit, $(nproc) cores,"
  echo "load average $load at the start (shared with other jobs: times are indicative only),"
  echo "\`--threads 2\`. Peak RSS is /usr/bin/time's maximum resident set, which counts the pages of"
  echo "the raw input mapped read-only once they are read, and the program's libraries: \`pupwave --help\` alone peaks at $(mib "$base") MiB (the baseline). \"Extra\" is peak"
  echo "RSS minus that baseline; the target is 1.5x the raw volume."
  echo
  echo "| input | raw MiB | mode | peak RSS MiB | extra MiB | extra / raw | CPU s | stream MiB |"
  echo "|---|---|---|---|---|---|---|---|"
} >"$out"

row() {  # label raw_file dims dtype mode args... (binary in $bin)
  local label=$1 file=$2 dims=$3 dtype=$4 mode=$5
  shift 5
  local raw_kib=$(($(stat -c %s "$file") / 1024))
  read -r s k < <(measure "$bin" compress "$file" --dims "$dims" --dtype "$dtype" --threads 2 -q "$@" "$work/s.pw")
  local stream=$(stat -c %s "$work/s.pw")
  awk -v l="$label" -v r="$raw_kib" -v m="$mode" -v k="$k" -v b="$base" -v s="$s" -v z="$stream" 'BEGIN {
    printf "| %s | %.0f | %s | %.1f | %.1f | %.2f | %.1f | %.2f |\n", l, r/1024, m, k/1024, (k-b)/1024, (k-b)/r, s, z/1048576 }' >>"$out"
}

for bin in "$pw" ${old:+"$old"}; do
  tag=$([[ $bin == "$pw" ]] && echo "" || echo " (old build)")
  row "256^3 u8$tag" "$work/t_u8.raw" 256,256,256 u8 lossless
  row "256^3 u8$tag" "$work/t_u8.raw" 256,256,256 u8 "max-error-rel 1e-3" --max-error-rel 1e-3
  # 1e-2 of 255 is a bound of 2.55: the lossy (max-error search) path, which 1e-3 (< 0.5) never takes.
  row "256^3 u8$tag" "$work/t_u8.raw" 256,256,256 u8 "max-error-rel 1e-2" --max-error-rel 1e-2
  row "256^3 u16$tag" "$work/t_u16.raw" 256,256,256 u16 lossless
  row "256^3 u16$tag" "$work/t_u16.raw" 256,256,256 u16 "max-error-rel 1e-3" --max-error-rel 1e-3
  row "256^3 f32$tag" "$work/t_f32.raw" 256,256,256 f32 "max-error-rel 1e-3" --max-error-rel 1e-3
done

{
  echo
  echo "Decoding to raw (the stored type, written brick by brick into one buffer of that type):"
  echo
  echo "| stream | raw MiB | peak RSS MiB | extra MiB | extra / raw | CPU s |"
  echo "|---|---|---|---|---|---|"
} >>"$out"
for bin in "$pw" ${old:+"$old"}; do
  tag=$([[ $bin == "$pw" ]] && echo "" || echo " (old build)")
  for t in u8 u16 f32; do  # each build decodes its own stream
    "$bin" compress "$work/t_$t.raw" --dims 256,256,256 --dtype $t --max-error-rel 1e-3 --threads 2 -q "$work/d.pw"
    read -r s k < <(measure "$bin" decompress "$work/d.pw" "$work/d.raw" --threads 2 -q)
    raw_kib=$(($(stat -c %s "$work/t_$t.raw") / 1024))
    awk -v l="256^3 $t$tag" -v r="$raw_kib" -v k="$k" -v b="$base" -v s="$s" 'BEGIN {
      printf "| %s | %.0f | %.1f | %.1f | %.2f | %.1f |\n", l, r/1024, k/1024, (k-b)/1024, (k-b)/r, s }' >>"$out"
  done
done

if [[ -z ${SKIP_BIG:-} ]]; then
  # 1024 x 1024 x 512 float: the 256^3 field tiled 4 x 4 x 2 (row by row, never all in memory).
  python3 - "$work" <<'EOF'
import sys
w = sys.argv[1]
src = open(w + '/t_f32.raw', 'rb').read()
row = 256 * 4
with open(w + '/big.raw', 'wb') as f:
    for z in range(512):
        for y in range(1024):
            at = ((z % 256) * 256 + (y % 256)) * row
            f.write(src[at:at + row] * 4)
EOF
  rm -f "$work"/t_*.raw "$work"/*.pw
  bin=$pw
  {
    echo
    echo "2 GiB float volume (target: compress within 3 GiB resident):"
    echo
    echo "| input | raw MiB | mode | peak RSS MiB | extra MiB | extra / raw | CPU s | stream MiB |"
    echo "|---|---|---|---|---|---|---|---|"
  } >>"$out"
  row "1024x1024x512 f32" "$work/big.raw" 1024,1024,512 f32 "max-error-rel 1e-3" --max-error-rel 1e-3
  if [[ -n ${BIG_OLD:-} && -n $old ]]; then  # BIG_OLD=1: the old build on it too (as long again)
    bin=$old
    row "1024x1024x512 f32 (old build)" "$work/big.raw" 1024,1024,512 f32 "max-error-rel 1e-3" --max-error-rel 1e-3
  fi
fi
cat "$out"
