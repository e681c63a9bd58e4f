#!/usr/bin/env bash
# The quick start's test job: install missing packages, build, and run the whole test suite.
# The Python tests run against the package pip-installed into build/venv (ctest's python.install).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" --timeout 900
