// NUT -> triangle mesh (mesh_export.hpp): a walk over the DAG that emits every solid cell's
// boundary in the root block's frame, clipped by its ancestor cells, and the OBJ/MTL writer.
//
// Every solid is built once per segment count in the unit cube as a union of convex pieces whose
// shared faces are marked internal: the planar solids and the quarter cylinder are one piece, the
// inverse quarter cylinder is a fan of triangular prisms, the octants are cones over the triangles
// of their spherical patch (from the corner, or for the inverse octant from the opposite corner,
// which also takes the three cut cube faces). A cell inside every ancestor cell emits the
// non-internal faces directly. A cell that an ancestor cell cuts maps the pieces to the root frame
// and clips each against the cutting planes; a convex piece cut by a plane stays convex and is
// closed by one convex cap on the plane. So clipping never needs general polygon booleans, and the
// pieces' caps meet edge to edge because a segment's crossing with a plane is computed from its
// endpoints in a fixed order (the same numbers on both sides of a shared edge).
#include <nut/mesh_export.hpp>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <unordered_map>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>

namespace nut {

namespace {

using glm::dvec3;

// Points within this distance of a clipping plane count as lying on it. Far above the rounding
// of root-frame coordinates (below 1e-11 m for 16 km blocks) and far below the format's 1 mm, so
// a sub-block that exactly fills its cell, or one turned by a quarter yaw (cos = 6e-17), is not cut.
constexpr double kOnPlaneM = 1e-7;

// ---------------------------------------------------------------------------------------------
// Convex polygons and pieces

struct Face {
  std::vector<dvec3> points;  // convex polygon, counter-clockwise seen from outside the piece
  bool internal = false;      // shared with another piece of the same solid: never emitted
};
using Piece = std::vector<Face>;  // a closed convex polyhedron
using Triangle = std::array<dvec3, 3>;

// Twice the area times the unit normal (Newell), relative to the first point for precision.
dvec3 areaNormal(const std::vector<dvec3>& points) {
  dvec3 n(0.0);
  for (std::size_t i = 1; i + 1 < points.size(); ++i) n += glm::cross(points[i] - points[0], points[i + 1] - points[0]);
  return n;
}

bool degenerate(const dvec3& a, const dvec3& b, const dvec3& c) {
  const dvec3 u = b - a, v = c - a;
  return glm::length(glm::cross(u, v)) <= 1e-12 * glm::length(u) * glm::length(v);
}

// Triangles of a convex polygon, same orientation. A fan from the first point unless that would
// make a sliver (three points in a row, which clipping can produce), then a fan from the centroid.
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

struct Plane {
  dvec3 normal;   // unit
  double offset;  // the kept side is dot(normal, p) <= offset
  double distance(const dvec3& p) const { return glm::dot(normal, p) - offset; }
};

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

// Clips a convex piece to the plane's kept side and closes it with a cap. Returns false when
// nothing of the piece is left.
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
    if (points.size() >= 3) clipped.push_back({std::move(points), f.internal});
  }
  std::vector<dvec3> cap = capPolygon(std::move(onPlane), plane);
  if (cap.size() >= 3) clipped.push_back({std::move(cap), false});
  piece = std::move(clipped);
  return true;
}

// ---------------------------------------------------------------------------------------------
// The 69 solids in the unit cube

// Builds a shape in primed coordinates q (distances from the solid's edge or corner, solids.hpp)
// and maps them to the unit cube; exact for q = 0 and q = 1, so cube faces stay exactly planar.
struct Placement {
  std::array<int, 3> axis{0, 1, 2};  // unit-cube axis of q[i]
  std::array<bool, 3> flip{};        // p = 1 - q on that axis
  dvec3 toCube(const dvec3& q) const {
    dvec3 p(0.0);
    for (int i = 0; i < 3; ++i) p[axis[i]] = flip[i] ? 1.0 - q[i] : q[i];
    return p;
  }
};

Placement placementOf(Solid s) {
  const int o = solidOrientation(s);
  Placement placement;
  switch (solidGroup(s)) {
    case SolidGroup::Box:
      break;
    case SolidGroup::Wedge:
    case SolidGroup::QuarterCylinder:
    case SolidGroup::InverseQuarterCylinder: {
      // q = (u', v', w): (u, v, axis) is a cyclic order of the cube's axes.
      const int axis = o / 4, corner = o % 4;
      placement.axis = {(axis + 1) % 3, (axis + 2) % 3, axis};
      placement.flip = {(corner & 1) != 0, (corner & 2) != 0, false};
      break;
    }
    default:
      placement.flip = {(o & 1) != 0, (o & 2) != 0, (o & 4) != 0};
      break;
  }
  return placement;
}

