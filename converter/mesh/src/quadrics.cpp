// Solid conversion, quarter cylinders: faces on a quarter of a cylinder parallel to an axis (round
// building corners, coves, rods) are found, given the boundaries that make each quarter arc fill
// one cell's cross-section, and those cells become QuarterCylinder or InverseQuarterCylinder
// solids (converter/solid.hpp, steps 2 and 3); a piece whose cross-section other boundaries cut
// becomes a sub-block of its own that the cells of its box redirect to. A cell stretches the unit
// shape, so an elliptic quarter fits as well as a circular one. Sphere octants (quarters of domes,
// equator to pole) are found, bounded and fitted the same way, as SphereOctant or
// InverseSphereOctant cells or sub-blocks; so are corner slopes (corner_slopes.cpp finds them), as
// Pyramid or InversePyramid cells or sub-blocks.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "solid_builder.hpp"
#include "union_find.hpp"

namespace nut::converter::solid {

namespace {

// Lateral area of a quarter of an elliptic cylinder of unit height (Ramanujan's perimeter).
double quarterArc(double a, double b) {
  return 0.25 * std::numbers::pi * (3 * (a + b) - std::sqrt((3 * a + b) * (a + 3 * b)));
}

// Surface area of an octant of an ellipsoid (Thomsen's formula, within 1.1 %; exact for a sphere).
double octantArea(double a, double b, double c) {
  constexpr double p = 1.6075;
  const double mean = (std::pow(a * b, p) + std::pow(a * c, p) + std::pow(b * c, p)) / 3;
  return 0.5 * std::numbers::pi * std::pow(mean, 1 / p);
}

// Polygon faces are chords of the arc: their area falls short of the arc's by (1 - sin x / x) for
// a segment of angle 2x, under 0.5 % from 8 segments a quarter on. Less than this share of the
// arc's area means the faces do not cover it (a hole, a sloped top, a partial arc).
constexpr double kMinCoverage = 0.95, kMaxCoverage = 1.02;

// A facet may turn at most this far from the curved surface's normal at its corners (half the
// angle it spans on the arc).
constexpr double kMaxFacetTurnDeg = 10;

// Sample points of a quadric cell, as a share of the cell's size from the axis edge along u and
// v: one well inside the quarter disk (radius 0.49) and one well outside it (radius 1.2).
constexpr double kInnerSample = 0.35, kOuterSample = 0.85;
// The same for a pyramid cell, from its corner along all three axes: x' + y' + z' = 0.6 and 1.8.
constexpr double kPyramidInnerSample = 0.2, kPyramidOuterSample = 0.6;

}  // namespace

// Slope faces (normal perpendicular to one axis e) are joined into pieces: connected through
// shared corners, same axis, normals in the same quadrant of (u, v). A piece whose corners and
// edge midpoints lie within the tolerance of a quarter ellipse spanning its bounding box, centred
// at the box corner behind its normals (a round corner) or in front of them (a cove), and whose
// area covers the arc over its whole extent along e, is a quadric piece; its faces are no longer
// slopes. Everything else stays as it was.
void Builder::findQuadrics() {
  if (!options.quadrics) return;
  const auto keyOf = [&](std::uint32_t f) {
    const int e = faces[f].axis;
    return e * 4 + (faces[f].areaVector[kU[e]] > 0 ? 1 : 0) + (faces[f].areaVector[kV[e]] > 0 ? 2 : 0);
  };
  UnionFind sets(faces.size());
  std::unordered_map<std::uint64_t, std::uint32_t> owner;  // (welded corner, key) -> a face there
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (faces[f].kind != FaceKind::Slope) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t id = static_cast<std::uint64_t>(cornerIds[f][static_cast<std::size_t>(k)]) * 12 +
                               static_cast<std::uint64_t>(keyOf(f));
      const auto [it, fresh] = owner.emplace(id, f);
      if (!fresh) sets.unite(f, it->second);
    }
  }
  for (std::vector<std::uint32_t>& members :
       sets.groups([&](std::uint32_t f) { return faces[f].kind == FaceKind::Slope; })) {
    QuadricPiece piece;
    piece.e = faces[members.front()].axis;
    const int e = piece.e, u = kU[e], v = kV[e];
    const PieceSpan span = spanOf(members);
    const dvec2 lo(span.lo[u], span.lo[v]), hi(span.hi[u], span.hi[v]);
    piece.e0 = span.lo[e];
    piece.e1 = span.hi[e];
    piece.area = span.area;
    piece.radius = hi - lo;
    if (std::min(piece.radius.x, piece.radius.y) <= 2 * tol || piece.e1 - piece.e0 <= 2 * tol) continue;
    const double expected = quarterArc(piece.radius.x, piece.radius.y) * (piece.e1 - piece.e0);
    if (piece.area < kMinCoverage * expected || piece.area > kMaxCoverage * expected) continue;
    // The normals' quadrant; a round corner's arc lies that way from its axis, a cove's the other.
    const dvec3 normal = faces[members.front()].areaVector;
    const std::array<int, 2> facing{normal[u] > 0 ? 1 : -1, normal[v] > 0 ? 1 : -1};
    const auto onArc = [&](const dvec2& centre, const dvec3& q) {
      const double rho = std::hypot((q[u] - centre.x) / piece.radius.x, (q[v] - centre.y) / piece.radius.y);
      return std::abs(rho - 1) * std::max(piece.radius.x, piece.radius.y) <= tol;
    };
    bool found = false;
    for (const int side : {1, -1}) {
      piece.quadrant = {side * facing[0], side * facing[1]};
      piece.centre = dvec2(piece.quadrant[0] > 0 ? lo.x : hi.x, piece.quadrant[1] > 0 ? lo.y : hi.y);
      // Corners and edge midpoints: a chord's midpoint is where a coarse polygon strays furthest.
      found = std::all_of(members.begin(), members.end(), [&](std::uint32_t f) {
        for (int k = 0; k < 3; ++k)
          if (!onArc(piece.centre, corner(f, k)) || !onArc(piece.centre, 0.5 * (corner(f, k) + corner(f, (k + 1) % 3))))
            return false;
        return true;
      });
      if (found) break;
    }
    if (!found || !facetsFollowSurface(piece, members, span)) continue;
    keepPiece(std::move(piece), std::move(members), span.materialArea);
  }
  stats.quadrics = static_cast<int>(quadrics.size());
}

