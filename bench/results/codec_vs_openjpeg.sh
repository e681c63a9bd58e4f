#!/bin/bash
# Compare pupwave (cdf97, --bpp) with OpenJPEG at the same rate on the four test photographs,
# and lossless sizes. Usage: P=build/tools/pupwave bench/results/codec_vs_openjpeg.sh
P=${P:-/work/main/build-codec/tools/pupwave}
T=${T:-/work/main/testimages}
W=$(mktemp -d)
printf "| image | bpp | pupwave bytes | pupwave PSNR | OpenJPEG bytes | OpenJPEG PSNR |\n|---|---|---|---|---|---|\n"
for img in camera astronaut coffee chelsea; do
  ch=$(oiiotool --info -v $T/$img.png | grep -o "[0-9] channel" | head -1 | cut -c1)
  if [ "$ch" = "1" ]; then ext=pgm; bits=8; else ext=ppm; bits=24; fi
  oiiotool $T/$img.png -o $W/$img.$ext
  for b in 0.25 0.5 1.0; do
    ratio=$(python3 -c "print($bits/$b)")
    $P compress $T/$img.png $W/$img.pw --bpp $b > /dev/null
    $P decompress $W/$img.pw $W/$img-pw.png > /dev/null
    pw_psnr=$($P psnr $T/$img.png $W/$img-pw.png | awk '/^all/{print $3}')
    opj_compress -i $W/$img.$ext -o $W/$img.j2k -I -r $ratio -n 6 > /dev/null
    opj_decompress -i $W/$img.j2k -o $W/$img-j2k.$ext > /dev/null
    oiiotool $W/$img-j2k.$ext -o $W/$img-j2k.png
    j_psnr=$($P psnr $T/$img.png $W/$img-j2k.png | awk '/^all/{print $3}')
    printf "| %s | %s | %d | %s | %d | %s |\n" $img $b $(stat -c %s $W/$img.pw) $pw_psnr $(stat -c %s $W/$img.j2k) $j_psnr
  done
done
rm -rf $W
W=$(mktemp -d)
printf "\n| image | pupwave lossless bytes | OpenJPEG lossless bytes |\n|---|---|---|\n"
for img in camera astronaut coffee chelsea; do
  ch=$(oiiotool --info -v $T/$img.png | grep -o "[0-9] channel" | head -1 | cut -c1)
  if [ "$ch" = "1" ]; then ext=pgm; else ext=ppm; fi
  oiiotool $T/$img.png -o $W/$img.$ext
  $P compress $T/$img.png $W/$img.pw --lossless > /dev/null
  opj_compress -i $W/$img.$ext -o $W/$img.j2k -n 6 > /dev/null
  printf "| %s | %d | %d |\n" $img $(stat -c %s $W/$img.pw) $(stat -c %s $W/$img.j2k)
done
rm -rf $W
