#!/usr/bin/env bash
# Peak resident memory (max RSS, /usr/bin/time -f %M) of two CLI front doors on a large RGB
# photograph, against their limits:
#   `pupwave compress --report-psnr` at most 1.5x the same encode without it (bit-plane coder
#   and the default coder, --bpp 1, from PPM);
#   `pupwave convert` between PPM and PNG, EXR (half, as oiiotool writes it), TIFF (8-bit) and
#   JPEG, and from EXR (whose attributes the PNG and TIFF writers store) to PNG and TIFF, at most
#   2x the image's raw bytes (its samples in the input's type) plus the output's
#   size (all read and written natively, without OpenImageIO). The fixed cost of loading the
#   OpenImageIO plugin, which other formats still pay, is measured apart: a 16 x 16 BMP
#   converted to PPM.
# Usage: bench/front_door_memory.sh [build-dir] [image] [work-dir]. Without an image, a
# 2560 x 1600 mosaic of the testimages/ photographs is made with oiiotool (astronaut, coffee and
# chelsea scaled to 512 rows and cropped to 512 x 512, camera as grey RGB; 5 x 4 tiles, cropped).
# Prints a markdown table.
set -euo pipefail
build=${1:-build}
image=${2:-}
work=${3:-/tmp/pupwave_front_door_memory}
here=$(cd "$(dirname "$0")" && pwd)
pw=$build/tools/pupwave
mkdir -p "$work"

if [[ -z $image ]]; then
  t=$here/../testimages
  tiles=()
  for i in $(seq 0 19); do
    case $((i % 4)) in
      0) tiles+=("$t/astronaut.png") ;;
      1) tiles+=("$t/coffee.png" --resize 768x512 --crop 512x512+128+0) ;;
      2) tiles+=("$t/chelsea.png" --resize 770x512 --crop 512x512+129+0) ;;
      3) tiles+=("$t/camera.png" --ch 0,0,0) ;;
    esac
  done
  image=$work/mosaic.png
  oiiotool --nosoftwareattrib "${tiles[@]}" --mosaic 5x4 --crop 2560x1600+0+0 --fullpixels -d uint8 -o "$image"
fi
"$pw" convert -q "$image" "$work/in.ppm"
"$pw" convert -q "$work/in.ppm" "$work/in.png"
# The other inputs written by OpenImageIO, so that builds before and after a change read the same files.
oiiotool --nosoftwareattrib "$work/in.ppm" -d half -o "$work/in.exr"
oiiotool --nosoftwareattrib "$work/in.ppm" -o "$work/in.tif"
oiiotool --nosoftwareattrib "$work/in.ppm" -o "$work/in.jpg"
oiiotool --nosoftwareattrib --pattern checker:width=4:height=4 16x16 3 -d uint8 -o "$work/tiny.bmp"
raw=$(($(stat -c %s "$work/in.ppm") - $(head -c 64 "$work/in.ppm" | head -n 3 | wc -c)))

# Max RSS of a command in KiB (its output discarded); exits on failure.
rss() {
  /usr/bin/time -f "%M" -o "$work/time.txt" "$@" >/dev/null 2>&1 || {
    echo "failed: $*" >&2
    exit 1
  }
  tail -n 1 "$work/time.txt"
}
mib() { awk -v k="$1" 'BEGIN { printf "%.1f", k / 1024 }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

echo "Image: $(basename "$image") ($("$pw" info "$work/in.ppm" 2>/dev/null | head -n 1 || true)), raw $(mib $((raw / 1024))) MiB"
echo
echo "| command | max RSS (MiB) | limit (MiB) | RSS / limit |"
echo "|---|---|---|---|"
for coder in ebcot default; do
  flags=(--bpp 1)
  [[ $coder == ebcot ]] && flags+=(--entropy ebcot)
  plain=$(rss "$pw" compress -q "$work/in.ppm" "$work/$coder.pw" "${flags[@]}")
  psnr=$(rss "$pw" compress -q "$work/in.ppm" "$work/$coder.pw" "${flags[@]}" --report-psnr)
  echo "| compress --bpp 1 ($coder coder) | $(mib "$plain") | | |"
  echo "| compress --bpp 1 ($coder coder) --report-psnr | $(mib "$psnr") ($(ratio "$psnr" "$plain")x plain) | $(mib $((plain * 3 / 2))) (1.5x plain) | $(ratio "$psnr" $((plain * 3 / 2))) |"
done
base=$(rss "$pw" convert -q "$work/tiny.bmp" "$work/tiny.ppm")
for pair in "png ppm" "ppm png" "exr ppm" "ppm exr" "exr exr" "exr png" "exr tif" "tif ppm" "ppm tif" "jpg ppm" "ppm jpg"; do
  read -r from to <<<"$pair"
  rm -f "$work/out.$to"
  used=$(rss "$pw" convert -q "$work/in.$from" "$work/out.$to")
  samples=$raw
  [[ $from == exr ]] && samples=$((2 * raw)) # half samples: 2 bytes each
  limit=$(((2 * samples + $(stat -c %s "$work/out.$to")) / 1024))
  echo "| convert ${from^^} -> ${to^^} | $(mib "$used") | $(mib "$limit") (2x raw + output) | $(ratio "$used" "$limit") |"
done
echo "| convert 16 x 16 BMP -> PPM (the OpenImageIO plugin's fixed cost) | $(mib "$base") | | |"
