#!/usr/bin/env bash
# Full PSNR-target sweep (issue 12): targets 20..70 dB in 0.1 dB steps on every test
# photograph, through the same code as the strided ctest sweep (tests/rate/psnr_sweep_test.cpp),
# which checks every point; the table goes to bench/results/psnr_sweep.md.
# Usage: bash bench/psnr_sweep.sh [build-dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=$here/results/psnr_sweep.md
table=$(mktemp)
trap 'rm -f "$table"' EXIT
start=$(date +%s)
PUPWAVE_SWEEP_STEP=0.1 PUPWAVE_SWEEP_OUT="$table" "$build/tests/rate_tests" --gtest_filter='PsnrSweep.*'
{
  echo "# PSNR-target sweep: 20..70 dB in 0.1 dB steps"
  echo
  echo "Produced by \`bash bench/psnr_sweep.sh\` ($(date -u +%Y-%m-%d), $(( $(date +%s) - start )) s on"
  echo "$(nproc) cores, $(uname -m)). Every point passed the checks of tests/rate/psnr_sweep_test.cpp:"
  echo "PSNR >= target and <= target + 0.15 dB, or the lossless file where no smaller lossy file reaches"
  echo "the target; no file larger than the lossless one; sizes non-decreasing in the target within 0.5%."
  echo "'worst excess' is the largest PSNR above the target over the lossy points; 'largest size drop'"
  echo "the largest relative fall in size from one target to the next (0: sizes only rose)."
  echo
  cat "$table"
} > "$out"
echo "wrote $out"
