#!/usr/bin/env bash
# Builds wedge-dzhanibekov (Release), runs the study and plots it: CSVs into $CSV_DIR (default
# build-bench/dzhanibekov), PNGs into docs/dzhanibekov/. See docs/dzhanibekov.md.
#
# usage: docs/dzhanibekov/run.sh [wedge-dzhanibekov flags, e.g. --dt 1e-3 --duration 30]
# Env: BUILD_DIR (default build-bench), CSV_DIR, JOBS (default 2).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${BUILD_DIR:-$root/build-bench}"
csv="${CSV_DIR:-$build/dzhanibekov}"
cd "$root"
if [[ -f "$build/CMakeCache.txt" ]]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
else
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" --target wedge-dzhanibekov -j "${JOBS:-2}"
"$build/apps/dzhanibekov/wedge-dzhanibekov" --out "$csv" "$@"
/usr/bin/python3 docs/dzhanibekov/plot.py "$csv" docs/dzhanibekov
