#!/usr/bin/env python3
"""Checks that every object of a Wavefront OBJ is a closed, consistently oriented 2-manifold.

check-closed-obj.py FILE.obj [--apart] [--quiet]

Reads `v` and `f` lines (corners as v, v/vt, v//vn or v/vt/vn; negative indices count back from
the latest vertex) and splits the faces into objects as nut's OBJ reader does: at `o` lines when
the file has any, else at `g` lines; a name seen again continues its object, and faces before the
first name belong to an object named after the file. Vertices at identical positions are welded.
An object passes when every directed edge (a, b) of its faces occurs exactly once and (b, a)
exactly once (closed, no T-junctions, consistently oriented), the faces round each vertex form one
fan (no two shells meeting at a vertex), no face has two corners at one position, and its signed
volume is positive (faces outward). Polygons count as n - 2 triangles.

Prints one line per object to stdout (triangles, shells, volume, pass or the reason) and a
summary. --apart also checks that the objects' horizontal bounding circles (centred on the
object's x/z bounding box, reaching its farthest vertex) are pairwise disjoint. --quiet prints
only the summary.

Exit status 0 when every object passes; 1 when one does not, with one line on stderr per failing
object, `error: FILE: OBJECT: REASON`; 2 when the file cannot be read or parsed.

Example:
  scripts/lod2-district.py --seed 7 --buildings 24 -o district.obj
  scripts/check-closed-obj.py district.obj --apart
"""
import argparse
import math
import os
import sys


class ParseError(Exception):
    pass


