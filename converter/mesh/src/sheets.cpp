// Open sheets peeled off a closed body (sheets.hpp).
#include <converter/sheets.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <converter/winding.hpp>

#include "closed_surface.hpp"
#include "union_find.hpp"

namespace nut::converter {

namespace {

using glm::dvec3;
using Triangle = std::array<std::uint32_t, 3>;

// The mesh as a step leaves it: points are only appended, and each triangle is a part of the
// previous step's triangle `origin`.
struct Soup {
  std::vector<dvec3> points;
  std::vector<Triangle> triangles;
  std::vector<std::uint16_t> material;
  std::vector<std::uint32_t> origin;

  void add(const Triangle& t, const Soup& from, std::size_t i) {
    triangles.push_back(t);
    material.push_back(from.material[i]);
    origin.push_back(static_cast<std::uint32_t>(i));
  }
};

double twiceArea(const Soup& s, const Triangle& t) {
  return glm::length(glm::cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]));
}

// Below this twice-area (m^2) a triangle has no extent worth keeping: a sliver left where a cut
// ran along an edge.
constexpr double kNoArea = 1e-12;

// Vertices within `tol` of each other become one; triangles left without area are dropped. The
// others keep their origin.
std::vector<std::uint32_t> weldPlaces(Soup& s, double tol) {
  std::vector<std::uint32_t> all(s.points.size());
  std::iota(all.begin(), all.end(), 0u);
  const std::vector<std::uint32_t> place = placesOf(s.points, all, tol);
  Soup out{s.points, {}, {}, {}};
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Triangle welded{place[s.triangles[t][0]], place[s.triangles[t][1]], place[s.triangles[t][2]]};
    if (welded[0] == welded[1] || welded[1] == welded[2] || welded[0] == welded[2]) continue;
    if (twiceArea(out, welded) <= kNoArea) continue;
    out.triangles.push_back(welded);  // welding moves no face: each keeps its origin
    out.material.push_back(s.material[t]);
    out.origin.push_back(s.origin[t]);
  }
  s = std::move(out);
  return place;
}

// Takes out of `s` the triangles narrower than `tol` (a corner within it of the opposite edge):
// a sliver's edges run along one line both ways, and a polygon triangulated with a corner on a
// straight edge has one. They carry no surface worth a cell and are drawn as mesh.
Soup takeSlivers(Soup& s, double tol) {
  Soup slivers{s.points, {}, {}, {}}, rest{s.points, {}, {}, {}};
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Triangle& tri = s.triangles[t];
    double longest = 0;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, glm::length(s.points[tri[(k + 1) % 3]] - s.points[tri[k]]));
    Soup& to = twiceArea(s, tri) <= tol * longest ? slivers : rest;
    to.triangles.push_back(tri);
    to.material.push_back(s.material[t]);
    to.origin.push_back(s.origin[t]);
  }
  s = std::move(rest);
  return slivers;
}

// The vertices of the soup other than the triangle's corners a, b and c within `tol` of its edge
// ab and more than `tol` from its ends, in order from a. byX: the vertices used, sorted by x.
std::vector<std::uint32_t> verticesOnEdge(const Soup& s, const std::vector<std::uint32_t>& byX, std::uint32_t a,
                                          std::uint32_t b, std::uint32_t c, double tol) {
  const dvec3 &pa = s.points[a], &pb = s.points[b];
  const double length = glm::length(pb - pa);
  std::vector<std::pair<double, std::uint32_t>> found;
  if (length <= 2 * tol) return {};
  const dvec3 d = (pb - pa) / length;
  const double lo = std::min(pa.x, pb.x) - tol, hi = std::max(pa.x, pb.x) + tol;
  auto it = std::lower_bound(byX.begin(), byX.end(), lo, [&](std::uint32_t v, double x) { return s.points[v].x < x; });
  for (; it != byX.end() && s.points[*it].x <= hi; ++it) {
    if (*it == a || *it == b || *it == c) continue;
    const dvec3 v = s.points[*it] - pa;
    const double along = glm::dot(v, d);
    if (along > tol && along < length - tol && glm::length(v - along * d) <= tol) found.emplace_back(along, *it);
  }
  std::sort(found.begin(), found.end());
  std::vector<std::uint32_t> out;
  for (const auto& [along, v] : found) out.push_back(v);
  return out;
}