// A prism over a convex polygon of the (q0, q1) square, from q2 = 0 to q2 = 1.
Piece prism(const std::vector<glm::dvec2>& polygon, const std::vector<bool>& sideInternal) {
  Face bottom, top;
  for (const glm::dvec2& v : polygon) {
    bottom.points.push_back({v.x, v.y, 0.0});
    top.points.push_back({v.x, v.y, 1.0});
  }
  Piece piece{bottom, top};
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    piece.push_back({{{a.x, a.y, 0.0}, {b.x, b.y, 0.0}, {b.x, b.y, 1.0}, {a.x, a.y, 1.0}}, sideInternal[i]});
  }
  return piece;
}

// The tetrahedron from apex over a triangle of a solid's surface; its sides are shared with the
// cones over the neighbouring triangles.
Piece cone(const dvec3& apex, const Triangle& base) {
  Piece piece{{{base[0], base[1], base[2]}, false}};
  for (int i = 0; i < 3; ++i) piece.push_back({{apex, base[i], base[(i + 1) % 3]}, true});
  return piece;
}

Piece unitCube() { return prism({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {false, false, false, false}); }

// The cube's part where dot(normal, q) <= offset (wedge, pyramid and inverse pyramid all cut the
// cube through its corners, so no new points are made).
Piece cutCube(const dvec3& normal, double offset) {
  Piece piece = unitCube();
  const double length = glm::length(normal);
  clipPiece(piece, {normal / length, offset / length});
  return piece;
}

// The quarter arc from (1, 0) to (0, 1) in n segments, exact at both ends.
std::vector<glm::dvec2> quarterArc(int n) {
  std::vector<glm::dvec2> arc{{1.0, 0.0}};
  for (int i = 1; i < n; ++i) {
    const double angle = std::numbers::pi / 2 * i / n;
    arc.push_back({std::cos(angle), std::sin(angle)});
  }
  arc.push_back({0.0, 1.0});
  return arc;
}

// The unit sphere's positive octant as n^2 triangles: the triangle with corners on the three axes,
// subdivided n times along each edge, its points pushed onto the sphere. Points on the arcs have
// exact zeros, and the arc in the plane q_a = 0 is the same list of points wherever it is used.
struct OctantPatch {
  int n = 0;
  std::vector<dvec3> points;  // (i, j) -> index, i + j <= n
  std::vector<std::array<int, 3>> triangles;
  int index(int i, int j) const { return j * (n + 1) - j * (j - 1) / 2 + i; }
  const dvec3& at(int i, int j) const { return points[static_cast<std::size_t>(index(i, j))]; }
};

OctantPatch octantPatch(int n) {
  OctantPatch patch;
  patch.n = n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j <= n; ++i) {
      // Divided by the length, not multiplied by its inverse (glm::normalize): n / sqrt(n^2) is
      // exactly 1, so the arcs' end points are exactly the cube's corners.
      const dvec3 p(i, j, n - i - j);
      patch.points.push_back(p / glm::length(p));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      patch.triangles.push_back({patch.index(i, j), patch.index(i + 1, j), patch.index(i, j + 1)});
      if (i + j + 1 < n)
        patch.triangles.push_back({patch.index(i + 1, j), patch.index(i + 1, j + 1), patch.index(i, j + 1)});
    }
  return patch;
}

// Largest gap between the unit sphere and the patch's triangles: a triangle lies in its circumdisk,
// which is a slice of the unit ball at distance sqrt(1 - R^2) from the centre.
double octantUnitError(int n) {
  const OctantPatch patch = octantPatch(n);
  double worst = 0.0;
  for (const auto& t : patch.triangles) {
    const dvec3 a = patch.points[static_cast<std::size_t>(t[0])], b = patch.points[static_cast<std::size_t>(t[1])],
                c = patch.points[static_cast<std::size_t>(t[2])];
    const double r =
        glm::length(a - b) * glm::length(b - c) * glm::length(c - a) / (2.0 * glm::length(glm::cross(b - a, c - a)));
    worst = std::max(worst, 1.0 - std::sqrt(std::max(0.0, 1.0 - r * r)));
  }
  return worst;
}

