#!/usr/bin/env python3
"""Writes a deterministic district of LoD2-style buildings as Wavefront OBJ + MTL.

lod2-district.py [--seed N] [--buildings N] [--street M] [--detail] -o DISTRICT.obj

Each building is one `o building_N` object (N from 1), y up, metres: a closed, consistently
outward-oriented triangle mesh (every edge shared by exactly two triangles running it opposite
ways; where a roof edge meets a wall the vertices are shared, so no T-junctions), standing on
y = 0 with walls 3-15 m high. Its footprint is one of five families, with these roofs:

  rectangle       8-25 x 6-25 m
                  flat, gable (ridge along the longer side), gable at any ridge direction,
                  hip, mansard, shed, pyramid
  parallelogram   sides 10-24 m and 6-16 m (1 m shorter at least), corners 55-78 degrees
                  flat, gable (ridge along the longer sides), hip, mansard, shed
  trapezoid       base 10-25 m, top 35-85 % of it, 6-18 m deep, corners 35 degrees or more
                  flat, shed, pyramid, gable at any ridge direction
  convex polygon  5 or 6 corners on an ellipse of semi-axes 4-12 m, edges 2.5 m or more,
                  corners 165 degrees or less
                  flat, shed, pyramid, gable at any ridge direction
  L-shape         12-25 x 10-22 m, arms 6 and 5 m wide or more, notch 4 m or more
                  flat, shed

Pitches are drawn from 15-50 degrees (a roof rises at most 12 m: a steeper draw is lowered to
that, not below 15 degrees). A gable along a side has its ridge on the footprint's midline and
gable walls ending in a triangle; a gable at any direction has its ridge through the centroid
(0.5 m or more from every corner), so its eaves slope and its walls' tops follow the roof. A hip's
ridge is parallel to the longer sides, half the shorter side in from each end (equal pitches: the
straight skeleton), shortened to keep 1 m when the sides are almost equal. A mansard's lower
pitch is 55-75 degrees, rising 1.5-3.5 m, under a hip of 15-30 degrees or a flat top. A shed
slopes towards a random direction. A pyramid's apex stands over the centroid at tan(pitch) times
the mean distance to the walls, so its faces' slopes spread about the pitch.

Buildings are turned by a random yaw and laid out on a grid with streets (--street, default
10 m) between them: each building's horizontal bounding circle (centred on its x/z bounding box)
lies inside its cell less half a street, so no two overlap. --detail adds to about half of the
buildings an annex: a small separate closed shell (a box with a flat or shed roof) standing
apart from the main shell (touching nothing) in the same object; the main buildings are the
same with and without it.

The MTL beside the OBJ (same name, .mtl) has the materials wall, roof_tile, roof_slate and
roof_flat. Both files are written to temporary files in the output's folder and renamed into
place. The same options give the same bytes. Progress and a summary go to stderr.

Example:
  scripts/lod2-district.py --seed 7 --buildings 24 -o district.obj
  scripts/check-closed-obj.py district.obj --apart
"""
import argparse
import math
import os
import random
import sys
import tempfile

MATERIALS = {
    "wall": (0.86, 0.82, 0.74),
    "roof_tile": (0.62, 0.27, 0.18),
    "roof_slate": (0.30, 0.32, 0.36),
    "roof_flat": (0.55, 0.55, 0.53),
}
MAX_RISE = 12.0  # metres: a steeper pitch draw is lowered to this rise, not below 15 degrees


class Mesh:
    """Vertices (x, y, z) and planar polygon faces (material, vertex indices, outward CCW)."""

    def __init__(self):
        self.verts = []
        self.faces = []

    def add(self, u, v, y):
        # Footprint (u, v) is counter-clockwise seen from above with x = u, z = -v: y up,
        # right-handed, so a counter-clockwise footprint's top face points up.
        self.verts.append((u, y, -v))
        return len(self.verts) - 1

    def face(self, material, idx):
        self.faces.append((material, list(idx)))

    def merge(self, other):
        base = len(self.verts)
        self.verts.extend(other.verts)
        self.faces.extend((m, [i + base for i in f]) for m, f in other.faces)

    def transform(self, yaw, du=0.0, dv=0.0):
        """Turns about the vertical by yaw (counter-clockwise from above), then moves by (du, dv)."""
        c, s = math.cos(yaw), math.sin(yaw)
        out = []
        for x, y, z in self.verts:
            u, v = x, -z
            u, v = c * u - s * v + du, s * u + c * v + dv
            out.append((u, y, -v))
        self.verts = out


