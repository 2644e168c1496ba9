#!/usr/bin/env bash
# The demo: builds the sample hierarchies by hand through the API, compiles them to HNIs, and
# reports on each one. Usage: scripts/demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
mkdir -p "$out/hni"
"$build/samples/make_samples" "$out/hni"
for hni in "$out"/hni/*.png; do
  "$build/cli/nut" validate "$hni" >&2
  "$build/cli/nut" info "$hni" --json > "${hni%.png}.json"
  "$build/cli/nut" info "$hni"
done
echo
echo "demo: HNIs and their reports (JSON) are in $out/hni/"
