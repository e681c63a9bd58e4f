#!/usr/bin/env bash
# Builds the photograph sets the block coder's priors are trained and checked on
# (codec/entropy/ctx_priors.h, tools/train/README.md) from Debian packages, as 8-bit PNG:
#   OUT/train    the 12 photographs of mate-backgrounds (nature/*.jpg), box-reduced to <= 1024 px
#   OUT/heldout  scikit-image's motorcycle_left, rocket, retina, hubble_deep_field (RGB), coins,
#                moon, brick, grass, gravel (grey) from python3-skimage, and f3.jpg of the Rust
#                embedded book when FILE_F3 names it
# Needs apt-get download (Debian mirrors), dpkg-deb and python3-pil. Nothing is added to the
# repository. Usage: tools/train/prior_training_sets.sh OUT [FILE_F3]
# Then: build/train/train_priors OUT/train --check testimages/*.png  (and --check OUT/heldout)
set -euo pipefail
out=$(realpath -m "${1:?usage: prior_training_sets.sh OUT [FILE_F3]}")
f3=${2:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && apt-get download mate-backgrounds python3-skimage >/dev/null)
for deb in "$tmp"/*.deb; do dpkg-deb -x "$deb" "$tmp/x"; done
mkdir -p "$out/train" "$out/heldout"
# Debian's python3 (where python3-pil installs), not one earlier on PATH.
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
"$py" - "$tmp/x" "$out" "$f3" <<'PY'
import os, sys
from PIL import Image
root, out, f3 = sys.argv[1:4]
mate = root + '/usr/share/backgrounds/mate/nature/'
ski = root + '/usr/lib/python3/dist-packages/skimage/data/'
def save(im, path):
    f = max(1, -(-max(im.size) // 1024))  # integer box reduction: also removes JPEG artefacts
    (im.reduce(f) if f > 1 else im).save(path)
for n in sorted(os.listdir(mate)):
    save(Image.open(mate + n).convert('RGB'), f"{out}/train/{n.rsplit('.', 1)[0].lower()}.png")
for n, mode in [('motorcycle_left.png', 'RGB'), ('rocket.jpg', 'RGB'), ('retina.jpg', 'RGB'),
                ('hubble_deep_field.jpg', 'RGB'), ('coins.png', 'L'), ('moon.png', 'L'),
                ('brick.png', 'L'), ('grass.png', 'L'), ('gravel.png', 'L')]:
    save(Image.open(ski + n).convert(mode), f"{out}/heldout/{n.rsplit('.', 1)[0]}.png")
if f3:
    save(Image.open(f3).convert('RGB'), f"{out}/heldout/f3.png")
PY
echo "training set: $(ls "$out/train" | wc -l) images, held-out: $(ls "$out/heldout" | wc -l) images in $out"
