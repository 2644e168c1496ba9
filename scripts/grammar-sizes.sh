#!/usr/bin/env bash
# The size table of docs/GRAMMAR.md: every sample grammar compiled (seed 0) to an HNI and to the
# derivation's own meshes (solid: what the HNI shows; fronts: a quad per facade terminal, as a
# shape-grammar system emits), each packed the way a user would ship it: gltfpack -cc (the
# meshoptimizer project's packer, from npm) and gzip -9.
#   scripts/grammar-sizes.sh [BUILD]        (BUILD: the build folder, default build)
# gltfpack comes from scripts/install-deps.sh (npm, into .tools/).
set -euo pipefail
build=${1:-build}
root=$(cd "$(dirname "$0")/.." && pwd)
gltfpack="$root/.tools/node_modules/.bin/gltfpack"
[ -x "$gltfpack" ] || { echo "grammar-sizes: $gltfpack is missing: run scripts/install-deps.sh" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| sample | shapes | blocks | HNI raw | HNI PNG | solid: triangles | OBJ + MTL | gltfpack -cc | + gzip -9 | fronts: triangles | gltfpack -cc + gzip -9 | PNG / fronts |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for grammar in "$root"/samples/grammars/*.grammar; do
  name=$(basename "$grammar" .grammar)
  "$root/$build/cli/nut" grammar "$grammar" -o "$work/$name.png" --mesh "$work/$name.obj" --report "$work/$name.json" --quiet
  "$root/$build/cli/nut" grammar "$grammar" -o "$work/$name.fronts.png" --mesh "$work/$name.fronts.obj" \
    --mesh-faces fronts --report "$work/$name.fronts.json" --quiet
  for mesh in "$name" "$name.fronts"; do
    "$gltfpack" -i "$work/$mesh.obj" -o "$work/$mesh.glb" -cc >/dev/null
    gzip -9 -c "$work/$mesh.glb" > "$work/$mesh.glb.gz"
  done
  python3 - "$name" "$work" <<'PY'
import json, os, sys
name, work = sys.argv[1], sys.argv[2]
r = json.load(open(f"{work}/{name}.json"))
size = lambda p: os.path.getsize(f"{work}/{p}")
fronts = json.load(open(f"{work}/{name}.fronts.json"))
png, gz, frontsGz = r["png_bytes"], size(f"{name}.glb.gz"), size(f"{name}.fronts.glb.gz")
raw = r["image"][0] * r["image"][1] * 4
print(f"| {name} | {r['shapes']:,} | {r['blocks']} | {raw:,} | {png:,} | {r['mesh']['triangles']:,} | "
      f"{size(name + '.obj') + size(name + '.mtl'):,} | {size(name + '.glb'):,} | {gz:,} | "
      f"{fronts['mesh']['triangles']:,} | {frontsGz:,} | {png / frontsGz:.2f} |")
PY
done