// A fitted piece: its faces are shown by its cells (or sub-block), in the material of largest area.
void Builder::keepPiece(QuadricPiece piece, std::vector<std::uint32_t> members,
                        const std::vector<double>& materialArea) {
  piece.material =
      static_cast<std::uint16_t>(std::max_element(materialArea.begin(), materialArea.end()) - materialArea.begin());
  const auto id = static_cast<int>(quadrics.size());
  for (std::uint32_t f : members) {
    faces[f].kind = FaceKind::Quadric;
    faces[f].group = id;
  }
  piece.faces = std::move(members);
  quadrics.push_back(std::move(piece));
}

// Whether every face of a piece that fits its surface turns from the surface's normal by at most
// kMaxFacetTurnDeg at each of its corners. A quarter arc of two to four facets (a low-poly bevel)
// is drawn faceted, and a true curve in its place would shade unlike it; its faces stay what they
// were (slopes, or general faces for the mesh), and its box's planes become boundaries all the
// same, so that the cells its faces cut, trimmed where they are not shown, are the box's alone
// rather than whatever large cells reach over the corner.
bool Builder::facetsFollowSurface(const QuadricPiece& piece, const std::vector<std::uint32_t>& members,
                                  const PieceSpan& span) {
  const double minCos = std::cos(kMaxFacetTurnDeg * std::numbers::pi / 180);
  const bool fine = std::all_of(members.begin(), members.end(), [&](std::uint32_t f) {
    const dvec3 facet = glm::normalize(faces[f].areaVector);
    for (int k = 0; k < 3; ++k)
      if (std::abs(glm::dot(facet, piece.normalAt(corner(f, k)))) < minCos) return false;
    return true;
  });
  if (!fine) bevelBoxes.push_back({span.lo, span.hi});
  return fine;
}

