// Triangles grouped into planes (plane_clusters.hpp).
#include "plane_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include <glm/geometric.hpp>

namespace nut::converter {

std::vector<int> clusterPlanes(std::span<const std::array<glm::dvec3, 3>> triangles, double cosAngle, double tol,
                               std::vector<ClusterPlane>& planes) {
  std::vector<glm::dvec3> areaVectors(triangles.size());
  std::vector<double> areas(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& [p0, p1, p2] = triangles[t];
    areaVectors[t] = 0.5 * glm::cross(p1 - p0, p2 - p0);
    areas[t] = glm::length(areaVectors[t]);
  }
  std::vector<std::uint32_t> order(triangles.size());
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return areas[a] > areas[b]; });
  std::vector<int> planeOf(triangles.size(), -1);
  for (const std::uint32_t t : order) {
    if (!(areas[t] > 0)) continue;
    const glm::dvec3 n = areaVectors[t] / areas[t];
    for (std::size_t k = 0; k < planes.size() && planeOf[t] < 0; ++k) {
      const ClusterPlane& q = planes[k];
      if (glm::dot(q.normal, n) < cosAngle) continue;
      bool near = true;
      for (const glm::dvec3& p : triangles[t]) near = near && std::abs(glm::dot(q.normal, p) - q.offset) <= tol;
      if (near) planeOf[t] = static_cast<int>(k);
    }
    if (planeOf[t] < 0) {
      planeOf[t] = static_cast<int>(planes.size());
      planes.push_back({n, glm::dot(n, triangles[t][0]), 0.0});
    }
    planes[static_cast<std::size_t>(planeOf[t])].area += areas[t];
  }
  return planeOf;
}

}  // namespace nut::converter