# --- 2D helpers -------------------------------------------------------------------------------

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def add2(a, b):
    return (a[0] + b[0], a[1] + b[1])


def mul(a, k):
    return (a[0] * k, a[1] * k)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def length(a):
    return math.hypot(a[0], a[1])


def unit(a):
    n = length(a)
    return (a[0] / n, a[1] / n)


def area(poly):
    return 0.5 * sum(cross(poly[i], poly[(i + 1) % len(poly)]) for i in range(len(poly)))


def centroid(poly):
    a = area(poly)
    cx = cy = 0.0
    for i in range(len(poly)):
        p, q = poly[i], poly[(i + 1) % len(poly)]
        w = cross(p, q)
        cx += (p[0] + q[0]) * w
        cy += (p[1] + q[1]) * w
    return (cx / (6 * a), cy / (6 * a))


def interior_angles(poly):
    """Interior angles in degrees of a counter-clockwise polygon (above 180 at reflex corners)."""
    n = len(poly)
    out = []
    for i in range(n):
        a, b, c = poly[i - 1], poly[i], poly[(i + 1) % n]
        d1, d2 = sub(a, b), sub(c, b)
        turn = math.degrees(math.atan2(cross(d2, d1), dot(d1, d2)))
        out.append(turn if turn > 0 else 360 + turn)
    return out


def is_convex(poly):
    n = len(poly)
    return all(cross(sub(poly[(i + 1) % n], poly[i]), sub(poly[(i + 2) % n], poly[(i + 1) % n])) > 1e-9
               for i in range(n))


def inset(poly, a):
    """A convex counter-clockwise polygon with every edge moved a inwards, or None when an edge vanishes."""
    n = len(poly)
    lines = []
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        d = unit(sub(q, p))
        lines.append((add2(p, mul((-d[1], d[0]), a)), d))
    out = []
    for i in range(n):
        (p1, d1), (p2, d2) = lines[i - 1], lines[i]
        t = cross(sub(p2, p1), d2) / cross(d1, d2)
        out.append(add2(p1, mul(d1, t)))
    for i in range(n):
        e_new, e_old = sub(out[(i + 1) % n], out[i]), sub(poly[(i + 1) % n], poly[i])
        if dot(e_new, e_old) <= 0 or length(e_new) < 1.0:
            return None
    return out


# --- footprints: counter-clockwise, centred on their area centroid ------------------------------

def recentre(poly):
    c = centroid(poly)
    return [sub(p, c) for p in poly]


def fp_rectangle(rng):
    long_side = rng.uniform(8, 25)
    short_side = rng.uniform(6, long_side)
    lx, sy = long_side / 2, short_side / 2
    return [(-lx, -sy), (lx, -sy), (lx, sy), (-lx, sy)]  # p0 -> p1 along the longer side


def fp_parallelogram(rng):
    long_side = rng.uniform(10, 24)
    slant = rng.uniform(6, min(long_side - 1, 16))
    angle = math.radians(rng.uniform(55, 78))
    if rng.random() < 0.5:
        angle = math.pi - angle
    p3 = (slant * math.cos(angle), slant * math.sin(angle))
    return recentre([(0.0, 0.0), (long_side, 0.0), (long_side + p3[0], p3[1]), p3])


def fp_trapezoid(rng):
    while True:
        bottom = rng.uniform(10, 25)
        top = bottom * rng.uniform(0.35, 0.85)
        depth = rng.uniform(6, 18)
        x0 = (bottom - top) / 2 + rng.uniform(-1, 1) * (bottom - top) * 0.6
        poly = [(0.0, 0.0), (bottom, 0.0), (x0 + top, depth), (x0, depth)]
        if min(interior_angles(poly)) >= 35:
            return recentre(poly)


