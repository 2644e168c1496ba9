// Solid conversion, corner slopes: a planar piece sloped along all three axes (a chamfered box
// corner, the cut corner of a roof) that is the triangle through the three corners of its
// bounding box next to one corner V is kept as a quadric piece of its own kind (planar), which
// quadrics.cpp bounds and fits like a sphere octant: its box becomes one Pyramid cell at V (V's
// side of the plane solid) or InversePyramid cell at V (the other side solid), or a sub-block of
// one cell where boundaries from elsewhere cut the box (converter/solid.hpp, step 2). Any other
// face sloped along three axes stays in the complementary mesh.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "solid_builder.hpp"
#include "union_find.hpp"

namespace nut::converter::solid {

namespace {

// How far a piece's area may be from its corner triangle's, as a share of it: faces that cover
// the triangle exactly, up to the tolerance along its edges.
constexpr double kAreaSlack = 0.03;

}  // namespace

// Faces sloped along all three axes (each normal component beyond the angle tolerance; sphere
// octants taken) are joined into planar pieces: connected through shared corners, normals within
// the angle tolerance of each other. A piece whose corners all lie within the tolerance of the
// plane through the three corners of its bounding box next to one box corner V (within the box,
// that plane is the triangle) and whose area is within kAreaSlack of that triangle's is a corner
// slope (e = z, as for an octant, V its centre): V lies behind the piece's normals (a notch's
// inner corner) or in front of them (a chamfer's removed corner). A piece under kMinSlopeShare of
// the surface, like a slope, is not worth its boundaries. Everything else stays as it was.
void Builder::findCornerSlopes() {
  stats.cornerSlopes = 0;
  if (!options.pyramids) return;
  const double angle = options.angleToleranceDeg * std::numbers::pi / 180.0;
  const double sinAlong = std::sin(angle), cosSame = std::cos(angle);
  const auto unitNormal = [&](std::uint32_t f) { return faces[f].areaVector / faces[f].area; };
  const auto candidate = [&](std::uint32_t f) {
    if (faces[f].kind != FaceKind::General || faces[f].area <= 0) return false;
    const dvec3 absN = glm::abs(unitNormal(f));
    return absN.x > sinAlong && absN.y > sinAlong && absN.z > sinAlong;
  };
  bool any = false;
  for (std::uint32_t f = 0; f < faces.size() && !any; ++f) any = candidate(f);
  if (!any) return;
  UnionFind sets(faces.size());
  // Per welded corner, one face for each normal met there (within the angle tolerance).
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> seenAt;
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (!candidate(f)) continue;
    const dvec3 normal = unitNormal(f);
    for (int k = 0; k < 3; ++k) {
      std::vector<std::uint32_t>& seen = seenAt[cornerIds[f][static_cast<std::size_t>(k)]];
      const auto same = std::find_if(seen.begin(), seen.end(), [&](std::uint32_t g) { return glm::dot(unitNormal(g), normal) >= cosSame; });
      if (same != seen.end()) sets.unite(f, *same);
      else seen.push_back(f);
    }
  }
  for (std::vector<std::uint32_t>& members : sets.groups(candidate)) {
    const PieceSpan span = spanOf(members);
    const dvec3 &lo = span.lo, &hi = span.hi;
    const dvec3 normalSum = span.areaVector;
    const double area = span.area;
    const dvec3 extent = hi - lo;
    if (std::min({extent.x, extent.y, extent.z}) <= 2 * tol || glm::length(normalSum) <= 0) continue;
    const dvec3 normal = glm::normalize(normalSum);
    // One plane: every face within the angle tolerance of the piece's normal, not just of a
    // neighbour's (a gently curved shell would chain along).
    if (!std::all_of(members.begin(), members.end(), [&](std::uint32_t f) { return glm::dot(unitNormal(f), normal) >= cosSame; }))
      continue;
    // Like a slope, a piece too small to pay for its three boundaries stays in the mesh.
    if (area < kMinSlopeShare * stats.areaM2) continue;
    const double ab = extent.x * extent.y, bc = extent.y * extent.z, ca = extent.z * extent.x;
    const double expected = 0.5 * std::sqrt(ab * ab + bc * bc + ca * ca);
    if (std::abs(area - expected) > kAreaSlack * expected) continue;
    QuadricPiece piece;
    piece.spanBox(lo, hi, area);
    piece.planar = true;
    bool found = false;
    for (const int side : {1, -1}) {
      piece.centreAtCorner(normal, side, lo, hi);
      // Distance from the plane x'/a + y'/b + z'/c = 1 (x', y', z' from V along the box).
      found = std::all_of(members.begin(), members.end(), [&](std::uint32_t f) {
        for (int k = 0; k < 3; ++k)
          if (std::abs(piece.rho(corner(f, k)) - 1) / piece.rhoPerMetre() > tol) return false;
        return true;
      });
      if (found) break;
    }
    if (!found) continue;
    keepPiece(std::move(piece), std::move(members), span.materialArea);
    ++stats.cornerSlopes;
  }
}

}  // namespace nut::converter::solid
