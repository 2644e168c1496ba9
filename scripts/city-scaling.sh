#!/usr/bin/env bash
# City scaling (docs/BENCHMARKS.md, "City scaling"): cities of the NUT paper's sizes generated with
# `nut city --layout grid`, each drawn from the same street and overview cameras by the streaming
# NUT renderer (full detail, and with far buildings and cells as their summaries) and, in the same
# GL context, by rasterising the exported meshes of the same buildings
# (build/bench/city_scaling_bench); generation speed, memory and frame time per city, a Markdown
# table on stdout and a plot (PNG, gnuplot).
#   scripts/city-scaling.sh [BUILD] [OUT] [PLOT]
#   (defaults: build, out/city-scaling, OUT/city-scaling.png; SIZES="225 900 2116 8464",
#    GL_BACKEND=osmesa, HOLD=5 timed frames a view or fewer once they pass HOLD_SECONDS (0: no cap),
#    MESH_BUDGET_MB=12288 of mesh vertex buffers)
set -euo pipefail
build=${1:-build}
out=${2:-out/city-scaling}
plot=${3:-$out/city-scaling.png}
sizes=${SIZES:-225 900 2116 8464}
mkdir -p "$out"
for n in $sizes; do
  echo "city-scaling: $n buildings" >&2
  rm -rf "$out/city$n"
  "$build/cli/nut" city --count "$n" --out "$out/city$n" --seed 1 --layout grid --report "$out/city$n-report.json"
  "$build/bench/city_scaling_bench" "$out/city$n/city.json" --out "$out/city$n-result.json" \
    --screenshots "$out/shots$n" --gl "${GL_BACKEND:-osmesa}" --hold "${HOLD:-5}" --hold-seconds "${HOLD_SECONDS:-0}" --mesh-budget-mb "${MESH_BUDGET_MB:-12288}"
done
python3 - "$out" "$sizes" <<'PY'
import json, sys
out, sizes = sys.argv[1], [int(n) for n in sys.argv[2].split()]
rows = []
for n in sizes:
    report = json.load(open(f"{out}/city{n}-report.json"))
    result = json.load(open(f"{out}/city{n}-result.json"))
    rows.append((n, report, result))
gl = rows[0][2]["gl"]
mib = lambda b: b / 2**20
print(f"Cities of `nut city --layout grid --seed 1`, {rows[0][2]['width']}x{rows[0][2]['height']}, GL: {gl}.\n")
print("| buildings | generation (buildings/s) | NUT PNG | PNG per building | NUT texels | grammar meshes, indexed | exported meshes, indexed | exported meshes as drawn | memory ratio |")
print("|---|---|---|---|---|---|---|---|---|")
data = open(f"{out}/scaling.dat", "w")
data.write("# buildings png texels grammar_indexed exported_indexed buffers nut_street nut_above mesh_street mesh_above "
           "nut_lod_street nut_lod_above\n")
for n, report, result in rows:
    nut, mesh = result["nut"], result["mesh"]
    grammar_indexed = report["grammar_mesh"]["vertices"] * 12 + report["grammar_mesh"]["triangles"] * 12
    buffers = mesh.get("buffer_bytes")
    drawn = f"{mib(buffers):,.0f} MiB" if buffers else "over the budget"
    ratio = min(grammar_indexed, mesh["indexed_bytes"]) / nut["png_bytes"]
    print(f"| {n:,} | {report['buildings_per_second']:.0f} | {mib(nut['png_bytes']):.1f} MiB | {nut['png_bytes'] / n:,.0f} B "
          f"| {mib(nut['texel_bytes']):.1f} MiB "
          f"| {mib(grammar_indexed):,.0f} MiB | {mib(mesh['indexed_bytes']):,.0f} MiB | {drawn} | {ratio:.0f}x |")
    views = lambda key: [result[key]["views"][v]["median_ms"] if key in result and "views" in result[key] else float("nan")
                         for v in ("street", "above")]
    lod = [nut["lod_views"][v]["median_ms"] for v in ("street", "above")]
    data.write(" ".join(str(x) for x in [n, nut["png_bytes"], nut["texel_bytes"], grammar_indexed, mesh["indexed_bytes"],
                                          buffers or "nan", *views("nut"), *views("mesh"), *lod]) + "\n")
