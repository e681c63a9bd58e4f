#!/usr/bin/env bash
# Instructions executed inside encode_image (callgrind --toggle-collect: no process start, no PNG
# read) for one `pupwave compress --threads 1` of each test photograph: a deterministic measure of
# encode CPU that a loaded machine does not disturb (bench/results/image-speed-memory.md).
# Usage: bench/encode_instructions.sh BIN ENTROPY [BPP]   (ENTROPY: ebcot, pc, ...; default: no
# --entropy, the default coder's choice; BPP default 1)
# Prints "photo instructions" per line. Needs valgrind.
set -euo pipefail
bin=${1:?usage: encode_instructions.sh BIN ENTROPY [BPP]}
entropy=${2:?usage: encode_instructions.sh BIN ENTROPY [BPP]}
bpp=${3:-1}
coder=(--entropy "$entropy")
[ "$entropy" = default ] && coder=()
here=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp --suffix=.pw)
trap 'rm -f "$out"' EXIT
for im in astronaut camera chelsea coffee; do
  n=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "--toggle-collect=pupwave::encode_image(*" \
    "$bin" compress -q --threads 1 "$here/testimages/$im.png" "$out" "${coder[@]}" --bpp "$bpp" 2>&1 |
    grep -o "Collected : [0-9]*" | grep -o "[0-9]*")
  echo "$im $n"
done