Builder::PieceSpan Builder::spanOf(const std::vector<std::uint32_t>& members) const {
  PieceSpan span;
  span.materialArea.assign(mesh.materials.size(), 0.0);
  for (std::uint32_t f : members) {
    for (int k = 0; k < 3; ++k) {
      span.lo = glm::min(span.lo, corner(f, k));
      span.hi = glm::max(span.hi, corner(f, k));
    }
    span.areaVector += faces[f].areaVector;
    span.area += faces[f].area;
    span.materialArea[mesh.triangleMaterial[f]] += faces[f].area;
  }
  return span;
}

// Faces sloped along all three axes (quarter-round pieces taken) are joined into pieces the same
// way, by the octant of their normals. A piece whose corners and edge midpoints lie within the
// tolerance of an ellipsoid octant spanning its bounding box, centred at the box corner behind its
// normals (a dome) or in front of them (a niche), and whose area covers the octant's, is a
// sphere-octant piece (e = z, so that (u, v, e) is (x, y, z) and the corner bits come straight
// from the signs). A cap flatter than a hemisphere, or a bulging one, fits no octant of its box.
void Builder::findSphereOctants() {
  if (!options.quadrics) return;
  const auto candidate = [&](std::uint32_t f) {
    const dvec3& normal = faces[f].areaVector;
    return (faces[f].kind == FaceKind::General || faces[f].kind == FaceKind::Slope) && normal.x != 0 && normal.y != 0 &&
           normal.z != 0;
  };
  const auto keyOf = [&](std::uint32_t f) {
    const dvec3& normal = faces[f].areaVector;
    return (normal.x > 0 ? 1 : 0) + (normal.y > 0 ? 2 : 0) + (normal.z > 0 ? 4 : 0);
  };
  UnionFind sets(faces.size());
  std::unordered_map<std::uint64_t, std::uint32_t> owner;  // (welded corner, key) -> a face there
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (!candidate(f)) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t id = static_cast<std::uint64_t>(cornerIds[f][static_cast<std::size_t>(k)]) * 8 +
                               static_cast<std::uint64_t>(keyOf(f));
      const auto [it, fresh] = owner.emplace(id, f);
      if (!fresh) sets.unite(f, it->second);
    }
  }
  stats.sphereOctants = 0;
  for (std::vector<std::uint32_t>& members : sets.groups(candidate)) {
    const PieceSpan span = spanOf(members);
    const dvec3 &lo = span.lo, &hi = span.hi;
    const double area = span.area;
    const dvec3 radius = hi - lo;
    if (std::min({radius.x, radius.y, radius.z}) <= 2 * tol) continue;
    const double expected = octantArea(radius.x, radius.y, radius.z);
    if (area < kMinCoverage * expected || area > kMaxCoverage * expected) continue;
    QuadricPiece piece;
    piece.spanBox(lo, hi, area);
    const dvec3 normal = faces[members.front()].areaVector;
    bool found = false;
    for (const int side : {1, -1}) {
      piece.centreAtCorner(normal, side, lo, hi);
      // Corners on the surface; edge midpoints too, but a chord's midpoint lies inside by its
      // sagitta (length^2 / 8 radius), which a dome's few rings make more than the tolerance.
      found = std::all_of(members.begin(), members.end(), [&](std::uint32_t f) {
        for (int k = 0; k < 3; ++k) {
          const dvec3 a = corner(f, k), b = corner(f, (k + 1) % 3);
          const double sagitta = glm::dot(b - a, b - a) / (8 * std::min({radius.x, radius.y, radius.z}));
          const double off = (piece.rho(0.5 * (a + b)) - 1) * piece.reach();
          if (std::abs(piece.rho(a) - 1) * piece.reach() > tol || off > tol || off < -tol - sagitta) return false;
        }
        return true;
      });
      if (found) break;
    }
    if (!found || !facetsFollowSurface(piece, members, span)) continue;
    keepPiece(std::move(piece), std::move(members), span.materialArea);
    ++stats.sphereOctants;
  }
}

