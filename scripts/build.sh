#!/usr/bin/env bash
# Installs missing Debian packages, then configures and builds pupwave (Release) in ./build.
# Usage: scripts/build.sh [extra cmake args...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# Ninja for a new build folder (it compiles a library's sources while the libraries it links are
# still building); an existing folder keeps the generator it was configured with.
generator=()
[ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j"$(nproc)"
