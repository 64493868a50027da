#!/usr/bin/env bash
# Long fuzzing runs: each target (tests/fuzz) for RUNS executions (default 1,000,000) from its seeds, in a
# build with ASan, UBSan and libFuzzer (BUILD, default build-fuzz). New corpus entries go to a scratch
# folder, not the source tree; a crash leaves its input as crash-* in the current folder and stops.
#   tools/fuzz.sh [RUNS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-1000000}
shift || true
build=${BUILD:-build-fuzz}
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_scene fuzz_inertia fuzz_recording fuzz_questset_csv fuzz_coremotion_csv fuzz_mouse_script)
fi
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DWEDGE_SANITIZE=address,undefined -DWEDGE_BUILD_FUZZERS=ON \
    -DWEDGE_BUILD_BENCH=OFF
fi
cmake --build "$build" -j2 --target "${targets[@]}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
for t in "${targets[@]}"; do
  scratch="$build/fuzz_corpus/$t"
  mkdir -p "$scratch"
  echo "== $t: $runs runs"
  log="$build/fuzz_$t.log"
  status=0
  # (-timeout is wall-clock: a unit that runs in half a second alone can take ten times that while a build
  # shares the machine, so the limit for a hang is a minute.)
  "$build/tests/fuzz/$t" -runs="$runs" -timeout=60 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 \
    "$scratch" "tests/fuzz/corpus/$t" >"$log" 2>&1 || status=$?
  grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|Done|SUMMARY|fuzz:)|#[0-9]+ +DONE" "$log" || true
  if [ "$status" -ne 0 ]; then
    tail -n 40 "$log"
    echo "$t: a finding (exit $status; the input is the crash-*/leak-*/timeout-* file named above)"
    exit 1
  fi
done
