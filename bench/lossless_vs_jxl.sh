#!/usr/bin/env bash
# Lossless sizes and CPU times on the four test photographs: pupwave's lc coder (the --lossless
# default), pupwave's bit-plane coder (--entropy ebcot), JPEG XL
# (cjxl -d 0 -e 7) and OpenJPEG (opj_compress, lossless 5/3 by default). Every tool reads the
# same binary PNM (pupwave maps it without its image library, whose start-up costs about 0.25 s
# of CPU per process; cjxl and opj_compress read PNM natively). Each time is the least CPU time
# (user + system) of RUNS interleaved runs, single-threaded where the tool has the option, so
# other work on the machine inflates it as little as possible. Every decode is checked
# bit-exact against the input. A peer that is not installed is skipped, saying so.
# Usage: bench/lossless_vs_jxl.sh [BUILD_DIR] [RUNS]   (writes $OUT, default
# /tmp/lossless.md; its tables go into bench/results/image-lossless-hdr.md)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-3}
pw=$build/tools/pupwave
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${OUT:-/tmp/lossless.md}
images="astronaut camera chelsea coffee"

have() { command -v "$1" >/dev/null 2>&1; }
peers=""
for tool in cjxl djxl opj_compress opj_decompress; do
  if have "$tool"; then peers="$peers $tool"; else echo "lossless_vs_jxl: $tool not installed, skipped" >&2; fi
done
jxl=0; opj=0
[[ $peers == *cjxl* && $peers == *djxl* ]] && jxl=1
[[ $peers == *opj_compress* && $peers == *opj_decompress* ]] && opj=1

# cpu KEY CMD...: one run, its CPU seconds appended to series KEY.
declare -A best
cpu() {
  local key=$1
  shift
  /usr/bin/time -f "%U %S" -o "$work/time" "$@" >/dev/null 2>&1 || { echo "failed: $*" >&2; exit 1; }
  local t
  t=$(awk '{printf "%.3f", $1 + $2}' "$work/time")
  if [[ -z ${best[$key]:-} ]] || awk -v a="$t" -v b="${best[$key]}" 'BEGIN{exit !(a < b)}'; then best[$key]=$t; fi
}

# exact A B: pupwave psnr says max abs error 0 for every channel.
exact() {
  "$pw" psnr "$1" "$2" | awk 'NR > 2 && $NF != 0 {bad = 1} END {exit bad}' && echo yes || echo NO
}

for f in $images; do
  ext=ppm
  [[ $f == camera ]] && ext=pgm
  "$pw" convert "testimages/$f.png" "$work/$f.$ext" >/dev/null
done

for ((r = 0; r < runs; ++r)); do
  for f in $images; do
    ext=ppm
    [[ $f == camera ]] && ext=pgm
    in=$work/$f.$ext
    cpu "$f lc enc" "$pw" compress "$in" "$work/$f.lc.pw" --lossless --threads 1 -q
    cpu "$f lc dec" "$pw" decompress "$work/$f.lc.pw" "$work/$f.lc.$ext" --threads 1 -q
    cpu "$f ebcot enc" "$pw" compress "$in" "$work/$f.eb.pw" --lossless --entropy ebcot --threads 1 -q
    cpu "$f ebcot dec" "$pw" decompress "$work/$f.eb.pw" "$work/$f.eb.$ext" --threads 1 -q
    if ((jxl)); then
      cpu "$f jxl enc" cjxl "$in" "$work/$f.jxl" -d 0 -e 7 --num_threads=0 --quiet
      cpu "$f jxl dec" djxl "$work/$f.jxl" "$work/$f.jxl.$ext" --num_threads=1 --quiet
    fi
    if ((opj)); then
      cpu "$f opj enc" opj_compress -i "$in" -o "$work/$f.j2k"
      cpu "$f opj dec" opj_decompress -i "$work/$f.j2k" -o "$work/$f.opj.$ext"
    fi
  done
done

size() { stat -c %s "$1"; }
pct() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%+.1f%%", 100 * (a / b - 1)}'; }
{
  echo "# Lossless: pupwave lc against JPEG XL and OpenJPEG"
  echo
  echo "Made by \`bench/lossless_vs_jxl.sh $build $runs\` on $(date -u +%Y-%m-%d) ($(nproc) cores;"
  if have cjxl; then cjxl --version 2>&1 | sed -n 1p; else echo "cjxl not installed"; fi
  if have opj_compress; then
    { opj_compress -h 2>&1 || true; } | sed -n 's/.*\(openjp2 library v[0-9][0-9.]*[0-9]\).*/OpenJPEG (\1))./p'
  else
    echo "OpenJPEG not installed)."
  fi
  echo "Bytes of each lossless file; CPU seconds (user + system, least of $runs interleaved runs, one thread)"
  echo "of the whole process, reading and writing binary PNM. \"exact\": the decode equals the input."
  echo
  echo "| image | lc bytes | ebcot bytes (before) | cjxl -e 7 bytes | OpenJPEG bytes | lc vs cjxl | lc vs ebcot | lc exact | cjxl exact |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for f in $images; do
    ext=ppm
    [[ $f == camera ]] && ext=pgm
    in=$work/$f.$ext
    lc=$(size "$work/$f.lc.pw")
    eb=$(size "$work/$f.eb.pw")
    jx=-; oj=-; vs=-; jex=-
    if ((jxl)); then jx=$(size "$work/$f.jxl"); vs=$(pct "$lc" "$jx"); jex=$(exact "$in" "$work/$f.jxl.$ext"); fi
    ((opj)) && oj=$(size "$work/$f.j2k")
    echo "| $f | $lc | $eb | $jx | $oj | $vs | $(pct "$lc" "$eb") | $(exact "$in" "$work/$f.lc.$ext") | $jex |"
  done
  echo
  echo "| image | lc enc s | ebcot enc s | cjxl enc s | OpenJPEG enc s | cjxl / lc enc | lc dec s | ebcot dec s | djxl dec s | OpenJPEG dec s |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for f in $images; do
    le=${best[$f lc enc]}; ee=${best[$f ebcot enc]}
    je=${best[$f jxl enc]:--}; oe=${best[$f opj enc]:--}
    ratio=-
    ((jxl)) && ratio=$(awk -v a="$je" -v b="$le" 'BEGIN{printf "%.1fx", a / b}')
    echo "| $f | $le | $ee | $je | $oe | $ratio | ${best[$f lc dec]} | ${best[$f ebcot dec]} | ${best[$f jxl dec]:--} | ${best[$f opj dec]:--} |"
  done
  # The hand-written "## Notes" section of an earlier run is kept (it reads these tables).
  if [[ -f $out ]] && grep -q '^## Notes' "$out"; then
    echo
    sed -n '/^## Notes/,$p' "$out"
  fi
} >"$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
