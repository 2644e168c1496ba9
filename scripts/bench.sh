#!/usr/bin/env bash
# make bench: every benchmark of the build, then the generated sections of docs/BENCHMARKS.md
# rewritten from this run (scripts/bench_report.py): the pinned ratios, run time against error
# with its plots (docs/images/pareto-*.png), and size against peers. Google Benchmark results go to OUT/*.json.
# Usage: scripts/bench.sh BUILD_DIR [OUT]   (default out/bench)
set -euo pipefail
build=${1:-build}
out=${2:-out/bench}
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$out"
for bench in packer_bench lookup_bench grammar_bench render_bench load_bench scene_bench gl_bench convert_bench winding_bench; do
  echo "== $bench" >&2
  "$build/bench/$bench" --benchmark_out="$out/$bench.json" --benchmark_out_format=json
done
echo "== viewer frame time" >&2
"$root/scripts/viewer-bench.sh" "$build" "$out/viewer"

echo "== run time against error" >&2
python3 "$root/scripts/pareto-sweep.py" "$build" "$out/pareto" "$root/docs/images"

echo "== size against peers" >&2
python3 "$root/scripts/size-peers.py" "$build" "$out/sizes"

echo "== pinned ratios" >&2
status=0
"$root/scripts/pinned-ratios.sh" "$build" "$out/ratios" >"$out/ratios.txt" || status=$?
{ echo '```'; cat "$out/ratios.txt"; echo '```'; } >"$out/pinned.md"

python3 "$root/scripts/bench_report.py" "$root/docs/BENCHMARKS.md" pinned="$out/pinned.md" pareto="$out/pareto/pareto.md" \
  sizes="$out/sizes/sizes.md"
[ "$status" -eq 0 ] || echo "bench: a pinned ratio fell past its guard (see above)" >&2
exit "$status"
