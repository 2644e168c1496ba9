#!/usr/bin/env bash
# Runs every benchmark of the build in one go; results also go to out/bench/*.json.
# Usage: scripts/bench.sh BUILD_DIR
set -euo pipefail
build=${1:-build}
mkdir -p out/bench
for bench in packer_bench lookup_bench grammar_bench render_bench load_bench scene_bench gl_bench convert_bench winding_bench; do
  echo "== $bench" >&2
  "$build/bench/$bench" --benchmark_out="out/bench/$bench.json" --benchmark_out_format=json
done
echo "== viewer frame time" >&2
scripts/viewer-bench.sh "$build" out/bench/viewer
echo "bench: results in out/bench/" >&2