std::vector<Piece> shapePieces(SolidGroup group, int n) {
  std::vector<Piece> pieces;
  switch (group) {
    case SolidGroup::Box:
      pieces.push_back(unitCube());
      break;
    case SolidGroup::Wedge:
      pieces.push_back(cutCube({1, 1, 0}, 1));
      break;
    case SolidGroup::Pyramid:
      pieces.push_back(cutCube({1, 1, 1}, 1));
      break;
    case SolidGroup::InversePyramid:
      pieces.push_back(cutCube({-1, -1, -1}, -1));
      break;
    case SolidGroup::QuarterCylinder: {
      std::vector<glm::dvec2> polygon{{0.0, 0.0}};
      for (const glm::dvec2& p : quarterArc(n)) polygon.push_back(p);
      pieces.push_back(prism(polygon, std::vector<bool>(polygon.size(), false)));
      break;
    }
    case SolidGroup::InverseQuarterCylinder: {
      // A fan of prisms from the far edge; the first and last radial sides lie on cube faces.
      const std::vector<glm::dvec2> arc = quarterArc(n);
      for (std::size_t i = 0; i + 1 < arc.size(); ++i)
        pieces.push_back(prism({{1.0, 1.0}, arc[i + 1], arc[i]}, {true, false, true}));
      break;
    }
    case SolidGroup::SphereOctant: {
      const OctantPatch patch = octantPatch(n);
      for (const auto& t : patch.triangles)
        pieces.push_back(cone(
            dvec3(0.0), {patch.points[static_cast<std::size_t>(t[0])], patch.points[static_cast<std::size_t>(t[1])],
                         patch.points[static_cast<std::size_t>(t[2])]}));
      break;
    }
    case SolidGroup::InverseSphereOctant: {
      // Star-shaped from the far corner: cones over the patch and over the three cube faces at the
      // corner minus their quarter discs (each a fan from that face's far corner).
      const OctantPatch patch = octantPatch(n);
      const dvec3 far(1.0);
      for (const auto& t : patch.triangles)
        pieces.push_back(
            cone(far, {patch.points[static_cast<std::size_t>(t[0])], patch.points[static_cast<std::size_t>(t[1])],
                       patch.points[static_cast<std::size_t>(t[2])]}));
      for (int k = 0; k < n; ++k) {
        pieces.push_back(cone(far, {dvec3(0, 1, 1), patch.at(0, k), patch.at(0, k + 1)}));              // q0 = 0
        pieces.push_back(cone(far, {dvec3(1, 0, 1), patch.at(k, 0), patch.at(k + 1, 0)}));              // q1 = 0
        pieces.push_back(cone(far, {dvec3(1, 1, 0), patch.at(k, n - k), patch.at(k + 1, n - k - 1)}));  // q2 = 0
      }
      break;
    }
  }
  return pieces;
}

// The cube face (2 * axis + 0 for the face at 0, + 1 for the face at 1) a polygon lies on, or -1.
int cubeFaceOf(const std::vector<dvec3>& points) {
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side)
      if (std::all_of(points.begin(), points.end(), [&](const dvec3& p) { return p[a] == side; })) return 2 * a + side;
  return -1;
}

struct UnitSolid {
  std::vector<Piece> pieces;  // unit-cube coordinates, oriented outwards
  struct Tri {
    std::array<std::uint32_t, 3> v;
    int cubeFace;  // the face of the unit cube the triangle lies on, or -1
  };
  std::vector<dvec3> vertices;      // of the boundary triangles
  std::vector<Tri> triangles;       // the non-internal faces
  std::array<bool, 6> fullFaces{};  // the solid covers that cube face completely
};

UnitSolid buildUnitSolid(Solid s, int n) {
  UnitSolid unit;
  const Placement placement = placementOf(s);
  unit.pieces = shapePieces(solidGroup(s), n);
  std::map<std::array<double, 3>, std::uint32_t> ids;
  std::array<double, 6> faceArea{};
  std::vector<Triangle> triangles;
  for (Piece& piece : unit.pieces) {
    dvec3 centre(0.0);
    int count = 0;
    for (Face& f : piece)
      for (dvec3& p : f.points) p = placement.toCube(p), centre += p, ++count;
    centre /= count;
    for (Face& f : piece) {
      // The constructors do not track winding (and mirrored placements flip it): orient each face
      // away from the convex piece's centre, keeping its first point (a cylinder's end face fans
      // out from the axis).
      dvec3 faceCentre(0.0);
      for (const dvec3& p : f.points) faceCentre += p;
      faceCentre /= static_cast<double>(f.points.size());
      if (glm::dot(areaNormal(f.points), faceCentre - centre) < 0) std::reverse(f.points.begin() + 1, f.points.end());
      const int cubeFace = cubeFaceOf(f.points);
      if (cubeFace >= 0) f.internal = false;  // nothing of the solid lies beyond a cube face
      if (f.internal) continue;
      if (cubeFace >= 0) faceArea[static_cast<std::size_t>(cubeFace)] += glm::length(areaNormal(f.points)) / 2;
      triangles.clear();
      triangulateConvex(f.points, triangles);
      for (const Triangle& t : triangles) {
        UnitSolid::Tri tri{{}, cubeFace};
        for (int i = 0; i < 3; ++i) {
          const auto [it, added] =
              ids.try_emplace({t[i].x, t[i].y, t[i].z}, static_cast<std::uint32_t>(unit.vertices.size()));
          if (added) unit.vertices.push_back(t[i]);
          tri.v[i] = it->second;
        }
        unit.triangles.push_back(tri);
      }
    }
  }
  for (int f = 0; f < 6; ++f) unit.fullFaces[f] = std::abs(faceArea[f] - 1.0) < 1e-9;
  return unit;
}

