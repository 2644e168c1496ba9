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
: >"$out/steps.tsv"
# Each step's start on stderr, and in OUT/steps.tsv for the report's "duration" block.
step() {
  echo "bench: $1 ($(( $(date +%s) - start )) s so far)" >&2
  printf '%s\t%s\n' "$1" "$(( $(date +%s) - start ))" >>"$out/steps.tsv"
}

for program in lookup_bench render_bench scene_bench gl_bench packer_bench convert_bench grammar_bench load_bench \
               winding_bench; do
  step "$program"
  filter=.
  # The global batch packing of 100 and 200 blocks takes 10 and 46 s an iteration, and the
  # tolerance sweep of the three larger samples seconds a case: the smaller cases show the same.
  [ "$program" = packer_bench ] && filter='-BM_MaxRectsGlobalBAF/(100|200)'
  [ "$program" = convert_bench ] && filter='-convertAtTolerance/(highrise|street|residential)'
  # A quarter second a repetition (Google Benchmark's default is half): three interleaved
  # repetitions and their spread say more than longer single ones, and the run fits its 20 minutes.
  "$build/bench/$program" --benchmark_min_time=0.25 --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true \
    --benchmark_filter="$filter" --benchmark_out="$out/$program.json" --benchmark_out_format=json >"$out/$program.log"
done
python3 "$root/scripts/bench_tables.py" "$out"

step "run time against error"
python3 "$root/scripts/pareto-sweep.py" "$build" "$out/pareto" "$root/docs/images"

step "size against peers"
python3 "$root/scripts/size-peers.py" "$build" "$out/sizes"

step "city scaling"
HOLD=${HOLD:-3} HOLD_SECONDS=${HOLD_SECONDS:-10} "$root/scripts/city-scaling.sh" "$build" "$out/scaling" "$root/docs/images/city-scaling.png" >"$out/scaling.md"

status=0
step "stability"
FUZZ_SMOKE_SECONDS=${FUZZ_SMOKE_SECONDS:-15} FUZZ_SMOKE_OTHER_SECONDS=${FUZZ_SMOKE_OTHER_SECONDS:-5} \
  python3 "$root/scripts/stability-counts.py" "$build" "$out/stability" || status=$?

step "pinned ratios"
"$root/scripts/pinned-ratios.sh" "$build" "$out/ratios" >"$out/ratios.txt" || status=$?
{ echo '```'; cat "$out/ratios.txt"; echo '```'; } >"$out/pinned.md"

step "report"
python3 - "$out/steps.tsv" >"$out/duration.md" <<'PY'
import sys
steps = [line.rstrip("\n").split("\t") for line in open(sys.argv[1])]
starts = [int(t) for _, t in steps]
parts = [(name, end - begin) for (name, _), begin, end in zip(steps, starts, starts[1:])]
programs = sum(s for name, s in parts if name.endswith("_bench"))
rest = ", ".join(f"{s} s for {name}" for name, s in parts if not name.endswith("_bench"))
print(f"This run took {starts[-1]:,} s ({starts[-1] / 60:.1f} minutes): {programs} s for the benchmark programs, {rest}.")
PY
sections=(pinned="$out/pinned.md" duration="$out/duration.md" pareto="$out/pareto/pareto.md" sizes="$out/sizes/sizes.md" scaling="$out/scaling.md"
          stability="$out/stability/stability.md")
for name in lookups raycast planecells scene gl glplanecells packing convert grammar load winding; do
  sections+=("$name=$out/sections/$name.md")
done
python3 "$root/scripts/bench_report.py" "$root/docs/BENCHMARKS.md" "${sections[@]}"
step "done"
[ "$status" -eq 0 ] || echo "bench: the stress suite, the fuzz run or a pinned ratio failed (above)" >&2
exit "$status"
