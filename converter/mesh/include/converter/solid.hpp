// converter/solid.hpp — solid conversion (paper section 5, first step): a triangle mesh becomes
// one non-uniform grid G0 of empty, box, wedge, pyramid, quarter-cylinder and sphere-octant cells,
// plus the complementary mesh of the faces the grid cannot show.
//
// 1. Planes. A face whose normal is within `angleToleranceDeg` of an axis is axis-aligned. Per
//    axis, the faces' coordinate intervals (a face tilted by 0.5 degrees spans several
//    centimetres) are clustered: intervals closer than `toleranceM` join one cluster, whose
//    position is the area-weighted mean of its faces (paper: "weighted averages ... where mesh face
//    areas are used as weights"). A cluster spanning more than twice the tolerance whose flat
//    faces lie at several depths (a facade turned against the rest of its building, its panes and
//    frames chained to the wall) becomes a staircase of positions instead, one per depth.
// 2. Grid. The clusters and the mesh's bounding box give each axis's boundaries, snapped to the
//    encoding's millimetres. A face sloped along one axis only (a roof pitch, a ramp) adds its end
//    lines, and boundaries where it crosses other boundaries, so that it runs through cells from
//    corner to corner: those cells become wedges, where the slope's faces cover the cell's whole
//    cross-section. Where its outline cuts a cell diagonally (a hip or valley: two planes meeting
//    in a crease no solid has) the cell is no wedge and the faces' part over it goes to the
//    complementary mesh; a few points along each hip and valley become boundaries, so that those
//    cells are one row of small cells along the crease. Faces on a quarter of a cylinder whose axis
//    is parallel to an axis (a round corner, a cove), drawn with facets fine enough to shade like
//    it (a bevel of two to four facets stays faceted), add the axis and the two tangent lines, so
//    that the quarter arc fills the cross-section of one cell: those cells become quarter cylinders.
//    Where other boundaries cut that cross-section, the piece gets a block of its own, one quarter
//    cylinder across, which every cell of G0 in the piece's box redirects to. Faces on an octant of
//    a sphere (a quarter of a dome) add the planes of its box likewise: one sphere-octant cell, or
//    a block of its own; so does a corner slope (a planar piece sloped along all three axes that
//    is the triangle through the three box corners next to one corner: a chamfered corner), as
//    one pyramid or inverse-pyramid cell. These cells are judged first, by winding numbers
//    sampled in them: a slope or piece that fails is given up, and the grid is built again
//    without its boundaries before the occupancy of any other cell is computed.
// 3. Occupancy. Lines through the cell centres along one axis are intersected with the faces.
//    When the mesh is a closed surface (every edge cancels, T-junctions matched) and a line's
//    entries and exits balance (merged where it passes through a shared edge or vertex), the
//    running count of entries minus exits is the winding number and decides every cell on it
//    exactly. Otherwise (holes, open shells, flipped faces) a cell is inside when the generalized
//    winding number at its centre is at least 1/2 in magnitude (winding.hpp), which needs no
//    closed mesh and no luck at edges; cells between the same two
//    crossings share one evaluation, and an ambiguous value (a centre on a surface) is sampled at
//    four more points. Cells that faces of the complementary mesh cut stay solid only when they
//    are inside all over, so they never poke through the mesh. Where such a cell is solid all
//    over on one side of what cuts it (a house under a roof left to the mesh, with no face ending
//    at the eaves), the grid is built once more with a boundary there, when the faces it wins
//    back from the mesh are worth it (2 % of the surface). With plane cells (planeCells), on a
//    closed surface, the corners of the planes the mesh's faces lie on become boundaries too
//    (plane_corners.cpp), so that plane_fit.hpp finds cells crossed by one or two of them.
// 4. Materials. Each axis-aligned face is clipped against the cell faces it covers; where exactly
//    one side is solid, that cell gains the face's area for the face's material and the cell takes
//    the material of largest area. Uncovered parts of faces (thin sheets, details below the
//    tolerance) and every face the grid does not show go to the complementary mesh.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <scene/obj.hpp>

