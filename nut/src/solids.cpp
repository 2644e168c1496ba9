// nut/src/solids.cpp — the 69 cell solids (paper section 4.2): catalogue, inside test, ray
// intersection, volume.
//
// Every solid is the unit cube intersected with a region P, or (inverse groups) the cube minus P.
// P is written in primed coordinates q, the distances from the solid's oriented edge or corner:
// per unit-cube axis i, q_i = p_i (sign +1), q_i = 1 - p_i (sign -1), or q_i = 0 (sign 0) on the
// axis P does not depend on (the extrusion axis of wedges and quarter cylinders). So
// q = sign * p + offset, and P is  sum(q) <= 1  (half-space) or  dot(q, q) <= 1  (ball; a
// cylinder when one axis is unused) for every orientation; a gradient with respect to q maps back
// to the cube by one multiplication with sign. The box is the half-space with no axis (0 <= 1
// everywhere), so it needs no case of its own.
//
// The float instantiation of intersectSolid is mirrored by the GLSL ray caster; the double one is
// the reference. Both solve from the cube entry point, where all terms are of order one.
#include <nut/solids.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace nut {
namespace {

// The shape of P.
enum class Region : std::uint8_t {
  HalfSpace,  // sum(q) <= 1
  Ball,       // dot(q, q) <= 1
};

struct GroupInfo {
  SolidGroup group;
  int first;       // catalogue index of orientation 0
  int count;       // number of orientations
  bool edgeBased;  // orientation = axis * 4 + corner; otherwise orientation = corner bits
  Region region;
  bool inverse;    // the solid is the cube minus P, not the cube intersected with P
  const char* name;
  double volume;
};

constexpr double kPi = std::numbers::pi;

// Indexed by SolidGroup. The first indices are the file format's numbering (solids.hpp).
constexpr std::array<GroupInfo, 8> kGroups{{
    {SolidGroup::Box, 0, 1, false, Region::HalfSpace, false, "box", 1.0},
    {SolidGroup::Wedge, 1, 12, true, Region::HalfSpace, false, "wedge", 1.0 / 2},
    {SolidGroup::Pyramid, 13, 8, false, Region::HalfSpace, false, "pyramid", 1.0 / 6},
    {SolidGroup::InversePyramid, 21, 8, false, Region::HalfSpace, true, "inverse-pyramid",
     5.0 / 6},
    {SolidGroup::QuarterCylinder, 29, 12, true, Region::Ball, false, "quarter-cylinder", kPi / 4},
    {SolidGroup::InverseQuarterCylinder, 41, 12, true, Region::Ball, true,
     "inverse-quarter-cylinder", 1 - kPi / 4},
    {SolidGroup::SphereOctant, 53, 8, false, Region::Ball, false, "octant", kPi / 6},
    {SolidGroup::InverseSphereOctant, 61, 8, false, Region::Ball, true, "inverse-octant",
     1 - kPi / 6},
}};

constexpr bool groupsTileCatalogue() {
  int next = 0;
  for (std::size_t g = 0; g < kGroups.size(); ++g) {
    if (static_cast<std::size_t>(kGroups[g].group) != g || kGroups[g].first != next) return false;
    next += kGroups[g].count;
  }
  return next == kSolidCount;
}
static_assert(groupsTileCatalogue(), "groups must be in SolidGroup order and cover 0..68");

constexpr std::size_t groupOf(int index) {
  std::size_t g = 0;
  while (g + 1 < kGroups.size() && kGroups[g + 1].first <= index) ++g;
  return g;
}

struct Shape {
  Region region = Region::HalfSpace;
  bool inverse = false;
  std::array<int, 3> sign{};  // per unit-cube axis: q = p (+1), q = 1 - p (-1), q = 0 (0)
};

constexpr Shape makeShape(int index) {
  const GroupInfo& info = kGroups[groupOf(index)];
  const int orientation = index - info.first;
  Shape shape{info.region, info.inverse, {}};
  if (info.group == SolidGroup::Box) return shape;
  // A set corner bit puts the shape's edge or corner at 1 on that axis: q measures from there.
  const auto signOf = [](int corner, int bit) { return ((corner >> bit) & 1) != 0 ? -1 : 1; };
  if (info.edgeBased) {
    const int axis = orientation / 4, corner = orientation % 4;
    shape.sign[(axis + 1) % 3] = signOf(corner, 0);  // u
    shape.sign[(axis + 2) % 3] = signOf(corner, 1);  // v
  } else {
    for (int i = 0; i < 3; ++i) shape.sign[i] = signOf(orientation, i);
  }
  return shape;
}

constexpr std::array<Shape, kSolidCount> kShapes = [] {
  std::array<Shape, kSolidCount> shapes{};
  for (int i = 0; i < kSolidCount; ++i) shapes[i] = makeShape(i);
  return shapes;
}();

const Shape& shapeOf(Solid s) {
  assert(s.index < kSolidCount);
  return kShapes[s.index];
}

template <typename T>
using Vec = glm::vec<3, T>;

template <typename T>
Vec<T> signVec(const Shape& shape) {
  return {T(shape.sign[0]), T(shape.sign[1]), T(shape.sign[2])};
}

template <typename T>
Vec<T> offsetVec(const Shape& shape) {
  return {T(shape.sign[0] < 0), T(shape.sign[1] < 0), T(shape.sign[2] < 0)};
}

// P is {regionValue(q) <= 1}.
template <typename T>
T regionValue(Region region, const Vec<T>& q) {
  return region == Region::HalfSpace ? q.x + q.y + q.z : glm::dot(q, q);
}

// Outward unit normal of P at the surface point with primed coordinates q, in unit-cube axes.
template <typename T>
Vec<T> regionNormal(const Shape& shape, const Vec<T>& q) {
  const Vec<T> sign = signVec<T>(shape);
  return glm::normalize(shape.region == Region::HalfSpace ? sign : sign * q);
}

// The parameters [lo, hi] where the ray q0 + s * qd lies in P; empty when lo > hi.
template <typename T>
struct Interval {
  T lo, hi;
};

template <typename T>
constexpr Interval<T> kEverything{-std::numeric_limits<T>::infinity(),
                                  std::numeric_limits<T>::infinity()};
template <typename T>
constexpr Interval<T> kNothing{std::numeric_limits<T>::infinity(),
                               -std::numeric_limits<T>::infinity()};

template <typename T>
Interval<T> halfSpaceInterval(const Vec<T>& q0, const Vec<T>& qd) {
  const T c0 = q0.x + q0.y + q0.z - 1;  // sum(q) - 1 = c0 + s * c1
  const T c1 = qd.x + qd.y + qd.z;
  if (c1 == 0) return c0 <= 0 ? kEverything<T> : kNothing<T>;  // parallel to the plane
  const T root = -c0 / c1;
  return c1 > 0 ? Interval<T>{-std::numeric_limits<T>::infinity(), root}
                : Interval<T>{root, std::numeric_limits<T>::infinity()};
}

// dot(q, q) - 1 = a s^2 + 2 b s + c.
template <typename T>
Interval<T> ballInterval(const Vec<T>& q0, const Vec<T>& qd) {
  const T a = glm::dot(qd, qd);
  const T c = glm::dot(q0, q0) - 1;
  // Moving along the cylinder axis: inside everywhere or nowhere. Also catches an underflowed a.
  if (a == 0) return c <= 0 ? kEverything<T> : kNothing<T>;
  const T b = glm::dot(q0, qd);
  // b^2 - a c = a - |q0 x qd|^2 (Lagrange's identity). The right side does not subtract the
  // nearly equal b^2 and a c, which grow with |q0|^2: accurate even for q0 far from the cell.
  const Vec<T> m = glm::cross(q0, qd);
  const T discriminant = a - glm::dot(m, m);
  if (discriminant < 0) return kNothing<T>;
  // Both roots without subtracting nearly equal numbers: h / a and c / h.
  const T h = -(b + std::copysign(std::sqrt(discriminant), b));
  if (h == 0) return {0, 0};  // b = 0 and a tangent ray: the double root is at s = 0
  const T r0 = h / a, r1 = c / h;
  return {std::min(r0, r1), std::max(r0, r1)};
}

// Outward normal of the cube face the ray entered through at the point entry (see solids.hpp).
template <typename T>
Vec<T> entryNormal(const Vec<T>& origin, const Vec<T>& dir, const Vec<T>& entry, T tEnter) {
  const bool originInside = origin.x > 0 && origin.x < 1 && origin.y > 0 && origin.y < 1 &&
                            origin.z > 0 && origin.z < 1;
  if (tEnter <= 0 && originInside) return -glm::normalize(dir);
  // Of the faces the ray moves into the cube through, the one whose plane is nearest to the
  // entry point; robust for entries through edges and corners (any of the faces is right).
  int axis = 0;
  T nearest = std::numeric_limits<T>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (dir[i] == 0) continue;
    const T plane = dir[i] > 0 ? T(0) : T(1);
    const T distance = std::abs(entry[i] - plane);
    if (distance < nearest) {
      nearest = distance;
      axis = i;
    }
  }
  Vec<T> normal(0);
  normal[axis] = dir[axis] > 0 ? T(-1) : T(1);
  return normal;
}

}  // namespace

