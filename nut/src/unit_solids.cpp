// The 69 solids in the unit cube (unit_solids.hpp).
#include "unit_solids.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace nut::mesh {

using glm::dvec3;

namespace {

// A prism over a convex polygon of the (q0, q1) square, from q2 = 0 to q2 = 1.
Piece prism(const std::vector<glm::dvec2>& polygon, const std::vector<bool>& sideInternal) {
  Face bottom, top;
  for (const glm::dvec2& v : polygon) {
    bottom.points.push_back({v.x, v.y, 0.0});
    top.points.push_back({v.x, v.y, 1.0});
  }
  Piece piece{bottom, top};
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    piece.push_back({{{a.x, a.y, 0.0}, {b.x, b.y, 0.0}, {b.x, b.y, 1.0}, {a.x, a.y, 1.0}}, sideInternal[i]});
  }
  return piece;
}

// The tetrahedron from apex over a triangle of a solid's surface; its sides are shared with the
// cones over the neighbouring triangles.
Piece cone(const dvec3& apex, const Triangle& base) {
  Piece piece{{{base[0], base[1], base[2]}, false}};
  for (int i = 0; i < 3; ++i) piece.push_back({{apex, base[i], base[(i + 1) % 3]}, true});
  return piece;
}

Piece unitCube() { return prism({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {false, false, false, false}); }

// The cube's part where dot(normal, q) <= offset (wedge, pyramid and inverse pyramid all cut the
// cube through its corners, so no new points are made).
Piece cutCube(const dvec3& normal, double offset) {
  Piece piece = unitCube();
  const double length = glm::length(normal);
  clipPiece(piece, {normal / length, offset / length});
  return piece;
}

// The quarter arc from (1, 0) to (0, 1) in n segments, exact at both ends.
std::vector<glm::dvec2> quarterArc(int n) {
  std::vector<glm::dvec2> arc{{1.0, 0.0}};
  for (int i = 1; i < n; ++i) {
    const double angle = std::numbers::pi / 2 * i / n;
    arc.push_back({std::cos(angle), std::sin(angle)});
  }
  arc.push_back({0.0, 1.0});
  return arc;
}

// The unit sphere's positive octant as n^2 triangles: the triangle with corners on the three axes,
// subdivided n times along each edge, its points pushed onto the sphere. Points on the arcs have
// exact zeros, and the arc in the plane q_a = 0 is the same list of points wherever it is used.
struct OctantPatch {
  int n = 0;
  std::vector<dvec3> points;  // (i, j) -> index, i + j <= n
  std::vector<std::array<int, 3>> triangles;
  int index(int i, int j) const { return j * (n + 1) - j * (j - 1) / 2 + i; }
  const dvec3& at(int i, int j) const { return points[static_cast<std::size_t>(index(i, j))]; }
};

OctantPatch octantPatch(int n) {
  OctantPatch patch;
  patch.n = n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j <= n; ++i) {
      // Divided by the length, not multiplied by its inverse (glm::normalize): n / sqrt(n^2) is
      // exactly 1, so the arcs' end points are exactly the cube's corners.
      const dvec3 p(i, j, n - i - j);
      patch.points.push_back(p / glm::length(p));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      patch.triangles.push_back({patch.index(i, j), patch.index(i + 1, j), patch.index(i, j + 1)});
      if (i + j + 1 < n)
        patch.triangles.push_back({patch.index(i + 1, j), patch.index(i + 1, j + 1), patch.index(i, j + 1)});
    }
  return patch;
}

std::vector<Piece> shapePieces(SolidGroup group, int n) {
  std::vector<Piece> pieces;
  switch (group) {
    case SolidGroup::Box:
      pieces.push_back(unitCube());
      break;
    case SolidGroup::Wedge:
      pieces.push_back(cutCube({1, 1, 0}, 1));
      break;
    case SolidGroup::Pyramid:
      pieces.push_back(cutCube({1, 1, 1}, 1));
      break;
    case SolidGroup::InversePyramid:
      pieces.push_back(cutCube({-1, -1, -1}, -1));
      break;
    case SolidGroup::QuarterCylinder: {
      std::vector<glm::dvec2> polygon{{0.0, 0.0}};
      for (const glm::dvec2& p : quarterArc(n)) polygon.push_back(p);
      pieces.push_back(prism(polygon, std::vector<bool>(polygon.size(), false)));
      break;
    }
    case SolidGroup::InverseQuarterCylinder: {
      // A fan of prisms from the far edge; the first and last radial sides lie on cube faces.
      const std::vector<glm::dvec2> arc = quarterArc(n);
      for (std::size_t i = 0; i + 1 < arc.size(); ++i)
        pieces.push_back(prism({{1.0, 1.0}, arc[i + 1], arc[i]}, {true, false, true}));
      break;
    }
    case SolidGroup::SphereOctant: {
      const OctantPatch patch = octantPatch(n);
      for (const auto& t : patch.triangles)
        pieces.push_back(cone(
            dvec3(0.0), {patch.points[static_cast<std::size_t>(t[0])], patch.points[static_cast<std::size_t>(t[1])],
                         patch.points[static_cast<std::size_t>(t[2])]}));
      break;
    }
    case SolidGroup::InverseSphereOctant: {
      // Star-shaped from the far corner: cones over the patch and over the three cube faces at the
      // corner minus their quarter discs (each a fan from that face's far corner).
      const OctantPatch patch = octantPatch(n);
      const dvec3 far(1.0);
      for (const auto& t : patch.triangles)
        pieces.push_back(
            cone(far, {patch.points[static_cast<std::size_t>(t[0])], patch.points[static_cast<std::size_t>(t[1])],
                       patch.points[static_cast<std::size_t>(t[2])]}));
      for (int k = 0; k < n; ++k) {
        pieces.push_back(cone(far, {dvec3(0, 1, 1), patch.at(0, k), patch.at(0, k + 1)}));              // q0 = 0
        pieces.push_back(cone(far, {dvec3(1, 0, 1), patch.at(k, 0), patch.at(k + 1, 0)}));              // q1 = 0
        pieces.push_back(cone(far, {dvec3(1, 1, 0), patch.at(k, n - k), patch.at(k + 1, n - k - 1)}));  // q2 = 0
      }
      break;
    }
  }
  return pieces;
}

