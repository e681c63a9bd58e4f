#!/usr/bin/env bash
# Contact sheets of the sqrt(3) levels of detail (bench/results/meshes.md): two real meshes of
# testimages/ subdivided three times, then `pupwave mesh lod --sheet` back down to the original.
set -euo pipefail
cd "$(dirname "$0")/.."
out=bench/results/meshes
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for name in nefertiti pig; do
  build/tools/pupwave mesh subdivide testimages/$name.off "$tmp/$name.obj" --levels 3
  build/tools/pupwave mesh lod "$tmp/$name.obj" "$tmp/$name" --levels 3 --sheet "$out/mesh_lod_$name.png"
done
