#!/usr/bin/env bash
# Fine PSNR-target sweep on 256 x 256 crops (camera, astronaut): targets 20..55 dB every 0.1 dB
# with the default, bit-plane and ht coders, through the code of the ctest grid
# (tests/cli_codec/psnr_window_test.cpp), which checks every point: PSNR in [T, T + 0.15] dB or
# the lossless stream. Prints the table (image, coder, targets, lossy points, misses, worst
# excess dB); exits non-zero when a point fails.
# Usage: bash bench/psnr_crop_sweep.sh [build-dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
table=$(mktemp)
trap 'rm -f "$table"' EXIT
status=0
PUPWAVE_WINDOW_STEP=0.1 PUPWAVE_WINDOW_CODERS=default,ebcot,ht PUPWAVE_WINDOW_OUT="$table" \
  "$build/tests/cli_codec_tests" --gtest_filter='PsnrWindow.*InTheWindow*' || status=1
echo "| image | coder | targets | lossy | misses | worst excess dB |"
echo "|---|---|---|---|---|---|"
cat "$table"
exit $status
