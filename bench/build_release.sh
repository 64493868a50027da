#!/usr/bin/env bash
# Configures a Release build in $BUILD_DIR (default build-bench/, Ninja when new) and builds the given
# targets; shared by bench/run.sh and bench/run_contact.sh.
#
# usage: bench/build_release.sh TARGET...
# Env: BUILD_DIR (default build-bench), JOBS (default 2).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${BUILD_DIR:-$root/build-bench}"
cd "$root"
if [[ -f "$build/CMakeCache.txt" ]]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
else
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
for target in "$@"; do
  cmake --build "$build" --target "$target" -j "${JOBS:-2}"
done
