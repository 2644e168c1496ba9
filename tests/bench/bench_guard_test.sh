#!/usr/bin/env bash
# The guard of make bench-quick fails when a pinned ratio is made worse on purpose:
# render_bench with its test-only NUT_BENCH_SLOWDOWN=4 (each NUT frame four times as long) must
# take every NUT/fastest-Embree ratio below its guard (baseline x 0.6), and scripts/bench_ratios.py must
# exit 1 naming them.
# Usage: bench_guard_test.sh RENDER_BENCH SOURCE_DIR WORK_DIR
set -uo pipefail
render_bench=$1 source=$2 work=$3
mkdir -p "$work"
NUT_BENCH_SLOWDOWN=4 "$render_bench" --benchmark_min_time=0.05 --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true \
  --benchmark_filter="$(python3 "$source/scripts/bench_ratios.py" --filters | sed -n 's/^render_bench //p')" \
  --benchmark_out="$work/render_bench.json" \
  --benchmark_out_format=json >/dev/null 2>"$work/render_bench.log" || { echo "FAIL: render_bench did not run"; cat "$work/render_bench.log"; exit 1; }
python3 "$source/scripts/bench_ratios.py" "$work" --programs render_bench >"$work/ratios.txt" 2>"$work/errors.txt"
status=$?
cat "$work/ratios.txt" "$work/errors.txt"
[ "$status" -eq 1 ] || { echo "FAIL: the guard exited $status, not 1"; exit 1; }
for scene in facade building solids; do
  grep -q "^NUT/fastest Embree rays/s ($scene, 1 thread): .* REGRESSED$" "$work/ratios.txt" ||
    { echo "FAIL: the $scene ratio was not caught"; exit 1; }
  grep -q "regressed past its margin: NUT/fastest Embree rays/s ($scene, 1 thread)" "$work/errors.txt" ||
    { echo "FAIL: the $scene ratio is not named on stderr"; exit 1; }
done
echo "ok: the guard caught the slower caster"