// The cube face (2 * axis + 0 for the face at 0, + 1 for the face at 1) a polygon lies on, or -1.
int cubeFaceOf(const std::vector<dvec3>& points) {
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side)
      if (std::all_of(points.begin(), points.end(), [&](const dvec3& p) { return p[a] == side; })) return 2 * a + side;
  return -1;
}

}  // namespace

Placement placementOf(Solid s) {
  const int o = solidOrientation(s);
  Placement placement;
  switch (solidGroup(s)) {
    case SolidGroup::Box:
      break;
    case SolidGroup::Wedge:
    case SolidGroup::QuarterCylinder:
    case SolidGroup::InverseQuarterCylinder: {
      // q = (u', v', w): (u, v, axis) is a cyclic order of the cube's axes.
      const int axis = o / 4, corner = o % 4;
      placement.axis = {(axis + 1) % 3, (axis + 2) % 3, axis};
      placement.flip = {(corner & 1) != 0, (corner & 2) != 0, false};
      break;
    }
    default:
      placement.flip = {(o & 1) != 0, (o & 2) != 0, (o & 4) != 0};
      break;
  }
  return placement;
}

// A triangle lies in its circumdisk, which is a slice of the unit ball at distance sqrt(1 - R^2)
// from the centre.
double octantUnitError(int n) {
  const OctantPatch patch = octantPatch(n);
  double worst = 0.0;
  for (const auto& t : patch.triangles) {
    const dvec3 a = patch.points[static_cast<std::size_t>(t[0])], b = patch.points[static_cast<std::size_t>(t[1])],
                c = patch.points[static_cast<std::size_t>(t[2])];
    const double r =
        glm::length(a - b) * glm::length(b - c) * glm::length(c - a) / (2.0 * glm::length(glm::cross(b - a, c - a)));
    worst = std::max(worst, 1.0 - std::sqrt(std::max(0.0, 1.0 - r * r)));
  }
  return worst;
}

UnitSolid buildUnitSolid(Solid s, int n) {
  UnitSolid unit;
  const Placement placement = placementOf(s);
  unit.pieces = shapePieces(solidGroup(s), n);
  std::map<std::array<double, 3>, std::uint32_t> ids;
  std::array<double, 6> faceArea{};
  std::vector<Triangle> triangles;
  for (Piece& piece : unit.pieces) {
    dvec3 centre(0.0);
    int count = 0;
    for (Face& f : piece)
      for (dvec3& p : f.points) p = placement.toCube(p), centre += p, ++count;
    centre /= count;
    for (Face& f : piece) {
      // The constructors do not track winding (and mirrored placements flip it): orient each face
      // away from the convex piece's centre, keeping its first point (a cylinder's end face fans
      // out from the axis).
      dvec3 faceCentre(0.0);
      for (const dvec3& p : f.points) faceCentre += p;
      faceCentre /= static_cast<double>(f.points.size());
      if (glm::dot(areaNormal(f.points), faceCentre - centre) < 0) std::reverse(f.points.begin() + 1, f.points.end());
      const int cubeFace = cubeFaceOf(f.points);
      if (cubeFace >= 0) f.internal = false;  // nothing of the solid lies beyond a cube face
      if (f.internal) continue;
      if (cubeFace >= 0) faceArea[static_cast<std::size_t>(cubeFace)] += glm::length(areaNormal(f.points)) / 2;
      triangles.clear();
      triangulateConvex(f.points, triangles);
      for (const Triangle& t : triangles) {
        UnitSolid::Tri tri{{}, cubeFace};
        for (int i = 0; i < 3; ++i) {
          const auto [it, added] =
              ids.try_emplace({t[i].x, t[i].y, t[i].z}, static_cast<std::uint32_t>(unit.vertices.size()));
          if (added) unit.vertices.push_back(t[i]);
          tri.v[i] = it->second;
        }
        unit.triangles.push_back(tri);
      }
    }
  }
  for (int f = 0; f < 6; ++f) unit.fullFaces[f] = std::abs(faceArea[f] - 1.0) < 1e-9;
  return unit;
}

}  // namespace nut::mesh
