// converter/mesh_check.hpp — what is wrong with an input mesh, and the repairs the converter makes
// before it classifies cells.
//
// Real building meshes are rarely closed: windows fill wall holes (edges shared by more than two
// faces), shells sit open on a base plate, faces are flipped. The converter's inside test (the
// generalized winding number, winding.hpp) does not need a closed mesh, but it does need faces
// oriented outwards, so the orientation is made consistent (CGAL's orient_polygon_soup) and each
// closed piece is turned outwards. Degenerate faces (collinear corners, by CGAL's exact
// predicate) carry no area and no normal and are removed.
#pragma once

#include <cstddef>
#include <string>

#include <scene/obj.hpp>

namespace nut::converter {

struct MeshCheck {
  std::size_t triangles = 0;          // before repairs
  std::size_t vertices = 0;           // distinct positions used by faces
  std::size_t degenerate = 0;         // collinear corners: removed
  std::size_t slivers = 0;            // smallest altitude below 0.1 mm: kept
  std::size_t duplicateFaces = 0;     // the same three positions as an earlier face: kept
  std::size_t boundaryEdges = 0;      // used by one face
  std::size_t nonManifoldEdges = 0;   // used by more than two faces
  std::size_t inconsistentEdges = 0;  // two faces that run the edge the same way (one is flipped)
  std::size_t components = 0;         // pieces connected through manifold edges
  std::size_t flippedTriangles = 0;   // turned by the orientation repair
  // After the repair, every edge cancels (is run as often one way as the other) once edges that
  // meet at T-junctions are matched along their lines (closed_surface.hpp): the occupancy step may
  // count crossings along lines of cells.
  bool closedSurface = false;
  bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
  // One line per finding, for the report and stderr.
  std::string summary() const;
};

// Checks `mesh` and repairs it in place: removes degenerate triangles, orients every connected
// piece consistently, and turns closed pieces outwards (positive signed volume); an open piece
// keeps the orientation most of its area had. Then decides whether the repaired mesh is a closed
// surface (closed_surface.hpp), and turns its open pieces if together they have a negative
// volume. On an open mesh, open pieces meeting along lines where their edges cancel are taken as
// one; an open piece that the winding number on either side of its faces finds facing into the
// solid is turned, and then each small open piece (below 1 % of the area: a window pane) whose
// front the rest of the mesh, half the piece's size out, finds more inside than its back. Inside
// is then w >= 1/2 everywhere. Positions and materials are kept.
MeshCheck checkAndRepair(TriangleMesh& mesh);

}  // namespace nut::converter
