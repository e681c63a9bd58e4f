#!/usr/bin/env bash
# --tune visual against --tune psnr and the peers (OpenJPEG, AVIF 4:4:4 libaom speed 6, JPEG XL
# cjxl -e 7) on 2560x1600 photographs of Debian's plasma-workspace-wallpapers, at 0.25, 0.5 and
# 1 bpp: PSNR, SSIM and MS-SSIM of luma, butteraugli, MS-SSIM BD-rate against OpenJPEG and encode
# times, all from one `pupwave bench rd` run; then a crop grid of one photograph at 0.5 bpp.
# Results: bench/results/image-rd.md ("Visual tuning"). Needs apt-get download (Debian mirrors),
# dpkg-deb, python3-pil, butteraugli, libopenjp2-tools, libavif-bin, ffmpeg, libjxl-tools.
# Usage: bench/visual_rd.sh OUT [PHOTO...]  (default photographs: Path, the one the weights were
# tuned on, and Autumn, ColorfulCups, BytheWater, checked on)
set -euo pipefail
out=$(realpath -m "${1:?usage: visual_rd.sh OUT [PHOTO...]}")
shift
photos=("$@")
[ ${#photos[@]} -gt 0 ] || photos=(Path Autumn ColorfulCups BytheWater)
here=$(cd "$(dirname "$0")/.." && pwd)
pw=${PUPWAVE:-$here/build/tools/pupwave}
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
mkdir -p "$out/photos"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && apt-get download plasma-workspace-wallpapers >/dev/null)
dpkg-deb -x "$tmp"/plasma-workspace-wallpapers_*.deb "$tmp/x"
for p in "${photos[@]}"; do
  "$py" -c 'import sys; from PIL import Image; Image.open(sys.argv[1]).convert("RGB").save(sys.argv[2])' \
    "$tmp/x/usr/share/wallpapers/$p/contents/images/2560x1600.jpg" "$out/photos/$(echo "$p" | tr A-Z a-z).png"
done
"$pw" bench rd --images "$out/photos" --transforms cdf97 --tune psnr,visual --bpp 0.25,0.5,1 \
  --anchors openjpeg,avif-s6,jxl --jobs 2 --out "$out/rd"
first=$(echo "${photos[0]}" | tr A-Z a-z)
"$py" "$here/bench/crop_grid.py" "$out/rd/results.csv" "$out/photos/$first.png" 0.5 1100,700,256,160 \
  "$out/crops-visual.png" "$pw"
echo "tables: $out/rd/summary.md, crop grid: $out/crops-visual.png"
