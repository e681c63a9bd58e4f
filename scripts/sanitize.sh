#!/usr/bin/env bash
# CI's robustness job (docs/fuzzing.md): the decoder test programs built once with ASan +
# UBSan (build-asan, gcc) and run, then every libFuzzer target (build-fuzz, clang) run for
# PUPWAVE_FUZZ_SECONDS (default 45) from its seed corpus. Any sanitizer report, failed test,
# crash, invariant failure, leak or timeout found by a fuzzer fails the job; a finding is
# left in build-fuzz/findings/<target>/ (add it to tests/fuzz/corpus/<target>/regress-*).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${PUPWAVE_FUZZ_SECONDS:-45}
jobs=$(nproc)

# The test programs that exercise the decoders and parsers, plus the fuzz targets' corpus
# runners; tests/hostile is not built (ASan cannot run under an address-space limit).
asan_tests="codec_tests volcodec_tests cli_tests fuzz_image fuzz_image_level fuzz_volume fuzz_info fuzz_pnm fuzz_png
  fuzz_exr fuzz_tiff fuzz_jpeg fuzz_spec fuzz_mesh fuzz_c_api fuzz_hdf5_chunk"
# -O1: sanitizer builds compile about twice as fast as at -O3 and still run the tests quickly.
# Ninja for a new build folder (better parallelism); an existing one keeps its generator.
generator() { [ -f "$1/CMakeCache.txt" ] || echo "-G Ninja"; }
# shellcheck disable=SC2046
cmake -S . -B build-asan $(generator build-asan) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DPUPWAVE_SANITIZE=ON -DPUPWAVE_BUILD_BENCH=OFF > /dev/null
# shellcheck disable=SC2086
cmake --build build-asan -j"$jobs" --target pupwave $asan_tests
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Test programs not in the list above are configured but not built: ctest names them *_NOT_BUILT.
# The library, Python, HDF5 and OpenImageIO plugin tests load shared objects into other programs
# (python3, h5dump, oiiotool) that are not built with ASan; they run in the normal build only.
ctest --test-dir build-asan --output-on-failure -j"$jobs" --timeout 900 \
  -E '_NOT_BUILT$|^api\.|^hdf5\.|^python\.|^oiio_plugin\.'

# libFuzzer targets, two at a time, each from a scratch copy of its corpus (new inputs stay
# out of the repository) with the dictionaries.
# shellcheck disable=SC2046
cmake -S . -B build-fuzz $(generator build-fuzz) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DPUPWAVE_BUILD_FUZZERS=ON -DPUPWAVE_BUILD_TESTS=OFF -DPUPWAVE_BUILD_BENCH=OFF > /dev/null
targets="image image_level volume info pnm png exr tiff jpeg spec mesh c_api hdf5_chunk"
cmake --build build-fuzz -j"$jobs" --target $(printf 'fuzz_%s ' $targets)
dict_for() {
  case $1 in
    spec) echo tests/fuzz/dict/spec.dict ;;
    pnm) echo tests/fuzz/dict/pnm.dict ;;
    *) echo tests/fuzz/dict/stream.dict ;;
  esac
}
run_target() {
  local t=$1 work=build-fuzz/work/$1 found=build-fuzz/findings/$1
  rm -rf "$work" "$found"
  mkdir -p "$work" "$found"
  ASAN_OPTIONS=detect_leaks=1 build-fuzz/tests/fuzz/fuzz_"$t" -max_total_time="$seconds" -timeout=25 \
    -rss_limit_mb=2048 -print_final_stats=1 -dict="$(dict_for "$t")" -artifact_prefix="$found/" \
    "$work" tests/fuzz/corpus/"$t" > build-fuzz/findings/"$t".log 2>&1
}
export -f run_target dict_for
export seconds
status=0
# shellcheck disable=SC2086
printf '%s\n' $targets | xargs -P 2 -I{} bash -c 'run_target {} || { echo "fuzz_{}: FINDING"; exit 1; }' ||
  status=1
for t in $targets; do
  grep -E 'stat::number_of_executed_units|cov: ' build-fuzz/findings/"$t".log | tail -2 | sed "s/^/fuzz_$t: /"
done
if [ "$status" -ne 0 ]; then
  for t in $targets; do tail -30 build-fuzz/findings/"$t".log; done
  echo "fuzzing found a failure: see build-fuzz/findings/" >&2
  exit 1
fi
