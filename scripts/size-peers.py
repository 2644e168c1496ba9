#!/usr/bin/env python3
"""Size against peers (docs/BENCHMARKS.md, "Size vs peers"): NUT bytes against the mesh formats
a user would ship the same building in.

size-peers.py BUILD OUT [--quick]

For each input: the converted samples (samples/obj) and, when ../shared/data is there, the
meshes beside the project; the hand-built samples (samples/hni, whose mesh is `nut export-mesh`
of the HNI); three building grammars (`nut grammar --mesh`, the derivation's solid mesh). Each
mesh is packed as a user would ship it, with the peers' own tools:
  - binary glTF: `gltfpack -noq` (no quantisation, no compression);
  - `gltfpack -cc` (meshoptimizer's quantisation and compression), then `gzip -9`;
  - Draco: `draco_encoder -qp 14 -cl 10` (geometry only; 14 position bits, as gltfpack's default).
An OBJ of several objects is converted to a folder (one HNI per building, as `nut convert` does)
and packed with `gltfpack -kn` (one node per object). NUT is the HNI PNG (`nut convert`'s
default Zopfli encoding) plus its complementary mesh, if any, packed with `gltfpack -cc` and gzip.

Writes OUT/sizes.json and OUT/sizes.md (the report's section). --quick does one sample of each
kind (make bench-quick: the harness works). Needs gltfpack in .tools/ and draco_encoder
(scripts/install-deps.sh).
"""
import argparse
import glob
import gzip
import json
import os
import subprocess
import sys

SOURCE = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
GLTFPACK = os.path.join(SOURCE, ".tools", "node_modules", ".bin", "gltfpack")
DATA = os.path.normpath(os.path.join(SOURCE, "..", "shared", "data"))


def run(args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"size-peers: {' '.join(args)} failed:\n{r.stderr}")
    return r


def triangles(obj):
    count, objects = 0, set()
    with open(obj) as f:
        for line in f:
            if line.startswith("f "):
                count += len(line.split()) - 3
            elif line.startswith("o "):
                objects.add(line[2:].strip())
    return count, len(objects)


def gzipped(path):
    with open(path, "rb") as f:
        return len(gzip.compress(f.read(), 9))


def obj_bytes(obj):
    """The OBJ and the MTL files it names."""
    total = os.path.getsize(obj)
    with open(obj) as f:
        for line in f:
            if line.startswith("mtllib "):
                mtl = os.path.join(os.path.dirname(obj), line.split(None, 1)[1].strip())
                total += os.path.getsize(mtl) if os.path.exists(mtl) else 0
    return total


class Sizes:
    def __init__(self, build, out):
        self.nut, self.out = os.path.join(build, "cli", "nut"), out

    def peers(self, obj, name, several):
        base = os.path.join(self.out, name)
        keep = ["-kn"] if several else []
        run([GLTFPACK, "-i", obj, "-o", base + ".raw.glb", "-noq"] + keep)
        run([GLTFPACK, "-i", obj, "-o", base + ".glb", "-cc"] + keep)
        run(["draco_encoder", "-i", obj, "-o", base + ".drc", "-qp", "14", "-cl", "10"])
        tris, _ = triangles(obj)
        return {"triangles": tris, "obj_bytes": obj_bytes(obj), "glb_bytes": os.path.getsize(base + ".raw.glb"),
                "gltfpack_cc_bytes": os.path.getsize(base + ".glb"), "gltfpack_cc_gzip_bytes": gzipped(base + ".glb"),
                "draco_bytes": os.path.getsize(base + ".drc")}

    def packed_complement(self, obj, name, several):
        if not os.path.exists(obj) or triangles(obj)[0] == 0:
            return 0
        glb = os.path.join(self.out, name + ".rest.glb")
        run([GLTFPACK, "-i", obj, "-o", glb, "-cc"] + (["-kn"] if several else []))
        return gzipped(glb)

    def hni_raw(self, png):
        return json.loads(run([self.nut, "info", png, "--json"]).stdout)["bytes_raw"]

    def converted(self, obj, kind):
        name = os.path.splitext(os.path.basename(obj))[0]
        several = triangles(obj)[1] > 1
        row = dict(self.peers(obj, name, several), input=name, kind=kind)
        if several:
            folder = os.path.join(self.out, name)
            # OBJ complements, which gltfpack packs as one file below.
            run([self.nut, "convert", obj, "-o", folder + "/", "--quiet", "--complement-format", "obj"])
            pngs = sorted(glob.glob(folder + "/*.png"))
            rests = sorted(glob.glob(folder + "/*.obj"))
            merged = os.path.join(self.out, name + ".rest.obj")
            self.merge_objs(rests, merged)
            row.update(buildings=len(pngs), hni_raw_bytes=sum(self.hni_raw(p) for p in pngs),
                       hni_png_bytes=sum(os.path.getsize(p) for p in pngs),
                       complement_bytes=self.packed_complement(merged, name, True))
        else:
            png = os.path.join(self.out, name + ".png")
            rest = os.path.join(self.out, name + ".rest.obj")
            run([self.nut, "convert", obj, "-o", png, "--complement", rest, "--quiet"])
            row.update(buildings=1, hni_raw_bytes=self.hni_raw(png), hni_png_bytes=os.path.getsize(png),
                       complement_bytes=self.packed_complement(rest, name, False))
        return row

    @staticmethod
    def merge_objs(paths, merged):
        """The complementary meshes of a folder as one OBJ of several objects (no materials)."""
        offset = 0
        with open(merged, "w") as out:
            for path in paths:
                out.write(f"o {os.path.basename(path)}\n")
                count = 0
                with open(path) as f:
                    for line in f:
                        if line.startswith("v "):
                            out.write(line)
                            count += 1
                        elif line.startswith("f "):
                            out.write("f " + " ".join(str(int(v.split("/")[0]) + offset) for v in line.split()[1:]) + "\n")
                offset += count

    def exported(self, png, kind, obj=None, name=None):
        """An HNI (hand-built, or compiled from a grammar) against a mesh of the same building."""
        name = name or os.path.splitext(os.path.basename(png))[0]
        if obj is None:
            obj = os.path.join(self.out, name + ".export.obj")
            run([self.nut, "export-mesh", png, "-o", obj])
        return dict(self.peers(obj, name, False), input=name, kind=kind, buildings=1, hni_raw_bytes=self.hni_raw(png),
                    hni_png_bytes=os.path.getsize(png), complement_bytes=0)

    def grammar(self, grammar):
        name = os.path.splitext(os.path.basename(grammar))[0]
        png, obj = os.path.join(self.out, name + ".png"), os.path.join(self.out, name + ".obj")
        run([self.nut, "grammar", grammar, "-o", png, "--mesh", obj, "--quiet"])
        return self.exported(png, "grammar (solid mesh)", obj, name)