SolidGroup solidGroup(Solid s) {
  assert(s.index < kSolidCount);
  return kGroups[groupOf(s.index)].group;
}

int solidOrientation(Solid s) { return s.index - kGroups[groupOf(s.index)].first; }

int groupOrientationCount(SolidGroup g) { return kGroups[static_cast<std::size_t>(g)].count; }

Solid makeSolid(SolidGroup g, int orientation) {
  const GroupInfo& info = kGroups[static_cast<std::size_t>(g)];
  assert(orientation >= 0 && orientation < info.count);
  return Solid{static_cast<std::uint8_t>(info.first + orientation)};
}

std::string solidName(Solid s) {
  const GroupInfo& info = kGroups[groupOf(s.index)];
  if (info.group == SolidGroup::Box) return info.name;
  int corner = solidOrientation(s);
  std::string name = info.name;
  if (info.edgeBased) {
    name += '-';
    name += "xyz"[corner / 4];
    corner %= 4;
  }
  return name + "-c" + std::to_string(corner);
}

double solidVolume(Solid s) { return kGroups[groupOf(s.index)].volume; }

bool solidContains(Solid s, const glm::dvec3& p) {
  const bool inCube = p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1 && p.z >= 0 && p.z <= 1;
  if (!inCube) return false;  // also rejects NaN
  const Shape& shape = shapeOf(s);
  const double value =
      regionValue(shape.region, signVec<double>(shape) * p + offsetVec<double>(shape));
  // The surface value == 1 belongs to both a solid and its inverse: exact, no epsilon needed.
  return shape.inverse ? value >= 1 : value <= 1;
}

