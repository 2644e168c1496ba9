// converter/plane_fit.hpp — plane cells from the complementary mesh (HNI version 3).
//
// After the solid grid is built, the faces it could not show (hips and valleys across cells,
// faces sloped along all three axes, walls at odd angles) are the complementary mesh. A cell of
// the grid becomes a plane cell (nut/plane_cells.hpp) when
//   - the complementary faces crossing it lie on one or two planes (normals within the angle
//     tolerance, points within the tolerance) and share one material,
//   - on each plane they cover the cut's surface in the cell (the area of the faces' parts in the
//     cell is that surface's, within the tolerance along its outline): no face ends inside it,
//   - the mesh's winding number agrees with the cut at sample points of the cell (3 x 3 x 3, each
//     farther than twice the tolerance from the planes), for one plane, or for two combined as a
//     ridge (inside both) or as a valley (inside either).
// The faces' parts in such cells leave the complementary mesh, which keeps the rest of each face
// as convex pieces. Only empty cells (what the occupancy makes of most cells a face cuts) and boxes
// of the faces' material become plane cells: a plane cell shows one material on its cut and on its
// box's faces alike. A triangle whose part in a cell is less than the tolerance squared (it only
// touches the cell) does not count there.
#pragma once

#include <nut/triangle_mesh.hpp>

#include <converter/solid.hpp>

namespace nut::converter {

struct PlaneFitStats {
  long long candidateCells = 0;  // cells the complementary mesh crosses
  long long planeCells = 0;      // of those, made plane cells
  long long twoPlaneCells = 0;   // of those, with two planes (a ridge, hip or valley)
  double areaM2 = 0;             // surface moved from the complementary mesh to plane cells
};

// Fits plane cells to `grid` (its block and complementary mesh change). `inside` is the surface
// whose winding number decides what is solid: the building (or, for a part, the whole building).
PlaneFitStats fitPlaneCells(SolidGrid& grid, const TriangleMesh& inside, const SolidOptions& options);

}  // namespace nut::converter