data.close()
# The NUT paper's modern city (its Figure 1 and Table 2): 10.6 MB of PNG for 5,061 buildings whose
# meshes have 671 million triangles.
paper_png, paper_triangles = 10.6e6 / 5061, 671e6 / 5061
n, report, result = rows[-1]
here = result["nut"]["png_bytes"] / n
triangles = result["mesh"]["triangles"] / n
print(f"\nAgainst the NUT paper's modern city (10.6 MB of PNG for 5,061 buildings, {paper_png:,.0f} B each, "
      f"meshes of {paper_triangles:,.0f} triangles each): {here:,.0f} B of PNG per building at {n:,} buildings "
      f"here ({here / paper_png:.2f}x), for exported meshes of {triangles:,.0f} triangles each "
      f"({triangles / paper_triangles:.2f}x).")
print()
print("| buildings | view | NUT frame (ms, median, min-max) | drawn | culled by frustum | culled by occlusion "
      "| NUT with LOD (ms) | as summaries | pixels off | mesh frame (ms) | meshes drawn |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for n, report, result in rows:
    for v in ("street", "above"):
        nv, lv = result["nut"]["views"][v], result["nut"]["lod_views"][v]
        mv = result["mesh"].get("views", {}).get(v)
        mesh_cols = f"{mv['median_ms']:.0f} | {mv['drawn']}" if mv else "over the budget | "
        print(f"| {n:,} | {v} | {nv['median_ms']:.0f} ({nv['min_ms']:.0f}-{nv['max_ms']:.0f}) | {nv['drawn']} "
              f"| {nv['culled_frustum']} | {nv['culled_occlusion']} | {lv['median_ms']:.0f} | {lv['as_summary']} "
              f"| {lv['pixels_off_pct']:.2f} % | {mesh_cols} |")
first, last = rows[0], rows[-1]
print()
for v in ("street", "above"):
    growth = last[2]["nut"]["views"][v]["median_ms"] / first[2]["nut"]["views"][v]["median_ms"]
    lod = last[2]["nut"]["lod_views"][v]["median_ms"] / first[2]["nut"]["lod_views"][v]["median_ms"]
    line = f"{v}: NUT frame time grows {growth:.2f}x from {first[0]:,} to {last[0]:,} buildings ({lod:.2f}x with LOD)"
    if "views" in last[2]["mesh"] and "views" in first[2]["mesh"]:
        line += f"; the meshes' {last[2]['mesh']['views'][v]['median_ms'] / first[2]['mesh']['views'][v]['median_ms']:.2f}x"
    print(line)
PY
gnuplot <<GP
set terminal pngcairo size 1100,420 font ",10"
set output "$plot"
set multiplot layout 1,2
set logscale x
set xlabel "buildings"
set key top left
set grid
set title "Frame time, 1280x720 (${GL_BACKEND:-osmesa})"
set ylabel "ms"
plot "$out/scaling.dat" using 1:7 with linespoints title "NUT, street", \
     "" using 1:8 with linespoints title "NUT, above", \
     "" using 1:11 with linespoints title "NUT with LOD, street", \
     "" using 1:12 with linespoints title "NUT with LOD, above", \
     "" using 1:9 with linespoints title "mesh, street", \
     "" using 1:10 with linespoints title "mesh, above"
set logscale y
set title "Memory"
set ylabel "bytes"
plot "$out/scaling.dat" using 1:2 with linespoints title "NUT PNG", \
     "" using 1:3 with linespoints title "NUT texels", \
     "" using 1:4 with linespoints title "grammar meshes, indexed", \
     "" using 1:5 with linespoints title "exported meshes, indexed", \
     "" using 1:6 with linespoints title "exported meshes as drawn"
unset multiplot
GP
echo "city-scaling: plot in $plot" >&2
