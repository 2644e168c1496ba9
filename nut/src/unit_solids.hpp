// unit_solids.hpp — the 69 cell solids (solids.hpp) as closed surfaces in the unit cube, for the
// mesh export (mesh_export.cpp).
//
// Each solid is a union of convex pieces (convex_pieces.hpp) whose shared faces are marked
// internal: the planar solids and the quarter cylinder are one piece, the inverse quarter cylinder
// is a fan of triangular prisms, the octants are cones over the triangles of their spherical patch
// (from the corner, or for the inverse octant from the opposite corner, which also takes the three
// cut cube faces). Curved surfaces have every vertex on the surface.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/solids.hpp>

#include "convex_pieces.hpp"

namespace nut::mesh {

// Shapes are built in primed coordinates q (distances from the solid's edge or corner,
// solids.hpp); a placement maps them to the unit cube, exactly for q = 0 and q = 1, so that cube
// faces stay exactly planar.
struct Placement {
  std::array<int, 3> axis{0, 1, 2};  // unit-cube axis of q[i]
  std::array<bool, 3> flip{};        // p = 1 - q on that axis
  glm::dvec3 toCube(const glm::dvec3& q) const {
    glm::dvec3 p(0.0);
    for (int i = 0; i < 3; ++i) p[axis[i]] = flip[i] ? 1.0 - q[i] : q[i];
    return p;
  }
};

// The placement of solid s (its orientation).
Placement placementOf(Solid s);

struct UnitSolid {
  std::vector<Piece> pieces;  // unit-cube coordinates, oriented outwards
  struct Tri {
    std::array<std::uint32_t, 3> v;
    int cubeFace;  // the face of the unit cube the triangle lies on, or -1
  };
  std::vector<glm::dvec3> vertices;  // of the boundary triangles
  std::vector<Tri> triangles;        // the non-internal faces
  std::array<bool, 6> fullFaces{};   // the solid covers that cube face completely
};

// Solid s in the unit cube, its curved surfaces in n segments per quarter arc.
UnitSolid buildUnitSolid(Solid s, int n);

// Largest gap between the unit sphere and the triangles of a sphere octant built with n segments
// per quarter arc: the chord error per metre of radius.
double octantUnitError(int n);

}  // namespace nut::mesh
