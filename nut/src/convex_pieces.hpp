// convex_pieces.hpp — convex polyhedra ("pieces") in double precision and their clipping by
// planes, for the mesh export (mesh_export.cpp) and the unit solids (unit_solids.hpp).
//
// A piece is closed and convex, so a plane leaves one convex piece of it, closed by one convex cap
// on the plane: clipping never needs general polygon booleans. A segment's crossing with a plane
// is computed from its endpoints in a fixed order, so the faces on both sides of a shared edge get
// the same point, bit for bit, and the caps of pieces clipped by one plane meet edge to edge.
#pragma once

#include <array>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace nut::mesh {

// Points within this distance of a clipping plane count as lying on it. Far above the rounding
// of root-frame coordinates (below 1e-11 m for 16 km blocks) and far below the format's 1 mm, so
// a sub-block that exactly fills its cell, or one turned by a quarter yaw (cos = 6e-17), is not cut.
inline constexpr double kOnPlaneM = 1e-7;

struct Face {
  std::vector<glm::dvec3> points;  // convex polygon, counter-clockwise seen from outside the piece
  bool internal = false;           // shared with another piece of the same solid: never emitted
  int material = -1;               // -1: the solid's; else a plane cell's surface material
};
using Piece = std::vector<Face>;  // a closed convex polyhedron
using Triangle = std::array<glm::dvec3, 3>;

struct Plane {
  glm::dvec3 normal;  // unit
  double offset;      // the kept side is dot(normal, p) <= offset
  double distance(const glm::dvec3& p) const { return glm::dot(normal, p) - offset; }
};

// Twice the area times the unit normal (Newell), relative to the first point for precision.
glm::dvec3 areaNormal(const std::vector<glm::dvec3>& points);

// Appends the triangles of a convex polygon to `out`, same orientation. A fan from the first point
// unless that would make a sliver (three points in a row, which clipping can produce), then a fan
// from the centroid.
void triangulateConvex(const std::vector<glm::dvec3>& polygon, std::vector<Triangle>& out);

// Clips a convex piece to the plane's kept side and closes it with a cap. Returns false when
// nothing of the piece is left.
bool clipPiece(Piece& piece, const Plane& plane);

}  // namespace nut::mesh