def markdown(rows):
    out = ["| input | kind | buildings | triangles | OBJ + MTL | binary glTF | gltfpack -cc | + gzip -9 | Draco "
           "| HNI raw | HNI PNG | + complement | NUT / (gltfpack -cc + gzip) |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        nut = r["hni_png_bytes"] + r["complement_bytes"]
        out.append(f"| {r['input']} | {r['kind']} | {r['buildings']} | {r['triangles']:,} | {r['obj_bytes']:,} "
                   f"| {r['glb_bytes']:,} | {r['gltfpack_cc_bytes']:,} | {r['gltfpack_cc_gzip_bytes']:,} "
                   f"| {r['draco_bytes']:,} | {r['hni_raw_bytes']:,} | {r['hni_png_bytes']:,} "
                   f"| {r['complement_bytes']:,} | {nut / r['gltfpack_cc_gzip_bytes']:.2f} |")
    smaller = sum(1 for r in rows if r["hni_png_bytes"] + r["complement_bytes"] < r["gltfpack_cc_gzip_bytes"])
    out.append(f"\nNUT (PNG and packed complement) is smaller than gltfpack -cc + gzip on {smaller} of {len(rows)} inputs.")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build")
    parser.add_argument("out")
    parser.add_argument("--quick", action="store_true")
    a = parser.parse_args()
    for tool in (GLTFPACK, "draco_encoder"):
        if subprocess.run(["sh", "-c", f"command -v {tool}"], capture_output=True).returncode != 0:
            sys.exit(f"size-peers: {tool} is missing (scripts/install-deps.sh installs it)")
    os.makedirs(a.out, exist_ok=True)
    s = Sizes(a.build, a.out)
    samples = ["house"] if a.quick else ["house", "carpark", "residential", "highrise"]
    rows = [s.converted(f"{SOURCE}/samples/obj/{n}.obj", "converted sample") for n in samples]
    if os.path.isdir(DATA) and not a.quick:
        rows += [s.converted(obj, "converted, shared data") for obj in sorted(glob.glob(DATA + "/*.obj"))]
    hand = ["building"] if a.quick else ["building", "facade", "solids"]
    rows += [s.exported(f"{SOURCE}/samples/hni/{n}.png", "hand-built sample (exported mesh)") for n in hand]
    grammars = ["pga_simple_house"] if a.quick else ["pga_simple_house", "pga_complex_house", "marvie_building"]
    rows += [s.grammar(f"{SOURCE}/samples/grammars/{n}.grammar") for n in grammars]
    with open(os.path.join(a.out, "sizes.json"), "w") as f:
        json.dump(rows, f, indent=1)
    with open(os.path.join(a.out, "sizes.md"), "w") as f:
        f.write(markdown(rows))
    print(f"size-peers: {len(rows)} inputs; {a.out}/sizes.md", file=sys.stderr)


if __name__ == "__main__":
    main()
