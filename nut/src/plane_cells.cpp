// Plane cells: the octahedral encoding of a plane's normal and the ray's span inside a cut.
#include <nut/plane_cells.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <nut/format.hpp>

namespace nut {

namespace {

constexpr double kOffsetStepsPerMetre = format::kPlaneOffsetStepsPerUnit / format::kMetresPerUnit;

template <typename T>
T signNotZero(T v) {
  return v < T(0) ? T(-1) : T(1);
}

// The octahedral coordinate u (1 .. 2^24 - 1) as a number in [-1, 1]; both operations are exact
// or correctly rounded in float, as in the shader.
template <typename T>
T octahedralValue(std::uint32_t u) {
  return (static_cast<T>(u) - static_cast<T>(format::kOctahedralCentre)) / static_cast<T>(format::kOctahedralSteps);
}

// Unfolds octahedral coordinates (x, y) into a unit vector; the lower half of the octahedron is
// folded over the upper one's corners.
template <typename T>
glm::vec<3, T> unfold(T x, T y) {
  const T z = T(1) - std::abs(x) - std::abs(y);
  if (z < T(0)) {
    const T foldedX = (T(1) - std::abs(y)) * signNotZero(x);
    y = (T(1) - std::abs(x)) * signNotZero(y);
    x = foldedX;
  }
  return glm::normalize(glm::vec<3, T>(x, y, z));
}

std::uint32_t octahedralCode(double value) {
  const double code = std::round(value * format::kOctahedralSteps + format::kOctahedralCentre);
  return static_cast<std::uint32_t>(std::clamp(code, 1.0, static_cast<double>(format::kOctahedralMax)));
}

}  // namespace

bool cutContains(const PlaneCut& cut, const glm::dvec3& p) {
  const bool first = glm::dot(cut.planes[0].normal, p) <= cut.planes[0].offsetM;
  if (cut.combine == PlaneCombine::One) return first;
  const bool second = glm::dot(cut.planes[1].normal, p) <= cut.planes[1].offsetM;
  return cut.combine == PlaneCombine::Both ? first && second : first || second;
}

std::optional<EncodedPlane> encodePlane(const CutPlane& p) {
  const double l1 = std::abs(p.normal.x) + std::abs(p.normal.y) + std::abs(p.normal.z);
  if (!(l1 > 0.0) || !std::isfinite(l1) || !std::isfinite(p.offsetM)) return std::nullopt;
  const double offset = std::round(p.offsetM * kOffsetStepsPerMetre);
  if (offset < std::numeric_limits<std::int32_t>::min() || offset > std::numeric_limits<std::int32_t>::max())
    return std::nullopt;
  double x = p.normal.x / l1, y = p.normal.y / l1;
  if (p.normal.z < 0.0) {
    const double foldedX = (1.0 - std::abs(y)) * signNotZero(x);
    y = (1.0 - std::abs(x)) * signNotZero(y);
    x = foldedX;
  }
  return EncodedPlane{octahedralCode(x), octahedralCode(y), static_cast<std::int32_t>(offset)};
}

CutPlane decodePlane(const EncodedPlane& e) {
  return {unfold(octahedralValue<double>(e.octX), octahedralValue<double>(e.octY)),
          static_cast<double>(e.offset) / kOffsetStepsPerMetre};
}

CutPlane quantizedPlane(const CutPlane& p) { return decodePlane(*encodePlane(p)); }

glm::vec3 decodeNormalFloat(std::uint32_t octX, std::uint32_t octY) {
  return unfold(octahedralValue<float>(octX), octahedralValue<float>(octY));
}

template <typename T>
std::optional<PlaneSpan<T>> intersectPlaneCut(const std::array<glm::vec<3, T>, 2>& normals,
                                              const std::array<T, 2>& offsets, PlaneCombine combine,
                                              const glm::vec<3, T>& origin, const glm::vec<3, T>& dir, T tEnter,
                                              T tExit) {
  constexpr T kInf = std::numeric_limits<T>::infinity();
  // The span of the whole line inside plane i's half-space: dot(n, o) + t dot(n, d) <= offset.
  struct Span {
    T in, out;
    int plane;  // the plane `in` lies on, -1 when the span starts at -infinity
  };
  const auto spanOf = [&](int i) -> Span {
    const glm::vec<3, T>& n = normals[static_cast<std::size_t>(i)];
    const T along = glm::dot(n, dir), room = offsets[static_cast<std::size_t>(i)] - glm::dot(n, origin);
    if (along > T(0)) return {-kInf, room / along, -1};
    if (along < T(0)) return {room / along, kInf, i};
    return room >= T(0) ? Span{-kInf, kInf, -1} : Span{kInf, -kInf, -1};
  };
  // Clipped to [tEnter, tExit]; empty when in > out.
  const auto clip = [&](Span s) {
    if (s.in <= tEnter) s.in = tEnter, s.plane = -1;
    s.out = std::min(s.out, tExit);
    return s;
  };
  Span span = clip(spanOf(0));
  if (combine == PlaneCombine::Both) {
    const Span second = clip(spanOf(1));
    if (second.in > span.in) span.in = second.in, span.plane = second.plane;
    span.out = std::min(span.out, second.out);
  } else if (combine == PlaneCombine::Either) {
    const Span second = clip(spanOf(1));
    if (second.in <= second.out) {
      if (span.in > span.out) {
        span = second;
      } else {
        if (second.in < span.in) span.in = second.in, span.plane = second.plane;
        span.out = std::max(span.out, second.out);
      }
    }
  }
  if (!(span.in <= span.out)) return std::nullopt;
  return PlaneSpan<T>{span.in, span.out, span.plane};
}

std::optional<PlaneSpan<double>> intersectPlaneCut(const PlaneCut& cut, const glm::dvec3& origin,
                                                   const glm::dvec3& dir, double tEnter, double tExit) {
  return intersectPlaneCut<double>({cut.planes[0].normal, cut.planes[1].normal},
                                   {cut.planes[0].offsetM, cut.planes[1].offsetM}, cut.combine, origin, dir, tEnter,
                                   tExit);
}

template std::optional<PlaneSpan<float>> intersectPlaneCut(const std::array<glm::vec3, 2>&, const std::array<float, 2>&,
                                                           PlaneCombine, const glm::vec3&, const glm::vec3&, float,
                                                           float);
template std::optional<PlaneSpan<double>> intersectPlaneCut(const std::array<glm::dvec3, 2>&,
                                                            const std::array<double, 2>&, PlaneCombine,
                                                            const glm::dvec3&, const glm::dvec3&, double, double);

}  // namespace nut
