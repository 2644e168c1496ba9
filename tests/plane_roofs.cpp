#include "plane_roofs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

namespace nut::testing {

namespace {

double planeDepth(const CutPlane& p, const glm::dvec3& x) { return p.offsetM - glm::dot(p.normal, x); }

double cutDepth(const PlaneCut& cut, const glm::dvec3& x) {
  const double a = planeDepth(cut.planes[0], x), b = planeDepth(cut.planes[1], x);
  return cut.combine == PlaneCombine::Both ? std::min(a, b) : std::max(a, b);
}

}  // namespace

double PlaneRoof::depthInside(const glm::dvec3& p) const {
  double d = cutDepth(cut, p);
  for (int a = 0; a < 3; ++a) d = std::min({d, p[a] - lo[a], hi[a] - p[a]});
  return d;
}

PlaneRoof planeRoofHouse(PlaneCombine combine, double ridgeYawDeg, double pitchDeg) {
  PlaneRoof roof;
  roof.h.materials = {{190, 180, 170, 255, 0}, {170, 60, 50, 255, 0}, {60, 70, 160, 255, 0}};
  // x: 1 m margin, unequal cells over [1, 9]; y: floor layer, walls to the eaves at 4 m, roof
  // layers to 7 m, 1 m above; z: as x over [1, 7].
  const std::array<std::vector<double>, 3> bounds{std::vector<double>{0, 1, 2.3, 3.1, 4.9, 5.05, 6.2, 7.5, 9, 10},
                                                  std::vector<double>{0, 1, 2.5, 4, 4.8, 5.5, 6.3, 7, 8},
                                                  std::vector<double>{0, 1, 1.7, 3.3, 4.0, 5.6, 7, 8}};
  std::array<std::vector<double>, 3> sizes;
  for (int a = 0; a < 3; ++a)
    for (std::size_t i = 1; i < bounds[a].size(); ++i) sizes[a].push_back(bounds[a][i] - bounds[a][i - 1]);
  Block b = Block::fromSizes(sizes);
  roof.eaves = 4.0;
  const double yaw = ridgeYawDeg * std::numbers::pi / 180.0, slope = std::tan(pitchDeg * std::numbers::pi / 180.0);
  const glm::dvec3 across{-std::sin(yaw), 0.0, std::cos(yaw)};  // horizontal, perpendicular to the ridge
  const glm::dvec3 centre{5.0, combine == PlaneCombine::Both ? 6.5 : 4.2, 4.0};
  // Plane s: y - centre.y + s * slope * (across . (x - centre)) <= 0 for a ridge, >= for a valley's
  // rising sides, written as dot(n, x) <= offset with n of unit length.
  roof.cut.combine = combine;
  for (int s = 0; s < 2; ++s) {
    const double sign = (s == 0 ? 1.0 : -1.0) * (combine == PlaneCombine::Both ? 1.0 : -1.0);
    const glm::dvec3 n{sign * slope * across.x, 1.0, sign * slope * across.z};
    const double length = glm::length(n);
    roof.cut.planes[static_cast<std::size_t>(s)] = {n / length, glm::dot(n, centre) / length};
  }
  // The first plane's surface shows a material of its own; the second shows its cell's.
  roof.cut.surfaceMaterials = {std::uint16_t{2}, std::nullopt};
  roof.lo = {1.0, 1.0, 1.0};
  roof.hi = {9.0, 7.0, 7.0};
  b.cuts.push_back(roof.cut);
  const glm::ivec3 n{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
  for (int z = 1; z + 1 < n.z; ++z)
    for (int y = 1; y + 1 < n.y; ++y)
      for (int x = 1; x + 1 < n.x; ++x) {
        const auto material = static_cast<std::uint16_t>((x + z) % 2);
        if (b.boundsM[1][static_cast<std::size_t>(y) + 1] <= roof.eaves) {
          b.cell(x, y, z) = Cell::box(material);
          continue;
        }
        // Per plane: corners inside (depth >= 0) and outside.
        std::array<int, 2> inside{0, 0};
        for (int c = 0; c < 8; ++c) {
          const glm::dvec3 corner{b.boundsM[0][static_cast<std::size_t>(x + (c & 1))],
                                  b.boundsM[1][static_cast<std::size_t>(y + (c >> 1 & 1))],
                                  b.boundsM[2][static_cast<std::size_t>(z + (c >> 2 & 1))]};
          for (std::size_t p = 0; p < 2; ++p) inside[p] += planeDepth(roof.cut.planes[p], corner) >= 0;
        }
        const bool full =
            combine == PlaneCombine::Both ? inside[0] == 8 && inside[1] == 8 : inside[0] == 8 || inside[1] == 8;
        const bool none =
            combine == PlaneCombine::Both ? inside[0] == 0 || inside[1] == 0 : inside[0] == 0 && inside[1] == 0;
        if (full)
          b.cell(x, y, z) = Cell::box(material);
        else if (!none)
          b.cell(x, y, z) = Cell::planeCell(0, 2);
      }
  roof.h.addBlock(std::move(b));
  return roof;
}

}  // namespace nut::testing
