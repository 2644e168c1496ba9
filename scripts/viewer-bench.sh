#!/usr/bin/env bash
# Frame time of a streamed city (docs/PERFORMANCE.md, "Streaming viewer frame time"): a generated
# city of 225 buildings (the NUT paper's smallest) at 1280x720 from an overview and a street-level
# camera, on the CPU caster (`nut render`, all cores, median of three) and on the GL caster
# (`nut-viewer --headless`, median of ten frames of the settled view), and a flight of 120 frames
# along a street that streams the city in as it goes. GL_BACKEND=egl uses EGL (a GPU when there is
# one; Mesa's llvmpipe otherwise).
#   scripts/viewer-bench.sh [BUILD] [OUT]   (defaults: build, out/viewer-bench)
set -euo pipefail
build=${1:-build}
out=${2:-out/viewer-bench}
gl=${GL_BACKEND:-osmesa}
mkdir -p "$out"
"$build/cli/nut" city --count 225 --out "$out/city225" --seed 1 --quiet
city="$out/city225/city.json"
cat > "$out/overview.json" <<'JSON'
{"fov_deg": 40, "keyframes": [{"eye": [-80, 140, -100], "target": [120, 0, 110]}]}
JSON
cat > "$out/street.json" <<'JSON'
{"fov_deg": 40, "keyframes": [{"eye": [60, 3, 8], "target": [240, 6, 8]}]}
JSON
cat > "$out/flight.json" <<'JSON'
{"fov_deg": 40, "keyframes": [{"eye": [-20, 5, 8], "target": [100, 5, 8]},
                              {"eye": [220, 5, 8], "target": [340, 5, 8]}]}
JSON
size=1280x720
for view in overview street; do
  eye=$(python3 -c "import json;k=json.load(open('$out/$view.json'))['keyframes'][0];print(','.join(map(str,k['eye'])),','.join(map(str,k['target'])))")
  read -r e t <<< "$eye"
  for run in 1 2 3; do
    "$build/cli/nut" render "$city" -o "$out/$view-cpu.png" --size $size --eye "$e" --target "$t" --fov 40 \
      --stats "$out/$view-cpu$run.json" 2>/dev/null
  done
  "$build/viewer/nut-viewer" "$city" --headless --gl "$gl" --size $size --camera-path "$out/$view.json" --hold 10 \
    --screenshot "$out/$view-gl.png" --stats "$out/$view-gl.json" 2>/dev/null
done
# What each culling test saves, in the same run: the street view with each turned off.
"$build/viewer/nut-viewer" "$city" --headless --gl "$gl" --size $size --camera-path "$out/street.json" --hold 10 \
  --no-occlusion-culling --stats "$out/street-no-occlusion-gl.json" 2>/dev/null
"$build/viewer/nut-viewer" "$city" --headless --gl "$gl" --size $size --camera-path "$out/street.json" --hold 10 \
  --no-occlusion-culling --no-frustum-culling --stats "$out/street-no-culling-gl.json" 2>/dev/null
"$build/viewer/nut-viewer" "$city" --headless --gl "$gl" --size $size --camera-path "$out/flight.json" --frames 120 \
  --stats "$out/flight-gl.json" 2>/dev/null
python3 - "$out" "$gl" <<'PY'
import json, statistics, sys
out, gl = sys.argv[1], sys.argv[2]
def held(name):
    frames = json.load(open(f"{out}/{name}-gl.json"))["frames"]
    return statistics.median(f["ms"] for f in frames if f["phase"] == "holding"), frames[-1]
print(f"| view (1280x720, 225 buildings) | CPU caster, 2 threads (ms) | GL caster, {gl} (ms) | drawn | culled by frustum | culled by occlusion |")
print("|---|---|---|---|---|---|")
for view in ("overview", "street"):
    cpu = statistics.median(json.load(open(f"{out}/{view}-cpu{r}.json"))["seconds"] for r in (1, 2, 3)) * 1000
    ms, last = held(view)
    print(f"| {view} | {cpu:.0f} | {ms:.0f} | {last['drawn']} | {last['culled_frustum']} | {last['culled_occlusion']} |")
for view, label in (("street-no-occlusion", "street, occlusion culling off"), ("street-no-culling", "street, both culling tests off")):
    ms, last = held(view)
    print(f"| {label} | | {ms:.0f} | {last['drawn']} | {last['culled_frustum']} | {last['culled_occlusion']} |")
flight = json.load(open(f"{out}/flight-gl.json"))
path = [f for f in flight["frames"] if f["phase"] == "path"][1:]  # the first builds the programs
ms = sorted(f["ms"] for f in path)
print()
print(f"flight: {len(path)} frames along the street, GL {gl}: median {statistics.median(ms):.0f} ms, "
      f"90th percentile {ms[len(ms) * 9 // 10]:.0f} ms, max {ms[-1]:.0f} ms; "
      f"{flight['loaded']} of {flight['known']} buildings loaded, {flight['bytes_streamed']:,} bytes streamed")
mean = lambda key: statistics.mean(f[key] for f in path)
print(f"flight, per frame on average: {mean('drawn'):.1f} buildings ray-cast, {mean('culled_frustum'):.1f} culled by "
      f"the frustum, {mean('culled_occlusion'):.1f} by occlusion, {mean('proxies'):.1f} drawn as proxies")
PY