namespace nut::converter {

struct SolidOptions {
  double toleranceM = 0.01;         // plane clustering and wedge fitting
  double angleToleranceDeg = 1.0;   // how far a normal may be from an axis and still count as on it
  bool wedges = true;               // fit wedge cells to faces sloped along one axis
  bool quadrics = true;             // fit quarter-cylinder and sphere-octant cells to curved pieces
  bool pyramids = true;             // fit pyramid cells to corner slopes (chamfered corners)
  // Build the grid with boundaries at the corners of the complementary mesh's planes, for plane
  // cells (HNI version 3; plane_fit.hpp fits them to the grid, convert.cpp keeps them when smaller).
  bool planeCells = false;
  // Keep a slope whose cells mostly became wedges, leaving its faces over the other cells to the
  // complementary mesh; false: only slopes that became wedges everywhere stay (a smaller grid).
  bool partialWedges = true;
  std::size_t maxCells = 64'000'000;  // refuse grids larger than this (memory)
  int threads = 0;                  // 0: all cores
  // The mesh is a closed surface (MeshCheck::closedSurface): lines of cells whose crossings
  // balance are counted; otherwise every cell asks the winding number.
  bool closedSurface = false;
  // When the mesh is one part of a building, clipped to a region of it (wings.hpp): the whole
  // building in the same frame, whose winding number decides what is inside (the part alone is
  // open where it was cut, so closedSurface does not apply).
  const TriangleMesh* enclosing = nullptr;
  // Called from the calling thread with the fraction done of the pass over cells under way: the
  // cells classified, then the cut cells trimmed (each pass, and each build of the grid, starts at 0).
  std::function<void(double)> progress;
};

struct SolidStats {
  std::array<int, 3> planes{};        // axis-aligned plane clusters per axis
  std::array<int, 3> cells{};         // grid cells per axis
  int slopes = 0;                     // planes sloped along one axis
  int slopesAsWedges = 0;             // of those, shown by wedge cells
  long long slopeBoundaries = 0;      // boundaries added so that slopes run corner to corner
  long long materialBoundaries = 0;   // boundaries added to separate faces of different materials
  double conflictAreaM2 = 0;          // faces shown in another material than their own (last build)
  long long solidCells = 0;
  long long wedgeCells = 0;
  int quadrics = 0;                   // quarter-round pieces found (quarter cylinders)
  int quadricsAsCells = 0;            // of those, shown by quadric cells
  int quadricsAsSubBlocks = 0;        // of those, shown by a block of their own (cut by other boundaries)
  long long quadricCells = 0;         // quarter-cylinder and inverse quarter-cylinder cells
  int sphereOctants = 0;              // sphere-octant pieces found (quarters of domes)
  int sphereOctantsAsCells = 0;       // of those, shown by sphere-octant cells (a cell or a sub-block)
  long long sphereOctantCells = 0;    // sphere-octant and inverse sphere-octant cells
  int cornerSlopes = 0;               // corner-slope pieces found (triangles cutting a box corner)
  int cornerSlopesAsCells = 0;        // of those, shown by pyramid cells (a cell or a sub-block)
  int cornerSlopesAsSubBlocks = 0;    // of those, shown by a block of their own (cut by other boundaries)
  long long pyramidCells = 0;         // pyramid and inverse pyramid cells
  long long planeCells = 0;           // plane cells fitted to the complementary mesh (plane_fit.hpp)
  long long twoPlaneCells = 0;        // of those, with two planes (a ridge, hip or valley)
  long long trimmedCells = 0;         // cut by the complementary mesh and not inside all over: empty
  long long planeBoundaries = 0;      // boundaries added at the corners of planes the mesh shows (plane cells)
  long long trimBoundaries = 0;       // boundaries added to keep the solid part of such cells (under a roof left to the mesh)
  int gridBuilds = 0;                 // grids built: again for boundaries added, or without a slope given up
  int gridsClassified = 0;            // of those, the ones whose occupancy was computed (the rest gave up
                                      // a slope or round piece first)
  long long columns = 0;              // lines of cells along the sweep axis
  long long windingColumns = 0;       // of those, decided by winding numbers (all, on an open surface)
  long long windingEvaluations = 0;
  long long ambiguousCells = 0;       // needed the extra samples
  int sweepAxis = 0;
  double areaM2 = 0;                  // whole mesh
  double nutAreaM2 = 0;               // shown by grid cells (axis-aligned faces, wedges, pyramids, quadrics)
  double complementAreaM2 = 0;        // left to the complementary mesh
  double hiddenAreaM2 = 0;            // between two solid cells: inner faces nobody sees
  double drawnTwiceAreaM2 = 0;        // of nutAreaM2, also drawn by the complementary mesh (faces
                                      // given to it whole rather than in many pieces)
  // Seconds per step: planes and grid, occupancy, wedges, materials; the winding-number tree is
  // built within the first step that needs it (treeSeconds of it).
  double planesSeconds = 0, treeSeconds = 0, occupancySeconds = 0, wedgesSeconds = 0, materialsSeconds = 0;
};

struct SolidGrid {
  glm::dvec3 originM{0.0};            // world position of the block's minimum corner
  Block block;                        // boundaries relative to originM, on the millimetre grid
  // What block's redirection cells show: Redirection::target indexes this list (quarter-round
  // pieces cut by boundaries from elsewhere). buildHierarchy adds them and renumbers the targets.
  std::vector<Block> subBlocks;
  std::vector<Material> materials;    // cells index into these (the mesh's materials)
  TriangleMesh complement;                    // world coordinates, the mesh's materials
  SolidStats stats;
};

// Converts one building. Errors: a mesh without triangles, or a grid above options.maxCells
// (the message gives the grid size and suggests a larger tolerance).
Result<SolidGrid> buildSolidGrid(const TriangleMesh& mesh, const SolidOptions& options = {});

}  // namespace nut::converter