// ---------------------------------------------------------------------------------------------
// The walk

struct Frame {  // block-local coordinates (tile offsets included) -> root frame
  glm::dmat3 rotation{1.0};
  dvec3 translation{0.0};
  dvec3 apply(const dvec3& p) const { return translation + rotation * p; }
};

struct Box {
  dvec3 lo, hi;
  // Exact at t = 0 and t = 1, so neighbouring cells share their corners bit for bit.
  dvec3 at(const dvec3& t) const { return lo * (dvec3(1.0) - t) + hi * t; }
};

// The planes among `planes` that cut the box; nullopt when the box lies outside one of them.
std::optional<std::vector<Plane>> cuttingPlanes(const std::vector<Plane>& planes, const Frame& frame, const Box& box) {
  std::vector<Plane> cutting;
  if (planes.empty()) return cutting;
  std::array<dvec3, 8> corners;
  for (int i = 0; i < 8; ++i)
    corners[static_cast<std::size_t>(i)] =
        frame.apply({(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y, (i & 4) ? box.hi.z : box.lo.z});
  for (const Plane& plane : planes) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const dvec3& c : corners) {
      const double d = plane.distance(c);
      lo = std::min(lo, d), hi = std::max(hi, d);
    }
    if (lo >= -kOnPlaneM) return std::nullopt;
    if (hi > kOnPlaneM) cutting.push_back(plane);
  }
  return cutting;
}

struct PointHash {
  std::size_t operator()(const dvec3& p) const {
    std::size_t h = 0;
    for (int i = 0; i < 3; ++i)
      h = h * 0x9E3779B97F4A7C15ull + std::hash<std::uint64_t>{}(std::bit_cast<std::uint64_t>(p[i]));
    return h;
  }
};

// One instance of a block: where it is, how it tiles, and the clip planes of its ancestor cells.
struct Instance {
  BlockId block = 0;
  Frame frame;
  std::array<bool, 3> wrap{};
  const std::vector<Plane>* planes = nullptr;
  int depth = 0;
};

class Exporter {
 public:
  // boundsOnly: keep only the bounding box of the vertices the mesh would have (contentBounds), with
  // no welding and no triangles, which were most of the time and memory of a large HNI's bounds.
  Exporter(const Hierarchy& h, const MeshExportOptions& options, bool boundsOnly = false)
      : h_(h), options_(options), boundsOnly_(boundsOnly) {
    for (int s = 0; s < kSolidCount; ++s)
      fullFaces_[static_cast<std::size_t>(s)] = buildUnitSolid(Solid{static_cast<std::uint8_t>(s)}, 2).fullFaces;
    findBlocksWithSolids();
  }

  Result<ExportedMesh> run(const glm::dvec3& originM) {
    const std::vector<Plane> none;
    visitTile({h_.root, Frame{}, {}, &none, 0}, dvec3(0.0));
    if (failure_) return *failure_;
    for (dvec3& p : mesh_.positions) p += originM;
    return std::move(mesh_);
  }

  // The vertex bounds run() would give, or nothing when the mesh has no vertex. Adding the origin
  // to the extremes gives the extremes of the vertices moved by it (rounding is monotonic).
  Result<std::optional<WorldBox>> runBounds(const glm::dvec3& originM) {
    const std::vector<Plane> none;
    visitTile({h_.root, Frame{}, {}, &none, 0}, dvec3(0.0));
    if (failure_) return *failure_;
    if (!bounds_) return std::optional<WorldBox>{};
    return std::optional<WorldBox>{WorldBox{bounds_->min + originM, bounds_->max + originM}};
  }

 private:
  void findBlocksWithSolids() {
    // Post-order over the DAG with an explicit stack: chains of thousands of blocks are valid.
    content_.assign(h_.blocks.size(), Content::Unknown);
    for (BlockId start = 0; start < h_.blocks.size(); ++start) {
      std::vector<BlockId> stack{start};
      while (!stack.empty()) {
        const BlockId b = stack.back();
        if (content_[b] == Content::Empty || content_[b] == Content::Solid) {
          stack.pop_back();
          continue;
        }
        const Block& block = h_.blocks[b];
        bool pending = false;
        if (content_[b] == Content::Unknown) {
          content_[b] = Content::Visiting;
          for (const Redirection& r : block.redirections)
            if (content_[r.target] == Content::Unknown) stack.push_back(r.target), pending = true;
        }
        if (pending) continue;
        bool solid = false;
        for (const Cell& c : block.cells)
          solid |= c.kind == CellKind::Solid ||
                   (c.kind == CellKind::Redirection && hasSolid(block.redirections[c.redirection].target));
        content_[b] = solid ? Content::Solid : Content::Empty;
        stack.pop_back();
      }
    }
  }

