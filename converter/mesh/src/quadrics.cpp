// Solid conversion, quarter cylinders: faces on a quarter of a cylinder parallel to an axis (round
// building corners, coves, rods) are found, given the boundaries that make each quarter arc fill
// one cell's cross-section, and those cells become QuarterCylinder or InverseQuarterCylinder
// solids (converter/solid.hpp, steps 2 and 3). A cell stretches the unit shape, so an elliptic
// quarter fits as well as a circular one.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
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

// Polygon faces are chords of the arc: their area falls short of the arc's by (1 - sin x / x) for
// a segment of angle 2x, under 0.5 % from 8 segments a quarter on. Less than this share of the
// arc's area means the faces do not cover it (a hole, a sloped top, a partial arc).
constexpr double kMinCoverage = 0.95, kMaxCoverage = 1.02;

// Sample points of a quadric cell, as a share of the cell's size from the axis edge along u and
// v: one well inside the quarter disk (radius 0.49) and one well outside it (radius 1.2).
constexpr double kInnerSample = 0.35, kOuterSample = 0.85;

}  // namespace

// Slope faces (normal perpendicular to one axis e) are joined into pieces: connected through
// shared corners, same axis, normals in the same quadrant of (u, v). A piece whose corners and
// edge midpoints lie within the tolerance of a quarter ellipse spanning its bounding box, centred
// at the box corner behind its normals (a round corner) or in front of them (a cove), and whose
// area covers the arc over its whole extent along e, is a quadric piece; its faces are no longer
// slopes. Everything else stays as it was.
void Builder::findQuadrics() {
  if (!options.quadrics) return;
  // Corners are matched by position: a mesh may repeat a vertex on either side of a seam.
  std::unordered_map<std::uint32_t, std::uint32_t> weld;
  {
    std::vector<std::uint32_t> order(p.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return p[a].x != p[b].x ? p[a].x < p[b].x : p[a].y != p[b].y ? p[a].y < p[b].y : p[a].z < p[b].z;
    });
    for (std::size_t i = 0; i < order.size(); ++i)
      weld[order[i]] = i > 0 && p[order[i]] == p[order[i - 1]] ? weld[order[i - 1]] : order[i];
  }
  const auto keyOf = [&](std::uint32_t f) {
    const int e = faces[f].axis;
    return e * 4 + (faces[f].areaVector[kU[e]] > 0 ? 1 : 0) + (faces[f].areaVector[kV[e]] > 0 ? 2 : 0);
  };
  UnionFind sets(faces.size());
  std::unordered_map<std::uint64_t, std::uint32_t> owner;  // (welded corner, key) -> a face there
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (faces[f].kind != FaceKind::Slope) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t id = static_cast<std::uint64_t>(weld[mesh.triangles[f][static_cast<std::size_t>(k)]]) * 12 +
                               static_cast<std::uint64_t>(keyOf(f));
      const auto [it, fresh] = owner.emplace(id, f);
      if (!fresh) sets.unite(f, it->second);
    }
  }
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> groups;
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    if (faces[f].kind == FaceKind::Slope) groups[sets.find(f)].push_back(f);
  std::vector<std::vector<std::uint32_t>> pieces;
  for (auto& [root, members] : groups) pieces.push_back(std::move(members));
  // Deterministic order whatever the hash map did.
  std::sort(pieces.begin(), pieces.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });

  for (std::vector<std::uint32_t>& members : pieces) {
    QuadricPiece piece;
    piece.e = faces[members.front()].axis;
    const int e = piece.e, u = kU[e], v = kV[e];
    dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    piece.e0 = std::numeric_limits<double>::infinity();
    piece.e1 = -std::numeric_limits<double>::infinity();
    std::vector<double> materialArea(mesh.materials.size(), 0.0);
    for (std::uint32_t f : members) {
      for (int k = 0; k < 3; ++k) {
        const dvec3 q = corner(f, k);
        lo = glm::min(lo, dvec2(q[u], q[v]));
        hi = glm::max(hi, dvec2(q[u], q[v]));
        piece.e0 = std::min(piece.e0, q[e]);
        piece.e1 = std::max(piece.e1, q[e]);
      }
      piece.area += faces[f].area;
      materialArea[mesh.triangleMaterial[f]] += faces[f].area;
    }
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
    if (!found) continue;
    piece.material = static_cast<std::uint16_t>(std::max_element(materialArea.begin(), materialArea.end()) - materialArea.begin());
    const auto id = static_cast<int>(quadrics.size());
    for (std::uint32_t f : members) {
      faces[f].kind = FaceKind::Quadric;
      faces[f].group = id;
    }
    piece.faces = std::move(members);
    quadrics.push_back(std::move(piece));
  }
  stats.quadrics = static_cast<int>(quadrics.size());
}

namespace {

// The cell range [lo, hi] of one axis: the single cell from lo to hi within the tolerance, or -1.
int singleCell(const std::vector<double>& bounds, double lo, double hi, double tol) {
  const int i = cellOf(bounds, 0.5 * (lo + hi));
  return std::abs(bounds[static_cast<std::size_t>(i)] - lo) <= tol && std::abs(bounds[static_cast<std::size_t>(i + 1)] - hi) <= tol ? i : -1;
}

}  // namespace

