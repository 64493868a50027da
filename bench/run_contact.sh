#!/usr/bin/env bash
# Builds wedge_bench_contact (Release, build-bench/) and runs it with 5 repetitions; writes Google
# Benchmark's JSON to bench/results/contact.json and prints the medians as a Markdown table, then the
# ratios Wedge / peer engine and the goals of bench/README.md ("Contact").
#
# usage: bench/run_contact.sh [extra wedge_bench_contact flags, e.g. --benchmark_filter=Pyramid]
# Env: BUILD_DIR (default build-bench), JOBS (default 2), REPS (default 5). A whole run takes 12-17 min on
# 2 cores, most of it the 10,000-tesseract pile.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${BUILD_DIR:-$root/build-bench}"
cd "$root"
bench/build_release.sh wedge_bench_contact
mkdir -p bench/results
out=bench/results/contact.json
# Random interleaving runs the repetitions of all benchmarks in a shuffled order, so that a change of
# load on a shared machine falls on Wedge and its peer alike rather than on whichever ran last.
"$build/bench/wedge_bench_contact" --benchmark_repetitions="${REPS:-5}" --benchmark_report_aggregates_only=true \
  --benchmark_enable_random_interleaving=true --benchmark_out="$out" --benchmark_out_format=json "$@"

echo
echo "Medians of ${REPS:-5} repetitions ($out):"
/usr/bin/python3 bench/contact_table.py "$out"