def fp_convex(rng):
    while True:
        n = rng.choice((5, 6))
        rx, ry = rng.uniform(4, 12), rng.uniform(4, 12)
        turn = rng.uniform(0, 2 * math.pi)
        step = 2 * math.pi / n
        poly = []
        for i in range(n):
            t = i * step + rng.uniform(-0.3, 0.3) * step
            x, y = rx * math.cos(t), ry * math.sin(t)
            poly.append((x * math.cos(turn) - y * math.sin(turn), x * math.sin(turn) + y * math.cos(turn)))
        edges = [length(sub(poly[(i + 1) % n], poly[i])) for i in range(n)]
        if is_convex(poly) and max(interior_angles(poly)) <= 165 and min(edges) >= 2.5:
            return recentre(poly)


def fp_l_shape(rng):
    width, depth = rng.uniform(12, 25), rng.uniform(10, 22)
    arm_w, arm_d = rng.uniform(6, width - 4), rng.uniform(5, depth - 4)
    return recentre([(0.0, 0.0), (width, 0.0), (width, arm_d), (arm_w, arm_d), (arm_w, depth), (0.0, depth)])


FAMILIES = [  # (name, footprint, roof types with repeats as weights)
    ("rectangle", fp_rectangle, ["flat", "gable", "gable", "gable_any", "hip", "hip", "mansard", "shed", "pyramid"]),
    ("parallelogram", fp_parallelogram, ["flat", "gable", "gable", "hip", "hip", "mansard", "shed"]),
    ("trapezoid", fp_trapezoid, ["flat", "shed", "pyramid", "gable_any"]),
    ("convex", fp_convex, ["flat", "shed", "pyramid", "gable_any"]),
    ("l_shape", fp_l_shape, ["flat", "shed", "shed"]),
]
FAMILY_WEIGHTS = [4, 2, 2, 2, 2]


# --- roofs ----------------------------------------------------------------------------------

def pitch_for(rng, run, low=15.0, high=50.0):
    """A pitch in degrees drawn from [low, high], lowered so that rising over run stays within MAX_RISE."""
    p = rng.uniform(low, high)
    if run * math.tan(math.radians(p)) > MAX_RISE:
        p = max(low, math.degrees(math.atan(MAX_RISE / run)))
    return p


def walls(mesh, fp, tops, extra=None):
    """The ground face and the walls of a footprint whose top ring is tops (vertex indices).

    extra[i] lists the vertices on the top edge from corner i to corner i + 1 (a gable's peak),
    in that order, so the wall shares them with the roof."""
    extra = extra or {}
    n = len(fp)
    bottom = [mesh.add(u, v, 0.0) for u, v in fp]
    mesh.face("wall", reversed(bottom))
    for i in range(n):
        j = (i + 1) % n
        chain = [tops[i]] + extra.get(i, []) + [tops[j]]
        mesh.face("wall", [bottom[i], bottom[j]] + chain[::-1])


def roof_flat(mesh, fp, h, rng, material):
    tops = [mesh.add(u, v, h) for u, v in fp]
    mesh.face(material, tops)
    walls(mesh, fp, tops)
    return {}


def roof_shed(mesh, fp, h, rng, material):
    phi = rng.uniform(0, 2 * math.pi)
    d = (math.cos(phi), math.sin(phi))
    s = [dot(p, d) for p in fp]
    run = max(s) - min(s)
    pitch = pitch_for(rng, run)
    k = math.tan(math.radians(pitch))
    tops = [mesh.add(u, v, h + k * (si - min(s))) for (u, v), si in zip(fp, s)]
    mesh.face(material, tops)
    walls(mesh, fp, tops)
    return {"pitch": pitch, "towards": math.degrees(phi) % 360}


