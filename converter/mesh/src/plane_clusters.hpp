// converter/mesh/src/plane_clusters.hpp — triangles grouped into planes at any orientation, for
// plane cells: the grid's boundaries at the planes' corners (plane_corners.cpp) and the fitting of
// the cells (plane_fit.cpp) group faces the same way.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace nut::converter {

struct ClusterPlane {
  glm::dvec3 normal;  // unit, the first triangle's (outward on a mesh turned outwards)
  double offset;      // dot(normal, p) on the plane
  double area;        // of its triangles
};

// Triangles clustered into planes, largest first: a triangle joins the first plane whose normal is
// within the angle (cosAngle) and which all its corners lie within `tol` of. A plane is its first
// triangle's, so that every cell it crosses cuts exactly the same one. Returns each triangle's
// plane index; -1 for a triangle without area.
std::vector<int> clusterPlanes(std::span<const std::array<glm::dvec3, 3>> triangles, double cosAngle, double tol,
                               std::vector<ClusterPlane>& planes);

}  // namespace nut::converter
