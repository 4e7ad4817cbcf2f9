#!/usr/bin/env bash
# Sets up, builds and runs every test (README, "Quick start"): the Release build's whole
# suite (labels unit, validation, gis, cli), then the unit tests again in a build with
# AddressSanitizer and UndefinedBehaviorSanitizer, then the fuzz targets of the input readers for
# a bounded time each (scripts/fuzz.sh, docs/fuzzing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTALUS_SANITIZE=ON -DTALUS_ENGINE_ONLY=ON \
      -DTALUS_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j"$jobs" --target talus_unit_tests
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan -L unit --output-on-failure -j"$jobs"

scripts/fuzz.sh
