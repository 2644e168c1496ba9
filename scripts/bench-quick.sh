#!/usr/bin/env bash
# scripts/bench-quick.sh BUILD [OUT]: make bench-quick, about 2 minutes on 2 cores.
#  1. Every Google Benchmark program of the build once per case (one iteration; the slowest cases
#     left out): the harness runs. city_scaling_bench and gl_lookup_bench have their own drivers
#     (scripts/city-scaling.sh, docs/BENCHMARKS.md) and run under make bench only.
#  2. The programs behind the pinned ratios again, with repetitions, and the guard:
#     scripts/bench_ratios.py against the baselines of bench/pinned_ratios.json. Exit 1 when a
#     ratio fell past its margin.
# Results: OUT/smoke/*.json and OUT/*.json (default out/bench-quick).
set -euo pipefail
build=${1:-build}
out=${2:-out/bench-quick}
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$out/smoke"

declare -A smoke_filter=(
  [packer_bench]='-BM_MaxRectsGlobalBAF/(100|200)'  # 10 and 46 s a case
  [convert_bench]='(carpark|house)'                  # the larger samples take seconds a case
)
for program in packer_bench lookup_bench grammar_bench render_bench load_bench scene_bench gl_bench winding_bench \
               convert_bench; do
  [ -x "$build/bench/$program" ] || { echo "bench-quick: $build/bench/$program is not built" >&2; exit 2; }
  echo "bench-quick: $program" >&2
  "$build/bench/$program" --benchmark_min_time=0.000001 --benchmark_filter="${smoke_filter[$program]:-.}" \
    --benchmark_out="$out/smoke/$program.json" --benchmark_out_format=json >"$out/smoke/$program.log" 2>&1 ||
    { cat "$out/smoke/$program.log" >&2; echo "bench-quick: $program failed" >&2; exit 1; }
done

# Each program behind a pinned ratio, filtered to the benchmarks its ratios need.
python3 "$root/scripts/bench_ratios.py" --filters | while read -r program filter; do
  echo "bench-quick: $program, 5 repetitions" >&2
  "$build/bench/$program" --benchmark_min_time=0.05 --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true \
    --benchmark_filter="$filter" --benchmark_out="$out/$program.json" --benchmark_out_format=json \
    >"$out/$program.log" 2>&1 || { cat "$out/$program.log" >&2; echo "bench-quick: $program failed" >&2; exit 1; }
done
python3 "$root/scripts/bench_ratios.py" "$out"