// Adds each piece's axis, tangent lines and ends, so that its box is whole cells. Boundaries from
// elsewhere (a window recess in the wall beside a round corner: the grid is global) may still cut
// the box into several cells; fitQuadrics gives such a piece a sub-block.
void Builder::addQuadricBounds() {
  for (const auto& [lo, hi] : bevelBoxes)
    for (int a = 0; a < 3; ++a) insertBoundaries(bounds[static_cast<std::size_t>(a)], {lo[a], hi[a]}, size[a], tol);
  for (const QuadricPiece& q : quadrics) {
    if (!q.represented) continue;
    const int e = q.e, u = kU[e], v = kV[e];
    insertBoundaries(bounds[static_cast<std::size_t>(u)], {q.centre.x, q.centre.x + q.quadrant[0] * q.radius.x},
                     size[u], tol);
    insertBoundaries(bounds[static_cast<std::size_t>(v)], {q.centre.y, q.centre.y + q.quadrant[1] * q.radius.y},
                     size[v], tol);
    insertBoundaries(bounds[static_cast<std::size_t>(e)], {q.e0, q.e1}, size[e], tol);
  }
}

namespace {

// Whether a piece's layer is solid at point x (grid frame) inside its box, the arc widened by
// `slack` (metres) towards the solid side.
bool solidInPiece(const QuadricPiece& q, std::int8_t layer, const dvec3& x, double slack = 0) {
  const SolidGroup group = solidGroup(Solid{static_cast<std::uint8_t>(layer)});
  if (group == SolidGroup::Box) return true;
  const double widened = q.planar ? slack * q.rhoPerMetre() : slack / q.reach();
  return convexQuadric(group) ? q.rho(x) <= 1 + widened : q.rho(x) >= 1 - widened;
}

}  // namespace