def gable(mesh, fp, h, pitch, centre, direction, material):
    """Two planes meeting at a ridge along direction through centre, over a convex footprint
    none of whose corners lies on the ridge line. The walls under the ridge end in a peak."""
    normal = (-direction[1], direction[0])
    s = [dot(sub(p, centre), normal) for p in fp]
    run = max(abs(x) for x in s)
    k = math.tan(math.radians(pitch))
    ridge_y = h + k * run
    tops = [mesh.add(u, v, h + k * (run - abs(si))) for (u, v), si in zip(fp, s)]
    n = len(fp)
    extra, ring = {}, []  # ring: (vertex, side) round the footprint, peaks included
    for i in range(n):
        j = (i + 1) % n
        ring.append((tops[i], 1 if s[i] > 0 else -1))
        if s[i] * s[j] < 0:
            p = add2(fp[i], mul(sub(fp[j], fp[i]), s[i] / (s[i] - s[j])))
            peak = mesh.add(p[0], p[1], ridge_y)
            extra[i] = [peak]
            ring.append((peak, 0))
    mesh.face(material, [v for v, side in ring if side >= 0])
    mesh.face(material, [v for v, side in ring if side <= 0])
    walls(mesh, fp, tops, extra)


def longest_first(fp):
    """fp rotated so that edge 0 is its longest (of a rectangle or parallelogram: a longer side)."""
    n = len(fp)
    i = max(range(n), key=lambda k: (length(sub(fp[(k + 1) % n], fp[k])), -k))
    return fp[i:] + fp[:i]


def roof_gable(mesh, fp, h, rng, material):
    fp = longest_first(fp)
    d = unit(sub(fp[1], fp[0]))
    half = abs(cross(d, sub(fp[3], fp[0]))) / 2
    pitch = pitch_for(rng, half)
    gable(mesh, fp, h, pitch, centroid(fp), d, material)
    return {"pitch": pitch, "ridge": math.degrees(math.atan2(d[1], d[0])) % 180}


def roof_gable_any(mesh, fp, h, rng, material):
    c = centroid(fp)
    for _ in range(100):
        phi = rng.uniform(0, math.pi)
        d = (math.cos(phi), math.sin(phi))
        normal = (-d[1], d[0])
        if min(abs(dot(sub(p, c), normal)) for p in fp) >= 0.5:
            break
    else:
        raise RuntimeError("no ridge direction keeps the corners 0.5 m off the ridge")
    run = max(abs(dot(sub(p, c), normal)) for p in fp)
    pitch = pitch_for(rng, run)
    gable(mesh, fp, h, pitch, c, d, material)
    return {"pitch": pitch, "ridge": math.degrees(phi)}


def hip_on(mesh, pts, ring, base_y, pitch, material):
    """A hip roof on a parallelogram pts whose corners are the vertices ring at height base_y."""
    i0 = max(range(4), key=lambda k: (length(sub(pts[(k + 1) % 4], pts[k])), -k))
    pts, ring = pts[i0:] + pts[:i0], ring[i0:] + ring[:i0]
    p0, p1, p2, p3 = pts
    long_side = length(sub(p1, p0))
    e = unit(sub(p1, p0))
    short_side = length(sub(p3, p0))
    half = abs(cross(e, sub(p3, p0))) / 2
    inset_by = min(short_side / 2, long_side / 2 - 0.5)
    r0 = add2(mul(add2(p0, p3), 0.5), mul(e, inset_by))
    r1 = sub(mul(add2(p1, p2), 0.5), mul(e, inset_by))
    ridge_y = base_y + math.tan(math.radians(pitch)) * half
    a, b = mesh.add(r0[0], r0[1], ridge_y), mesh.add(r1[0], r1[1], ridge_y)
    t0, t1, t2, t3 = ring
    mesh.face(material, [t0, t1, b, a])
    mesh.face(material, [t2, t3, a, b])
    mesh.face(material, [t1, t2, b])
    mesh.face(material, [t3, t0, a])
    return half


def roof_hip(mesh, fp, h, rng, material):
    tops = [mesh.add(u, v, h) for u, v in fp]
    p0, p1, _, p3 = longest_first(fp)
    half = abs(cross(unit(sub(p1, p0)), sub(p3, p0))) / 2
    pitch = pitch_for(rng, half)
    hip_on(mesh, fp, tops, h, pitch, material)
    walls(mesh, fp, tops)
    return {"pitch": pitch}