// Splits every edge at the vertices within `tol` of it (T-junctions), so that faces meeting along a
// line share its edges: a triangle with such vertices becomes a fan about its centroid over its
// corners and those vertices in order.
Soup conform(const Soup& s, double tol) {
  std::vector<std::uint32_t> byX;
  {
    std::vector<std::uint8_t> used(s.points.size(), 0);
    for (const Triangle& t : s.triangles)
      for (std::uint32_t v : t) used[v] = 1;
    for (std::uint32_t v = 0; v < s.points.size(); ++v)
      if (used[v]) byX.push_back(v);
    std::sort(byX.begin(), byX.end(), [&](std::uint32_t a, std::uint32_t b) { return s.points[a].x < s.points[b].x; });
  }
  Soup out{s.points, {}, {}, {}};
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const Triangle& t = s.triangles[i];
    std::vector<std::uint32_t> outline;
    for (int k = 0; k < 3; ++k) {
      outline.push_back(t[k]);
      for (std::uint32_t v : verticesOnEdge(s, byX, t[k], t[(k + 1) % 3], t[(k + 2) % 3], tol)) outline.push_back(v);
    }
    if (outline.size() == 3) {
      out.add(t, s, i);
      continue;
    }
    out.points.push_back((s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0);
    const auto centre = static_cast<std::uint32_t>(out.points.size() - 1);
    for (std::size_t k = 0; k < outline.size(); ++k)
      out.add({centre, outline[k], outline[(k + 1) % outline.size()]}, s, i);
  }
  return out;
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// How many triangles use each edge, either way.
std::unordered_map<std::uint64_t, int> edgeUses(const Soup& s, const std::vector<std::uint8_t>* kept = nullptr) {
  std::unordered_map<std::uint64_t, int> uses;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (kept && !(*kept)[t]) continue;
    for (int k = 0; k < 3; ++k) ++uses[edgeKey(s.triangles[t][k], s.triangles[t][(k + 1) % 3])];
  }
  return uses;
}

// A line in a triangle's plane: the points x with dot(x - point, across) = 0.
struct Cut {
  dvec3 point, across;
};

// The cut of triangle t along the free edge pq, when pq crosses its interior along more than a
// place's length and lies within `tol` of its plane there. Only the stretch inside the triangle is
// measured: the two triangles of a surveyed roof pitch are rarely coplanar to a centimetre.
std::optional<Cut> cutAlong(const std::vector<dvec3>& points, const Triangle& t, const dvec3& p, const dvec3& q,
                            double tol) {
  const dvec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
  const dvec3 cross = glm::cross(b - a, c - a);
  const double twice = glm::length(cross);
  if (twice <= kNoArea) return std::nullopt;
  const dvec3 n = cross / twice;
  const double dp = glm::dot(p - a, n), dq = glm::dot(q - a, n);
  const dvec3 p0 = p - dp * n, q0 = q - dq * n;
  const double length = glm::length(q0 - p0);
  if (length <= kSamePlaceM) return std::nullopt;
  const dvec3 along = (q0 - p0) / length, across = glm::cross(n, along);
  // The corners' sides of the line, and the stretch of the line inside the triangle.
  const std::array<dvec3, 3> corner{a, b, c};
  std::array<double, 3> side{};
  for (int k = 0; k < 3; ++k) side[k] = glm::dot(corner[k] - p0, across);
  if (*std::max_element(side.begin(), side.end()) <= kSamePlaceM ||
      *std::min_element(side.begin(), side.end()) >= -kSamePlaceM)
    return std::nullopt;
  double from = INFINITY, to = -INFINITY;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if ((side[k] > 0) == (side[l] > 0)) continue;
    const dvec3 x = corner[k] + (corner[l] - corner[k]) * (side[k] / (side[k] - side[l]));
    const double at = glm::dot(x - p0, along);
    from = std::min(from, at);
    to = std::max(to, at);
  }
  from = std::max(from, 0.0);
  to = std::min(to, length);
  if (to - from <= kSamePlaceM) return std::nullopt;
  const auto offPlane = [&](double at) { return std::abs(dp + (dq - dp) * (at / length)); };
  if (offPlane(from) > tol || offPlane(to) > tol) return std::nullopt;
  return Cut{p0, across};
}

