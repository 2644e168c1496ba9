#!/usr/bin/env bash
# scripts/pinned-ratios.sh BUILD OUT: the pinned ratios of docs/BENCHMARKS.md. Each program behind
# a ratio runs the benchmarks its ratios need (bench/pinned_ratios.json), 5 repetitions interleaved
# at random, results in OUT/PROGRAM.json; then scripts/bench_ratios.py prints one line per ratio
# on stdout and exits 1 when one fell past its guard. Called by make bench-quick and make bench.
set -euo pipefail
build=${1:-build}
out=${2:-out/bench-quick}
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$out"
python3 "$root/scripts/bench_ratios.py" --filters | while read -r program filter; do
  echo "pinned ratios: $program, 5 repetitions" >&2
  "$build/bench/$program" --benchmark_min_time=0.05 --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true \
    --benchmark_filter="$filter" --benchmark_out="$out/$program.json" --benchmark_out_format=json \
    >"$out/$program.log" 2>&1 || { cat "$out/$program.log" >&2; echo "pinned ratios: $program failed" >&2; exit 1; }
done
python3 "$root/scripts/bench_ratios.py" "$out"
