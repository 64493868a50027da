#!/usr/bin/env bash
# Builds wedge_bench (Release, build-bench/) and runs it with 5 repetitions; writes Google Benchmark's
# JSON to bench/results/core.json and prints the medians as a Markdown table (as in bench/README.md).
#
# usage: bench/run.sh [extra wedge_bench flags, e.g. --benchmark_filter=WorldStep]
# Env: BUILD_DIR (default build-bench), JOBS (default 2).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${BUILD_DIR:-$root/build-bench}"
cd "$root"
bench/build_release.sh wedge_bench
mkdir -p bench/results
out=bench/results/core.json
"$build/bench/wedge_bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_out="$out" --benchmark_out_format=json "$@"

echo
echo "Medians of 5 repetitions ($out):"
/usr/bin/python3 - "$out" <<'PY'
import json, sys
data = json.load(open(sys.argv[1]))
ctx = data["context"]
print(f"host {ctx.get('host_name')}, {ctx.get('num_cpus')} cpus @ {ctx.get('mhz_per_cpu')} MHz, "
      f"load {ctx.get('load_avg')}, library build {ctx.get('library_build_type')}")
print()
print("| benchmark | wall time / iteration | CPU time / iteration | CPU time per item | items/s |")
print("|---|---:|---:|---:|---:|")
for b in data["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    per = b.get("time_per_body", b.get("time_per_op"))
    unit = b["time_unit"]
    print(f"| {b['run_name']} | {b['real_time']:.0f} {unit} | {b['cpu_time']:.0f} {unit} | "
          f"{per * 1e9:.2f} ns | {b['items_per_second'] / 1e6:.2f} M |")
PY