// A convex polygon (vertex ids) split by a cut into the parts on either side; one part when the
// cut does not cross it. New vertices are appended to points.
std::vector<std::vector<std::uint32_t>> splitPolygon(std::vector<dvec3>& points,
                                                     const std::vector<std::uint32_t>& polygon, const Cut& cut) {
  std::vector<double> side(polygon.size());
  bool above = false, below = false;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    side[k] = glm::dot(points[polygon[k]] - cut.point, cut.across);
    if (std::abs(side[k]) <= kSamePlaceM) side[k] = 0;
    above = above || side[k] > 0;
    below = below || side[k] < 0;
  }
  if (!above || !below) return {polygon};
  std::vector<std::uint32_t> front, back;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const std::size_t l = (k + 1) % polygon.size();
    if (side[k] >= 0) front.push_back(polygon[k]);
    if (side[k] <= 0) back.push_back(polygon[k]);
    if ((side[k] > 0 && side[l] < 0) || (side[k] < 0 && side[l] > 0)) {
      const dvec3 &x = points[polygon[k]], &y = points[polygon[l]];
      points.push_back(x + (y - x) * (side[k] / (side[k] - side[l])));
      const auto id = static_cast<std::uint32_t>(points.size() - 1);
      front.push_back(id);
      back.push_back(id);
    }
  }
  return {front, back};
}

// Step 2 of detachSheets: each face of the conformed soup `s` cut along the free edges of `s`
// lying in it, each part a fan of its convex outline.
Soup cutAlongFreeEdges(const Soup& s, double tol, std::size_t& cutFaces) {
  const auto uses = edgeUses(s);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> free;
  for (const Triangle& t : s.triangles)
    for (int k = 0; k < 3; ++k)
      if (uses.at(edgeKey(t[k], t[(k + 1) % 3])) == 1) free.emplace_back(t[k], t[(k + 1) % 3]);
  Soup out{s.points, {}, {}, {}};
  cutFaces = 0;
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const Triangle& t = s.triangles[i];
    dvec3 lo = out.points[t[0]], hi = lo;
    for (std::uint32_t v : t) {
      lo = glm::min(lo, out.points[v]);
      hi = glm::max(hi, out.points[v]);
    }
    std::vector<std::vector<std::uint32_t>> pieces{{t[0], t[1], t[2]}};
    for (const auto& [a, b] : free) {
      const dvec3 p = out.points[a], q = out.points[b];
      if (glm::any(glm::lessThan(glm::max(p, q), lo - tol)) || glm::any(glm::greaterThan(glm::min(p, q), hi + tol)))
        continue;
      const std::optional<Cut> cut = cutAlong(out.points, t, p, q, tol);
      if (!cut) continue;
      std::vector<std::vector<std::uint32_t>> split;
      for (const auto& piece : pieces)
        for (auto& part : splitPolygon(out.points, piece, *cut)) split.push_back(std::move(part));
      pieces = std::move(split);
    }
    cutFaces += pieces.size() > 1;
    for (const auto& piece : pieces) {
      // A corner on the straight line between its neighbours would make a fan triangle without
      // width; the neighbouring faces' edges meet it again once the cut faces are conformed.
      std::vector<std::uint32_t> corners;
      for (std::size_t k = 0; k < piece.size(); ++k) {
        const dvec3 &before = out.points[piece[(k + piece.size() - 1) % piece.size()]], &here = out.points[piece[k]],
                    &after = out.points[piece[(k + 1) % piece.size()]];
        const double base = glm::length(after - before);
        if (base > 0 && glm::length(glm::cross(here - before, after - before)) / base > kSamePlaceM)
          corners.push_back(piece[k]);
      }
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) out.add({corners[0], corners[k], corners[k + 1]}, s, i);
    }
  }
  return out;
}

