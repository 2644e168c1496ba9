// converter/sheets.hpp — open sheets hanging off a closed body: roofs that overhang their walls,
// ground plates wider than the footprint, dormers that float a few centimetres above their roof.
//
// Municipal LoD2 models are written surface by surface (CityGML's WallSurface, RoofSurface,
// GroundSurface), so a roof is a sheet that runs past the top of its walls. Such a mesh is open:
// its winding number is fractional under the eaves, and the converter, which proposes boundaries
// at the corners of planes only on closed surfaces, leaves the roof and the walls near it to the
// complementary mesh. Where a wall's free top edge lies in a roof face, cutting the roof along it
// separates the overhang; what is left, once every piece with a free edge is peeled off, is often
// closed. The body is then converted like any closed mesh and the sheets are drawn as mesh; a body
// still open somewhere (two parts of a building meeting along a line) is converted by its winding
// number, no longer fractional under the eaves.
//
// The decisions are taken on a copy of the mesh made to match at the tolerance (vertices welded,
// edges split at the vertices on them), which a survey's millimetres need; the body and sheets are
// the input's own faces, except those cut, which are written as their parts.
#pragma once

#include <cstddef>
#include <optional>

#include <converter/mesh_check.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::converter {

struct SheetSplit {
  TriangleMesh body;    // repaired by checkAndRepair (bodyCheck), faces turned to face out
  TriangleMesh sheets;  // what was peeled off, and faces narrower than the tolerance
  MeshCheck bodyCheck;
  bool closed = false;              // the body closes at the tolerance: every edge run once each way
  std::size_t cutTriangles = 0;     // input triangles cut along another face's free edge
  std::size_t hiddenTriangles = 0;  // pieces inside the body (a roof under its dormer): dropped
};

// The share of a mesh's area that may be peeled off at most: more than that is no overhang but an
// open building, whose walls or roof would go to the mesh.
inline constexpr double kMaxSheetShare = 0.2;

// Splits an open, repaired mesh (checkAndRepair) into a body and the sheets around it:
//  1. vertices within `planeToleranceM` are welded, faces narrower than it set apart (drawn as
//     sheets), and edges split where another vertex lies within it;
//  2. each face in whose plane (within the tolerance) a free edge of another face lies is cut
//     along that edge's line, where the edge crosses it (a wall's top under an overhanging roof);
//  3. faces are grouped into pieces joined across edges that exactly two faces share, and every
//     piece with an edge that one face alone uses is peeled off, until none is left;
//  4. a piece that meets others along edges of three or more faces and lies inside the solid the
//     rest bounds is dropped: it is hidden (the roof under a dormer standing on it);
//  5. each piece left is turned to run its shared edges consistently and to face outwards.
// Nothing (nullopt) when nothing is peeled or dropped, or when the sheets are more than
// kMaxSheetShare of the area.
std::optional<SheetSplit> detachSheets(const TriangleMesh& mesh, double planeToleranceM);

}  // namespace nut::converter
