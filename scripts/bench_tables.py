#!/usr/bin/env python3
"""The tables of docs/BENCHMARKS.md's generated sections, from one `make bench` run.

bench_tables.py RESULTS_DIR

Reads the Google Benchmark JSON files RESULTS_DIR/PROGRAM.json that scripts/bench.sh writes
(each case repeated, repetitions interleaved) and writes RESULTS_DIR/sections/NAME.md, one per
section: lookups, raycast, scene, gl, packing, load, convert, grammar, winding. A value is the
median of a case's repetitions; "spread" is (max - min) / median over them. A ratio is taken
between medians of the same run. scripts/bench_report.py puts the sections into the report.
"""
import json
import os
import statistics
import sys


class Results:
    def __init__(self, path):
        with open(path) as f:
            data = json.load(f)
        self.runs = {}
        self.labels = {}
        for b in data.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration":
                continue
            name = b.get("run_name", b["name"])
            self.runs.setdefault(name, []).append(b)
            if b.get("label"):
                self.labels[name] = b["label"]

    def has(self, name):
        return name in self.runs

    def values(self, name, metric):
        return [b[metric] for b in self.runs[name] if metric in b]

    def median(self, name, metric="real_time"):
        return statistics.median(self.values(name, metric))

    def spread(self, name, metric="real_time"):
        v = self.values(name, metric)
        return (max(v) - min(v)) / statistics.median(v) if len(v) > 1 and statistics.median(v) else 0.0


def pct(x):
    return f"{100 * x:.1f} %"


def lookups(r):
    sizes = [4, 8, 16, 32, 64]
    methods = ["native", "heuristic", "exact", "binary"]
    out = ["ns per lookup (`per_lookup`), median of the repetitions:\n",
           "| method | " + " | ".join(f"n = {n}" for n in sizes) + " | spread |",
           "|---|" + "---|" * (len(sizes) + 1)]
    for m in methods:
        cells = [f"{1e9 * r.median(f'BM_Lookup/{m}/{n}', 'per_lookup'):.2f}" for n in sizes]
        spread = max(r.spread(f"BM_Lookup/{m}/{n}", "per_lookup") for n in sizes)
        out.append(f"| {m} | " + " | ".join(cells) + f" | {pct(spread)} |")
    out += ["", "| ratio | " + " | ".join(f"n = {n}" for n in sizes) + " | target |",
            "|---|" + "---|" * (len(sizes) + 1)]
    targets = {"heuristic": "at most 1.3", "exact": "at most 1.6", "binary": "(paper: 16 at 32 x 32)"}
    for m in methods[1:]:
        cells = [f"{r.median(f'BM_Lookup/{m}/{n}', 'per_lookup') / r.median(f'BM_Lookup/native/{n}', 'per_lookup'):.2f}"
                 for n in sizes]
        out.append(f"| {m} / native | " + " | ".join(cells) + f" | {targets[m]} |")
    wrong = [100 * r.median(f"BM_Lookup/heuristic/{n}", "wrong_cells") for n in sizes]
    out.append(f"\nHeuristic answers that are the neighbour of the exact cell (`wrong_cells`): "
               f"{min(wrong):.3f} to {max(wrong):.3f} % of per-axis lookups.")
    return out


EMBREE_MODES = (("embree", "1"), ("embree_packet8", "8"), ("embree_packet16", "16"), ("embree_stream", "stream"))


