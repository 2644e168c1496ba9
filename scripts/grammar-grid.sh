#!/usr/bin/env bash
# The PGA thesis's test scene (section 5.2.2): a 16 x 16 grid of RandomRule houses, each its own
# seed of samples/grammars/pga_random_rule.grammar, compiled to HNIs and a city manifest, then
# rendered at full detail and with level of detail (visual summaries for redirection cells below
# 2, 4 and 8 pixels), each compared with the full render.
#   scripts/grammar-grid.sh [BUILD] [OUT]   (defaults: build, out/grammar-grid)
set -euo pipefail
build=${1:-build}
out=${2:-out/grammar-grid}
nut="$build/cli/nut"
mkdir -p "$out"
start=$(date +%s.%N)
seq 0 255 | xargs -P "$(nproc)" -I{} "$nut" grammar samples/grammars/pga_random_rule.grammar --seed {} \
  -o "$out/house{}.png" --report "$out/house{}.json" --quiet
compiled=$(date +%s.%N)
python3 - "$out" <<'PY'
import json, os, sys
out = sys.argv[1]
buildings, png = [], 0
for i in range(256):
    r = json.load(open(f"{out}/house{i}.json"))
    png += r["png_bytes"]
    x, z = 12.0 * (i % 16), 12.0 * (i // 16)
    o = r["origin_m"]
    buildings.append({"name": f"house{i}", "hni": f"house{i}.png", "position_m": [x + o[0], o[1], z + o[2]], "yaw_deg": 0.0})
json.dump({"format": "nut-city", "version": 1, "name": "pga-grid", "units": "m", "up": "y", "buildings": buildings},
          open(f"{out}/city.json", "w"), indent=1)
print(f"grid: 256 HNIs, {png:,} bytes PNG in all ({png / 256:,.0f} per house)")
PY
echo "grid: compiled in $(echo "$compiled - $start" | bc) s ($(nproc) processes, Zopfli PNGs)"
view=(--size 1280x720 --eye -40,60,-40 --target 96,0,96)
"$nut" render "$out/city.json" -o "$out/full.png" "${view[@]}" --stats "$out/full.stats.json" 2>/dev/null
for lod in 2 4 8; do
  "$nut" render "$out/city.json" -o "$out/lod$lod.png" "${view[@]}" --lod-px "$lod" --stats "$out/lod$lod.stats.json" 2>/dev/null
  "$nut" compare "$out/full.png" "$out/lod$lod.png" --diff "$out/lod$lod-diff.png" | grep differing > "$out/lod$lod.compare"
done
python3 - "$out" <<'PY'
import json, re, sys
out = sys.argv[1]
print("| render (1280x720, 2 threads) | seconds | iterations per ray | pixels off by > 8/255 |")
print("|---|---|---|---|")
for name in ("full", "lod2", "lod4", "lod8"):
    s = json.load(open(f"{out}/{name}.stats.json"))
    off = "" if name == "full" else re.search(r"differing ([0-9.]+%)", open(f"{out}/{name}.compare").read()).group(1)
    label = "full detail" if name == "full" else f"--lod-px {name[3:]}"
    print(f"| {label} | {s['seconds']:.3f} | {s['iterations_mean']:.2f} | {off} |")
PY
