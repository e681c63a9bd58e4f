#!/usr/bin/env bash
# Whole-process speed and peak memory of pupwave against OpenJPEG, Grok and OpenJPH (HTJ2K) on
# 4096 x 4096 mosaics of the bundled photographs (RGB and grey), at 0.25, 1 and 2 bpp, CDF 9/7
# irreversible everywhere. Runs are interleaved (one run of every coder, then the next round), so
# a machine shared with other work slows all coders alike and the ratios stay meaningful.
# OpenJPH has no rate control: its -qstep is bisected once per image and rate to the largest
# file not above the target size, then timed. Writes $OUT (default
# /tmp/codec_speed.md); its tables go into bench/results/image-speed-memory.md.
# Usage: bench/codec_speed.sh [BUILD_DIR] [RUNS] [RATES]
#   (after scripts/build.sh; defaults: build, 5 runs, "0.25 1 2"; grk/ojph from install-deps.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-5}
rates=${3:-0.25 1 2}
pw=$build/tools/pupwave
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
out=${OUT:-/tmp/codec_speed.md}
side=4096

"$build/bench/codec_bench" --write-mosaic "$work/rgb.ppm"
"$build/bench/codec_bench" --write-grey-mosaic "$work/grey.pgm"

# One timed run of a command: appends its wall and CPU (user + system) seconds and max RSS (MiB)
# to the named series. CPU time shows the work done when other jobs share the machine.
declare -A times cpus rss
timed() {
  local key=$1
  shift
  /usr/bin/time -f "%e %M %U %S" -o "$work/time" "$@" >/dev/null 2>&1 || {
    echo "codec_speed: failed: $*" >&2
    exit 1
  }
  read -r t m u s <"$work/time"
  times[$key]="${times[$key]:-} $t"
  cpus[$key]="${cpus[$key]:-} $(awk -v u="$u" -v s="$s" 'BEGIN{print u+s}')"
  local mib=$((m / 1024))
  ((mib > ${rss[$key]:-0})) && rss[$key]=$mib
  return 0
}
median() { tr ' ' '\n' <<<"${times[$1]}" | grep . | sort -g | awk '{a[NR]=$1} END {printf "%.3f", a[int((NR+1)/2)]}'; }
psnr_of() { "$pw" psnr "$1" "$2" | awk '$1=="all"{print $3}'; }
bpp_of() { awk -v b="$(stat -c %s "$1")" -v n=$((side * side)) 'BEGIN{printf "%.4f", b*8/n}'; }
median_cpu() { tr ' ' '\n' <<<"${cpus[$1]}" | grep . | sort -g | awk '{a[NR]=$1} END {printf "%.2f", a[int((NR+1)/2)]}'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN{printf "%.2f", a/b}'; }

# Largest OpenJPH file not above `bytes`: bisects log(qstep) (the size falls as qstep grows).
ojph_qstep() {
  local in=$1 bytes=$2 lo=0.0005 hi=0.5 mid size
  for ((k = 0; k < 14; k++)); do
    mid=$(awk -v a="$lo" -v b="$hi" 'BEGIN{printf "%.6g", sqrt(a*b)}')
    ojph_compress -i "$in" -o "$work/q.j2c" -num_decomps 6 -qstep "$mid" >/dev/null 2>&1
    size=$(stat -c %s "$work/q.j2c")
    if ((size > bytes)); then lo=$mid; else hi=$mid; fi
  done
  echo "$hi"
}

rows=()
for image in rgb grey; do
  [[ $image == rgb ]] && in=$work/rgb.ppm ext=ppm channels=3 || in=$work/grey.pgm ext=pgm channels=1
  for rate in $rates; do
    bytes=$(awk -v r="$rate" -v n=$((side * side)) 'BEGIN{printf "%d", r*n/8}')
    ratio_r=$(awk -v r="$rate" -v c=$channels 'BEGIN{printf "%.6g", 8*c/r}')
    q=$(ojph_qstep "$in" "$bytes")
    times=() cpus=() rss=()
    one_thread=$([[ $rate == 1 ]] && echo 1 || echo 0)  # thread scaling at 1 bpp only
    for ((i = 0; i < runs; i++)); do
      timed pe "$pw" compress "$in" "$work/m.pw" --bpp "$rate"
      timed pd "$pw" decompress "$work/m.pw" "$work/m_pw.$ext"
      timed te "$pw" compress "$in" "$work/t.pw" --bpp "$rate" --entropy ht
      timed td "$pw" decompress "$work/t.pw" "$work/t_pw.$ext"
      if ((one_thread)); then
        timed pe1 "$pw" compress "$in" "$work/m1.pw" --bpp "$rate" --threads 1
        timed pd1 "$pw" decompress "$work/m1.pw" "$work/m1_pw.$ext" --threads 1
        timed ge1 grk_compress -H 1 -i "$in" -o "$work/g1.j2k" -I -r "$ratio_r" -n 6
        timed gd1 grk_decompress -H 1 -i "$work/g1.j2k" -o "$work/g1.$ext"
      fi
      timed oe opj_compress -i "$in" -o "$work/m.j2k" -I -r "$ratio_r" -n 6
      timed od opj_decompress -i "$work/m.j2k" -o "$work/m_j2k.$ext"
      timed ge grk_compress -H 2 -i "$in" -o "$work/g.j2k" -I -r "$ratio_r" -n 6
      timed gd grk_decompress -H 2 -i "$work/g.j2k" -o "$work/g.$ext"
      timed he ojph_compress -i "$in" -o "$work/h.j2c" -num_decomps 6 -qstep "$q"
      timed hd ojph_expand -i "$work/h.j2c" -o "$work/h.$ext"
    done
    pe=$(median pe) pd=$(median pd)
    row() {  # name enc_key dec_key file decoded
      local e d
      e=$(median "$2") d=$(median "$3")
      rows+=("| $image | $rate | $1 | $e ($(median_cpu "$2")) | $d ($(median_cpu "$3")) | $(ratio "$e" "$pe") | $(ratio "$d" "$pd") | ${rss[$2]} / ${rss[$3]} | $(bpp_of "$4") | $(psnr_of "$in" "$5") |")
    }
    row "pupwave (2 threads)" pe pd "$work/m.pw" "$work/m_pw.$ext"
    row "pupwave --entropy ht" te td "$work/t.pw" "$work/t_pw.$ext"
    if ((one_thread)); then
      row "pupwave --threads 1" pe1 pd1 "$work/m1.pw" "$work/m1_pw.$ext"
      row "grk -H 1" ge1 gd1 "$work/g1.j2k" "$work/g1.$ext"
    fi
    row "grk -H 2" ge gd "$work/g.j2k" "$work/g.$ext"
    row "OpenJPH -qstep $q" he hd "$work/h.j2c" "$work/h.$ext"
    row "OpenJPEG" oe od "$work/m.j2k" "$work/m_j2k.$ext"
  done
done

# Hand-written notes after this marker in the results file survive a rerun.
marker='<!-- notes: kept by codec_speed.sh -->'
notes=$( [[ -f $out ]] && sed -n "/^$marker\$/,\$p" "$out" || true)

gbench=$("$build/bench/codec_bench" --benchmark_min_time=1 2>/dev/null | grep -E '^bm_' || true)

{
  echo "# Codec speed and memory: pupwave vs OpenJPEG, Grok and OpenJPH"
  echo
  echo "Generated by \`bench/codec_speed.sh $build $runs\` on $(date -u +%Y-%m-%d)."
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'),"
  echo "$(free -g | awk '/Mem:/{print $2}') GiB; load average at start: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo "Inputs: 4096 x 4096 mosaics of the four photographs in testimages/ (\`codec_bench --write-mosaic\`,"
  echo "\`--write-grey-mosaic\` for its Rec. 601 luma). Whole-process wall time, median of $runs interleaved"
  echo "runs; peak resident memory (max RSS) over the runs. Ratios are the peer's time over pupwave's"
  echo "(2 threads) in the same run: above 1, pupwave is faster; CPU s is user + system time. Commands:"
  echo "\`pupwave compress --bpp R\` (and \`--entropy ht\`, the high-throughput block coder),"
  echo "\`opj_compress -I -r 8C/R -n 6\`, \`grk_compress -H T -I -r 8C/R -n 6\`, \`ojph_compress -num_decomps 6"
  echo "-qstep Q\` (Q bisected to the largest file within the target), decoders at their defaults."
  echo
  echo "| image | bpp target | coder | encode s (CPU s) | decode s (CPU s) | enc ratio | dec ratio | peak MiB enc / dec | bpp | PSNR dB |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "In-process (Google Benchmark, \`$build/bench/codec_bench\`, RGB mosaic at 1 bpp; items = pixels):"
  echo
  echo '```'
  echo "$gbench"
  echo '```'
  if [[ -n $notes ]]; then
    echo
    echo "$notes"
  fi
} >"$out"
cat "$out"
