#!/usr/bin/env bash
# The PGA thesis's test scene (section 5.2.2): a 16 x 16 grid of RandomRule houses, each its own
# seed of samples/grammars/pga_random_rule.grammar, compiled with measured level of detail
# (`nut grammar --lod`) to HNIs and a city manifest, then rendered from a near and a far camera at
# full detail, with `--lod auto`, and with summaries for redirection cells below 2, 4 and 8 pixels,
# each compared with the full render of its camera.
#   scripts/grammar-grid.sh [BUILD] [OUT]   (defaults: build, out/grammar-grid)
set -euo pipefail
build=${1:-build}
out=${2:-out/grammar-grid}
nut="$build/cli/nut"
mkdir -p "$out"
start=$(date +%s.%N)
seq 0 255 | xargs -P "$(nproc)" -I{} "$nut" grammar samples/grammars/pga_random_rule.grammar --seed {} \
  -o "$out/house{}.png" --report "$out/house{}.json" --lod --quiet
compiled=$(date +%s.%N)
python3 - "$out" <<'PY'
import json, os, sys
out = sys.argv[1]
buildings, png, lod = [], 0, 0.0
for i in range(256):
    r = json.load(open(f"{out}/house{i}.json"))
    png += r["png_bytes"]
    lod += r["seconds"]["lod"]
    x, z = 12.0 * (i % 16), 12.0 * (i // 16)
    o = r["origin_m"]
    buildings.append({"name": f"house{i}", "hni": f"house{i}.png", "position_m": [x + o[0], o[1], z + o[2]], "yaw_deg": 0.0})
json.dump({"format": "nut-city", "version": 1, "name": "pga-grid", "units": "m", "up": "y", "buildings": buildings},
          open(f"{out}/city.json", "w"), indent=1)
print(f"grid: 256 HNIs, {png:,} bytes PNG in all ({png / 256:,.0f} per house)")
print(f"grid: level-of-detail measurement {lod:.1f} s of the compile's CPU time ({1000 * lod / 256:.0f} ms per house)")
PY
echo "grid: compiled in $(echo "$compiled - $start" | bc) s ($(nproc) processes, Zopfli PNGs)"
# near: inside the grid's corner; far: the whole grid, a house 30 to 60 px wide; small: the same
# framing at 320x180, a house 8 to 15 px wide, as a grid seen in a corner of a city view.
near=(--size 1280x720 --eye -40,60,-40 --target 96,0,96)
far=(--size 1280x720 --eye -200,160,-200 --target 96,0,96 --fov 30)
small=(--size 320x180 --eye -200,160,-200 --target 96,0,96 --fov 30)
for camera in near far small; do
  declare -n view=$camera
  for lod in full auto px2 px4 px8; do
    option=()
    [[ $lod == auto ]] && option=(--lod auto)
    [[ $lod == px* ]] && option=(--lod-px "${lod#px}")
    for run in 1 2 3; do  # the table takes the median time of three
      "$nut" render "$out/city.json" -o "$out/$camera-$lod.png" "${view[@]}" "${option[@]}" \
        --stats "$out/$camera-$lod.stats$run.json" 2>/dev/null
    done
    [[ $lod == full ]] && continue
    "$nut" compare "$out/$camera-full.png" "$out/$camera-$lod.png" --diff "$out/$camera-$lod-diff.png" |
      grep differing > "$out/$camera-$lod.compare"
  done
done
# At 320x180 one ray per pixel aliases the windows; the far render (the same framing, 4 x 4 rays
# per small pixel) box-filtered is the anti-aliased reference every small render is also held to.
for lod in full auto px2 px4 px8; do
  "$nut" compare "$out/far-full.png" "$out/small-$lod.png" --reduce 4 | grep differing > "$out/small-$lod.aa-compare"
done
python3 - "$out" <<'PY'
import json, re, sys
out = sys.argv[1]
print("| camera | render (2 threads) | seconds (median of 3) | iterations per ray | pixels off by > 8/255 | the same against 4x4 supersampled |")
print("|---|---|---|---|---|---|")
for camera in ("near", "far", "small"):
    for name in ("full", "auto", "px2", "px4", "px8"):
        runs = sorted((json.load(open(f"{out}/{camera}-{name}.stats{r}.json")) for r in (1, 2, 3)),
                      key=lambda s: s["seconds"])
        s = runs[1]
        off = "" if name == "full" else re.search(r"differing ([0-9.]+%)", open(f"{out}/{camera}-{name}.compare").read()).group(1)
        label = {"full": "full detail", "auto": "--lod auto"}.get(name, f"--lod-px {name[2:]}")
        aa = ""
        if camera == "small":
            aa = re.search(r"differing ([0-9.]+%)", open(f"{out}/small-{name}.aa-compare").read()).group(1)
        print(f"| {camera} | {label} | {s['seconds']:.3f} | {s['iterations_mean']:.2f} | {off} | {aa} |")
PY
