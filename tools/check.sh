#!/usr/bin/env bash
# The checks, each build in its own folder (docs/testing.md says what each covers):
#   release    Release (gcc): the whole suite, with floating-point traps on.
#   asan       The program, the replay runtime and the fuzz targets built with ASan + UBSan (clang; UBSan
#              without its pointer-overflow check, below): every
#              test of the program (the [cli] tests: each shipped scene's and recording's state hash, the
#              importers, replays, `wedge xr` over the runtime) run against that build, and a short run
#              of each fuzz target from its seeds. Needs `release` first (its tests drive the program).
#   install    The libraries installed into a scratch prefix (build-install/prefix), and examples/ built
#              against that package with find_package(Wedge) and run: a hand's grab and the pulse it
#              feels; a shipped recording replayed to its recorded state hash. Needs `release` first.
#   asan-full  The whole suite built and run under ASan + every UBSan check (about an hour on 2 cores).
#   tsan       The multi-threaded step's tests (--workers) under ThreadSanitizer.
#   debug      The program built Debug (gcc -O0): every shipped scene's and recording's state hash, in
#              each instruction set of the solver's lanes (WEDGE_SIMD: the best the CPU has, AVX2,
#              SSE2), must come out as the Release build's (determinism across builds). Needs `release`
#              first.
# CI runs `release install asan` (the README's test command). Any sanitizer report fails.
#   tools/check.sh [release|install|asan|asan-full|tsan|debug]...
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${JOBS:-2}
stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(release)

# Leaks in the system's own libraries (Mesa's and GLFW's one-time allocations) are not ours.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}

sanitized() {  # folder, sanitizers, extra cmake arguments...
  local dir=$1 sanitize=$2
  shift 2
  CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DWEDGE_SANITIZE="$sanitize" -DWEDGE_BUILD_BENCH=OFF "$@"
}

# The tests that open windows (GLX under Xvfb) run without leak checking: Mesa's GLX driver is loaded with
# dlopen and closed before exit, so LeakSanitizer cannot name the library its one-time allocations (240
# bytes in 3 blocks) came from and no suppression can match them. ASan and UBSan still check every access.
windowed='^wedge (view|xr: each eye)'

for stage in "${stages[@]}"; do
  echo "==== check: $stage ($(date -u +%H:%M:%S))"
  case $stage in
    release)
      cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
      cmake --build build -j"$jobs"
      ctest --test-dir build --output-on-failure -j"$jobs"
      ;;
    install)
      rm -rf build-install
      cmake --install build --prefix build-install/prefix
      cmake -S examples -B build-install/examples -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$PWD/build-install/prefix"
      cmake --build build-install/examples -j"$jobs"
      tools/check_examples.sh build-install/examples
      ;;
    asan)
      # UBSan's pointer-overflow check (pointer arithmetic that wraps the address space) is left out here:
      # it instruments every index computation in Eigen's expression templates (soft_step.cpp compiled in
      # 165 s with it, 97 s without; the whole build 2938 s of CPU against 2412 s), while ASan still stops
      # any access through a pointer outside its object. asan-full keeps it.
      sanitized build-asan address,undefined -DWEDGE_BUILD_FUZZERS=ON -DWEDGE_SANITIZE_EXCLUDE=pointer-overflow
      cmake --build build-asan -j"$jobs" --target wedge-programs wedge_xr_replay fuzz_scene fuzz_inertia fuzz_recording \
        fuzz_questset_csv fuzz_coremotion_csv fuzz_mouse_script
      # (WEDGE_FP_TRAPS=0: clang vectorises scalar divisions into packed ones whose unused lane divides
      # 0 by 0, which a trap cannot tell from a real invalid operation; tests/main.cpp.)
      WEDGE_FP_TRAPS=0 WEDGE_PROGRAM=$PWD/build-asan/apps/wedge/wedge \
        ctest --test-dir build --output-on-failure -j"$jobs" -R '^wedge' -E "$windowed"
      ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 WEDGE_FP_TRAPS=0 WEDGE_PROGRAM=$PWD/build-asan/apps/wedge/wedge \
        ctest --test-dir build --output-on-failure -j"$jobs" -R "$windowed"
      ctest --test-dir build-asan --output-on-failure -j"$jobs" -R '^fuzz:'
      ;;
    asan-full)
      sanitized build-asan-full address,undefined -DWEDGE_BUILD_FUZZERS=ON -DWEDGE_SANITIZE_EXCLUDE=
      cmake --build build-asan-full -j"$jobs"
      WEDGE_FP_TRAPS=0 ctest --test-dir build-asan-full --output-on-failure -j"$jobs" -E "$windowed"
      ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 WEDGE_FP_TRAPS=0 \
        ctest --test-dir build-asan-full --output-on-failure -j"$jobs" -R "$windowed"
      ;;
    tsan)
      sanitized build-tsan thread
      cmake --build build-tsan -j"$jobs" --target wedge_workers_tests
      WEDGE_FP_TRAPS=0 ctest --test-dir build-tsan --output-on-failure -j"$jobs"
      ;;
    debug)
      cmake -S . -B build-debug -G Ninja -DCMAKE_BUILD_TYPE=Debug -DWEDGE_BUILD_BENCH=OFF -DWEDGE_BUILD_TESTS=OFF
      cmake --build build-debug -j"$jobs" --target wedge
      WEDGE_PROGRAM=$PWD/build-debug/apps/wedge/wedge ctest --test-dir build --output-on-failure -j"$jobs" -R 'state hashes'
      ;;
    *)
      echo "tools/check.sh: unknown stage '$stage' (the stages are release, install, asan, asan-full, tsan and debug)" >&2
      exit 2
      ;;
  esac
done
echo "==== check: passed ($(date -u +%H:%M:%S))"
