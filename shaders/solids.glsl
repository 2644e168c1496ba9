// solids.glsl — ray intersection with the 69 cell solids in the cell's unit cube.
//
// References: Kuang et al. 2013, section 4.2 and Figure 8 (the cell solids); a line-by-line port
// of nut::intersectSolid<float> (nut/src/solids.cpp), which documents the method: every solid is
// the unit cube intersected with a region P (or, inverse solids, the cube minus P), P written in
// primed coordinates q = sign * p + offset as sum(q) <= 1 (half-space) or dot(q, q) <= 1 (ball, a
// cylinder when one sign is 0). kSolidShape (format_constants.glsl) holds (sign, flags) per solid.

struct SolidHit {
  bool hit;
  float t;      // ray parameter of the first point inside the solid
  vec3 normal;  // outward unit normal there, in unit-cube space
};

const vec2 kEverything = vec2(-kInfinity, kInfinity);
const vec2 kNothing = vec2(kInfinity, -kInfinity);

// The parameters [x, y] where the ray q0 + s qd lies in sum(q) <= 1; empty when x > y.
vec2 halfSpaceInterval(vec3 q0, vec3 qd) {
  float c0 = q0.x + q0.y + q0.z - 1.0;
  float c1 = qd.x + qd.y + qd.z;
  if (c1 == 0.0) return c0 <= 0.0 ? kEverything : kNothing;  // parallel to the plane
  float root = -c0 / c1;
  return c1 > 0.0 ? vec2(-kInfinity, root) : vec2(root, kInfinity);
}

// dot(q, q) - 1 = a s^2 + 2 b s + c, solved without cancellation (see solids.cpp).
vec2 ballInterval(vec3 q0, vec3 qd) {
  float a = dot(qd, qd);
  float c = dot(q0, q0) - 1.0;
  if (a == 0.0) return c <= 0.0 ? kEverything : kNothing;  // along the cylinder axis
  float b = dot(q0, qd);
  vec3 m = cross(q0, qd);
  float discriminant = a - dot(m, m);  // b^2 - a c by Lagrange's identity
  if (discriminant < 0.0) return kNothing;
  float root = sqrt(discriminant);
  // copysign(root, b): the sign bit of b, so that b = -0 behaves as in C++.
  float h = -(b + ((floatBitsToUint(b) & 0x80000000u) != 0u ? -root : root));
  if (h == 0.0) return vec2(0.0);  // b = 0 and a tangent ray: the double root is at s = 0
  float r0 = h / a, r1 = c / h;
  return vec2(min(r0, r1), max(r0, r1));
}

// Outward normal of the cube face the ray entered through at the point `entry`; -dir when the
// origin is inside the cube. Of the faces the ray moves in through, the one nearest to the entry.
vec3 cubeEntryNormal(vec3 origin, vec3 dir, vec3 entry, float tEnter) {
  bool originInside = all(greaterThan(origin, vec3(0.0))) && all(lessThan(origin, vec3(1.0)));
  if (tEnter <= 0.0 && originInside) return -normalize(dir);
  int axis = 0;
  float nearest = kInfinity;
  for (int i = 0; i < 3; ++i) {
    if (dir[i] == 0.0) continue;
    float plane = dir[i] > 0.0 ? 0.0 : 1.0;
    float distance = abs(entry[i] - plane);
    if (distance < nearest) {
      nearest = distance;
      axis = i;
    }
  }
  vec3 normal = vec3(0.0);
  normal[axis] = dir[axis] > 0.0 ? -1.0 : 1.0;
  return normal;
}

// First point of origin + t dir, t in [tEnter, tExit] (the part of the ray inside the unit cube),
// inside solid `index`. At tEnter the normal is the entry face's; elsewhere P's surface normal.
SolidHit intersectSolid(int index, vec3 origin, vec3 dir, float tEnter, float tExit) {
  SolidHit miss = SolidHit(false, 0.0, vec3(0.0));
  if (!(tEnter <= tExit)) return miss;
  ivec4 shape = kSolidShape[index];
  bool ball = (shape.w & kShapeBall) != 0;
  bool inverse = (shape.w & kShapeInverse) != 0;
  vec3 sign = vec3(shape.xyz);
  // Solve for at = t - tEnter from the entry point, where all terms are of order one.
  vec3 entry = origin + tEnter * dir;
  float span = tExit - tEnter;
  vec3 q0 = sign * entry + vec3(lessThan(shape.xyz, ivec3(0)));
  vec3 qd = sign * dir;
  vec2 inP = ball ? ballInterval(q0, qd) : halfSpaceInterval(q0, qd);

  float at;
  if (!inverse) {
    at = max(0.0, inP.x);
    if (!(at <= min(span, inP.y))) return miss;
  } else if (inP.x > 0.0 || inP.y < 0.0) {
    at = 0.0;
  } else if (inP.y <= span) {
    at = inP.y;
  } else {
    return miss;
  }
  // The hit may round past tExit; the inverse solid lies on the other side of P's surface.
  float t = min(tEnter + at, tExit);
  vec3 normal;
  if (t == tEnter) {
    normal = cubeEntryNormal(origin, dir, entry, tEnter);
  } else {
    vec3 q = q0 + at * qd;
    normal = (inverse ? -1.0 : 1.0) * normalize(ball ? sign * q : sign);
  }
  return SolidHit(true, t, normal);
}

// The part of origin + t dir, t in [tEnter, tExit], inside a plane cell's cut (nut::intersectPlaneCut)
// of planes (n0, d0) and (n1, d1) combined as `combine` says: x = first parameter, y = last, z = the
// plane the first lies on (-1: tEnter, the cell's entry face). An empty part has x > y.
vec3 planeSpan(vec3 n, float offset, vec3 origin, vec3 dir) {
  float along = dot(n, dir), room = offset - dot(n, origin);
  if (along > 0.0) return vec3(-kInfinity, room / along, -1.0);
  if (along < 0.0) return vec3(room / along, kInfinity, 0.0);
  return room >= 0.0 ? vec3(-kInfinity, kInfinity, -1.0) : vec3(kInfinity, -kInfinity, -1.0);
}

vec3 clipSpan(vec3 s, float tEnter, float tExit) {
  if (s.x <= tEnter) s.xz = vec2(tEnter, -1.0);
  s.y = min(s.y, tExit);
  return s;
}

vec3 intersectPlaneCut(vec3 n0, float d0, vec3 n1, float d1, int combine, vec3 origin, vec3 dir, float tEnter,
                       float tExit) {
  vec3 span = clipSpan(planeSpan(n0, d0, origin, dir), tEnter, tExit);
  if (combine == kPlaneCombineOne) return span;
  vec3 second = clipSpan(planeSpan(n1, d1, origin, dir), tEnter, tExit);
  if (second.z == 0.0) second.z = 1.0;
  if (combine == kPlaneCombineBoth) {
    if (second.x > span.x) span.xz = second.xz;
    span.y = min(span.y, second.y);
  } else if (second.x <= second.y) {
    if (span.x > span.y) return second;
    if (second.x < span.x) span.xz = second.xz;
    span.y = max(span.y, second.y);
  }
  return span;
}