  bool hasSolid(BlockId b) const { return content_[b] == Content::Solid; }

  void fail(std::string message) {
    if (!failure_) failure_ = Error{"mesh export: " + std::move(message)};
  }

  static std::string cellName(BlockId b, int x, int y, int z) {
    return "block " + std::to_string(b) + " cell (" + std::to_string(x) + "," + std::to_string(y) + "," +
           std::to_string(z) + ")";
  }

  // Boundary i of axis a in tile `tile` (block-local, tiles along wrapped axes). The last boundary
  // of tile k is written as the first of tile k + 1, so cells on both sides of a wrap seam share
  // their corners bit for bit.
  static double boundary(const Block& block, int a, double tile, int i) {
    const auto& bounds = block.boundsM[static_cast<std::size_t>(a)];
    const double size = bounds.back();
    return static_cast<std::size_t>(i) + 1 == bounds.size() ? (tile + 1) * size
                                                            : tile * size + bounds[static_cast<std::size_t>(i)];
  }

  static Box cellBox(const Block& block, const dvec3& tile, const glm::ivec3& c) {
    Box box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = boundary(block, a, tile[a], c[a]);
      box.hi[a] = boundary(block, a, tile[a], c[a] + 1);
    }
    return box;
  }

  static Box tileBox(const Block& block, const dvec3& tile) {
    return {cellBox(block, tile, {0, 0, 0}).lo,
            cellBox(block, tile, {block.cellCount(0) - 1, block.cellCount(1) - 1, block.cellCount(2) - 1}).hi};
  }

  // Segments per quarter arc for a quadric whose largest radius is radiusM.
  int segmentsFor(SolidGroup group, double radiusM) {
    const bool octant = group == SolidGroup::SphereOctant || group == SolidGroup::InverseSphereOctant;
    for (int n = options_.minSegmentsPerQuarter; n < options_.maxSegmentsPerQuarter; ++n) {
      double unitError;
      if (octant) {
        while (static_cast<int>(octantErrors_.size()) <= n)
          octantErrors_.push_back(octantUnitError(static_cast<int>(octantErrors_.size())));
        unitError = octantErrors_[static_cast<std::size_t>(n)];
      } else {
        unitError = 1.0 - std::cos(std::numbers::pi / (4.0 * n));
      }
      if (unitError * radiusM <= options_.toleranceM) return n;
    }
    return options_.maxSegmentsPerQuarter;
  }

  const UnitSolid& unitSolid(Solid s, const dvec3& sizeM) {
    const SolidGroup group = solidGroup(s);
    int n = 0;
    if (group == SolidGroup::QuarterCylinder || group == SolidGroup::InverseQuarterCylinder) {
      const Placement p = placementOf(s);
      n = segmentsFor(group, std::max(sizeM[p.axis[0]], sizeM[p.axis[1]]));
    } else if (group == SolidGroup::SphereOctant || group == SolidGroup::InverseSphereOctant) {
      n = segmentsFor(group, std::max({sizeM.x, sizeM.y, sizeM.z}));
    }
    const auto key = std::make_pair(s.index, n);
    auto it = units_.find(key);
    if (it == units_.end()) it = units_.emplace(key, buildUnitSolid(s, n)).first;
    return it->second;
  }

  std::uint32_t vertex(const dvec3& p) {
    if (boundsOnly_) {
      // Every vertex is id 0, so triangle() drops every triangle as collapsed.
      const dvec3 q = p + dvec3(0.0);
      bounds_ = bounds_ ? WorldBox{glm::min(bounds_->min, q), glm::max(bounds_->max, q)} : WorldBox{q, q};
      return 0;
    }
    // + 0.0 turns -0.0 into +0.0: equal points must hash alike.
    const auto [it, added] = vertexIds_.try_emplace(p + dvec3(0.0), static_cast<std::uint32_t>(mesh_.positions.size()));
    if (added) mesh_.positions.push_back(it->first);
    return it->second;
  }

  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t material) {
    if (a == b || b == c || c == a) return;  // collapsed by welding: its edges cancel out
    if (mesh_.triangles.size() >= options_.maxTriangles) {
      fail("more than " + std::to_string(options_.maxTriangles) +
           " triangles (the limit); raise the tolerance or the limit");
      return;
    }
    mesh_.triangles.push_back({a, b, c});
    mesh_.triangleMaterial.push_back(material);
  }

  bool opaque(const Cell& c) const { return h_.materials[c.material].opacity == 255; }

  // Whether cell c's face (2 * axis + side) is culled: see mesh_export.hpp.
  bool culled(const Instance& inst, const dvec3& tile, const std::vector<Plane>& tilePlanes, const glm::ivec3& c,
              int face) {
    const Block& block = h_.blocks[inst.block];
    const int a = face / 2, step = face % 2 == 1 ? 1 : -1;
    glm::ivec3 n = c;
    dvec3 nTile = tile;
    n[a] += step;
    if (n[a] < 0 || n[a] >= block.cellCount(a)) {
      if (!inst.wrap[static_cast<std::size_t>(a)]) return false;
      n[a] = step > 0 ? 0 : block.cellCount(a) - 1;
      nTile[a] += step;
    }
    const Cell& neighbour = block.cell(n.x, n.y, n.z);
    if (neighbour.kind != CellKind::Solid || !opaque(neighbour) ||
        !fullFaces_[neighbour.solid.index][static_cast<std::size_t>(face ^ 1)])
      return false;
    // The neighbour must be whole, judged exactly as its own tile judges it.
    std::optional<std::vector<Plane>> planes = tilePlanes;
    if (nTile != tile) planes = cuttingPlanes(*inst.planes, inst.frame, tileBox(block, nTile));
    if (!planes) return false;
    const auto cut = cuttingPlanes(*planes, inst.frame, cellBox(block, nTile, n));
    return cut && cut->empty();
  }

  void emitWhole(const Instance& inst, const dvec3& tile, const std::vector<Plane>& tilePlanes, const glm::ivec3& c,
                 const Box& box) {
    const Cell& cell = h_.blocks[inst.block].cell(c.x, c.y, c.z);
    const UnitSolid& unit = unitSolid(cell.solid, box.hi - box.lo);
    std::array<bool, 6> skip{};
    if (opaque(cell))
      for (int f = 0; f < 6; ++f)
        skip[static_cast<std::size_t>(f)] =
            unit.fullFaces[static_cast<std::size_t>(f)] && culled(inst, tile, tilePlanes, c, f);
    std::vector<std::uint32_t> ids(unit.vertices.size(), std::numeric_limits<std::uint32_t>::max());
    const auto id = [&](std::uint32_t v) {
      if (ids[v] == std::numeric_limits<std::uint32_t>::max())
        ids[v] = vertex(inst.frame.apply(box.at(unit.vertices[v])));
      return ids[v];
    };
    for (const UnitSolid::Tri& t : unit.triangles)
      if (t.cubeFace < 0 || !skip[static_cast<std::size_t>(t.cubeFace)])
        triangle(id(t.v[0]), id(t.v[1]), id(t.v[2]), cell.material);
  }

  void emitCut(const Instance& inst, const Cell& cell, const Box& box, const std::vector<Plane>& cutting) {
    const UnitSolid& unit = unitSolid(cell.solid, box.hi - box.lo);
    std::vector<Triangle> triangles;
    for (Piece piece : unit.pieces) {
      for (Face& f : piece)
        for (dvec3& p : f.points) p = inst.frame.apply(box.at(p));
      bool left = true;
      for (const Plane& plane : cutting)
        if (!(left = clipPiece(piece, plane))) break;
      if (!left) continue;
      for (const Face& f : piece)
        if (!f.internal) triangulateConvex(f.points, triangles);
    }
    for (const Triangle& t : triangles) triangle(vertex(t[0]), vertex(t[1]), vertex(t[2]), cell.material);
  }

  void redirect(const Instance& inst, const glm::ivec3& c, const Box& box, const std::vector<Plane>& cutting) {
    const Block& block = h_.blocks[inst.block];
    const Redirection& r = block.redirections[block.cell(c.x, c.y, c.z).redirection];
    if (inst.depth + 1 > options_.maxDepth) {
      fail(cellName(inst.block, c.x, c.y, c.z) + ": redirections nested deeper than " +
           std::to_string(options_.maxDepth) + " levels (the ray casters draw deeper levels as visual summaries)");
      return;
    }
    const glm::dmat3 rotation = rotationMatrix(r.rotation);
    Instance child{r.target,
                   {inst.frame.rotation * rotation, inst.frame.apply(box.lo + r.offsetM)},
                   r.wrap,
                   nullptr,
                   inst.depth + 1};
    // The child is clipped by this cell and by whatever cuts this cell.
    std::vector<Plane> planes = cutting;
    const dvec3 lo = inst.frame.apply(box.lo), hi = inst.frame.apply(box.hi);
    for (int a = 0; a < 3; ++a) {
      const dvec3 axis = inst.frame.rotation[a];
      planes.push_back({axis, glm::dot(axis, hi)});
      planes.push_back({-axis, -glm::dot(axis, lo)});
    }
    child.planes = &planes;
    // The tiles that can reach into the cell: the cell's bounding box in the target's frame.
    const Block& target = h_.blocks[r.target];
    dvec3 sMin(std::numeric_limits<double>::infinity()), sMax(-std::numeric_limits<double>::infinity());
    const dvec3 size = box.hi - box.lo;
    for (int i = 0; i < 8; ++i) {
      const dvec3 corner((i & 1) ? size.x : 0.0, (i & 2) ? size.y : 0.0, (i & 4) ? size.z : 0.0);
      const dvec3 s = glm::transpose(rotation) * (corner - r.offsetM);
      sMin = glm::min(sMin, s), sMax = glm::max(sMax, s);
    }
    dvec3 first, last;
    double tiles = 1;
    for (int a = 0; a < 3; ++a) {
      const double d = target.sizeM()[a];
      if (r.wrap[static_cast<std::size_t>(a)]) {
        first[a] = std::floor(sMin[a] / d), last[a] = std::ceil(sMax[a] / d) - 1;
      } else {
        if (sMax[a] <= kOnPlaneM || sMin[a] >= d - kOnPlaneM) return;
        first[a] = last[a] = 0;
      }
      tiles *= std::max(0.0, last[a] - first[a] + 1);
    }
    if (tiles > static_cast<double>(options_.maxCellVisits - visits_)) {
      char count[32];
      std::snprintf(count, sizeof count, "%.0f", tiles);
      fail(cellName(inst.block, c.x, c.y, c.z) + " repeats block " + std::to_string(r.target) + " " + count +
           " times, over the limit of " + std::to_string(options_.maxCellVisits) + " cell visits");
      return;
    }
    for (double kz = first.z; kz <= last.z; ++kz)
      for (double ky = first.y; ky <= last.y; ++ky)
        for (double kx = first.x; kx <= last.x; ++kx) {
          visitTile(child, {kx, ky, kz});
          if (failure_) return;
        }
  }

  void visitTile(const Instance& inst, const dvec3& tile) {
    if (++visits_ > options_.maxCellVisits) {
      fail("more than " + std::to_string(options_.maxCellVisits) + " cell visits (the limit)");
      return;
    }
    const Block& block = h_.blocks[inst.block];
    const auto tilePlanes = cuttingPlanes(*inst.planes, inst.frame, tileBox(block, tile));
    if (!tilePlanes) return;
    for (int z = 0; z < block.cellCount(2); ++z)
      for (int y = 0; y < block.cellCount(1); ++y)
        for (int x = 0; x < block.cellCount(0); ++x) {
          if (++visits_ > options_.maxCellVisits) {
            fail("more than " + std::to_string(options_.maxCellVisits) + " cell visits (the limit)");
            return;
          }
          const Cell& cell = block.cell(x, y, z);
          if (cell.kind == CellKind::Empty) continue;
          if (cell.kind == CellKind::Redirection && !hasSolid(block.redirections[cell.redirection].target)) continue;
          const glm::ivec3 c(x, y, z);
          const Box box = cellBox(block, tile, c);
          const auto cutting = cuttingPlanes(*tilePlanes, inst.frame, box);
          if (!cutting) continue;
          if (cell.kind == CellKind::Redirection)
            redirect(inst, c, box, *cutting);
          else if (cutting->empty())
            emitWhole(inst, tile, *tilePlanes, c, box);
          else
            emitCut(inst, cell, box, *cutting);
          if (failure_) return;
        }
  }

  const Hierarchy& h_;
  const MeshExportOptions& options_;
  std::array<std::array<bool, 6>, kSolidCount> fullFaces_{};
  enum class Content : std::uint8_t { Unknown, Visiting, Empty, Solid };  // what a block holds, below it too
  std::vector<Content> content_;
  std::map<std::pair<std::uint8_t, int>, UnitSolid> units_;
  std::vector<double> octantErrors_{1.0};  // index n; n = 0 is never used
  const bool boundsOnly_;
  std::optional<WorldBox> bounds_;  // boundsOnly_: of the vertices so far
  std::unordered_map<dvec3, std::uint32_t, PointHash> vertexIds_;
  ExportedMesh mesh_;
  std::uint64_t visits_ = 0;
  std::optional<Error> failure_;
};

