// nut/solids.hpp — the 69 cell solids: enumeration, inside test, ray intersection, volume.
//
// Every solid is a canonical shape in the unit cube [0,1]^3 plus an orientation; a cell's
// non-uniform size stretches it (a wedge in a 4 m x 2 m cell is a 26.6 degree slope). The
// catalogue (paper section 4.2, Figure 8; numbering is part of the HNI format, docs/FORMAT.md):
//
//   index  count  group                     region of the unit cube
//   0      1      Box                       the whole cube
//   1-12   12     Wedge                     u' + v' <= 1
//   13-20  8      Pyramid (corner tetra)    x' + y' + z' <= 1
//   21-28  8      InversePyramid            x' + y' + z' >= 1
//   29-40  12     QuarterCylinder           u'^2 + v'^2 <= 1
//   41-52  12     InverseQuarterCylinder    u'^2 + v'^2 >= 1
//   53-60  8      SphereOctant              x'^2 + y'^2 + z'^2 <= 1
//   61-68  8      InverseSphereOctant       x'^2 + y'^2 + z'^2 >= 1
//
// Edge-based groups (wedges, quarter cylinders): orientation = axis * 4 + corner, where axis
// (0 = x, 1 = y, 2 = z) is the extrusion axis, (u, v) are the other two axes in cyclic order
// ((y,z) for x, (z,x) for y, (x,y) for z), and corner bit 0 / bit 1 say whether the shape's
// right-angle edge lies at u = 1 / v = 1. u' = u or 1 - u accordingly (distance from that edge).
// Corner-based groups (pyramids, octants): orientation = corner bits (bit 0: x = 1, bit 1: y = 1,
// bit 2: z = 1), and x', y', z' are distances from that corner.
// The cell descriptor g of a data pixel is index + 2 (0 = empty, 1 = redirection).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

namespace nut {

enum class SolidGroup : std::uint8_t {
  Box,
  Wedge,
  Pyramid,
  InversePyramid,
  QuarterCylinder,
  InverseQuarterCylinder,
  SphereOctant,
  InverseSphereOctant,
};

inline constexpr int kSolidCount = 69;

// A solid by its catalogue index 0..68.
struct Solid {
  std::uint8_t index = 0;
  friend bool operator==(Solid, Solid) = default;
};

SolidGroup solidGroup(Solid s);
int solidOrientation(Solid s);
// Number of orientations in a group (1, 12 or 8).
int groupOrientationCount(SolidGroup g);
// The solid of a group and orientation; orientation must be < groupOrientationCount(g).
Solid makeSolid(SolidGroup g, int orientation);
// A readable name such as "box", "wedge-x-c2", "inverse-octant-c5".
std::string solidName(Solid s);

// Closed-form volume of the solid in the unit cube.
double solidVolume(Solid s);

// Whether the unit-cube point p lies inside the solid (boundary counts as inside).
bool solidContains(Solid s, const glm::dvec3& p);

// How much of the box [lo, hi] (inside the unit cube) the solid fills: all of it, none of it, or
// part. A surface that only touches the box (within `epsilon` of the region value) counts as not
// entering it. Producers use it to replace a cell that shows one side of a curved solid by a plain
// box or empty cell.
enum class Coverage : std::uint8_t { None, Part, All };
Coverage solidCoverage(Solid s, const glm::dvec3& lo, const glm::dvec3& hi, double epsilon = 1e-9);

template <typename T>
struct SolidHit {
  T t;                      // ray parameter of the first point inside the solid
  glm::vec<3, T> normal;    // outward unit normal at that point, in unit-cube space
};

// First point of the ray origin + t * dir, t in [tEnter, tExit], that lies inside the solid.
// [tEnter, tExit] is the part of the ray inside the unit cube (the caller clips it). When the hit
// is at tEnter the normal is that of the cube face the ray entered through, or -dir when the origin
// lies inside the cube. For a cell of size s the world normal is normalize(normal / s).
// dir must be non-zero and tEnter, tExit finite; returns nullopt when tEnter > tExit.
template <typename T>
std::optional<SolidHit<T>> intersectSolid(Solid s, const glm::vec<3, T>& origin,
                                          const glm::vec<3, T>& dir, T tEnter, T tExit);

extern template std::optional<SolidHit<float>> intersectSolid(Solid, const glm::vec3&,
                                                              const glm::vec3&, float, float);
extern template std::optional<SolidHit<double>> intersectSolid(Solid, const glm::dvec3&,
                                                               const glm::dvec3&, double, double);

}  // namespace nut
