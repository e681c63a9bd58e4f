#!/usr/bin/env bash
# HDR image coding side by side on a real HDR photograph (testimages/forest_hdr.exr):
# pupwave (log-domain coding, several --psnr targets, default 40), OpenEXR's lossy DWAA/DWAB
# (through oiiotool's compression attribute) and JPEG XL (cjxl/djxl). Every decoded image is
# measured by `pupwave psnr` against the input: ordinary PSNR (peak = value range), log-PSNR,
# median relative luminance error per decade, sign flips. Writes $OUT (default
# /tmp/hdr.md); its table goes into bench/results/image-lossless-hdr.md.
# Usage: bench/hdr_compare.sh [path/to/pupwave]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pw=${1:-$root/build/tools/pupwave}
in=$root/testimages/forest_hdr.exr
out=${OUT:-/tmp/hdr.md}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pixels=$((512 * 256))

# One table row: codec, setting, coded file, decoded EXR.
row() {
  local codec=$1 setting=$2 coded=$3 decoded=$4 bytes report
  bytes=$(stat -c %s "$coded")
  report=$("$pw" psnr "$in" "$decoded")
  awk -v codec="$codec" -v setting="$setting" -v bytes="$bytes" -v pixels="$pixels" '
    $1 == "all" { psnr = $3 }
    $1 == "log-PSNR" { lpsnr = $2 }
    /^\[1e/ { share = $3 + 0; med = $4 + 0
              if (share >= 1.0) { split($1, d, /[\[,]/); decs = decs sprintf(" %s:%.2f", d[2], med)
                                  if (med > worst) worst = med } }
    /^sign flips/ { flips = $NF }
    END { printf "| %s | %s | %d | %.3f | %s | %s | %.2f | %s |%s |\n", codec, setting, bytes,
          8.0 * bytes / pixels, psnr, lpsnr, worst, flips, decs }' <<<"$report"
}

{
  echo "# HDR coding: pupwave against OpenEXR DWAA/DWAB and JPEG XL"
  echo
  echo "Input: \`testimages/forest_hdr.exr\` (512x256 half RGB, a real HDR photograph, luminance up to"
  echo "~600; provenance in testimages/README.md; raw half RGB = 786432 bytes, the zip EXR $(stat -c %s "$in") bytes)."
  echo "Made by \`bench/hdr_compare.sh\` on $(date -u +%Y-%m-%d) ($(nproc) cores, machine shared with other jobs;"
  echo "sizes and errors do not depend on load). Tools: OpenImageIO $(oiiotool --version 2>&1 | head -1), cjxl $(cjxl --version 2>&1 | head -1 | cut -d' ' -f2)."
  echo
  echo "Columns: whole-file bytes and bits per pixel; PSNR against the value range (what \`--psnr\`"
  echo "meant for float images before the log transfer); log-PSNR (PSNR with peak 1 over log2(1 + x/2^-14),"
  echo "the domain pupwave codes float images in); the worst median relative luminance error (%) over the"
  echo "decades holding >= 1 % of the pixels; sign flips (input >= 0, output < 0); then decade:median%"
  echo "for each such decade (decade d = luminance in [10^d, 10^(d+1)))."
  echo
  echo "| codec | setting | bytes | bpp | PSNR (dB) | log-PSNR (dB) | worst median rel. err. (%) | sign flips | per decade |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for p in 20 25 30 35 40 45; do
    "$pw" compress "$in" "$tmp/p$p.pw" --psnr "$p" >/dev/null
    "$pw" decompress "$tmp/p$p.pw" "$tmp/p$p.exr" >/dev/null
    row pupwave "--psnr $p$([ "$p" = 40 ] && echo ' (default)')" "$tmp/p$p.pw" "$tmp/p$p.exr"
  done
  "$pw" compress "$in" "$tmp/lin.pw" --transfer linear >/dev/null
  "$pw" decompress "$tmp/lin.pw" "$tmp/lin.exr" >/dev/null
  row pupwave "--transfer linear --psnr 40 (old default)" "$tmp/lin.pw" "$tmp/lin.exr"
  for c in dwaa dwab; do
    for q in 45 200; do
      oiiotool "$in" --compression "$c:$q" -o "$tmp/$c$q.exr"
      row OpenEXR "$c:$q" "$tmp/$c$q.exr" "$tmp/$c$q.exr"
    done
  done
  # Debian's cjxl 0.7 reads no EXR: hand it the same float samples as PFM, and read djxl's PFM back.
  oiiotool "$in" -d float --compression none --attrib tiff:RowsPerStrip 256 -o "$tmp/in.tif"
  python3 "$root/bench/tiff_to_pfm.py" "$tmp/in.tif" "$tmp/in.pfm"
  for d in 0.25 0.5 1 2; do
    # PFM carries no colour encoding: say it is linear sRGB both ways (else highlights clip at ~8.8).
    cjxl "$tmp/in.pfm" "$tmp/d$d.jxl" -d "$d" --dec-hints=color_space=RGB_D65_SRG_Rel_Lin >/dev/null 2>&1
    djxl "$tmp/d$d.jxl" "$tmp/d$d.pfm" --color_space=RGB_D65_SRG_Rel_Lin >/dev/null 2>&1
    oiiotool "$tmp/d$d.pfm" -d half -o "$tmp/d$d.exr"
    row "JPEG XL" "cjxl -d $d (PFM in/out)" "$tmp/d$d.jxl" "$tmp/d$d.exr"
  done
  echo
  echo "Notes: the EXR sizes are whole files written by oiiotool (DWAA/DWAB level 45 is OpenEXR's"
  echo "default). cjxl 0.7 (Debian) reads no EXR, so it codes the same float samples from a PFM"
  echo 'declared linear sRGB (`--dec-hints=color_space=RGB_D65_SRG_Rel_Lin`, and djxl decodes to the same'
  echo "space); without that hint its output clips the highlights at about 8.8. The input itself was"
  echo "DWAB-coded by Blender's packagers before it was resized, so it carries fine DWAB artefacts and"
  echo "photographic noise, which no codec here removes cheaply."
} >"$out"
cat "$out"