namespace {

// The boundary where the piece's box in cells starts (or, `high`, ends) along `axis`.
double boxBound(const Builder& b, const QuadricPiece& q, int axis, bool high) {
  const auto a = static_cast<std::size_t>(axis);
  return b.bounds[a][static_cast<std::size_t>(high ? q.hi[a] : q.lo[a])];
}

// The cells the piece's box spans along `axis`.
int cellsAlong(const QuadricPiece& q, int axis) {
  return q.hi[static_cast<std::size_t>(axis)] - q.lo[static_cast<std::size_t>(axis)];
}

// A piece's box in cells: its extent along each axis snapped to the nearest cells. Returns
// whether the boundaries there are within the tolerance of the piece's box.
bool placeInCells(const Builder& b, QuadricPiece& q) {
  const int e = q.e, u = kU[e], v = kV[e];
  const auto& U = b.bounds[static_cast<std::size_t>(u)];
  const auto& V = b.bounds[static_cast<std::size_t>(v)];
  const auto& E = b.bounds[static_cast<std::size_t>(e)];
  const double tol = b.tol;
  const double u1 = q.centre.x + q.quadrant[0] * q.radius.x, v1 = q.centre.y + q.quadrant[1] * q.radius.y;
  const double uLo = std::min(q.centre.x, u1), uHi = std::max(q.centre.x, u1);
  const double vLo = std::min(q.centre.y, v1), vHi = std::max(q.centre.y, v1);
  q.lo[static_cast<std::size_t>(u)] = cellOf(U, uLo + tol);
  q.hi[static_cast<std::size_t>(u)] = cellOf(U, uHi - tol) + 1;
  q.lo[static_cast<std::size_t>(v)] = cellOf(V, vLo + tol);
  q.hi[static_cast<std::size_t>(v)] = cellOf(V, vHi - tol) + 1;
  q.lo[static_cast<std::size_t>(e)] = cellOf(E, q.e0 + tol);
  q.hi[static_cast<std::size_t>(e)] = cellOf(E, q.e1 - tol) + 1;
  return snappedWithin(boxBound(b, q, u, false), uLo, tol) && snappedWithin(boxBound(b, q, u, true), uHi, tol) &&
         snappedWithin(boxBound(b, q, v, false), vLo, tol) && snappedWithin(boxBound(b, q, v, true), vHi, tol) &&
         snappedWithin(boxBound(b, q, e, false), q.e0, tol) && snappedWithin(boxBound(b, q, e, true), q.e1, tol);
}

// The solid each layer of the piece's box shows, by the winding number at a point well inside the
// piece and one well outside it. False when a layer is empty at both (the piece is missing from
// the solid there: the mesh must show it).
bool sampleLayers(const Builder& b, QuadricPiece& q, const LazyWinding& winding) {
  const int e = q.e, u = kU[e], v = kV[e];
  const auto& E = b.bounds[static_cast<std::size_t>(e)];
  const double ua = boxBound(b, q, u, false), ub = boxBound(b, q, u, true);
  const double va = boxBound(b, q, v, false), vb = boxBound(b, q, v, true);
  const double ea = boxBound(b, q, e, false), eb = boxBound(b, q, e, true);
  // A quarter cylinder: the box's edge on the axis, u = 1 (corner bit 0) when the arc lies below
  // the axis along u. A sphere octant or corner slope (e = z): the box's corner at the centre.
  const int orientation = q.octant() ? (q.quadrant[0] < 0 ? 1 : 0) + (q.quadrant[1] < 0 ? 2 : 0) + (q.eSign < 0 ? 4 : 0)
                                     : e * 4 + (q.quadrant[0] < 0 ? 1 : 0) + (q.quadrant[1] < 0 ? 2 : 0);
  const SolidGroup convex = q.planar     ? SolidGroup::Pyramid
                            : q.octant() ? SolidGroup::SphereOctant
                                         : SolidGroup::QuarterCylinder;
  const SolidGroup concave = q.planar     ? SolidGroup::InversePyramid
                             : q.octant() ? SolidGroup::InverseSphereOctant
                                          : SolidGroup::InverseQuarterCylinder;
  const double axisU = q.quadrant[0] > 0 ? ua : ub, axisV = q.quadrant[1] > 0 ? va : vb, axisE = q.eSign > 0 ? ea : eb;
  q.layers.clear();
  const int layerCount = q.octant() ? 1 : cellsAlong(q, e);
  for (int k = 0; k < layerCount; ++k) {
    std::array<bool, 2> in{};
    for (int h = 0; h < 2; ++h) {
      const double share = q.planar ? (h == 0 ? kPyramidInnerSample : kPyramidOuterSample)
                           : h == 0 ? kInnerSample
                                    : kOuterSample;
      dvec3 x;
      const int layer = q.lo[static_cast<std::size_t>(e)] + k;
      x[e] = q.octant() ? axisE + q.eSign * share * (eb - ea)
                        : 0.5 * (E[static_cast<std::size_t>(layer)] + E[static_cast<std::size_t>(layer + 1)]);
      x[u] = axisU + q.quadrant[0] * share * (ub - ua);
      x[v] = axisV + q.quadrant[1] * share * (vb - va);
      in[static_cast<std::size_t>(h)] = winding(x + b.origin) >= kInside;
    }
    if (!in[0] && !in[1]) return false;
    q.layers.push_back(in[0] && in[1]
                           ? std::int8_t{0}
                           : static_cast<std::int8_t>(makeSolid(in[0] ? convex : concave, orientation).index));
  }
  return true;
}

// Gives the cells of piece `id`'s box their layer's solid (and, for a sub-block, the piece), and
// the curved face's share to the cell where the surface's middle is, one per layer (a corner
// slope's: its centroid).
void markCells(Builder& b, int id) {
  const QuadricPiece& q = b.quadrics[static_cast<std::size_t>(id)];
  const int e = q.e, u = kU[e], v = kV[e];
  const auto& U = b.bounds[static_cast<std::size_t>(u)];
  const auto& V = b.bounds[static_cast<std::size_t>(v)];
  const auto& E = b.bounds[static_cast<std::size_t>(e)];
  const auto su = static_cast<std::size_t>(u), sv = static_cast<std::size_t>(v), se = static_cast<std::size_t>(e);
  const double middle = q.planar ? 1.0 / 3 : q.octant() ? 1 / std::numbers::sqrt3 : std::numbers::sqrt2 / 2;
  std::array<int, 3> arcCell{};
  arcCell[su] = cellOf(U, q.centre.x + q.quadrant[0] * q.radius.x * middle);
  arcCell[sv] = cellOf(V, q.centre.y + q.quadrant[1] * q.radius.y * middle);
  if (q.octant()) arcCell[se] = cellOf(E, (q.eSign > 0 ? q.e0 : q.e1) + q.eSign * (q.e1 - q.e0) * middle);
  for (int k = q.lo[se]; k < q.hi[se]; ++k) {
    const std::int8_t layer = q.layers[q.layerOf(k)];
    std::array<int, 3> c{};
    c[se] = k;
    for (c[sv] = q.lo[sv]; c[sv] < q.hi[sv]; ++c[sv])
      for (c[su] = q.lo[su]; c[su] < q.hi[su]; ++c[su]) {
        b.shape[b.index(c)] = layer;
        if (q.subBlock) b.subPiece[b.index(c)] = id;
      }
    if (layer == 0 || (q.octant() && k != arcCell[se])) continue;
    if (!q.octant()) arcCell[se] = k;
    const double length =
        q.octant() ? q.e1 - q.e0 : E[static_cast<std::size_t>(k + 1)] - E[static_cast<std::size_t>(k)];
    b.wedgeShares.push_back({b.index(arcCell), q.material, 6, q.area * length / (q.e1 - q.e0)});
  }
}

}  // namespace