def roof_mansard(mesh, fp, h, rng, material):
    lower = rng.uniform(55, 75)
    for _ in range(100):
        rise = rng.uniform(1.5, 3.5)
        inner = inset(fp, rise / math.tan(math.radians(lower)))
        if inner is not None and min(length(sub(inner[(i + 1) % 4], inner[i])) for i in range(4)) >= 3:
            break
    else:
        raise RuntimeError("footprint too small for a mansard")
    tops = [mesh.add(u, v, h) for u, v in fp]
    ring = [mesh.add(u, v, h + rise) for u, v in inner]
    for i in range(4):
        j = (i + 1) % 4
        mesh.face(material, [tops[i], tops[j], ring[j], ring[i]])
    info = {"pitch": lower}
    if rng.random() < 0.6:
        upper = rng.uniform(15, 30)
        hip_on(mesh, inner, ring, h + rise, upper, material)
        info["upper_pitch"] = upper
    else:
        mesh.face(material, ring)
        info["upper"] = "flat"
    walls(mesh, fp, tops)
    return info


def roof_pyramid(mesh, fp, h, rng, material):
    c = centroid(fp)
    n = len(fp)
    runs = []
    for i in range(n):
        p, q = fp[i], fp[(i + 1) % n]
        runs.append(abs(cross(unit(sub(q, p)), sub(c, p))))
    run = sum(runs) / n  # the pitch is the mean of the faces': the apex rises tan(pitch) x run
    pitch = pitch_for(rng, run)
    tops = [mesh.add(u, v, h) for u, v in fp]
    apex = mesh.add(c[0], c[1], h + math.tan(math.radians(pitch)) * run)
    for i in range(n):
        mesh.face(material, [tops[i], tops[(i + 1) % n], apex])
    walls(mesh, fp, tops)
    return {"pitch": pitch}


ROOFS = {"flat": roof_flat, "shed": roof_shed, "gable": roof_gable, "gable_any": roof_gable_any,
         "hip": roof_hip, "mansard": roof_mansard, "pyramid": roof_pyramid}


# --- triangulation ---------------------------------------------------------------------------

def triangulate(points):
    """Ear clipping of a planar simple polygon in 3D: index triples in the polygon's winding."""
    n = len(points)
    if n == 3:
        return [(0, 1, 2)]
    nx = ny = nz = 0.0
    for i in range(n):
        (x1, y1, z1), (x2, y2, z2) = points[i], points[(i + 1) % n]
        nx += (y1 - y2) * (z1 + z2)
        ny += (z1 - z2) * (x1 + x2)
        nz += (x1 - x2) * (y1 + y2)
    axis = max(range(3), key=lambda k: abs((nx, ny, nz)[k]))
    keep = {0: (1, 2), 1: (2, 0), 2: (0, 1)}[axis]  # cyclic, so the 2D area has the normal's sign
    sign = 1.0 if (nx, ny, nz)[axis] > 0 else -1.0
    pts = [(p[keep[0]] * sign, p[keep[1]]) for p in points]  # mirrored when negative: now CCW
    left = list(range(n))
    out = []
    guard = 0
    while len(left) > 3:
        guard += 1
        if guard > 4 * n * n:
            raise RuntimeError("polygon could not be triangulated")
        m = len(left)
        for k in range(m):
            a, b, c = left[k - 1], left[k], left[(k + 1) % m]
            pa, pb, pc = pts[a], pts[b], pts[c]
            if cross(sub(pb, pa), sub(pc, pa)) <= 1e-12:
                continue
            if any(inside(pts[o], pa, pb, pc) for o in left if o not in (a, b, c)):
                continue
            out.append((a, b, c))
            left.pop(k)
            break
        else:
            raise RuntimeError("polygon has no ear")
    out.append(tuple(left))
    return out


def inside(p, a, b, c):
    eps = -1e-12
    return (cross(sub(b, a), sub(p, a)) >= eps and cross(sub(c, b), sub(p, b)) >= eps
            and cross(sub(a, c), sub(p, c)) >= eps)


# --- buildings and layout ----------------------------------------------------------------------

