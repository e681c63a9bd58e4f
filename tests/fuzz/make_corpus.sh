#!/usr/bin/env bash
# Regenerates the seed corpora tests/fuzz/corpus/<target>/ from small real encodes of the
# test images (testimages/): crops of a few dozen pixels, a small generated volume, a tiny
# sqrt(3) mesh, PNM files, transform specs. Usage: tests/fuzz/make_corpus.sh [path/to/pupwave]
# (default build/tools/pupwave; the seeds the CLI cannot write come from fuzz_make_seeds of the
# same build, tests/fuzz/make_seeds.cpp). Keeps the corpora a few hundred KB in total; the
# hostile reproducers (corpus/*/regress-*) are kept, not regenerated.
set -euo pipefail
cd "$(dirname "$0")/../.."
cli=$(realpath "${1:-build/tools/pupwave}")
out=tests/fuzz/corpus
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
seeds=$(dirname "$(dirname "$cli")")/tests/fuzz/fuzz_make_seeds
for t in image image_level volume info pnm png exr tiff jpeg spec mesh c_api hdf5_chunk; do
  mkdir -p "$out/$t"
  find "$out/$t" -type f ! -name 'regress-*' -delete
done

# crop IN.pnm X Y W H OUT.pnm: a binary PNM region (P5/P6, 8-bit), in pure Python.
crop() {
  python3 - "$@" <<'PY'
import sys
src, x, y, w, h, dst = sys.argv[1], *map(int, sys.argv[2:6]), sys.argv[6]
data = open(src, 'rb').read()
fields, pos = [], 0
while len(fields) < 4:
    while data[pos:pos + 1].isspace(): pos += 1
    if data[pos:pos + 1] == b'#':
        pos = data.index(b'\n', pos)
        continue
    end = pos
    while not data[end:end + 1].isspace(): end += 1
    fields.append(data[pos:end]); pos = end
pos += 1
magic, width = fields[0], int(fields[1])
c = 3 if magic == b'P6' else 1
rows = [data[pos + ((y + r) * width + x) * c: pos + ((y + r) * width + x + w) * c] for r in range(h)]
open(dst, 'wb').write(magic + b'\n%d %d\n255\n' % (w, h) + b''.join(rows))
PY
}

"$cli" convert testimages/camera.png "$tmp/camera.pgm" > /dev/null
"$cli" convert testimages/astronaut.png "$tmp/astronaut.ppm" > /dev/null
crop "$tmp/camera.pgm" 200 100 40 32 "$tmp/grey.pgm"
crop "$tmp/astronaut.ppm" 180 60 24 20 "$tmp/rgb.ppm"
crop "$tmp/camera.pgm" 10 10 7 5 "$tmp/tiny.pgm"
cp "$tmp/grey.pgm" "$tmp/tiny.pgm" "$tmp/rgb.ppm" "$out/pnm/"
"$cli" convert "$tmp/grey.pgm" "$out/png/grey.png" > /dev/null
"$cli" convert "$tmp/rgb.ppm" "$out/png/rgb.png" > /dev/null
# EXR, TIFF and JPEG as the CLI writes them (half and float EXR, 8/16-bit TIFF), plus layouts only
# oiiotool writes here (a tiled PIZ EXR with alpha, an LZW TIFF).
"$cli" convert "$tmp/rgb.ppm" "$out/exr/seed-rgb-half.exr" > /dev/null
oiiotool "$tmp/grey.pgm" -d uint16 -o "$tmp/grey16.pgm"
"$cli" convert "$tmp/grey16.pgm" "$out/exr/seed-grey-float.exr" > /dev/null
oiiotool --nosoftwareattrib "$tmp/rgb.ppm" --eraseattrib ".*" --ch R,G,B,A=1 -d half --tile 8 8 --compression piz \
  -o "$out/exr/seed-tiled-rgba-piz.exr"
"$cli" convert "$tmp/rgb.ppm" "$out/tiff/seed-rgb-u8.tif" > /dev/null
"$cli" convert "$tmp/grey16.pgm" "$out/tiff/seed-grey-u16.tif" > /dev/null
"$cli" convert "$out/exr/seed-tiled-rgba-piz.exr" "$out/tiff/seed-rgba-float.tif" > /dev/null
oiiotool --nosoftwareattrib "$tmp/rgb.ppm" --eraseattrib ".*" --compression lzw -o "$out/tiff/seed-rgb-lzw.tif"
"$cli" convert "$tmp/rgb.ppm" "$out/jpeg/seed-rgb.jpg" > /dev/null
"$cli" convert "$tmp/grey.pgm" "$out/jpeg/seed-grey.jpg" > /dev/null

