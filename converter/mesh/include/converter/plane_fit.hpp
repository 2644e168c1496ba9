// converter/plane_fit.hpp — plane cells from the complementary mesh (HNI version 3).
//
// After the solid grid is built, the faces it could not show (hips and valleys across cells,
// faces sloped along all three axes, walls at odd angles) are the complementary mesh. A cell of
// the grid becomes a plane cell (nut/plane_cells.hpp) when
//   - the complementary faces crossing it lie on one or two planes (normals within the angle
//     tolerance, points within the tolerance; plane_clusters.hpp), one material per plane,
//   - on each plane they cover the cut's surface in the cell (the area of the faces' parts in the
//     cell is that surface's, within the tolerance along its outline): no face ends inside it,
//   - axis-aligned faces lying on the cell's sides (within the tolerance) lie where the cut leaves
//     the side solid, all in one material, which the box's sides then show,
//   - the mesh's winding number agrees with the cut at sample points of the cell (3 x 3 x 3, each
//     farther than twice the tolerance from the planes), for one plane, or for two combined as a
//     ridge (inside both) or as a valley (inside either).
// The cell's material is its box's sides'; a plane whose faces have another shows it as the cut's
// surface material. Only empty cells and boxes become plane cells; a box all of whose faces lie on
// its sides stays as it is. A face's parts in the cells that fit leave the mesh, and its parts in
// the other cells stay as polygons clipped to those cells (a roof pitch whose cell at the ridge's
// end meets a third plane keeps only that cell's part as mesh); a face with no part in a cell
// that fits stays whole. A part narrower than the tolerance (area at most half the tolerance
// times its perimeter) neither needs its cell to fit nor stays, unless all of its face is that
// narrow (a sliver), which leaves only where every cell it touches fits. A face reaching beyond
// the grid by more than the tolerance stays whole, and no cell it crosses is taken.
#pragma once

#include <nut/triangle_mesh.hpp>

#include <converter/solid.hpp>

namespace nut::converter {

struct PlaneFitStats {
  long long candidateCells = 0;  // cells the complementary mesh crosses
  long long planeCells = 0;      // of those, made plane cells
  long long twoPlaneCells = 0;   // of those, with two planes (a ridge, hip or valley)
  double drawnTwiceM2 = 0;       // surface of faces that left the mesh where boxes showed them already
  double complementLeftM2 = 0;   // the complementary mesh's surface after fitting
};

// Fits plane cells to `grid` (its block and complementary mesh change). `inside` is the surface
// whose winding number decides what is solid: the building (or, for a part, the whole building).
PlaneFitStats fitPlaneCells(SolidGrid& grid, const TriangleMesh& inside, const SolidOptions& options);

}  // namespace nut::converter