// The cells of each piece's box become quarter cylinders: which of the two regions is solid
// comes from the winding number at a point well inside the quarter disk and one well outside it
// (inside: QuarterCylinder; outside: InverseQuarterCylinder; both: a box, the piece hidden there).
// A box one cell across holds them itself; a box that other boundaries cut holds them in a
// sub-block S (one cell across, the box's layers along e), which each of its cells redirects to,
// when the box holds nothing but what S shows (subBlockFits). A piece with a layer empty at both
// points, whose box a boundary merged away, or that S cannot show is left to the complementary
// mesh whole. A sphere octant is one layer, its points taken along e as well: one SphereOctant or
// InverseSphereOctant cell, or S of one cell; a corner slope likewise, its points either side of
// its plane: one Pyramid (the centre's side solid) or InversePyramid cell, or S of one cell.
// Returns whether every piece was shown.
bool Builder::fitQuadrics(const LazyWinding& winding) {
  bool all = true;
  stats.quadricsAsCells = stats.quadricsAsSubBlocks = stats.sphereOctantsAsCells = 0;
  stats.cornerSlopesAsCells = stats.cornerSlopesAsSubBlocks = 0;
  subPiece.assign(shape.size(), -1);
  for (std::size_t id = 0; id < quadrics.size(); ++id) {
    QuadricPiece& q = quadrics[id];
    q.subBlock = false;
    if (!q.represented) continue;
    bool ok = placeInCells(*this, q);
    q.subBlock = cellsAlong(q, kU[q.e]) > 1 || cellsAlong(q, kV[q.e]) > 1 || (q.octant() && cellsAlong(q, q.e) > 1);
    if (ok) ok = sampleLayers(*this, q, winding);
    if (ok && q.subBlock) ok = subBlockFits(static_cast<int>(id), winding);
    if (!ok) {
      q.represented = false;
      q.subBlock = false;
      all = false;
      continue;
    }
    markCells(*this, static_cast<int>(id));
    if (q.planar) {
      ++stats.cornerSlopesAsCells;
      stats.cornerSlopesAsSubBlocks += q.subBlock;
    } else if (q.octant()) {
      ++stats.sphereOctantsAsCells;
    } else {
      ++stats.quadricsAsCells;
      stats.quadricsAsSubBlocks += q.subBlock;
    }
  }
  return all;
}

