// Boundaries at the corners of the planes that the complementary mesh shows (solid.hpp, step 3;
// SolidOptions::planeCells). A plane cell holds one or two planes whose faces cross it whole
// (plane_fit.hpp), so a cell where a planar face ends (the eaves corner of a hip roof, two walls
// at odd angles meeting, the apex of a pyramid roof) cannot be one, and neither can the face's
// other cells, since a face leaves the mesh only whole. The faces the grid leaves to the mesh are
// grouped into planes as the fitting groups them (plane_clusters.hpp), and every corner of a
// plane's outline becomes a boundary on all three axes: then the planes' corners are corners of
// cells, and the cells between them are crossed by one plane, or by two along the edge where they
// meet (a ridge, hip or valley).
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "plane_clusters.hpp"
#include "solid_builder.hpp"

namespace nut::converter::solid {

namespace {

// The complementary mesh's planes are not grouped above this many faces (the grouping compares
// each face with every plane so far), as in plane_fit.cpp.
constexpr std::size_t kMaxCornerFaces = 20000;

// The angle of a triangle at corner a.
double angleAt(const dvec3& a, const dvec3& b, const dvec3& c) {
  const dvec3 u = b - a, v = c - a;
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

}  // namespace

std::array<std::vector<double>, 3> Builder::proposePlaneCorners() const {
  std::array<std::vector<double>, 3> proposals;
  std::vector<std::uint32_t> members;
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    if (faces[f].area > 0 && shownByMesh(f)) members.push_back(f);
  if (members.empty() || members.size() > kMaxCornerFaces) return proposals;
  std::vector<std::array<dvec3, 3>> triangles(members.size());
  for (std::size_t i = 0; i < members.size(); ++i)
    triangles[i] = {corner(members[i], 0), corner(members[i], 1), corner(members[i], 2)};
  std::vector<ClusterPlane> planes;
  const std::vector<int> planeOf =
      clusterPlanes(triangles, std::cos(options.angleToleranceDeg * std::numbers::pi / 180.0), tol, planes);
  // The faces' angles at each (welded) vertex, per plane: a half turn is a point on a straight
  // edge of the plane's outline, a whole turn one inside it; anything else is a corner.
  std::map<std::pair<std::uint32_t, int>, double> turn;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const int plane = planeOf[i];
    // Planes too small to pay for their boundaries stay in the mesh, as small slopes do.
    if (plane < 0 || planes[static_cast<std::size_t>(plane)].area < kMinSlopeShare * stats.areaM2) continue;
    const auto& ids = cornerIds[members[i]];
    const auto& t = triangles[i];
    for (std::size_t k = 0; k < 3; ++k) turn[{ids[k], plane}] += angleAt(t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
  }
  const double straight = options.angleToleranceDeg * std::numbers::pi / 180.0;
  std::vector<std::pair<double, dvec3>> corners;  // the plane's area, the corner
  for (const auto& [key, angle] : turn)
    if (std::abs(angle - std::numbers::pi) > straight && std::abs(angle - 2 * std::numbers::pi) > straight)
      corners.emplace_back(planes[static_cast<std::size_t>(key.second)].area, p[key.first]);
  // The largest planes' corners first, within the slopes' budget of boundaries per axis.
  std::sort(corners.begin(), corners.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  if (corners.size() > kMaxSlopeBoundariesPerAxis) corners.resize(kMaxSlopeBoundariesPerAxis);
  for (const auto& [weight, q] : corners)
    for (int a = 0; a < 3; ++a) proposals[static_cast<std::size_t>(a)].push_back(q[a]);
  return proposals;
}

}  // namespace nut::converter::solid
