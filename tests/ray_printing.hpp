// How the ray-caster tests print a ray and a result when they fail: every number with 17
// significant digits, so that the failing ray can be reproduced exactly.
#pragma once

#include <sstream>
#include <string>

#include <glm/vec3.hpp>

#include <nut/raycast.hpp>

namespace nut::testing {

inline std::string describe(const glm::dvec3& v) {
  std::ostringstream o;
  o.precision(17);
  o << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return o.str();
}

inline std::string describe(const RayResult& r) {
  std::ostringstream o;
  o.precision(17);
  o << "hit " << r.hit << " distance " << r.distanceM << " normal " << describe(r.normal) << " colour ("
    << int(r.colour[0]) << ", " << int(r.colour[1]) << ", " << int(r.colour[2]) << ")" << (r.capped ? " capped" : "")
    << " iterations " << r.iterations;
  return o.str();
}

}  // namespace nut::testing
