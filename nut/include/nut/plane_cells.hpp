// nut/plane_cells.hpp — plane cells (HNI version 3): a cell's box cut by one or two planes of its
// block, for roofs at any pitch and direction and walls at any angle.
//
// A plane cell keeps the part of its cell inside one plane's half-space, inside both of two (a
// ridge or hip, convex) or inside either of two (a valley, concave). The planes live in the
// block's frame, not the cell's: every cell a face crosses cuts the same plane, computed from the
// same numbers, so a ray cannot leak along the seam between two of them. docs/FORMAT.md ("Plane
// cell record") gives the encoding: the normal as two 24-bit octahedral coordinates, the offset in
// 1/64 mm.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

namespace nut {

// The half-space dot(normal, p) <= offsetM of a block's frame, p in metres from the block's
// minimum corner.
struct CutPlane {
  glm::dvec3 normal{0.0, 1.0, 0.0};  // unit
  double offsetM = 0.0;
  friend bool operator==(const CutPlane&, const CutPlane&) = default;
};

// How a cell combines its planes; the values are the format's combination byte.
enum class PlaneCombine : std::uint8_t {
  One = 1,     // inside planes[0]
  Both = 2,    // inside planes[0] and planes[1]: a ridge or hip
  Either = 3,  // inside planes[0] or planes[1]: a valley
};

// How many planes a combination uses: 1 for One, else 2.
inline int planeCount(PlaneCombine combine) { return combine == PlaneCombine::One ? 1 : 2; }

struct PlaneCut {
  std::array<CutPlane, 2> planes{};
  PlaneCombine combine = PlaneCombine::One;
  // The material the cut shows on plane i (a roof over walls of another); none: the cell's, which
  // its box's sides show.
  std::array<std::optional<std::uint16_t>, 2> surfaceMaterials{};
  int planeCount() const { return nut::planeCount(combine); }
  friend bool operator==(const PlaneCut&, const PlaneCut&) = default;
};

// Whether point p of the planes' frame lies inside the cut (a point on a plane counts as inside).
bool cutContains(const PlaneCut& cut, const glm::dvec3& p);

// A plane as encoded: octahedral coordinates of the normal (u24 each) and the offset (s32, in
// 1/kPlaneOffsetStepsPerUnit of a unit).
struct EncodedPlane {
  std::uint32_t octX = 0, octY = 0;
  std::int32_t offset = 0;
  friend auto operator<=>(const EncodedPlane&, const EncodedPlane&) = default;
};

// The encoding of p, or nullopt when its offset is beyond the s32 range (about +-33.5 km) or the
// plane is not finite with a non-zero normal.
std::optional<EncodedPlane> encodePlane(const CutPlane& p);
// The plane an encoding stands for, in double (unit normal). Every u24 pair decodes to a normal.
CutPlane decodePlane(const EncodedPlane& e);
// What the format keeps of p: decodePlane(encodePlane(p)); p must be encodable.
CutPlane quantizedPlane(const CutPlane& p);
// The unit normal of an octahedral pair in float, with the operations of the shader.
glm::vec3 decodeNormalFloat(std::uint32_t octX, std::uint32_t octY);

// The part of a ray origin + t * dir, t in [tEnter, tExit], inside a plane cut: its first and last
// parameter and the plane the first lies on (-1 when it is tEnter, the face the ray entered the
// cell by). normals/offsets are the cut's planes in the ray's frame and units.
template <typename T>
struct PlaneSpan {
  T tIn, tOut;
  int plane;
};
template <typename T>
std::optional<PlaneSpan<T>> intersectPlaneCut(const std::array<glm::vec<3, T>, 2>& normals,
                                              const std::array<T, 2>& offsets, PlaneCombine combine,
                                              const glm::vec<3, T>& origin, const glm::vec<3, T>& dir, T tEnter,
                                              T tExit);

// The same for a cut of the model: its planes in the ray's frame, metres.
std::optional<PlaneSpan<double>> intersectPlaneCut(const PlaneCut& cut, const glm::dvec3& origin,
                                                   const glm::dvec3& dir, double tEnter, double tExit);

extern template std::optional<PlaneSpan<float>> intersectPlaneCut(const std::array<glm::vec3, 2>&,
                                                                  const std::array<float, 2>&, PlaneCombine,
                                                                  const glm::vec3&, const glm::vec3&, float, float);
extern template std::optional<PlaneSpan<double>> intersectPlaneCut(const std::array<glm::dvec3, 2>&,
                                                                   const std::array<double, 2>&, PlaneCombine,
                                                                   const glm::dvec3&, const glm::dvec3&, double,
                                                                   double);

}  // namespace nut
