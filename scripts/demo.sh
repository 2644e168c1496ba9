#!/usr/bin/env bash
# The demo: builds the sample hierarchies by hand through the API, compiles them to HNIs, reports
# on each one and ray-casts it with the CPU reference ray caster; then converts two of the sample
# OBJ buildings and a street of four (into a folder with a city manifest) and compares their
# renders with the source meshes' from the same camera; compiles the sample grammars, each
# rendered beside the render of the derivation's own mesh; and generates a city of 100 buildings.
# Usage: scripts/demo.sh BUILD_DIR OUT_DIR
set -euo pipefail
build=${1:-build}
out=${2:-out}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/hni" "$out/render" "$out/convert" "$out/grammar" "$out/city"
"$build/samples/make_samples" "$out/hni"
for hni in "$out"/hni/*.png; do
  name=$(basename "$hni" .png)
  "$build/cli/nut" validate "$hni" >&2
  "$build/cli/nut" info "$hni" --json > "$out/hni/$name.json"
  "$build/cli/nut" info "$hni"
  "$build/cli/nut" render "$hni" -o "$out/render/$name.png" --stats "$out/render/$name.json"
done
for name in house highrise; do
  obj="$root/samples/obj/$name.obj"
  "$build/cli/nut" convert "$obj" -o "$out/convert/$name.png" --report "$out/convert/$name.json"
  "$build/cli/nut" render "$out/convert/$name.png" -o "$out/convert/$name-nut.png"
  "$build/cli/nut" render-mesh "$obj" -o "$out/convert/$name-mesh.png"
  "$build/cli/nut" compare "$out/convert/$name-nut.png" "$out/convert/$name-mesh.png" --diff "$out/convert/$name-diff.png"
done
# A file of several buildings: one HNI (and complementary mesh) per building and a city manifest,
# rendered whole and compared with the source street.
rm -rf "$out/convert/street"
"$build/cli/nut" convert "$root/samples/obj/street.obj" -o "$out/convert/street/" --report "$out/convert/street.json"
"$build/cli/nut" render "$out/convert/street/city.json" -o "$out/convert/street-nut.png"
"$build/cli/nut" render-mesh "$root/samples/obj/street.obj" -o "$out/convert/street-mesh.png"
"$build/cli/nut" compare "$out/convert/street-nut.png" "$out/convert/street-mesh.png" --diff "$out/convert/street-diff.png"
# The sample grammars: HNI, the derivation's mesh, and both rendered from the same camera.
for grammar in "$root"/samples/grammars/*.grammar; do
  name=$(basename "$grammar" .grammar)
  "$build/cli/nut" grammar "$grammar" -o "$out/grammar/$name.png" --mesh "$out/grammar/$name.obj" --report "$out/grammar/$name.json"
  "$build/cli/nut" render "$out/grammar/$name.png" -o "$out/grammar/$name-nut.png"
  "$build/cli/nut" render-mesh "$out/grammar/$name.obj" -o "$out/grammar/$name-mesh.png"
  "$build/cli/nut" compare "$out/grammar/$name-nut.png" "$out/grammar/$name-mesh.png" --diff "$out/grammar/$name-diff.png"
done
# A city of 100 distinct buildings from the building grammars, rendered whole.
"$build/cli/nut" city --count 100 --out "$out/city/city100" --seed 1
"$build/cli/nut" render "$out/city/city100/city.json" -o "$out/city/city100.png" --size 1280x720
echo
echo "demo: HNIs and their reports (JSON) are in $out/hni/, renders (1280x720, CPU ray caster) in $out/render/"
echo "demo: converted OBJ samples in $out/convert/: NAME.png (HNI), NAME.json (report), NAME-nut.png and"
echo "      NAME-mesh.png (the HNI and its source mesh from the same camera), NAME-diff.png (their difference);"
echo "      street/ holds one HNI per building and city.json, which street-nut.png renders whole"
echo "demo: compiled sample grammars in $out/grammar/: NAME.png (HNI), NAME.obj (the derivation's mesh),"
echo "      NAME-nut.png and NAME-mesh.png (both rendered), NAME-diff.png"
echo "demo: a generated city in $out/city/city100/ (100 HNIs and city.json), rendered in $out/city/city100.png"