Coverage solidCoverage(Solid s, const glm::dvec3& lo, const glm::dvec3& hi, double epsilon) {
  const Shape& shape = shapeOf(s);
  // Each primed coordinate is p or 1 - p, so the box maps to a box in q, and the region value
  // grows with every q (q >= 0): its least and greatest values are at two opposite corners.
  const glm::dvec3 a = signVec<double>(shape) * lo + offsetVec<double>(shape);
  const glm::dvec3 b = signVec<double>(shape) * hi + offsetVec<double>(shape);
  const double least = regionValue(shape.region, glm::min(a, b)), greatest = regionValue(shape.region, glm::max(a, b));
  const bool inP = greatest <= 1 + epsilon, outOfP = least >= 1 - epsilon;
  if (!inP && !outOfP) return Coverage::Part;
  return inP != shape.inverse ? Coverage::All : Coverage::None;
}

template <typename T>
std::optional<SolidHit<T>> intersectSolid(Solid s, const glm::vec<3, T>& origin,
                                          const glm::vec<3, T>& dir, T tEnter, T tExit) {
  if (!(tEnter <= tExit)) return std::nullopt;  // also rejects NaN
  const Shape& shape = shapeOf(s);
  // Solve for at = t - tEnter from the entry point: the origin may be far from the cell (a camera
  // seen from a 1 cm cell), and terms of the origin's size cost float roots several times their
  // precision there.
  const Vec<T> entry = origin + tEnter * dir;
  const T length = tExit - tEnter;
  const Vec<T> sign = signVec<T>(shape);
  const Vec<T> q0 = sign * entry + offsetVec<T>(shape);
  const Vec<T> qd = sign * dir;
  const Interval<T> inP = shape.region == Region::HalfSpace ? halfSpaceInterval(q0, qd)
                                                              : ballInterval(q0, qd);

  // The hit at tEnter + at, which may round past tExit. At tEnter the normal is the entry face's
  // (solids.hpp), also when P's surface passes through the entry point; elsewhere it is P's, with
  // the inverse solid on the other side of P's surface.
  const auto hitAt = [&](T at, T side) {
    const T t = std::min(tEnter + at, tExit);
    const Vec<T> normal = t == tEnter ? entryNormal(origin, dir, entry, tEnter)
                                      : side * regionNormal(shape, q0 + at * qd);
    return SolidHit<T>{t, normal};
  };

  if (!shape.inverse) {
    const T at = std::max(T(0), inP.lo);
    if (at <= std::min(length, inP.hi)) return hitAt(at, T(1));
    return std::nullopt;
  }
  if (inP.lo > 0 || inP.hi < 0) return hitAt(0, T(-1));
  if (inP.hi <= length) return hitAt(inP.hi, T(-1));
  return std::nullopt;
}

template std::optional<SolidHit<float>> intersectSolid(Solid, const glm::vec3&, const glm::vec3&,
                                                       float, float);
template std::optional<SolidHit<double>> intersectSolid(Solid, const glm::dvec3&,
                                                        const glm::dvec3&, double, double);

}  // namespace nut
