// Yaw alignment: the dominant orientation, the turns between frames, and the wrapping root block
// (converter/align.hpp).
#include <converter/align.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <nut/format.hpp>

namespace nut::converter {

namespace {

constexpr double kQuarterTurn = std::numbers::pi / 2;
// The window must hold more than one angle even at --angle-tolerance 0, where the faces of one
// wall still differ by float noise.
constexpr double kMinHalfWindowRad = 0.01 * std::numbers::pi / 180;

struct Orientation {
  double angle;   // of the face's horizontal normal, yaw convention, modulo a quarter turn: [0, pi/2)
  double weight;  // area projected onto a vertical plane
};

struct Window {
  double weight = 0;
  double meanAngle = 0;
};

// The faces within `halfWidth` of `centre` (modulo a quarter turn): their weight and mean angle.
Window around(const std::vector<Orientation>& faces, double centre, double halfWidth) {
  Window w;
  double sum = 0;
  for (const Orientation& o : faces) {
    const double d = std::remainder(o.angle - centre, kQuarterTurn);
    if (std::abs(d) > halfWidth) continue;
    w.weight += o.weight;
    sum += o.weight * d;
  }
  w.meanAngle = w.weight > 0 ? centre + sum / w.weight : centre;
  return w;
}

}  // namespace

std::uint16_t dominantYaw(const TriangleMesh& mesh, double angleToleranceDeg) {
  std::vector<Orientation> faces;
  faces.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t[0]];
    const glm::dvec3 n = glm::cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a);  // twice the area
    const double horizontal = std::hypot(n.x, n.z);
    if (horizontal <= 1e-9 * glm::length(n)) continue;  // flat: no orientation
    // x turned by yaw y points along (cos y, 0, -sin y).
    double angle = std::fmod(std::atan2(-n.z, n.x), kQuarterTurn);
    if (angle < 0) angle += kQuarterTurn;
    faces.push_back({std::min(angle, std::nextafter(kQuarterTurn, 0.0)), 0.5 * horizontal});
  }
  if (faces.empty()) return 0;
  std::sort(faces.begin(), faces.end(), [](const Orientation& l, const Orientation& r) { return l.angle < r.angle; });

  // The window of width twice the tolerance holding the most weight, over the circle of quarter
  // turns (two pointers over the sorted angles, the second running on into the next turn).
  const double halfWidth = std::max(angleToleranceDeg * std::numbers::pi / 180, kMinHalfWindowRad);
  const std::size_t n = faces.size();
  const auto unwrapped = [&](std::size_t j) { return faces[j % n].angle + (j >= n ? kQuarterTurn : 0.0); };
  std::size_t end = 0, bestStart = 0;
  double weight = 0, bestWeight = -1;
  for (std::size_t start = 0; start < n; ++start) {
    while (end < start + n && unwrapped(end) - faces[start].angle <= 2 * halfWidth) weight += faces[end++ % n].weight;
    if (weight > bestWeight) {
      bestWeight = weight;
      bestStart = start;
    }
    weight -= faces[start].weight;
  }
  // Centred on its faces' mean angle, twice, so the window settles on them.
  Window best = around(faces, faces[bestStart].angle + halfWidth, halfWidth);
  best = around(faces, best.meanAngle, halfWidth);
  const double yaw = std::remainder(best.meanAngle, kQuarterTurn);
  // A building whose axes already gather as much area keeps them.
  if (std::abs(yaw) > halfWidth && around(faces, 0.0, halfWidth).weight >= best.weight) return 0;
  const long steps = std::lround(yaw / (2 * std::numbers::pi) * format::kYawSteps);
  return static_cast<std::uint16_t>((steps + format::kYawSteps) % format::kYawSteps);
}

double yawDegrees(std::uint16_t yaw) {
  const int signedSteps = yaw > format::kYawSteps / 2 ? yaw - format::kYawSteps : yaw;
  return 360.0 * signedSteps / format::kYawSteps;
}

void toAlignedFrame(TriangleMesh& mesh, const YawFrame& frame) {
  const glm::dmat3 inverse = glm::transpose(rotationMatrix(Rotation{0, frame.yaw}));
  for (glm::dvec3& p : mesh.positions) p = inverse * (p - frame.pivotM);
}

void toWorldFrame(TriangleMesh& mesh, const YawFrame& frame) {
  const glm::dmat3 r = rotationMatrix(Rotation{0, frame.yaw});
  for (glm::dvec3& p : mesh.positions) p = frame.pivotM + r * p;
}

glm::dvec3 wrapInWorldFrame(Hierarchy& hierarchy, const glm::dvec3& alignedOriginM, const YawFrame& frame) {
  const glm::dmat3 r = rotationMatrix(Rotation{0, frame.yaw});
  const glm::dvec3 size = hierarchy.blocks[hierarchy.root].sizeM();
  const glm::dvec3 origin = frame.pivotM + r * alignedOriginM;  // the old root's origin in the world
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner = origin + r * (size * glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
    lo = glm::min(lo, corner);
    hi = glm::max(hi, corner);
  }
  // The offset is whole millimetres and the new root's origin (a double in the PNG's text) takes
  // the rest, so the building lands exactly where it was; the millimetre of margin on each side
  // absorbs that rounding.
  constexpr double mm = format::kMetresPerUnit;
  std::array<std::vector<double>, 3> sizes;
  for (int a = 0; a < 3; ++a) sizes[a] = {(std::ceil((hi[a] - lo[a]) / mm - 1e-6) + 2) * mm};
  const glm::dvec3 offset = glm::round((origin - lo) / mm + 1.0) * mm;
  Block root = Block::fromSizes(sizes);
  root.redirections.push_back({hierarchy.root, offset, Rotation{0, frame.yaw}, {false, false, false}});
  root.cells[0] = Cell::redirect(0);
  hierarchy.root = hierarchy.addBlock(std::move(root));
  return origin - offset;
}

}  // namespace nut::converter
