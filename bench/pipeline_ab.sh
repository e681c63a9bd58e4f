#!/usr/bin/env bash
# CPU time (user + system) of compress and decompress of the 4096^2 RGB and grey mosaics at
# 1 bpp, --threads 1 and 2, for two pupwave binaries run interleaved (A, B, A, B, ...), so a
# machine shared with other work slows both alike. Median of RUNS; wall time beside it. Checks
# that both binaries write byte-identical streams and decoded images.
# Usage: bench/pipeline_ab.sh BASELINE_PUPWAVE NEW_PUPWAVE [RUNS] (codec_bench of NEW's build
# writes the mosaics). Prints a Markdown table.
set -euo pipefail
a=$1
b=$2
runs=${3:-5}
bench=$(dirname "$b")/../bench/codec_bench
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bench" --write-mosaic "$work/rgb.ppm"
"$bench" --write-grey-mosaic "$work/grey.pgm"

# One timed run: prints "wall cpu".
timed() {
  /usr/bin/time -f "%e %U %S" -o "$work/t" "$@" >/dev/null 2>&1
  awk '{printf "%s %.3f\n", $1, $2 + $3}' "$work/t"
}
median() { sort -g | awk '{v[NR]=$1} END {printf "%.3f", v[int((NR+1)/2)]}'; }

echo "| image | threads | step | baseline CPU s | new CPU s | change | baseline wall s | new wall s |"
echo "|---|---|---|---|---|---|---|---|"
for image in rgb grey; do
  ext=ppm
  [[ $image == grey ]] && ext=pgm
  for threads in 1 2; do
    : >"$work/enc_a" && : >"$work/enc_b" && : >"$work/dec_a" && : >"$work/dec_b"
    for ((i = 0; i < runs; i++)); do
      for v in a b; do
        bin=${!v}
        timed "$bin" compress "$work/$image.$ext" "$work/$v.pw" --bpp 1 --threads "$threads" >>"$work/enc_$v"
        timed "$bin" decompress "$work/$v.pw" "$work/$v.$ext" --threads "$threads" >>"$work/dec_$v"
      done
    done
    cmp -s "$work/a.pw" "$work/b.pw" || echo "WARNING: streams differ ($image, $threads threads)" >&2
    cmp -s "$work/a.$ext" "$work/b.$ext" || echo "WARNING: decoded images differ ($image)" >&2
    for step in enc dec; do
      ca=$(awk '{print $2}' "$work/${step}_a" | median)
      cb=$(awk '{print $2}' "$work/${step}_b" | median)
      wa=$(awk '{print $1}' "$work/${step}_a" | median)
      wb=$(awk '{print $1}' "$work/${step}_b" | median)
      name=$([[ $step == enc ]] && echo compress || echo decompress)
      echo "| $image | $threads | $name | $ca | $cb | $(awk -v a="$ca" -v b="$cb" 'BEGIN{printf "%+.1f%%", 100*(b-a)/a}') | $wa | $wb |"
    done
  done
done