// The pieces of the kept faces: joined across edges that exactly two kept faces share.
UnionFind piecesOf(const Soup& s, const std::vector<std::uint8_t>& kept,
                   const std::unordered_map<std::uint64_t, int>& uses) {
  UnionFind pieces(s.triangles.size());
  std::unordered_map<std::uint64_t, std::uint32_t> firstUser;
  for (std::uint32_t t = 0; t < s.triangles.size(); ++t) {
    if (!kept[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t key = edgeKey(s.triangles[t][k], s.triangles[t][(k + 1) % 3]);
      if (uses.at(key) != 2) continue;
      auto [it, first] = firstUser.try_emplace(key, t);
      if (!first) pieces.unite(it->second, t);
    }
  }
  return pieces;
}

// Step 3 of detachSheets: every piece with an edge that a single kept face uses is peeled off,
// until none is left. The pieces are those of the faces before peeling: a piece is not split by
// what is peeled beside it.
void peel(const Soup& s, std::vector<std::uint8_t>& kept) {
  UnionFind pieces = piecesOf(s, kept, edgeUses(s, &kept));
  for (bool peeled = true; peeled;) {
    peeled = false;
    const auto remaining = edgeUses(s, &kept);
    std::vector<std::uint8_t> pieceGoes(s.triangles.size(), 0);
    for (std::uint32_t t = 0; t < s.triangles.size(); ++t) {
      if (!kept[t]) continue;
      for (int k = 0; k < 3; ++k)
        if (remaining.at(edgeKey(s.triangles[t][k], s.triangles[t][(k + 1) % 3])) == 1) pieceGoes[pieces.find(t)] = 1;
    }
    for (std::uint32_t t = 0; t < s.triangles.size(); ++t)
      if (kept[t] && pieceGoes[pieces.find(t)]) {
        kept[t] = 0;
        peeled = true;
      }
  }
}

// Step 4 of detachSheets: a piece meeting others along edges of three or more faces that lies
// inside the solid the other kept faces bound (their winding number at its largest face's centre
// is above 1/2) is hidden: the roof under a dormer that stands on it. Its faces are marked 2.
void dropInnerPieces(const Soup& s, std::vector<std::uint8_t>& kept) {
  const auto uses = edgeUses(s, &kept);
  UnionFind pieces = piecesOf(s, kept, uses);
  std::vector<std::uint8_t> branches(s.triangles.size(), 0);
  for (std::uint32_t t = 0; t < s.triangles.size(); ++t) {
    if (!kept[t]) continue;
    for (int k = 0; k < 3; ++k)
      if (uses.at(edgeKey(s.triangles[t][k], s.triangles[t][(k + 1) % 3])) > 2) branches[pieces.find(t)] = 1;
  }
  std::vector<std::vector<std::uint32_t>> groups =
      pieces.groups([&](std::uint32_t t) { return kept[t] && branches[pieces.find(t)]; });
  std::vector<std::uint32_t> inner;
  for (const std::vector<std::uint32_t>& piece : groups) {
    std::uint32_t largest = piece.front();
    for (std::uint32_t t : piece)
      if (twiceArea(s, s.triangles[t]) > twiceArea(s, s.triangles[largest])) largest = t;
    const Triangle& l = s.triangles[largest];
    const dvec3 centre = (s.points[l[0]] + s.points[l[1]] + s.points[l[2]]) / 3.0;
    std::vector<std::uint8_t> others = kept;
    for (std::uint32_t t : piece) others[t] = 0;
    std::vector<Triangle> rest;
    for (std::uint32_t t = 0; t < s.triangles.size(); ++t)
      if (others[t]) rest.push_back(s.triangles[t]);
    if (exactWindingNumber(s.points, rest, centre) > 0.5) inner.insert(inner.end(), piece.begin(), piece.end());
  }
  for (std::uint32_t t : inner) kept[t] = 2;
}

// Which kept faces (kept[t] == 1) to turn over so that each piece of them runs every edge it
// shares one way and its other face the other, and faces outwards (a positive volume). Pieces
// that were apart before welding (a wing's walls and the body's) were oriented apart.
std::vector<std::uint8_t> orientation(const Soup& s, const std::vector<std::uint8_t>& kept) {
  const std::size_t n = s.triangles.size();
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> users;
  for (std::uint32_t t = 0; t < n; ++t)
    if (kept[t] == 1)
      for (int k = 0; k < 3; ++k) users[edgeKey(s.triangles[t][k], s.triangles[t][(k + 1) % 3])].push_back(t);
  // Whether t runs a -> b.
  const auto runs = [&](std::uint32_t t, std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k)
      if (s.triangles[t][k] == a && s.triangles[t][(k + 1) % 3] == b) return true;
    return false;
  };
  std::vector<std::uint8_t> flip(n, 0), seen(n, 0);
  for (std::uint32_t start = 0; start < n; ++start) {
    if (kept[start] != 1 || seen[start]) continue;
    std::vector<std::uint32_t> piece{start};
    seen[start] = 1;
    double volume = 0;
    for (std::size_t i = 0; i < piece.size(); ++i) {
      const std::uint32_t t = piece[i];
      const Triangle& tri = s.triangles[t];
      const double v = glm::dot(s.points[tri[0]], glm::cross(s.points[tri[1]], s.points[tri[2]]));
      volume += flip[t] ? -v : v;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
        const auto& shared = users[edgeKey(a, b)];
        if (shared.size() != 2) continue;
        const std::uint32_t other = shared[0] == t ? shared[1] : shared[0];
        if (seen[other]) continue;
        seen[other] = 1;
        // t runs a -> b once turned by flip[t]; the other must run it b -> a.
        const bool tForward = runs(t, a, b) != static_cast<bool>(flip[t]);
        const bool otherForward = runs(other, a, b);
        flip[other] = otherForward == tForward;
        piece.push_back(other);
      }
    }
    if (volume < 0)
      for (std::uint32_t t : piece) flip[t] = !flip[t];
  }
  return flip;
}

