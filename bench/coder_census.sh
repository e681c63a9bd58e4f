#!/usr/bin/env bash
# Census of the image entropy coders: for every coder that accepts the case, on three real
# photographs (camera: grey; astronaut, coffee: RGB) and a 16-bit source (courtyard16), the
# bytes, PSNR and encode / decode CPU seconds (user + system, one thread) at --bpp 0.5, 1, 2 and
# --lossless. CPU time, not wall time: the machine may be shared. Each encode and decode is run
# REPS times inside one /usr/bin/time (the images take milliseconds, below its 10 ms
# resolution) and the mean per run is reported, beside the floor every run pays (process start,
# `pupwave --version`). On images this small reading, writing and starting take much of a run,
# so a fifth case, astronaut tiled 4 x 4 (2048 x 2048, `oiiotool --mosaic`), run LARGE_REPS
# times, shows the coders' own speed. A coder that refuses a case shows its error.
# Writes Markdown tables to $OUT (default /tmp/coder_census.md); they go into
# bench/results/coders.md.
# Usage: bench/coder_census.sh [BUILD_DIR] [REPS] [LARGE_REPS]   (defaults: build, 10, 2)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-10}
large_reps=${3:-2}
pw=$build/tools/pupwave
out=${OUT:-/tmp/coder_census.md}
coders=${CODERS:-ebcot pc lc ht}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# CPU seconds (user + system) per run of `reps` runs of a command; non-zero exit if any fails.
cpu_per_run() {
  /usr/bin/time -f "%U %S" -o "$work/time" \
    bash -c 'for ((k = 0; k < $0; k++)); do "$@" >/dev/null 2>"'"$work"'/err" || exit 1; done' "$reps" "$@" ||
    return 1
  awk -v r="$reps" '{printf "%.4f", ($1 + $2) / r}' "$work/time"
}
psnr_of() { "$pw" psnr "$1" "$2" | awk '$1=="all"{print $3}'; }
# The coder the stream names (a rate target that gives no file smaller than lossless codes lc).
coder_of() { "$pw" info "$1" | sed -nE 's/.*, entropy ([a-z0-9]+),.*/\1/p'; }

# One table per image: every target, every coder.
table() {
  local img=$1 title=$2 w h channels type ext=ppm
  # `pupwave info` of an image: "PATH: png image, W x H, C channel(s) (...), TYPE".
  read -r w h channels type < <("$pw" info "$img" | sed -E 's/.*, ([0-9]+) x ([0-9]+), ([0-9]+) channels? .*, ([a-z0-9]+)$/\1 \2 \3 \4/')
  ((channels == 1)) && ext=pgm
  echo
  echo "### $title (${w}x${h}, $channels channel(s) $type, $reps run(s) each)"
  echo
  echo "| coder | target | stream coder | bytes | bpp | PSNR dB | encode s | decode s |"
  echo "|---|---|---|---:|---:|---:|---:|---:|"
  for target in 0.5 1 2 lossless; do
    for coder in $coders; do row "$img" "$ext" "$coder" "$target" $((w * h)); done
  done
}

# One table row: coder, target (a --bpp value or "lossless").
row() {
  local img=$1 ext=$2 coder=$3 target=$4 pixels=$5 rate_args enc dec bytes
  if [[ $target == lossless ]]; then rate_args=(--lossless); else rate_args=(--bpp "$target"); fi
  local stream=$work/s.pw decoded=$work/d.$ext
  if ! enc=$(cpu_per_run "$pw" compress -q --threads 1 --entropy "$coder" "${rate_args[@]}" "$img" "$stream"); then
    echo "| $coder | $target | refused: $(head -c 160 "$work/err" | tr '\n|' ' /') | | | | | |"
    return
  fi
  dec=$(cpu_per_run "$pw" decompress -q --threads 1 "$stream" "$decoded")
  bytes=$(stat -c %s "$stream")
  echo "| $coder | $target | $(coder_of "$stream") | $bytes | $(awk -v b="$bytes" -v n="$pixels" 'BEGIN{printf "%.4f", b*8/n}') | $(psnr_of "$img" "$decoded") | $enc | $dec |"
}

{
  echo "pupwave coder census: $(date -u +%F), $(nproc) CPU(s) ($(awk -F': ' '/model name/{print $2; exit}' /proc/cpuinfo)),"
  echo "CPU seconds (user + system) per run, --threads 1; floor (\`pupwave --version\`): $(cpu_per_run "$pw" --version) s."
  for img in testimages/camera.png testimages/astronaut.png testimages/coffee.png testimages/courtyard16.png; do
    table "$img" "$(basename "$img")"
  done
  oiiotool $(printf 'testimages/astronaut.png %.0s' {1..16}) --mosaic 4x4 -o "$work/astronaut4x4.ppm"
  reps=$large_reps
  table "$work/astronaut4x4.ppm" "astronaut.png tiled 4 x 4"
} | tee "$out"