def make_building(rng):
    names = [f[0] for f in FAMILIES]
    family = rng.choices(names, weights=FAMILY_WEIGHTS)[0]
    _, footprint, roofs = FAMILIES[names.index(family)]
    fp = footprint(rng)
    roof = rng.choice(roofs)
    h = rng.uniform(3, 15)
    material = "roof_flat" if roof == "flat" else rng.choice(("roof_tile", "roof_slate"))
    mesh = Mesh()
    info = ROOFS[roof](mesh, fp, h, rng, material)
    return mesh, family, roof, h, info


def make_annex(rng, main):
    """A small box with a flat or shed roof, apart from the main shell, in the main's frame."""
    radius = max(math.hypot(x, z) for x, _, z in main.verts)
    fp = fp_rectangle_small(rng)
    annex = Mesh()
    if rng.random() < 0.5:
        roof_flat(annex, fp, rng.uniform(2.5, 3.5), rng, "roof_flat")
    else:
        roof_shed(annex, fp, rng.uniform(2.5, 3.5), rng, rng.choice(("roof_tile", "roof_slate")))
    half_diagonal = max(length(p) for p in fp)
    away = radius + rng.uniform(1.5, 3.0) + half_diagonal
    psi = rng.uniform(0, 2 * math.pi)
    annex.transform(rng.uniform(0, 2 * math.pi), away * math.cos(psi), away * math.sin(psi))
    return annex


def fp_rectangle_small(rng):
    a = rng.uniform(3, 6)
    b = rng.uniform(3, a)
    return [(-a / 2, -b / 2), (a / 2, -b / 2), (a / 2, b / 2), (-a / 2, b / 2)]