def raycast(r):
    out = ["1280 x 720, one thread for every renderer. Embree traces the mesh exported from the same HNI one ray "
           "at a time (`rtcIntersect1`, column 1), in packets of 8 and 16 (`rtcIntersect8/16` on 4 x 2 and 4 x 4 "
           "pixels) and as a coherent stream of each 16 x 16 tile (`rtcIntersect1M`); the peer is the fastest "
           "of the four. The default view is the camera `nut render` fits; the close-up moves along the same "
           "line until the building covers the screen (the paper's Table 5), and gives the share it covers.\n",
           "NUT is measured one ray at a time with each lookup, and with the exact lookup in packets "
           "(`HniRayCaster::traceMany`, SIMD lanes through Google Highway).\n",
           "| building | view | Embree 1, Mrays/s | 8 | 16 | stream | NUT heuristic | NUT exact | NUT packets "
           "| NUT best / Embree best | spread |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    worst = None
    for sample in ("facade", "building", "solids", "house", "residential", "highrise"):
        for view in ("", "close/"):
            names = {k: f"Render/{k}/{view}{sample}/real_time"
                     for k in [m for m, _ in EMBREE_MODES] + ["nut_heuristic", "nut_exact", "nut_packets"]}
            if not all(r.has(n) for n in names.values()):
                continue
            rays = {k: r.median(n, "items_per_second") / 1e6 for k, n in names.items()}
            spread = max(r.spread(n, "items_per_second") for n in names.values())
            best_embree = max(rays[m] for m, _ in EMBREE_MODES)
            ratio = max(rays["nut_heuristic"], rays["nut_exact"], rays["nut_packets"]) / best_embree
            worst = ratio if worst is None else min(worst, ratio)
            label = "default"
            if view:
                coverage = r.median(names["embree"], "coverage_pct")
                label = f"close-up ({coverage:.0f} % covered)"
            cells = " | ".join(f"{rays[m]:.2f}" for m, _ in EMBREE_MODES)
            out.append(f"| {sample} | {label} | {cells} | {rays['nut_heuristic']:.2f} | {rays['nut_exact']:.2f} "
                       f"| {rays['nut_packets']:.2f} | {ratio:.2f} | {pct(spread)} |")
    out.append(f"\nTarget (issue 37): NUT at least 1.5 times the fastest Embree path on every building. "
               f"Lowest ratio in this run: {worst:.2f}.")
    return out


def planecells(r):
    base = "Render/district/{}/real_time"
    rows = [("NUT, boxes and wedges + complementary mesh", "nut_boxes_wedges_mesh"),
            ("NUT, plane cells + complementary mesh", "nut_plane_cells")]
    rows += [(f"Embree {label} on the source mesh", f"{mode}_source") for mode, label in EMBREE_MODES]
    if not all(r.has(base.format(key)) for _, key in rows):
        return ["Not run."]
    out = ["| renderer | ms per frame | Mrays/s | complementary triangles | plane cells | spread |",
           "|---|---|---|---|---|---|"]
    for label, key in rows:
        name = base.format(key)
        mesh = r.median(name, "complement_triangles") if key.startswith("nut") else r.median(name, "triangles")
        cells = f"{r.median(name, 'plane_cells'):.0f}" if key.startswith("nut") else ""
        triangles = f"{mesh:.0f}" if key.startswith("nut") else f"{mesh:.0f} (the source)"
        out.append(f"| {label} | {r.median(name):.1f} | {r.median(name, 'items_per_second') / 1e6:.2f} "
                   f"| {triangles} | {cells} | {pct(r.spread(name, 'items_per_second'))} |")
    best = max(r.median(base.format(f"{m}_source"), "items_per_second") for m, _ in EMBREE_MODES)
    planes = r.median(base.format("nut_plane_cells"), "items_per_second")
    boxes = r.median(base.format("nut_boxes_wedges_mesh"), "items_per_second")
    out.append(f"\nPlane cells / boxes and wedges: {planes / boxes:.2f}; plane cells / fastest Embree: "
               f"{planes / best:.2f}.")
    far = [("full detail", "far_complements_full"), ("levels the camera picks", "far_complements_levels")]
    if all(r.has(base.format(key)) for _, key in far):
        out += ["", "From four times as far, the default conversion's complements at full detail and at their levels "
                "of detail (`converter/mesh_lod.hpp`, picked as `nut render --lod auto` picks them):\n",
                "| complements | triangles drawn | ms | Mrays/s | pixels differing from full detail (> 8/255) |",
                "|---|---|---|---|---|"]
        for label, key in far:
            name = base.format(key)
            out.append(f"| {label} | {r.median(name, 'complement_triangles'):,.0f} | {r.median(name):.1f} "
                       f"| {r.median(name, 'items_per_second') / 1e6:.2f} | {r.median(name, 'differing_pct'):.4f} % |")
    return out


def glplanecells(r):
    rows = [("GLSL caster, boxes and wedges + complementary mesh", "glDistrict/district_boxes_wedges_mesh"),
            ("GLSL caster, plane cells + complementary mesh", "glDistrict/district_plane_cells"),
            ("GL raster of the source mesh", "glDistrictSource/district_source_raster")]
    out = ["| renderer | back-end | GL renderer | ms per frame | Mrays/s | spread |", "|---|---|---|---|---|---|"]
    for backend in ("osmesa", "egl"):
        for label, prefix in rows:
            name = f"{prefix}/{backend}/real_time"
            if not r.has(name):
                out.append(f"| {label} | {backend} | not run | | | |")
                continue
            out.append(f"| {label} | {backend} | {r.labels.get(name, '—')} | {r.median(name):.2f} "
                       f"| {r.median(name, 'items_per_second') / 1e6:.2f} | {pct(r.spread(name, 'items_per_second'))} |")
    return out


def scene(r):
    out = ["| view | ground grid, ms | Mrays/s | every HNI, ms | Mrays/s | every HNI / ground grid |",
           "|---|---|---|---|---|---|"]
    for view in ("above", "street"):
        grid, every = f"City1600/ground_grid/{view}/real_time", f"City1600/every_hni/{view}/real_time"
        out.append(f"| {view} | {r.median(grid):.1f} | {r.median(grid, 'items_per_second') / 1e6:.2f} "
                   f"| {r.median(every):.0f} | {r.median(every, 'items_per_second') / 1e6:.2f} "
                   f"| {r.median(every) / r.median(grid):.0f}x |")
    return out


def gl(r):
    rows = [("GLSL ray caster, heuristic lookup, OSMesa", "glFrame/gl_raycast/osmesa/real_time"),
            ("GLSL ray caster, exact lookup, OSMesa", "glFrame/gl_raycast_exact/osmesa/real_time"),
            ("GLSL ray caster, heuristic lookup, EGL", "glFrame/gl_raycast/egl/real_time"),
            ("GLSL ray caster, exact lookup, EGL", "glFrame/gl_raycast_exact/egl/real_time"),
            ("CPU ray caster (all cores)", "cpu_raycast/real_time"),
            ("GL mesh raster, OSMesa", "glFrame/gl_mesh_raster/osmesa/real_time"),
            ("GL mesh raster, EGL", "glFrame/gl_mesh_raster/egl/real_time"),
            ("Embree on the exported mesh (all cores)", "embree_mesh/real_time")]
    cpu = r.median("cpu_raycast/real_time")
    out = ["| renderer | GL renderer | ms per frame | Mrays/s | CPU caster's time / this |", "|---|---|---|---|---|"]
    for label, name in rows:
        if not r.has(name):
            out.append(f"| {label} | not run | | | |")
            continue
        out.append(f"| {label} | {r.labels.get(name, '—')} | {r.median(name):.1f} "
                   f"| {r.median(name, 'items_per_second') / 1e6:.2f} | {cpu / r.median(name):.2f} |")
    gpu = any("llvmpipe" not in r.labels.get(n, "llvmpipe") for _, n in rows)
    out.append("\nGPU columns: " + ("the EGL rows ran on the GPU named." if gpu else
                                    "none in this run. EGL found no GPU and fell back to llvmpipe."))
    return out


def packing(r):
    out = ["| packer | HNIs | ms | waste (mean) | waste (max) |", "|---|---|---|---|---|"]
    names = [("MaxRects best-area-fit, online width search", "BM_MaxRectsOnlineBAF"),
             ("MaxRects best-area-fit, global batch", "BM_MaxRectsGlobalBAF"),
             ("stb_rect_pack skyline, bottom-left", "BM_StbSkylineBL"),
             ("stb_rect_pack skyline, best-fit", "BM_StbSkylineBF")]
    for label, family in names:
        for n in (40, 100, 200):
            name = f"{family}/{n}"
            if r.has(name):
                out.append(f"| {label} | {n} | {r.median(name):.2f} | {r.median(name, 'waste_pct'):.2f} % "
                           f"| {r.median(name, 'waste_max_pct'):.2f} % |")
    out += ["", "In an atlas: the 2,116 HNIs of a city placed one at a time, in streaming order, into 2048 x 2048 "
            "pages (`bench/data/city_hni_sizes.txt`):\n",
            "| packer | ms | HNIs/s | pages | waste | spread |", "|---|---|---|---|---|---|"]
    for label, name in [("MaxRects bottom-left (the viewer's)", "BM_AtlasMaxRectsBL"),
                        ("MaxRects best-area-fit", "BM_AtlasMaxRectsBAF"),
                        ("stb_rect_pack skyline, bottom-left", "BM_AtlasStbSkylineBL"),
                        ("stb_rect_pack skyline, best-fit", "BM_AtlasStbSkylineBF")]:
        if r.has(name):
            out.append(f"| {label} | {r.median(name):.2f} | {r.median(name, 'items_per_second') / 1e3:,.0f} k "
                       f"| {r.median(name, 'pages'):.0f} | {r.median(name, 'waste_pct'):.1f} % | {pct(r.spread(name))} |")
    return out


def load(r):
    stages = ["read_png", "validate", "decode", "content_bounds", "export_coarse_mesh", "prepare_caster"]
    out = ["ms per stage:\n", "| sample | " + " | ".join(stages) + " |", "|---|" + "---|" * len(stages)]
    for sample in ("building", "facade", "solids"):
        out.append(f"| {sample} | " + " | ".join(f"{r.median(f'Load/{s}/{sample}'):.3f}" for s in stages) + " |")
    return out


def convert(r):
    out = ["| sample | triangles | 1 thread, ms | triangles/s | all cores, ms | triangles/s |", "|---|---|---|---|---|---|"]
    for sample in ("highrise", "street", "residential", "house", "carpark"):
        one, all_ = f"convert/{sample}/1/real_time", f"convert/{sample}/0/real_time"
        if r.has(one):
            out.append(f"| {sample} | {r.median(one, 'triangles'):,.0f} | {r.median(one):.0f} "
                       f"| {r.median(one, 'items_per_second') / 1e3:.0f} k | {r.median(all_):.0f} "
                       f"| {r.median(all_, 'items_per_second') / 1e3:.0f} k |")
    out += ["", "Time, size and fidelity against `--tolerance` (`convertAtTolerance`):\n",
            "| sample | tolerance (mm) | ms | HNI bytes | pixels within 8/255 of the source |", "|---|---|---|---|---|"]
    for sample in ("highrise", "street", "residential", "house", "carpark"):
        for mm in (5, 10, 20, 50):
            name = f"convertAtTolerance/{sample}/{mm}/real_time"
            if r.has(name):
                out.append(f"| {sample} | {mm} | {r.median(name):.0f} | {r.median(name, 'hni_bytes'):,.0f} "
                           f"| {r.median(name, 'within_8_pct'):.2f} % |")
    for label, name in (("Reading the high-rise's OBJ", "readObj/highrise/real_time"),
                        ("Encoding its HNI (Zopfli)", "encodeHni/highrise/real_time")):
        if r.has(name):
            out.append(f"\n{label}: {r.median(name):.0f} ms.")
    return out


def grammar(r):
    out = ["| step | sample | µs | per second | PNG bytes |", "|---|---|---|---|---|"]
    for name in sorted(r.runs):
        step, sample = name.split("/")[:2]
        png = r.median(name, "png_bytes") if r.values(name, "png_bytes") else None
        out.append(f"| {step.replace('BM_', '')} | {sample} | {r.median(name):.0f} "
                   f"| {r.median(name, 'items_per_second'):.0f} | {'' if png is None else f'{png:,.0f}'} |")
    return out


def winding(r):
    out = ["| case | triangles | µs per query | mean error | max error | sign flips |", "|---|---|---|---|---|---|"]
    for name in sorted(r.runs):
        if name.startswith("query/"):
            out.append(f"| {name} | {r.median(name, 'triangles'):,.0f} | {1e6 / r.median(name, 'items_per_second'):.2f} "
                       f"| {r.median(name, 'mean_error'):.2g} | {r.median(name, 'max_error'):.2g} "
                       f"| {r.median(name, 'flips'):.0f} |")
    for name in sorted(r.runs):
        if name.startswith("build/"):
            out.append(f"\nBuilding the tree for {name.split('/')[1]}: {r.median(name):.1f} ms.")
    return out


SECTIONS = {
    "lookups": ("lookup_bench", lookups),
    "raycast": ("render_bench", raycast),
    "planecells": ("render_bench", planecells),
    "scene": ("scene_bench", scene),
    "gl": ("gl_bench", gl),
    "glplanecells": ("gl_bench", glplanecells),
    "packing": ("packer_bench", packing),
    "load": ("load_bench", load),
    "convert": ("convert_bench", convert),
    "grammar": ("grammar_bench", grammar),
    "winding": ("winding_bench", winding),
}


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    results = sys.argv[1]
    os.makedirs(os.path.join(results, "sections"), exist_ok=True)
    for section, (program, table) in SECTIONS.items():
        path = os.path.join(results, program + ".json")
        if not os.path.exists(path):
            sys.exit(f"bench_tables: {path} is missing")
        with open(os.path.join(results, "sections", section + ".md"), "w") as f:
            f.write("\n".join(table(Results(path))) + "\n")
    print(f"bench_tables: {len(SECTIONS)} sections in {results}/sections", file=sys.stderr)


if __name__ == "__main__":
    main()
