// Convex pieces and their clipping (convex_pieces.hpp).
#include "convex_pieces.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace nut::mesh {

using glm::dvec3;

namespace {

bool degenerate(const dvec3& a, const dvec3& b, const dvec3& c) {
  const dvec3 u = b - a, v = c - a;
  return glm::length(glm::cross(u, v)) <= 1e-12 * glm::length(u) * glm::length(v);
}

enum class Side : std::uint8_t { In, On, Out };

Side sideOf(const Plane& plane, const dvec3& p) {
  const double d = plane.distance(p);
  return d < -kOnPlaneM ? Side::In : d > kOnPlaneM ? Side::Out : Side::On;
}

// Where the segment crosses the plane, computed from its endpoints in lexicographic order so that
// the faces on both sides of an edge get the same point.
dvec3 crossing(const Plane& plane, dvec3 a, dvec3 b) {
  if (std::lexicographical_compare(&b[0], &b[0] + 3, &a[0], &a[0] + 3)) std::swap(a, b);
  const double da = plane.distance(a), db = plane.distance(b);
  return a + (da / (da - db)) * (b - a);
}

// Sutherland-Hodgman against one plane; points of the result that lie on the plane are added to
// `onPlane` (they outline the cap).
std::vector<dvec3> clipPolygon(const std::vector<dvec3>& polygon, const Plane& plane, std::vector<dvec3>& onPlane) {
  std::vector<dvec3> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const dvec3& current = polygon[i];
    const dvec3& next = polygon[(i + 1) % polygon.size()];
    const Side sc = sideOf(plane, current), sn = sideOf(plane, next);
    if (sc != Side::Out) out.push_back(current);
    if (sc == Side::On) onPlane.push_back(current);
    if ((sc == Side::In && sn == Side::Out) || (sc == Side::Out && sn == Side::In)) {
      out.push_back(crossing(plane, current, next));
      onPlane.push_back(out.back());
    }
  }
  return out;
}

// The convex polygon through `points` (all on the plane), counter-clockwise seen from the plane's
// outer side: the cap's outward normal is the plane normal.
std::vector<dvec3> capPolygon(std::vector<dvec3> points, const Plane& plane) {
  dvec3 centroid(0.0);
  for (const dvec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  const dvec3 helper = std::abs(plane.normal.x) < 0.6 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
  const dvec3 e1 = glm::normalize(glm::cross(helper, plane.normal));
  const dvec3 e2 = glm::cross(plane.normal, e1);  // e1 x e2 = normal: increasing angle is counter-clockwise
  const auto angle = [&](const dvec3& p) { return std::atan2(glm::dot(p - centroid, e2), glm::dot(p - centroid, e1)); };
  std::sort(points.begin(), points.end(), [&](const dvec3& a, const dvec3& b) { return angle(a) < angle(b); });
  // Crossings on an edge shared by two faces are found twice, bit for bit the same.
  points.erase(std::unique(points.begin(), points.end()), points.end());
  while (points.size() > 1 && points.front() == points.back()) points.pop_back();
  return points;
}

}  // namespace

dvec3 areaNormal(const std::vector<dvec3>& points) {
  dvec3 n(0.0);
  for (std::size_t i = 1; i + 1 < points.size(); ++i) n += glm::cross(points[i] - points[0], points[i + 1] - points[0]);
  return n;
}

void triangulateConvex(const std::vector<dvec3>& polygon, std::vector<Triangle>& out) {
  std::vector<dvec3> p;
  for (const dvec3& q : polygon)
    if (p.empty() || q != p.back()) p.push_back(q);
  while (p.size() > 1 && p.front() == p.back()) p.pop_back();
  if (p.size() < 3) return;
  bool fan = true;
  for (std::size_t i = 1; i + 1 < p.size() && fan; ++i) fan = !degenerate(p[0], p[i], p[i + 1]);
  if (fan || p.size() == 3) {
    for (std::size_t i = 1; i + 1 < p.size(); ++i) out.push_back({p[0], p[i], p[i + 1]});
    return;
  }
  dvec3 centroid(0.0);
  for (const dvec3& q : p) centroid += q;
  centroid /= static_cast<double>(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) out.push_back({centroid, p[i], p[(i + 1) % p.size()]});
}

bool clipPiece(Piece& piece, const Plane& plane) {
  bool anyIn = false, anyOut = false;
  for (const Face& f : piece)
    for (const dvec3& p : f.points) {
      const Side s = sideOf(plane, p);
      anyIn |= s == Side::In;
      anyOut |= s == Side::Out;
    }
  if (!anyOut) {
    // Untouched, but a face lying on the plane now bounds the solid: the piece that shared it
    // (beyond the plane) is gone.
    for (Face& f : piece)
      if (std::all_of(f.points.begin(), f.points.end(), [&](const dvec3& p) { return sideOf(plane, p) == Side::On; }))
        f.internal = false;
    return true;
  }
  if (!anyIn) return false;
  Piece clipped;
  std::vector<dvec3> onPlane;
  for (const Face& f : piece) {
    std::vector<dvec3> points = clipPolygon(f.points, plane, onPlane);
    if (points.size() >= 3) clipped.push_back({std::move(points), f.internal, f.material});
  }
  std::vector<dvec3> cap = capPolygon(std::move(onPlane), plane);
  if (cap.size() >= 3) clipped.push_back({std::move(cap), false});
  piece = std::move(clipped);
  return true;
}

}  // namespace nut::mesh
