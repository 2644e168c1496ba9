#!/usr/bin/env bash
# scripts/bench-quick.sh BUILD [OUT]: make bench-quick, about 3 minutes on 2 cores.
#  1. Every Google Benchmark program of the build once per case (one iteration; the slowest cases
#     left out): the harness runs. city_scaling_bench and gl_lookup_bench have their own drivers
#     (scripts/city-scaling.sh, docs/BENCHMARKS.md) and run under make bench only.
#  2. The run-time-against-error sweep at 320x180 with fewer settings (scripts/pareto-sweep.py
#     --quick): every scene on both casters.
#  3. Size against peers on one input of each kind (scripts/size-peers.py --quick).
#  4. The programs behind the pinned ratios again, with repetitions, and the guard
#     (scripts/pinned-ratios.sh): scripts/bench_ratios.py against the baselines of
#     bench/pinned_ratios.json. Exit 1 when a ratio fell past its margin.
# Results: OUT/smoke/*.json, OUT/pareto/ and OUT/*.json (default out/bench-quick).
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

# The run-time-against-error sweep on tiny frames: every scene and back-end still runs.
echo "bench-quick: run time against error (scripts/pareto-sweep.py --quick)" >&2
python3 "$root/scripts/pareto-sweep.py" "$build" "$out/pareto" "$out/pareto/plots" --quick

# Size against peers on one input of each kind (gltfpack, draco_encoder).
echo "bench-quick: size against peers (scripts/size-peers.py --quick)" >&2
python3 "$root/scripts/size-peers.py" "$build" "$out/sizes" --quick

# The pinned ratios and their guard, last: the exit status of make bench-quick.
"$root/scripts/pinned-ratios.sh" "$build" "$out"
