#!/usr/bin/env bash
# Builds the libFuzzer targets of the input readers with clang in build-fuzz (TALUS_FUZZ=ON) and
# runs each on its seed corpus, tests/fuzz/corpus/<target>, for a bounded time; fails on any
# finding (crash, sanitizer report, uncaught exception other than InputError, leak, timeout,
# memory beyond the limit), whose reproducer is left in build-fuzz/findings/. See
# docs/fuzzing.md. FUZZ_SECONDS: seconds per target (default 20); FUZZ_TARGETS: which targets
# (default all); FUZZ_JOBS: compile jobs and targets at a time (default: the cores); FUZZ_SEED:
# libFuzzer's seed (default 1, so that CI tries the same inputs in the same order every time and a
# slower machine tries a prefix of them; another seed explores further).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-20}
seed=${FUZZ_SEED:-1}
jobs=${FUZZ_JOBS:-$(nproc)}
read -r -a targets <<<"${FUZZ_TARGETS:-scenario materials intensity raster release study}"

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DTALUS_FUZZ=ON -DTALUS_BUILD_TESTS=OFF -DTALUS_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$jobs" --target talus_fuzzers
built=$SECONDS
echo "fuzz: targets built in $built s"

# Each target on its own copy of the corpus (new inputs go there, not into tests/), at most
# $jobs at a time; its exit status lands in build-fuzz/<target>.status.
run_target() {
  local target=$1 work=build-fuzz/corpus/$1 status=0
  rm -rf "$work" && mkdir -p "$work" build-fuzz/findings
  UBSAN_OPTIONS=print_stacktrace=1 "build-fuzz/fuzzers/${target}_fuzzer" "$work" "tests/fuzz/corpus/$target" \
    -seed="$seed" -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/findings/${target}-" >"build-fuzz/${target}.log" 2>&1 || status=$?
  echo "$status" >"build-fuzz/${target}.status"
}
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do sleep 1; done
  run_target "$target" &
done
wait
echo "fuzz: targets run in $((SECONDS - built)) s"
failed=()
for target in "${targets[@]}"; do
  log=build-fuzz/$target.log
  if [ "$(cat "build-fuzz/$target.status")" = 0 ]; then
    echo "fuzz $target: $(grep -o 'number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$') inputs in $seconds s, no finding"
  else
    failed+=("$target")
    echo "fuzz $target: FINDING ($log):"
    grep -E -A30 'ERROR|SUMMARY|Test unit written' "$log" | head -60
  fi
done
[ ${#failed[@]} -eq 0 ] || { echo "fuzz: findings in ${failed[*]}; see docs/fuzzing.md, \"A finding\""; exit 1; }
