// Fuzz target render_fuzz: any image that validate accepts renders in bounded time. Arbitrary
// bytes as an HNI (frame.hpp); when valid, rays from around and inside its bounds go through the
// CPU ray caster with both lookups, with and without level of detail, under a small iteration cap.
// Every ray must end: within the cap, or flagged capped with one iteration over it (the caster's
// count includes the step that hit the cap); a hit has a finite distance and normal. A ray that
// never ends is a libFuzzer timeout.
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include <nut/hni.hpp>
#include <nut/raycast.hpp>

#include "frame.hpp"
#include "require.hpp"
#include "targets.hpp"

namespace nut::fuzz {

namespace {

constexpr int kIterationCap = 64;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void traceAndCheck(const HniRayCaster& caster, const glm::dvec3& eye, const glm::dvec3& direction,
                   const RayCastOptions& options) {
  const RayResult r = caster.trace(eye, glm::normalize(direction), 1e-3, options);
  NUT_FUZZ_REQUIRE(r.iterations >= 0 && r.iterations <= options.maxIterations + 1);
  NUT_FUZZ_REQUIRE(r.capped == (r.iterations > options.maxIterations));
  if (r.hit) NUT_FUZZ_REQUIRE(std::isfinite(r.distanceM) && r.distanceM >= 0 && finite(r.normal));
}

}  // namespace

int renderInput(const std::uint8_t* data, std::size_t size) {
  const Image image = unframe(data, size);
  if (!validate(image).ok()) return 0;
  const HniRayCaster caster(image, glm::dvec3(0.0));
  const WorldBox box = caster.bounds();
  NUT_FUZZ_REQUIRE(finite(box.min) && finite(box.max));
  const glm::dvec3 centre = box.centre();
  const double reach = 2.0 * glm::length(box.size()) + 1.0;
  // Towards the centre from the six sides and four corners, slightly askew so that rays cross
  // cell boundaries at odd places, and outwards from the centre.
  static constexpr std::array<glm::dvec3, 10> kFrom{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1},
                                                     {0, 0, -1}, {1, 1, 1}, {-1, 1, -1}, {1, -1, -1}, {-1, -1, 1}}};
  const std::array<RayCastOptions, 3> options{{{Lookup::Heuristic, 0.0, kIterationCap},
                                                {Lookup::Exact, 4.0, kIterationCap},
                                                {Lookup::Exact, 0.0, kIterationCap, true}}};
  for (const RayCastOptions& o : options) {
    for (const glm::dvec3& from : kFrom) {
      const glm::dvec3 eye = centre + reach * glm::normalize(from);
      traceAndCheck(caster, eye, centre - eye + glm::dvec3(0.013, 0.029, -0.017) * reach, o);
      traceAndCheck(caster, centre, from + glm::dvec3(0.1, 0.2, 0.3), o);
    }
  }
  return 0;
}

}  // namespace nut::fuzz