// ---------------------------------------------------------------------------------------------
// OBJ / MTL

void appendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);  // shortest exact form
  out.append(buffer, result.ptr);
}

void appendNumber(std::string& out, std::uint64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

std::filesystem::path temporarySibling(const std::filesystem::path& path) {
  std::random_device device;
  return path.parent_path() / (path.filename().string() + ".tmp" + std::to_string(device()));
}

// Streams `write`'s chunks to a temporary sibling of path; returns its name.
Result<std::filesystem::path> writeTemporary(const std::filesystem::path& path,
                                             const std::function<bool(std::ofstream&)>& write) {
  const std::filesystem::path temporary = temporarySibling(path);
  std::ofstream out(temporary, std::ios::binary);
  if (!out) return Error{path.string() + ": cannot create the file"};
  if (!write(out) || !out.flush()) {
    out.close();
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return Error{path.string() + ": write failed"};
  }
  return temporary;
}

}  // namespace

Result<ExportedMesh> exportMesh(const Hierarchy& h, const glm::dvec3& originM, const MeshExportOptions& options) {
  if (Status s = checkHierarchy(h); !s) return s.error();
  if (!(options.toleranceM > 0) || options.minSegmentsPerQuarter < 1 ||
      options.maxSegmentsPerQuarter < options.minSegmentsPerQuarter)
    return Error{"mesh export: the tolerance must be positive and 1 <= minimum segments <= maximum segments"};
  Exporter exporter(h, options);
  return exporter.run(originM);
}