// Whether the kept faces (kept[t] == 1) close: every edge they use is run once each way.
bool closes(const Soup& s, const std::vector<std::uint8_t>& kept) {
  std::unordered_map<std::uint64_t, int> runs;  // +1 for a -> b with a < b, -1 the other way
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (kept[t] != 1) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = s.triangles[t][k], b = s.triangles[t][(k + 1) % 3];
      runs[edgeKey(a, b)] += a < b ? 1 : -1;
    }
  }
  return std::all_of(runs.begin(), runs.end(), [&](const auto& r) { return r.second == 0; });
}

// The faces of `cut` that have `status`, as a mesh: a face of `base` all of whose parts (baseOf:
// each cut face's face of base) have it is written whole, as it was. Both use cut's points.
TriangleMesh meshOf(const Soup& base, const Soup& cut, const std::vector<std::uint32_t>& baseOf,
                    const std::vector<std::uint8_t>& cutStatus, const std::vector<std::uint8_t>& cutFlip,
                    std::uint8_t status, const TriangleMesh& like) {
  TriangleMesh mesh;
  mesh.name = like.name;
  mesh.materials = like.materials;
  mesh.materialNames = like.materialNames;
  std::vector<int> partsWith(base.triangles.size(), 0), parts(base.triangles.size(), 0);
  std::vector<std::uint8_t> baseFlip(base.triangles.size(), 0);
  for (std::size_t t = 0; t < cut.triangles.size(); ++t) {
    ++parts[baseOf[t]];
    partsWith[baseOf[t]] += cutStatus[t] == status;
    baseFlip[baseOf[t]] = cutFlip[t];  // a face's parts are one piece: they turn together
  }
  std::vector<std::int64_t> id(cut.points.size(), -1);
  const auto write = [&](Triangle t, std::uint16_t material, bool turn) {
    if (turn) std::swap(t[1], t[2]);
    Triangle out{};
    for (int k = 0; k < 3; ++k) {
      std::int64_t& v = id[t[k]];
      if (v < 0) {
        v = static_cast<std::int64_t>(mesh.positions.size());
        mesh.positions.push_back(cut.points[t[k]]);
      }
      out[k] = static_cast<std::uint32_t>(v);
    }
    mesh.triangles.push_back(out);
    mesh.triangleMaterial.push_back(material);
  };
  for (std::size_t t = 0; t < base.triangles.size(); ++t)
    if (parts[t] > 0 && partsWith[t] == parts[t]) write(base.triangles[t], base.material[t], baseFlip[t]);
  for (std::size_t t = 0; t < cut.triangles.size(); ++t)
    if (cutStatus[t] == status && partsWith[baseOf[t]] != parts[baseOf[t]])
      write(cut.triangles[t], cut.material[t], cutFlip[t]);
  return mesh;
}

}  // namespace

