#!/usr/bin/env bash
# The quick start's main job: build the CLI, then compress and decompress a bundled real photograph
# and print the compressed size, bits per pixel, PSNR and time.
# Usage: scripts/demo.sh [IMAGE] [BPP]   (default: testimages/astronaut.png at 1 bpp)
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
# Builds only the CLI (the pupwave target), reusing build/ when it is configured; the chatter goes
# to a log that is shown only when the build fails. scripts/build.sh builds everything.
build_cli() {
  bash scripts/install-deps.sh
  [ -f build/CMakeCache.txt ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
  cmake --build build -j"$(nproc)" --target pupwave
}
if ! build_cli >out/build.log 2>&1; then
  cat out/build.log
  exit 1
fi
image=${1:-testimages/astronaut.png}
bpp=${2:-1}
pw=build/tools/pupwave
name=$(basename "${image%.*}")

start=$(date +%s.%N)
"$pw" compress "$image" "out/$name.pw" --bpp "$bpp" >/dev/null
mid=$(date +%s.%N)
"$pw" decompress "out/$name.pw" "out/$name.decoded.png" >/dev/null
end=$(date +%s.%N)

bytes=$(stat -c %s "out/$name.pw")
pixels=$("$pw" info "$image" | sed -E 's/.*image, ([0-9]+) x ([0-9]+),.*/\1 \2/' | awk '{print $1*$2}')
psnr=$("$pw" psnr "$image" "out/$name.decoded.png" | awk '$1=="all"{print $3}')
printf 'image        %s (%s pixels)\n' "$image" "$pixels"
printf 'compressed   out/%s.pw, %d bytes\n' "$name" "$bytes"
printf 'bits/pixel   %s (target %s)\n' "$(awk -v b="$bytes" -v p="$pixels" 'BEGIN{printf "%.4f", b*8/p}')" "$bpp"
printf 'PSNR         %s dB (all channels, peak 255)\n' "$psnr"
printf 'time         compress %s s, decompress %s s\n' "$(awk -v a="$start" -v b="$mid" 'BEGIN{printf "%.3f", b-a}')" "$(awk -v a="$mid" -v b="$end" 'BEGIN{printf "%.3f", b-a}')"
printf 'decoded      out/%s.decoded.png\n' "$name"
