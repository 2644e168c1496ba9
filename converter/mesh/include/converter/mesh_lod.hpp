// converter/mesh_lod.hpp — levels of detail of a complementary mesh, for far views: the mesh
// decimated with OpenMesh's decimater at growing error tolerances, each level with the geometric
// error measured against the mesh (a renderer draws the coarsest level whose error spans under a
// pixel, as the HNI's visual summaries stand in for far blocks).
//
// Each level is decimated from the mesh itself (not from the level before): halfedge collapses in
// the order of OpenMesh's quadric error (ModQuadricT), each allowed only while the kept vertex lies
// within the level's tolerance of the removed one's face planes (a quadric error under its
// square), every vertex removed so far stays within the tolerance of the new surface
// (ModHausdorffT), no face turns over (ModNormalFlippingT), and a face is left around the kept
// vertex (so that no small piece vanishes). A vertex where faces of different materials meet is
// kept (locked), so colour regions keep their outlines; faces the decimater cannot take
// (non-manifold ones) are kept as they are in every level. A level is kept only when it has at
// most kLevelShrink times the triangles of the one before it.
//
// The error of a level is measured, not taken from the tolerance: the largest distance from a
// point of either surface (vertices, edge midpoints and face centroids) to the other, found with
// CGAL's AABB tree.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include <nut/triangle_mesh.hpp>

namespace nut::converter {

struct MeshLevel {
  TriangleMesh mesh;
  double errorM = 0;  // measured, both ways: see above
};

struct MeshLodOptions {
  double firstToleranceM = 0.05;  // the first level's tolerance; each next one is `factor` times it
  double factor = 4.0;
  int maxLevels = 3;
};

inline constexpr double kLevelShrink = 0.75;

// The coarser levels of `mesh`, finest first (the mesh itself is not among them); none when
// decimation does not shrink it enough.
std::vector<MeshLevel> meshLevels(const TriangleMesh& mesh, const MeshLodOptions& options = {});

// The points a distance between surfaces is measured at: each triangle's vertices, edge midpoints
// and centroid.
std::vector<glm::dvec3> surfaceSamples(const TriangleMesh& mesh);

// The largest distance (metres) from surfaceSamples(from) to the surface of `to`: the error of a
// level `to` of `from`, one way. Infinity when `to` has no triangles and `from` has.
double surfaceDistance(const TriangleMesh& from, const TriangleMesh& to);

}  // namespace nut::converter