def read_obj(path):
    """[(name, faces)] in order of first appearance; faces are lists of (x, y, z) position tuples."""
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    has_o = any(len(l) >= 2 and l[0] == "o" and l[1] in " \t" for l in lines)
    split_key = "o" if has_o else "g"
    stem = os.path.splitext(os.path.basename(path))[0]
    positions = []
    objects = {stem: []}
    order = [stem]
    current = stem
    for number, line in enumerate(lines, 1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        key = parts[0]
        if key == "v":
            try:
                positions.append(tuple(float(x) for x in parts[1:4]))
            except ValueError:
                raise ParseError(f"{path}:{number}: a vertex coordinate is not a number")
            if len(positions[-1]) != 3 or not all(math.isfinite(c) for c in positions[-1]):
                raise ParseError(f"{path}:{number}: a vertex needs three finite coordinates")
        elif key == "f":
            corners = []
            for token in parts[1:]:
                try:
                    i = int(token.split("/")[0])
                except ValueError:
                    raise ParseError(f"{path}:{number}: face corner '{token}' is not an index")
                j = i - 1 if i > 0 else len(positions) + i
                if i == 0 or not 0 <= j < len(positions):
                    raise ParseError(f"{path}:{number}: face index {i} out of range ({len(positions)} vertices)")
                corners.append(positions[j])
            if len(corners) < 3:
                raise ParseError(f"{path}:{number}: a face needs at least three corners")
            objects[current].append((number, corners))
        elif key == split_key:
            name = " ".join(parts[1:]) or f"{stem}_{len(order)}"
            if name not in objects:
                objects[name] = []
                order.append(name)
            current = name
    return [(name, objects[name]) for name in order if objects[name]]


def check_object(faces):
    """(triangles, shells, volume, reason or None) of one object's faces."""
    ids = {}
    polys = []
    for number, corners in faces:
        polys.append((number, [ids.setdefault(p, len(ids)) for p in corners]))
    points = [None] * len(ids)
    for p, i in ids.items():
        points[i] = p
    origin = points[0]
    triangles = sum(len(f) - 2 for _, f in polys)

    volume = 0.0
    for _, f in polys:
        a = [points[f[0]][k] - origin[k] for k in range(3)]
        for t in range(1, len(f) - 1):
            b = [points[f[t]][k] - origin[k] for k in range(3)]
            c = [points[f[t + 1]][k] - origin[k] for k in range(3)]
            volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2])
                       + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0

    def at(i):
        return "(" + ", ".join(f"{c:g}" for c in points[i]) + ")"

    parent = list(range(len(points)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for _, f in polys:
        for a, b in zip(f, f[1:]):
            ra, rb = find(a), find(b)
            if ra != rb:
                parent[ra] = rb
    shells = len({find(i) for i in range(len(points))})

    edges = {}
    corners_at = {}
    for number, f in polys:
        n = len(f)
        if len(set(f)) != n:
            return triangles, shells, volume, f"line {number}: a face has two corners at one position"
        for k in range(n):
            a, b = f[k], f[(k + 1) % n]
            edges[(a, b)] = edges.get((a, b), 0) + 1
            corners_at.setdefault(b, []).append((a, f[(k + 2) % n]))
    for (a, b), count in sorted(edges.items()):
        back = edges.get((b, a), 0)
        if count != 1 or back != 1:
            what = ("open" if count + back == 1 else
                    "inconsistently oriented" if count + back == 2 else "non-manifold")
            return triangles, shells, volume, (f"not closed: edge {at(a)}-{at(b)} is {what} "
                                               f"(faces along it {count} one way, {back} the other)")
    for v, fan in corners_at.items():
        following = {prev: nxt for prev, nxt in fan}
        start = fan[0][0]
        seen, cur = 0, start
        while True:
            cur = following[cur]
            seen += 1
            if cur == start or seen > len(fan):
                break
        if seen != len(fan):
            return triangles, shells, volume, f"non-manifold vertex {at(v)}: its faces form more than one fan"

    if not volume > 0:
        return triangles, shells, volume, f"volume {volume:.6g} m3 is not positive (faces point inwards)"
    return triangles, shells, volume, None


def bounding_circle(faces):
    pts = {p for _, corners in faces for p in corners}
    xs = [p[0] for p in pts]
    zs = [p[2] for p in pts]
    cx, cz = (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2
    return cx, cz, max(math.hypot(p[0] - cx, p[2] - cz) for p in pts)


def main():
    ap = argparse.ArgumentParser(
        description=__doc__.split("\nExample:")[0],
        epilog="example:\n  scripts/lod2-district.py --seed 7 --buildings 24 -o district.obj\n"
               "  scripts/check-closed-obj.py district.obj --apart",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("obj", metavar="FILE.obj")
    ap.add_argument("--apart", action="store_true",
                    help="also require the objects' horizontal bounding circles to be disjoint")
    ap.add_argument("--quiet", action="store_true", help="print only the summary")
    args = ap.parse_args()
    try:
        objects = read_obj(args.obj)
    except OSError as e:
        print(f"error: {args.obj}: {e.strerror or e}", file=sys.stderr)
        return 2
    except ParseError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if not objects:
        print(f"error: {args.obj}: no faces", file=sys.stderr)
        return 2

    failures = []
    total = 0
    for name, faces in objects:
        triangles, shells, volume, reason = check_object(faces)
        total += triangles
        if reason:
            failures.append(f"{name}: {reason}")
        if not args.quiet:
            state = f"FAIL: {reason}" if reason else "closed, oriented, volume positive"
            print(f"{name}: {triangles:,} triangle{'s' if triangles != 1 else ''}, "
                  f"{shells} shell{'s' if shells != 1 else ''}, volume {volume:,.3f} m3: {state}")
    if args.apart:
        circles = [(name, bounding_circle(faces)) for name, faces in objects]
        cells = {}
        size = 2 * max(c[2] for _, c in circles) or 1.0
        for k, (_, (x, z, _)) in enumerate(circles):
            cells.setdefault((math.floor(x / size), math.floor(z / size)), []).append(k)
        for k, (name, (x, z, r)) in enumerate(circles):
            gx, gz = math.floor(x / size), math.floor(z / size)
            for dx in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for m in cells.get((gx + dx, gz + dz), []):
                        if m <= k:
                            continue
                        other, (x2, z2, r2) = circles[m]
                        gap = math.hypot(x2 - x, z2 - z) - r - r2
                        if gap <= 0:
                            failures.append(f"{name}: its bounding circle overlaps {other}'s by {-gap:.3f} m")
    for line in failures:
        print(f"error: {args.obj}: {line}", file=sys.stderr)
    verdict = "all closed, consistently oriented, positive volume" + (", apart" if args.apart else "")
    print(f"{args.obj}: {len(objects):,} object{'s' if len(objects) != 1 else ''}, {total:,} triangles: "
          + (f"{len(failures)} failure{'s' if len(failures) != 1 else ''}" if failures else verdict))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