// Whether S can stand for every cell of the piece's box: no other face reaches into the box (a
// window recess or a sill beside a round corner), and the winding number agrees with S at points
// of every cell (a 3 x 3 lattice across the axis, at mid-layer; 3 x 3 x 3 for an octant or a
// corner slope) away from the arc.
bool Builder::subBlockFits(int piece, const LazyWinding& winding) const {
  const QuadricPiece& q = quadrics[static_cast<std::size_t>(piece)];
  const int e = q.e, u = kU[e], v = kV[e];
  dvec3 boxLo, boxHi;
  for (int a = 0; a < 3; ++a) {
    boxLo[a] = bounds[static_cast<std::size_t>(a)][static_cast<std::size_t>(q.lo[static_cast<std::size_t>(a)])];
    boxHi[a] = bounds[static_cast<std::size_t>(a)][static_cast<std::size_t>(q.hi[static_cast<std::size_t>(a)])];
  }
  // Shrunk by the tolerance: faces on the box's sides and ends (walls beyond the tangents, the
  // roof on top, the flat sides of a solid corner piece) do not count.
  const dvec3 centre = 0.5 * (boxLo + boxHi), half = 0.5 * (boxHi - boxLo) - dvec3(tol);
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (faces[f].area <= 0 || (faces[f].kind == FaceKind::Quadric && faces[f].group == piece)) continue;
    if (triangleOverlapsBox(corner(f, 0), corner(f, 1), corner(f, 2), centre, half)) return false;
  }
  const double margin = 2 * tol;  // from the arc: the polygon's chords and the tolerance
  const auto& U = bounds[static_cast<std::size_t>(u)];
  const auto& V = bounds[static_cast<std::size_t>(v)];
  const auto& E = bounds[static_cast<std::size_t>(e)];
  for (int k = q.lo[static_cast<std::size_t>(e)]; k < q.hi[static_cast<std::size_t>(e)]; ++k)
    for (int j = q.lo[static_cast<std::size_t>(v)]; j < q.hi[static_cast<std::size_t>(v)]; ++j)
      for (int i = q.lo[static_cast<std::size_t>(u)]; i < q.hi[static_cast<std::size_t>(u)]; ++i)
        for (int s = 0; s < (q.octant() ? 27 : 9); ++s) {
          const double su = 0.1 + 0.4 * (s % 3), sv = 0.1 + 0.4 * (s / 3 % 3),
                       se = q.octant() ? 0.1 + 0.4 * (s / 9) : 0.5;
          dvec3 x;
          x[e] = E[static_cast<std::size_t>(k)] +
                 se * (E[static_cast<std::size_t>(k + 1)] - E[static_cast<std::size_t>(k)]);
          x[u] = U[static_cast<std::size_t>(i)] +
                 su * (U[static_cast<std::size_t>(i + 1)] - U[static_cast<std::size_t>(i)]);
          x[v] = V[static_cast<std::size_t>(j)] +
                 sv * (V[static_cast<std::size_t>(j + 1)] - V[static_cast<std::size_t>(j)]);
          const double smallest = std::min({q.radius.x, q.radius.y, q.octant() ? q.e1 - q.e0 : q.radius.x});
          const double away = q.planar ? std::abs(q.rho(x) - 1) / q.rhoPerMetre() : std::abs(q.rho(x) - 1) * smallest;
          if (away < margin) continue;
          const std::int8_t layer = q.layers[q.layerOf(k)];
          if ((winding(x + origin) >= kInside) != solidInPiece(q, layer, x)) return false;
        }
  return true;
}

bool Builder::solidAt(std::size_t cell, std::span<const dvec3> points) const {
  if (subPiece[cell] < 0) return shape[cell] >= 0;
  const QuadricPiece& q = quadrics[static_cast<std::size_t>(subPiece[cell])];
  const std::int8_t layer = q.layers[q.layerOf(cellAt(cell)[static_cast<std::size_t>(q.e)])];
  return std::all_of(points.begin(), points.end(), [&](const dvec3& x) { return solidInPiece(q, layer, x, tol); });
}

}  // namespace nut::converter::solid