Result<WorldBox> contentBounds(const Hierarchy& h, const glm::dvec3& originM) {
  if (Status s = checkHierarchy(h); !s) return s.error();
  MeshExportOptions coarse;
  coarse.minSegmentsPerQuarter = coarse.maxSegmentsPerQuarter = 1;
  Exporter exporter(h, coarse, /*boundsOnly=*/true);
  auto bounds = exporter.runBounds(originM);
  if (!bounds) return bounds.error();
  if (!*bounds) return WorldBox{originM, originM + h.blocks[h.root].sizeM()};
  return **bounds;
}

Status writeObj(const std::string& objPath, const ExportedMesh& mesh, const std::vector<Material>& materials) {
  for (std::uint16_t m : mesh.triangleMaterial)
    if (m >= materials.size())
      return Error{objPath + ": material " + std::to_string(m) + " out of range (" + std::to_string(materials.size()) +
                   " materials)"};
  const std::filesystem::path obj(objPath);
  const std::filesystem::path mtl = std::filesystem::path(obj).replace_extension(".mtl");
  if (mtl == obj) return Error{objPath + ": the OBJ file needs a name other than its MTL file's"};

  auto mtlTemporary = writeTemporary(mtl, [&](std::ofstream& out) {
    std::string text = "# nut export-mesh materials: Kd = sRGB bytes / 255 (as stored), d = opacity / 255\n";
    for (std::size_t m = 0; m < materials.size(); ++m) {
      const Material& mat = materials[m];
      text += "\nnewmtl m";
      appendNumber(text, std::uint64_t{m});
      text += "\nKd ";
      appendNumber(text, mat.r / 255.0);
      text += ' ';
      appendNumber(text, mat.g / 255.0);
      text += ' ';
      appendNumber(text, mat.b / 255.0);
      text += "\nd ";
      appendNumber(text, mat.opacity / 255.0);
      text += '\n';
    }
    return static_cast<bool>(out.write(text.data(), static_cast<std::streamsize>(text.size())));
  });
  if (!mtlTemporary) return mtlTemporary.error();

  auto objTemporary = writeTemporary(obj, [&](std::ofstream& out) {
    std::string text = "# nut export-mesh: world coordinates in metres\nmtllib " + mtl.filename().string() + "\n";
    const auto flushIfLarge = [&] {
      if (text.size() < (1u << 20)) return true;
      const bool ok = static_cast<bool>(out.write(text.data(), static_cast<std::streamsize>(text.size())));
      text.clear();
      return ok;
    };
    for (const dvec3& p : mesh.positions) {
      text += "v ";
      appendNumber(text, p.x);
      text += ' ';
      appendNumber(text, p.y);
      text += ' ';
      appendNumber(text, p.z);
      text += '\n';
      if (!flushIfLarge()) return false;
    }
    // Triangles grouped by material, in their order within each group.
    std::vector<std::size_t> order(mesh.triangles.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return mesh.triangleMaterial[a] < mesh.triangleMaterial[b]; });
    for (std::size_t i = 0; i < order.size(); ++i) {
      const std::uint16_t m = mesh.triangleMaterial[order[i]];
      if (i == 0 || m != mesh.triangleMaterial[order[i - 1]]) {
        text += "usemtl m";
        appendNumber(text, std::uint64_t{m});
        text += '\n';
      }
      text += 'f';
      for (std::uint32_t v : mesh.triangles[order[i]]) {
        text += ' ';
        appendNumber(text, std::uint64_t{v} + 1);  // OBJ indices start at 1
      }
      text += '\n';
      if (!flushIfLarge()) return false;
    }
    return static_cast<bool>(out.write(text.data(), static_cast<std::streamsize>(text.size())));
  });
  std::error_code error;
  if (!objTemporary) {
    std::filesystem::remove(*mtlTemporary, error);
    return objTemporary.error();
  }
  for (const auto& [temporary, target] : {std::pair{*mtlTemporary, mtl}, std::pair{*objTemporary, obj}}) {
    std::filesystem::rename(temporary, target, error);
    if (error) {
      std::filesystem::remove(*mtlTemporary, error);
      std::filesystem::remove(*objTemporary, error);
      return Error{target.string() + ": cannot rename the written file into place"};
    }
  }
  return Ok{};
}

}  // namespace nut