// Adds each piece's axis, tangent lines and ends. A piece whose cross-section another boundary
// cuts (a window recess in the wall beside a round corner: the grid is global) cannot be one cell
// across and is left to the complementary mesh, and its boundaries are not added; pieces are
// dropped one at a time, since a dropped piece's boundaries may have been what cut another.
void Builder::addQuadricBounds() {
  for (;;) {
    std::array<std::vector<double>, 3> trial = bounds;
    for (const QuadricPiece& q : quadrics) {
      if (!q.represented) continue;
      const int e = q.e, u = kU[e], v = kV[e];
      insertBoundaries(trial[static_cast<std::size_t>(u)], {q.centre.x, q.centre.x + q.quadrant[0] * q.radius.x}, size[u], tol);
      insertBoundaries(trial[static_cast<std::size_t>(v)], {q.centre.y, q.centre.y + q.quadrant[1] * q.radius.y}, size[v], tol);
      insertBoundaries(trial[static_cast<std::size_t>(e)], {q.e0, q.e1}, size[e], tol);
    }
    const auto cut = std::find_if(quadrics.begin(), quadrics.end(), [&](const QuadricPiece& q) {
      if (!q.represented) return false;
      const int u = kU[q.e], v = kV[q.e];
      const double u1 = q.centre.x + q.quadrant[0] * q.radius.x, v1 = q.centre.y + q.quadrant[1] * q.radius.y;
      return singleCell(trial[static_cast<std::size_t>(u)], std::min(q.centre.x, u1), std::max(q.centre.x, u1), tol) < 0 ||
             singleCell(trial[static_cast<std::size_t>(v)], std::min(q.centre.y, v1), std::max(q.centre.y, v1), tol) < 0;
    });
    if (cut == quadrics.end()) {
      bounds = std::move(trial);
      return;
    }
    cut->represented = false;
  }
}

// The cells of each piece become quarter cylinders: which of the two regions of a cell is solid
// comes from the winding number at a point well inside the quarter disk and one well outside it
// (inside: QuarterCylinder; outside: InverseQuarterCylinder; both: a box, the piece hidden there).
// A piece with a cell empty at both points, or cut by a boundary added after addQuadricBounds
// (a slope's), is left to the complementary mesh whole. Returns whether every piece was shown.
bool Builder::fitQuadrics(const LazyWinding& winding) {
  bool all = true;
  stats.quadricsAsCells = 0;
  for (QuadricPiece& q : quadrics) {
    if (!q.represented) continue;
    const int e = q.e, u = kU[e], v = kV[e];
    const auto& U = bounds[static_cast<std::size_t>(u)];
    const auto& V = bounds[static_cast<std::size_t>(v)];
    const auto& E = bounds[static_cast<std::size_t>(e)];
    const double u1 = q.centre.x + q.quadrant[0] * q.radius.x, v1 = q.centre.y + q.quadrant[1] * q.radius.y;
    const int i = singleCell(U, std::min(q.centre.x, u1), std::max(q.centre.x, u1), tol);
    const int j = singleCell(V, std::min(q.centre.y, v1), std::max(q.centre.y, v1), tol);
    const int k0 = cellOf(E, q.e0 + tol), k1 = cellOf(E, q.e1 - tol);
    bool ok = i >= 0 && j >= 0 && std::abs(E[static_cast<std::size_t>(k0)] - q.e0) <= tol &&
              std::abs(E[static_cast<std::size_t>(k1 + 1)] - q.e1) <= tol;
    // The cell's edge on the axis: u = 1 (corner bit 0) when the arc lies below the axis along u.
    const int orientation = e * 4 + (q.quadrant[0] < 0 ? 1 : 0) + (q.quadrant[1] < 0 ? 2 : 0);
    struct Fitted {
      std::size_t id;
      std::int8_t solid;
      double length;  // along the axis
    };
    std::vector<Fitted> cells;
    for (int k = k0; ok && k <= k1; ++k) {
      const double ua = U[static_cast<std::size_t>(i)], ub = U[static_cast<std::size_t>(i + 1)];
      const double va = V[static_cast<std::size_t>(j)], vb = V[static_cast<std::size_t>(j + 1)];
      const double axisU = q.quadrant[0] > 0 ? ua : ub, axisV = q.quadrant[1] > 0 ? va : vb;
      std::array<bool, 2> in{};
      for (int h = 0; h < 2; ++h) {
        const double share = h == 0 ? kInnerSample : kOuterSample;
        dvec3 x;
        x[e] = 0.5 * (E[static_cast<std::size_t>(k)] + E[static_cast<std::size_t>(k + 1)]);
        x[u] = axisU + q.quadrant[0] * share * (ub - ua);
        x[v] = axisV + q.quadrant[1] * share * (vb - va);
        in[static_cast<std::size_t>(h)] = std::abs(winding(x + origin)) >= kInside;
      }
      std::array<int, 3> cell{};
      cell[static_cast<std::size_t>(e)] = k;
      cell[static_cast<std::size_t>(u)] = i;
      cell[static_cast<std::size_t>(v)] = j;
      const double length = E[static_cast<std::size_t>(k + 1)] - E[static_cast<std::size_t>(k)];
      if (!in[0] && !in[1]) {
        ok = false;  // the piece is missing from the solid here: the mesh must show it
      } else if (in[0] && in[1]) {
        cells.push_back({index(cell), 0, length});
      } else {
        const SolidGroup group = in[0] ? SolidGroup::QuarterCylinder : SolidGroup::InverseQuarterCylinder;
        cells.push_back({index(cell), static_cast<std::int8_t>(makeSolid(group, orientation).index), length});
      }
    }
    if (!ok) {
      q.represented = false;
      all = false;
      continue;
    }
    for (const Fitted& c : cells) {
      shape[c.id] = c.solid;
      if (c.solid == 0) continue;
      hint[c.id] = q.material;
      wedgeShares.push_back({c.id, q.material, 6, q.area * c.length / (q.e1 - q.e0)});  // the curved face's share
    }
    ++stats.quadricsAsCells;
  }
  return all;
}

}  // namespace nut::converter::solid