std::optional<SheetSplit> detachSheets(const TriangleMesh& mesh, double planeToleranceM) {
  Soup base{mesh.positions, mesh.triangles, mesh.triangleMaterial, {}};
  base.origin.resize(base.triangles.size());
  std::iota(base.origin.begin(), base.origin.end(), 0u);
  weldPlaces(base, planeToleranceM);
  Soup slivers = takeSlivers(base, planeToleranceM);
  SheetSplit split;
  const Soup conformed = conform(base, planeToleranceM);
  Soup cut = cutAlongFreeEdges(conformed, planeToleranceM, split.cutTriangles);
  // The parts of two faces cut where they meet share the cut's end; faces written whole use the
  // same places.
  const std::vector<std::uint32_t> place = weldPlaces(cut, planeToleranceM);
  for (Soup* whole : {&base, &slivers})
    for (Triangle& t : whole->triangles)
      for (std::uint32_t& v : t) v = place[v];
  // The cut faces' edges are matched where they meet, the decision taken on that surface, and
  // each cut face takes the decision of its parts (its fan's inner edges join them in one piece).
  Soup joined = conform(cut, planeToleranceM);
  std::vector<std::uint8_t> kept(joined.triangles.size(), 1);
  peel(joined, kept);
  dropInnerPieces(joined, kept);
  const std::vector<std::uint8_t> flip = orientation(joined, kept);
  for (std::size_t t = 0; t < joined.triangles.size(); ++t)
    if (flip[t]) std::swap(joined.triangles[t][1], joined.triangles[t][2]);
  if (std::all_of(kept.begin(), kept.end(), [](std::uint8_t k) { return k == 1; })) return std::nullopt;
  split.closed = closes(joined, kept);
  std::vector<std::uint8_t> cutStatus(cut.triangles.size(), 1);
  std::vector<std::uint8_t> cutFlip(cut.triangles.size(), 0);
  for (std::size_t t = 0; t < joined.triangles.size(); ++t) {
    cutStatus[joined.origin[t]] = kept[t];
    cutFlip[joined.origin[t]] = flip[t];
  }
  split.hiddenTriangles = static_cast<std::size_t>(std::count(cutStatus.begin(), cutStatus.end(), 2));
  std::vector<std::uint32_t> baseOf(cut.triangles.size());
  for (std::size_t t = 0; t < cut.triangles.size(); ++t) baseOf[t] = conformed.origin[cut.origin[t]];
  split.body = meshOf(base, cut, baseOf, cutStatus, cutFlip, 1, mesh);
  split.sheets = meshOf(base, cut, baseOf, cutStatus, cutFlip, 0, mesh);
  for (std::size_t t = 0; t < slivers.triangles.size(); ++t) {
    const auto first = static_cast<std::uint32_t>(split.sheets.positions.size());
    for (std::uint32_t v : slivers.triangles[t]) split.sheets.positions.push_back(cut.points[v]);
    split.sheets.triangles.push_back({first, first + 1, first + 2});
    split.sheets.triangleMaterial.push_back(slivers.material[t]);
  }
  if (split.body.triangles.empty() || split.sheets.area() > kMaxSheetShare * mesh.area()) return std::nullopt;
  split.bodyCheck = checkAndRepair(split.body);
  return split;
}

}  // namespace nut::converter
