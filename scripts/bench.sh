#!/usr/bin/env bash
# make bench: every benchmark of the build, then docs/BENCHMARKS.md rewritten from this run: each
# block between `<!-- make bench: NAME -->` and its end line (scripts/bench_report.py), with the
# plots under docs/images (run time against error, city scaling).
#   scripts/bench.sh BUILD_DIR [OUT]   (default out/bench; results and section texts go there)
# GL_BACKEND=egl runs the GL parts on a GPU where there is one.
set -euo pipefail
build=${1:-build}
out=${2:-out/bench}
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$out"
start=$(date +%s)
step() { echo "bench: $1 ($(( $(date +%s) - start )) s so far)" >&2; }

for program in lookup_bench render_bench scene_bench gl_bench packer_bench convert_bench grammar_bench load_bench \
               winding_bench; do
  step "$program"
  filter=.
  # The global batch packing of 100 and 200 blocks takes 10 and 46 s an iteration, and the
  # tolerance sweep of the three larger samples seconds a case: the smaller cases show the same.
  [ "$program" = packer_bench ] && filter='-BM_MaxRectsGlobalBAF/(100|200)'
  [ "$program" = convert_bench ] && filter='-convertAtTolerance/(highrise|street|residential)'
  "$build/bench/$program" --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true \
    --benchmark_filter="$filter" --benchmark_out="$out/$program.json" --benchmark_out_format=json >"$out/$program.log"
done
python3 "$root/scripts/bench_tables.py" "$out"

step "run time against error"
python3 "$root/scripts/pareto-sweep.py" "$build" "$out/pareto" "$root/docs/images"

step "size against peers"
python3 "$root/scripts/size-peers.py" "$build" "$out/sizes"

step "city scaling"
HOLD=${HOLD:-3} "$root/scripts/city-scaling.sh" "$build" "$out/scaling" "$root/docs/images/city-scaling.png" >"$out/scaling.md"

status=0
step "stability"
python3 "$root/scripts/stability-counts.py" "$build" "$out/stability" || status=$?

step "pinned ratios"
"$root/scripts/pinned-ratios.sh" "$build" "$out/ratios" >"$out/ratios.txt" || status=$?
{ echo '```'; cat "$out/ratios.txt"; echo '```'; } >"$out/pinned.md"

sections=(pinned="$out/pinned.md" pareto="$out/pareto/pareto.md" sizes="$out/sizes/sizes.md" scaling="$out/scaling.md"
          stability="$out/stability/stability.md")
for name in lookups raycast scene gl packing convert grammar load winding; do
  sections+=("$name=$out/sections/$name.md")
done
python3 "$root/scripts/bench_report.py" "$root/docs/BENCHMARKS.md" "${sections[@]}"
step "done"
[ "$status" -eq 0 ] || echo "bench: the stress suite, the fuzz run or a pinned ratio failed (above)" >&2
exit "$status"
