// nut/mesh_export.hpp — NUT -> triangle mesh: the solid the ray caster sees, as triangles.
//
// exportMesh walks the whole DAG from the root and emits, in world coordinates, the boundary of
// every solid cell and plane cell: planar faces exactly (a plane cell is its box clipped by its
// planes, a valley three convex pieces whose shared caps are dropped), quadric surfaces (quarter
// cylinders, sphere octants and their inverses) tessellated with every vertex on the surface and
// a chord error within the tolerance. Redirections follow the model's semantics (hierarchy.hpp, docs/FORMAT.md
// "Redirection record"): the target is placed at the offset, rotated, repeated along its wrapped
// axes and clipped by the redirecting cell and every ancestor cell; where a solid is cut, the cut
// is closed by a cap face on the clipping cell's boundary, because the ray caster sees solid
// material up to that face.
//
// The mesh is watertight: every cell contributes a closed surface (a cut cell's pieces and caps
// share their points bit for bit), and the only faces removed are matched pairs (below), so every
// directed edge occurs as often as its reverse, the signed volume is the solid's volume and the
// winding number is 1 inside, 0 outside. Where two cells touch without a culled pair, both cells'
// faces are kept (coplanar, opposite orientation): closed, but not a 2-manifold there.
//
// Interior faces culled (both faces of the pair are dropped): a face of a solid cell that lies on a
// face of its cell's box and covers that face completely, when the neighbouring cell across that
// face in the same block (or, along a wrapped axis, the first/last cell of the next tile of the
// same redirection) is a solid covering the opposite face completely, both cells are whole (not cut
// by any ancestor cell) and both materials are opaque. Full-face solids: the box on all six faces;
// wedges and quarter cylinders on the two faces at their right-angle edge; inverse quarter
// cylinders on the two faces opposite it; inverse pyramids and inverse octants on the three faces
// opposite their corner; pyramids, octants and plane cells on none. Faces between cells of different blocks
// (a sub-block next to its parent's cells), between different redirections' instances, at cut
// cells, and next to translucent cells are kept.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut {

struct MeshExportOptions {
  // Largest distance, in metres, between a quadric surface and its triangles (the chord error),
  // measured on the cell as stretched: a quarter cylinder in a 4 m x 2 m cell is tessellated for a
  // 4 m radius. The default is the format's own resolution (1 mm); at 1 cm the flat facets of a
  // 0.3 m column already shade visibly differently from the ray caster's exact normals.
  double toleranceM = 0.001;
  // Segments per quarter arc, whatever the tolerance asks for; above the maximum the tolerance is
  // not met (a 1 mm tolerance on a 16 km cell would need thousands).
  int minSegmentsPerQuarter = 2;
  int maxSegmentsPerQuarter = 256;
  // Guards against hostile files: exportMesh fails, naming the count, rather than exhausting
  // memory (every triangle costs about 40 bytes) or time (1000-fold wraps of 1000-fold wraps).
  std::size_t maxTriangles = 20'000'000;
  std::uint64_t maxCellVisits = 200'000'000;
  // Redirection levels below the root. The ray casters keep a stack of 32 levels and draw deeper
  // redirections as visual summaries, which have no geometry, so a deeper hierarchy is an error.
  int maxDepth = 31;
};


// The boundary of every solid cell of h, with the root block's minimum corner at originM and the
// world axes as the root block's axes. Identical points are welded, triangles turn counter-clockwise
// seen from outside, and the mesh's materials are h.materials (triangleMaterial indexes them). Checks h first (checkHierarchy). Fails, with the number
// that exceeded the limit, when the mesh would exceed options.maxTriangles, the walk
// options.maxCellVisits, or the nesting options.maxDepth.
Result<TriangleMesh> exportMesh(const Hierarchy& h, const glm::dvec3& originM, const MeshExportOptions& options = {});

// World bounding box of the solid content of h: the vertex bounds of its exported mesh, so that
// `nut render` of an HNI and `nut render-mesh` of its exported mesh fit the same default camera.
// Quadrics are tessellated coarsely here (their arcs end on the cell faces, which bound them). An
// HNI without any solid has the root block's box.
Result<WorldBox> contentBounds(const Hierarchy& h, const glm::dvec3& originM);

// Writes the mesh as Wavefront OBJ at objPath and its materials beside it (the same name with the
// extension .mtl, referenced by `mtllib`): material m is `newmtl m<m>` with Kd the sRGB bytes / 255
// and d the opacity / 255; triangles are grouped by material (`usemtl`). Both files are written to
// temporary siblings and renamed into place (the MTL first), so a failure never leaves a half-written
// file. Every material index of the mesh must be below mesh.materials.size().
Status writeObj(const std::string& objPath, const TriangleMesh& mesh);

}  // namespace nut
