#!/usr/bin/env bash
# Full PSNR-target sweep: targets 20..70 dB in 0.1 dB steps on every test
# photograph, through the same code as the strided ctest sweep (tests/rate/psnr_sweep_test.cpp),
# which checks every point; the table goes to $OUT
# (default /tmp/psnr_sweep.md) and from there into bench/results/image-rd.md.
# Usage: bash bench/psnr_sweep.sh [build-dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=${OUT:-/tmp/psnr_sweep.md}
table=$(mktemp)
part=$(mktemp)
trap 'rm -f "$table" "$part"' EXIT
start=$(date +%s)
status=0
for image in "$here"/../testimages/*.png; do  # one image per run, so each row lands as it is done
  name=$(basename "$image")
  if ! PUPWAVE_SWEEP_STEP=0.1 PUPWAVE_SWEEP_OUT="$part" PUPWAVE_SWEEP_IMAGE="$name" \
      "$build/tests/rate_tests" --gtest_filter='PsnrSweep.*' > "$part.log" 2>&1; then
    echo "$name: FAILED (see the test output below)"; tail -40 "$part.log"; status=1
  fi
  if [ -s "$table" ]; then tail -n +3 "$part" >> "$table"; else cat "$part" > "$table"; fi
  rm -f "$part.log"
done
{
  echo "# PSNR-target sweep: 20..70 dB in 0.1 dB steps"
  echo
  echo "Produced by \`bash bench/psnr_sweep.sh\` ($(date -u +%Y-%m-%d), $(( $(date +%s) - start )) s on"
  verdict=$([ "$status" = 0 ] && echo "Every point passed" || echo "NOT every point passed")
  echo "$(nproc) cores, $(uname -m)). $verdict the checks of tests/rate/psnr_sweep_test.cpp:"
  echo "PSNR >= target and <= target + 0.15 dB, or the lossless file where no smaller lossy file reaches"
  echo "the target; no file larger than the lossless one; sizes non-decreasing in the target within 0.5%."
  echo "'worst excess' is the largest PSNR above the target over the lossy points; 'largest size drop'"
  echo "the largest relative fall in size from one target to the next (0: sizes only rose)."
  echo
  cat "$table"
} > "$out"
echo "wrote $out"
exit $status
