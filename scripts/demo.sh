#!/usr/bin/env bash
# The demo: builds the sample hierarchies by hand through the API, compiles them to HNIs, reports
# on each one and ray-casts it with the CPU reference ray caster.
# Usage: scripts/demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out/hni" "$out/render"
"$build/samples/make_samples" "$out/hni"
for hni in "$out"/hni/*.png; do
  name=$(basename "$hni" .png)
  "$build/cli/nut" validate "$hni" >&2
  "$build/cli/nut" info "$hni" --json > "$out/hni/$name.json"
  "$build/cli/nut" info "$hni"
  "$build/cli/nut" render "$hni" -o "$out/render/$name.png" --stats "$out/render/$name.json"
done
echo
echo "demo: HNIs and their reports (JSON) are in $out/hni/, renders (1280x720, CPU ray caster) in $out/render/"