def bounding_circle(mesh):
    """Centre of the x/z bounding box and the distance from it to the farthest vertex."""
    xs = [p[0] for p in mesh.verts]
    zs = [p[2] for p in mesh.verts]
    cx, cz = (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2
    return cx, cz, max(math.hypot(x - cx, z - cz) for x, _, z in mesh.verts)


def generate(seed, count, street, detail):
    rng = random.Random(seed)
    buildings = []
    for i in range(count):
        mesh, family, roof, h, info = make_building(rng)
        if detail:
            drng = random.Random(f"{seed}:annex:{i}")
            if drng.random() < 0.5:
                mesh.merge(make_annex(drng, mesh))
                info = dict(info, annex=True)
        yaw = rng.uniform(0, 2 * math.pi)
        mesh.transform(yaw)
        info = dict(info, yaw=math.degrees(yaw))
        for key, period in (("ridge", 180), ("towards", 360)):
            if key in info:
                info[key] = (info[key] + info["yaw"]) % period
        buildings.append((mesh, family, roof, h, info))

    cols = max(1, math.ceil(math.sqrt(count)))
    rows = math.ceil(count / cols)
    circles = [bounding_circle(b[0]) for b in buildings]
    col_w = [0.0] * cols
    row_d = [0.0] * rows
    for i, (_, _, r) in enumerate(circles):
        col_w[i % cols] = max(col_w[i % cols], 2 * r + street)
        row_d[i // cols] = max(row_d[i // cols], 2 * r + street)
    col_x = [sum(col_w[:c]) + col_w[c] / 2 - sum(col_w) / 2 for c in range(cols)]
    row_z = [sum(row_d[:r]) + row_d[r] / 2 - sum(row_d) / 2 for r in range(rows)]
    for i, ((mesh, *_), (cx, cz, r)) in enumerate(zip(buildings, circles)):
        c, rr = i % cols, i // cols
        slack_x = (col_w[c] - street) / 2 - r
        slack_z = (row_d[rr] - street) / 2 - r
        tx = col_x[c] + rng.uniform(-slack_x, slack_x) - cx
        tz = row_z[rr] + rng.uniform(-slack_z, slack_z) - cz
        mesh.verts = [(x + tx, y, z + tz) for x, y, z in mesh.verts]
    return buildings, (sum(col_w), sum(row_d))


# --- output --------------------------------------------------------------------------------------

def num(x):
    s = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def write_atomic(path, text):
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp's 0600 would outlive the rename
        with os.fdopen(fd, "w", encoding="ascii", newline="\n") as f:
            f.write(text)
        return tmp
    except BaseException:
        os.unlink(tmp)
        raise


def render(buildings, args, mtl_name):
    lines = [f"# lod2-district.py --seed {args.seed} --buildings {args.buildings} --street {num(args.street)}"
             + (" --detail" if args.detail else ""),
             "# Units: metres. Axes: Y-up. One closed, outward-oriented triangle mesh per object.",
             "# Angles in degrees (pitch, upper_pitch; yaw, ridge, towards: from +x towards -z).",
             f"mtllib {mtl_name}"]
    base = 1
    triangles = 0
    for n, (mesh, family, roof, h, info) in enumerate(buildings, 1):
        extras = "".join(f", {k} {v:.1f}" if isinstance(v, float) else f", {k}" if v is True else f", {k} {v}"
                         for k, v in sorted(info.items()))
        lines.append(f"o building_{n}")
        lines.append(f"# {family}, {roof} roof, walls {h:.2f} m{extras}")
        lines.extend(f"v {num(x)} {num(y)} {num(z)}" for x, y, z in mesh.verts)
        for material in MATERIALS:
            faces = [f for m, f in mesh.faces if m == material]
            if not faces:
                continue
            lines.append(f"usemtl {material}")
            for f in faces:
                for a, b, c in triangulate([mesh.verts[i] for i in f]):
                    lines.append(f"f {f[a] + base} {f[b] + base} {f[c] + base}")
                    triangles += 1
        base += len(mesh.verts)
    return "\n".join(lines) + "\n", triangles


def main():
    ap = argparse.ArgumentParser(
        description=__doc__.split("\nExample:")[0],
        epilog="example:\n  scripts/lod2-district.py --seed 7 --buildings 24 -o district.obj\n"
               "  scripts/check-closed-obj.py district.obj --apart\n\n"
               "Footprints, roofs and layout are described in docs/CONVERTER.md (Generated LoD2 districts).",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=1, help="random seed (default 1): the same seed gives the same files")
    ap.add_argument("--buildings", type=int, default=24, help="number of buildings (default 24)")
    ap.add_argument("--street", type=float, default=10.0, help="street width between grid cells in metres (default 10)")
    ap.add_argument("--detail", action="store_true",
                    help="add an annex (a separate closed shell) to about half of the buildings")
    ap.add_argument("-o", "--output", required=True, help="the OBJ to write; the MTL goes beside it with .mtl")
    args = ap.parse_args()
    if args.buildings < 1:
        ap.error("--buildings must be at least 1")
    if not args.street > 0:
        ap.error("--street must be positive")

    stem, _ = os.path.splitext(args.output)
    mtl_path = stem + ".mtl"
    if os.path.abspath(mtl_path) == os.path.abspath(args.output):
        ap.error("the output must not end in .mtl")

    print(f"lod2-district: generating {args.buildings} buildings (seed {args.seed})", file=sys.stderr)
    buildings, (width, depth) = generate(args.seed, args.buildings, args.street, args.detail)
    obj_text, triangles = render(buildings, args, os.path.basename(mtl_path))
    mtl_text = "# lod2-district.py materials\n" + "".join(
        f"\nnewmtl {name}\nKd {r:.4f} {g:.4f} {b:.4f}\nd 1\n" for name, (r, g, b) in MATERIALS.items())

    tmps = []
    try:
        tmps.append((write_atomic(mtl_path, mtl_text), mtl_path))
        tmps.append((write_atomic(args.output, obj_text), args.output))
        for tmp, final in tmps:
            os.replace(tmp, final)
    except OSError as e:
        for tmp, _ in tmps:
            if os.path.exists(tmp):
                os.unlink(tmp)
        sys.exit(f"error: {args.output}: {e.strerror or e}")

    roofs = {}
    for b in buildings:
        roofs[b[2]] = roofs.get(b[2], 0) + 1
    annexes = sum(1 for b in buildings if b[4].get("annex"))
    print(f"lod2-district: {len(buildings):,} buildings, {triangles:,} triangles, {width:,.0f} x {depth:,.0f} m"
          + (f", {annexes:,} annexes" if args.detail else "") + f" -> {args.output}", file=sys.stderr)
    print("lod2-district: roofs " + ", ".join(f"{k} {v}" for k, v in sorted(roofs.items())), file=sys.stderr)


if __name__ == "__main__":
    main()
