#!/usr/bin/env bash
# ctest oiio_plugin.round_trip: OpenImageIO's own tools read and write .pw through the plugin
# pw.imageio.so: oiiotool writes the CLI's exact bytes for the same settings (the four
# photographs, ten option sets) and names an unknown coder, iinfo describes the file,
# resolution levels show as MIP levels (--iconfig pupwave:mip 1), oiiotool decodes to EXR/PNG
# exactly as the CLI decodes, a reduced MIP level reads as the CLI's --level decode, lossless
# survives, and a corrupt file is an error.
# Usage: oiio_round_trip.sh PLUGIN_DIR PUPWAVE_CLI TESTIMAGES WORK_DIR
set -euo pipefail
plugins=$1 cli=$2 images=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
export OIIO_LIBRARY_PATH=$plugins
fail() { echo "FAIL: $*" >&2; exit 1; }

# The CLI's flags as the plugin's attributes: --NAME VALUE is pupwave:NAME VALUE, --lossless
# pupwave:lossless 1. A decimal such as 35.3 becomes a float attribute, read as the CLI reads it.
attributes() {
  while [ $# -gt 0 ]; do
    if [ "$1" = --lossless ]; then echo "--attrib pupwave:lossless 1"; shift; continue; fi
    echo "--attrib pupwave:${1#--} $2"
    shift 2
  done
}
for name in camera astronaut chelsea coffee; do
  while IFS= read -r flags; do
    # shellcheck disable=SC2046,SC2086  # the flags and attributes are words on purpose
    oiiotool "$images/$name.png" $(attributes $flags) -o "$work/oiio.pw"
    # shellcheck disable=SC2086
    "$cli" compress -q "$images/$name.png" "$work/cli.pw" $flags
    cmp "$work/oiio.pw" "$work/cli.pw" || fail "oiiotool's .pw differs from the CLI's for $name.png [$flags]"
  done <<'SETS'

--bpp 1
--bpp 0.5 --entropy ebcot --effort 2
--lossless
--lossless --entropy ebcot
--psnr 35 --transform cdf53
--levels 3 --bpp 1
--entropy ht --bpp 1
--bpp 0.5 --tune visual
--psnr 35.3
--step 3.3 --entropy ebcot
SETS
done
oiiotool "$images/chelsea.png" --attrib pupwave:bpp 1 -o "$work/oiio.pw"
"$cli" compress "$images/chelsea.png" "$work/cli.pw" --bpp 1 > /dev/null
if oiiotool "$images/chelsea.png" --attrib pupwave:entropy jpeg -o "$work/bad.pw" 2> "$work/err.txt"; then
  fail "an unknown pupwave:entropy accepted"
fi
grep -q "unknown pupwave:entropy jpeg (one of auto, ebcot" "$work/err.txt" ||
  fail "no clear message for an unknown coder: $(cat "$work/err.txt")"

iinfo -v "$work/oiio.pw" | tee "$work/iinfo.txt"
grep -Eq "451 x +300, 3 channel, uint8 pw" "$work/iinfo.txt" || fail "iinfo does not describe the .pw file"
oiiotool --info -v --iconfig pupwave:mip 1 "$work/oiio.pw" | tee "$work/mip.txt"
grep -q "MIP-map levels: 451x300 226x150 113x75" "$work/mip.txt" || fail "no MIP levels with --iconfig pupwave:mip 1"

oiiotool "$work/oiio.pw" -o "$work/oiio.exr"
oiiotool "$work/oiio.pw" -o "$work/oiio.png"
"$cli" decompress "$work/cli.pw" "$work/cli.png" > /dev/null
idiff -a "$work/oiio.png" "$work/cli.png" || fail "oiiotool decodes differently from the CLI"
idiff -fail 0.02 -failpercent 100 -warnpercent 100 -warn 1 "$work/oiio.exr" "$work/oiio.png" > /dev/null ||
  fail "EXR and PNG decodes differ"

oiiotool --iconfig pupwave:mip 1 "$work/oiio.pw" --selectmip 1 -o "$work/half.png"
"$cli" decompress "$work/cli.pw" "$work/cli_half.png" --level 1 > /dev/null
idiff -a "$work/half.png" "$work/cli_half.png" || fail "MIP level 1 differs from the CLI's --level 1"
iinfo "$work/half.png" | grep -Eq "226 x +150" || fail "MIP level 1 is not 226 x 150"

oiiotool "$images/camera.png" --compression lossless -o "$work/lossless.pw"
oiiotool "$work/lossless.pw" -o "$work/lossless.png"
idiff -a "$images/camera.png" "$work/lossless.png" || fail "lossless round trip is not exact"
oiiotool "$images/camera.png" --attrib pupwave:psnr 35 --attrib pupwave:transform cdf53 -o "$work/psnr.pw"
"$cli" info "$work/psnr.pw" | grep -q cdf53 || fail "pupwave:transform ignored"

head -c 2000 "$work/cli.pw" > "$work/truncated.pw"
if oiiotool "$work/truncated.pw" -o "$work/bad.png" 2> "$work/err.txt"; then fail "truncated file accepted"; fi
grep -qi "truncated\|corrupt" "$work/err.txt" || fail "no clear message for a truncated file: $(cat "$work/err.txt")"
echo "oiio plugin round trip: ok"