# Image streams: lossless and lossy, every coder, every transform family, odd sizes.
img=0
enc() {  # enc INPUT ARGS...: one image seed
  local input=$1
  shift
  img=$((img + 1))
  "$cli" compress "$input" "$out/image/seed-$img.pw" "$@" --threads 1 > /dev/null
}
enc "$tmp/grey.pgm" --lossless --entropy ebcot
enc "$tmp/grey.pgm" --bpp 1.5
enc "$tmp/grey.pgm" --bpp 2 --transform pups:chaikin-ext
enc "$tmp/grey.pgm" --bpp 2 --transform kobbelt:k4pt --levels 2
enc "$tmp/rgb.ppm" --lossless --entropy ebcot
enc "$tmp/rgb.ppm" --psnr 30
enc "$tmp/tiny.pgm" --lossless --levels 1 --entropy ebcot
# The high-throughput coder (entropy coder 2): lossy and lossless, so the target reaches it.
enc "$tmp/grey.pgm" --bpp 1.5 --entropy ht
enc "$tmp/rgb.ppm" --lossless --entropy ht
# The lossless context coder (entropy coder 3, the --lossless default): predicted samples, and
# wavelet levels (detail bands with parent contexts).
enc "$tmp/rgb.ppm" --lossless
enc "$tmp/grey.pgm" --lossless --levels 2
# The parent-context coder (entropy coder 4, lossy only): parents across levels, RGB and grey.
enc "$tmp/rgb.ppm" --bpp 2 --entropy pc
enc "$tmp/grey.pgm" --psnr 35 --entropy pc --levels 3
# A half-float image in the adaptive log transfer (transfer 2, with its offset byte).
enc "$out/exr/seed-rgb-half.exr" --bpp 4 --transfer adaptive
for f in "$out"/image/seed-*.pw; do
  for level in 0 1 2; do
    { printf "\\x$(printf %02x $level)"; cat "$f"; } > "$out/image_level/$(basename "$f" .pw)-level$level"
  done
done

# Volume streams: a small generated field (dense), lossless and error-bounded.
"$cli" generate-volume --kind gray-scott --size 16 --steps 20 "$tmp/gs.raw" > /dev/null
"$cli" compress "$tmp/gs.raw" "$out/volume/seed-dense.pw" --dims 16,16,16 --dtype f32 --brick 8 \
  --max-error 0.01 --threads 1 > /dev/null
"$cli" compress "$tmp/gs.raw" "$out/volume/seed-lossless.pw" --dims 16,16,16 --dtype f32 --brick 16 \
  --bpv 4 --threads 1 > /dev/null
# Missing values (MASK chunk of a dense grid): NaN below the median, a block of fill values.
python3 - "$tmp/gs.raw" "$tmp/gs_missing.raw" <<'PY'
import sys, numpy as np
v = np.fromfile(sys.argv[1], '<f4')
v[v < np.median(v)] = np.nan
v[:300] = -999.0
v.tofile(sys.argv[2])
PY
"$cli" compress "$tmp/gs_missing.raw" "$out/volume/seed-missing.pw" --dims 16,16,16 --dtype f32 --brick 8 \
  --max-error 0.01 --fill-value -999 --threads 1 > /dev/null

# Mesh: a sqrt(3)-structured mesh from the smallest test mesh, decomposed.
"$cli" mesh subdivide testimages/u.off "$tmp/u3.off" --levels 1 > /dev/null
"$cli" mesh decompose "$tmp/u3.off" "$out/mesh/seed-u.pwm" --levels 1 > /dev/null

# A sparse box volume (MASK chunk) and HDF5 chunks: library writers only.
"$seeds" "$out"

cp "$out"/image/seed-1.pw "$out"/image/seed-5.pw "$out"/volume/seed-dense.pw "$out"/mesh/seed-u.pwm "$out/info/"

# C API: first byte level (bits 0-1) and decode-into (bit 2), then an image or volume stream.
for f in "$out"/image/seed-1.pw "$out"/image/seed-5.pw "$out"/volume/seed-*.pw; do
  name=$(basename "$(dirname "$f")")-$(basename "$f" .pw)
  { printf '\x04'; cat "$f"; } > "$out/c_api/$name-level0"
  { printf '\x05'; cat "$f"; } > "$out/c_api/$name-level1"
done

# Transform specs: every family, presets and explicit designs.
spec=0
for s in cdf97 cdf53 pups:chaikin-ext pups:poly10 'pups:bspline(degree=3)' 'pups:bspline(degree=5,l=4,samples=20000)' \
  'pups:cinpact(c=3,sigma=7.27,l=14)' 'pups:cinpact-interp(c=5,sigma=4.79,t=0.001)' \
  'pups:polynomial(coeffs=16:0:-8:0:1,domain=-2:2,boundary=wss)' kobbelt:k4pt kobbelt:kspl-raw; do
  spec=$((spec + 1))
  printf '%s' "$s" > "$out/spec/seed-$spec"
done
du -sh "$out"
