// NUT -> triangle mesh (mesh_export.hpp): a walk over the DAG that emits every solid cell's
// boundary in the root block's frame, clipped by its ancestor cells, and the OBJ/MTL writer.
//
// Every solid is built once per segment count in the unit cube as a union of convex pieces
// (unit_solids.hpp). A cell inside every ancestor cell emits the pieces' non-internal faces
// directly. A cell that an ancestor cell cuts maps the pieces to the root frame and clips each
// against the cutting planes (convex_pieces.hpp), whose caps meet edge to edge.
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
#include <unordered_map>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>

#include "atomic_file.hpp"
#include "convex_pieces.hpp"
#include "unit_solids.hpp"

namespace nut {

namespace {

using glm::dvec3;
using mesh::buildUnitSolid;
using mesh::clipPiece;
using mesh::Face;
using mesh::kOnPlaneM;
using mesh::octantUnitError;
using mesh::Piece;
using mesh::Placement;
using mesh::placementOf;
using mesh::Plane;
using mesh::Triangle;
using mesh::triangulateConvex;
using mesh::UnitSolid;

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
  // no welding and no triangles, which would be most of the time and memory of a large HNI's bounds.
  Exporter(const Hierarchy& h, const MeshExportOptions& options, bool boundsOnly = false)
      : h_(h), options_(options), boundsOnly_(boundsOnly) {
    for (int s = 0; s < kSolidCount; ++s)
      fullFaces_[static_cast<std::size_t>(s)] = buildUnitSolid(Solid{static_cast<std::uint8_t>(s)}, 2).fullFaces;
    findBlocksWithSolids();
  }

  Result<TriangleMesh> run(const glm::dvec3& originM) {
    const std::vector<Plane> none;
    visitTile({h_.root, Frame{}, {}, &none, 0}, dvec3(0.0));
    if (failure_) return *failure_;
    for (dvec3& p : mesh_.positions) p += originM;
    mesh_.materials = h_.materials;
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
          solid |= c.kind == CellKind::Solid || c.kind == CellKind::Plane ||
                   (c.kind == CellKind::Redirection && hasSolid(block.redirections[c.redirection].target));
        content_[b] = solid ? Content::Solid : Content::Empty;
        stack.pop_back();
      }
    }
  }

  bool hasSolid(BlockId b) const { return content_[b] == Content::Solid; }

  // The k-th of n indices to visit. The bounds walk takes them from both ends inwards (0, n - 1,
  // 1, n - 2, ...): the outermost cells and tiles set the bounds first, and the ones between them
  // are then skipped as covered. The export keeps the plain order, which numbers its vertices.
  std::int64_t visitOrder(std::int64_t k, std::int64_t n) const {
    if (!boundsOnly_) return k;
    return k % 2 == 0 ? k / 2 : n - 1 - k / 2;
  }

  // Whether the bounds so far hold everything a box could add (boundsOnly_): every vertex from
  // inside it lies in the box turned into the root frame, up to rounding and the kOnPlaneM by which
  // a piece may stand out of an ancestor cell uncut; the margin covers both many times over. The
  // bounds are extremes of vertices, so skipping such a box leaves them the same to the bit.
  bool covered(const Frame& frame, const Box& box) const {
    if (!bounds_) return false;
    constexpr double kMarginM = 10 * kOnPlaneM;
    const dvec3 centre = frame.apply(0.5 * (box.lo + box.hi));
    const glm::dmat3 absolute(glm::abs(frame.rotation[0]), glm::abs(frame.rotation[1]), glm::abs(frame.rotation[2]));
    const dvec3 reach = absolute * (0.5 * (box.hi - box.lo)) + kMarginM;
    return glm::all(glm::greaterThanEqual(centre - reach, bounds_->min)) &&
           glm::all(glm::lessThanEqual(centre + reach, bounds_->max));
  }

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
    std::vector<Piece> pieces = unitSolid(cell.solid, box.hi - box.lo).pieces;
    for (Piece& piece : pieces)
      for (Face& f : piece)
        for (dvec3& p : f.points) p = box.at(p);
    emitPieces(inst, std::move(pieces), cutting, cell.material);
  }

  // Pieces in block-local coordinates, turned into the root frame and clipped by `cutting`.
  void emitPieces(const Instance& inst, std::vector<Piece> pieces, const std::vector<Plane>& cutting,
                  std::uint16_t material) {
    std::vector<Triangle> triangles;
    std::vector<std::uint16_t> faceMaterials;  // per triangle
    for (Piece& piece : pieces) {
      for (Face& f : piece)
        for (dvec3& p : f.points) p = inst.frame.apply(p);
      bool left = true;
      for (const Plane& plane : cutting)
        if (!(left = clipPiece(piece, plane))) break;
      if (!left) continue;
      for (const Face& f : piece) {
        if (f.internal) continue;
        triangulateConvex(f.points, triangles);
        faceMaterials.resize(triangles.size(), f.material < 0 ? material : static_cast<std::uint16_t>(f.material));
      }
    }
    for (std::size_t k = 0; k < triangles.size(); ++k)
      triangle(vertex(triangles[k][0]), vertex(triangles[k][1]), vertex(triangles[k][2]), faceMaterials[k]);
  }

  // A plane cell: its box clipped by its planes (block frame, moved into the tile), one convex
  // piece; a valley is three, inside both planes, the first only and the second only, whose shared
  // caps are internal. The box's corners are those of the neighbouring cells, and a plane's
  // crossings with a shared edge are computed alike, so the caps of neighbours meet edge to edge.
  void emitPlaneCell(const Instance& inst, const Cell& cell, const dvec3& tile, const Box& box,
                     const std::vector<Plane>& cutting) {
    const Block& block = h_.blocks[inst.block];
    const PlaneCut& cut = block.cuts[cell.cut];
    const dvec3 tileOrigin = tile * block.sizeM();
    std::array<Plane, 2> planes{};
    for (std::size_t p = 0; p < 2; ++p)
      planes[p] = {cut.planes[p].normal, cut.planes[p].offsetM + glm::dot(cut.planes[p].normal, tileOrigin)};
    const auto flipped = [](const Plane& p) { return Plane{-p.normal, -p.offset}; };
    Piece cube = unitSolid(Solid{0}, box.hi - box.lo).pieces.front();
    for (Face& f : cube)
      for (dvec3& p : f.points) p = box.at(p);
    const auto clipped = [&](std::initializer_list<Plane> by) -> std::optional<Piece> {
      Piece piece = cube;
      for (const Plane& plane : by)
        if (!clipPiece(piece, plane)) return std::nullopt;
      return piece;
    };
    std::vector<Piece> pieces;
    if (cut.combine != PlaneCombine::Either) {
      const auto piece = cut.combine == PlaneCombine::One ? clipped({planes[0]}) : clipped({planes[0], planes[1]});
      if (piece) pieces.push_back(*piece);
    } else {
      auto both = clipped({planes[0], planes[1]});
      auto firstOnly = clipped({planes[0], flipped(planes[1])});
      auto secondOnly = clipped({flipped(planes[0]), planes[1]});
      const auto markInternal = [](Piece& piece, const Plane& plane) {
        for (Face& f : piece)
          if (std::all_of(f.points.begin(), f.points.end(),
                          [&](const dvec3& p) { return std::abs(plane.distance(p)) <= kOnPlaneM; }))
            f.internal = true;
      };
      if (both && firstOnly) markInternal(*both, planes[1]), markInternal(*firstOnly, planes[1]);
      if (both && secondOnly) markInternal(*both, planes[0]), markInternal(*secondOnly, planes[0]);
      for (auto* piece : {&both, &firstOnly, &secondOnly})
        if (*piece) pieces.push_back(**piece);
    }
    // The faces on a plane show its surface material.
    for (Piece& piece : pieces)
      for (Face& f : piece)
        for (std::size_t p = 0; p < static_cast<std::size_t>(cut.planeCount()); ++p)
          if (cut.surfaceMaterials[p] && std::all_of(f.points.begin(), f.points.end(), [&](const dvec3& q) {
                return std::abs(planes[p].distance(q)) <= kOnPlaneM;
              }))
            f.material = *cut.surfaceMaterials[p];
    emitPieces(inst, std::move(pieces), cutting, cell.material);
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
    // At most maxCellVisits tiles in all (above), so each count fits.
    const std::array<std::int64_t, 3> count{static_cast<std::int64_t>(last.x - first.x + 1),
                                            static_cast<std::int64_t>(last.y - first.y + 1),
                                            static_cast<std::int64_t>(last.z - first.z + 1)};
    for (std::int64_t kz = 0; kz < count[2]; ++kz)
      for (std::int64_t ky = 0; ky < count[1]; ++ky)
        for (std::int64_t kx = 0; kx < count[0]; ++kx) {
          const dvec3 k(visitOrder(kx, count[0]), visitOrder(ky, count[1]), visitOrder(kz, count[2]));
          visitTile(child, first + k);
          if (failure_) return;
        }
  }

  void visitTile(const Instance& inst, const dvec3& tile) {
    if (++visits_ > options_.maxCellVisits) {
      fail("more than " + std::to_string(options_.maxCellVisits) + " cell visits (the limit)");
      return;
    }
    const Block& block = h_.blocks[inst.block];
    const glm::ivec3 n(block.cellCount(0), block.cellCount(1), block.cellCount(2));
    // The box of cells first..last; the bounds walk skips a covered tile, layer or row whole.
    const auto coveredCells = [&](const glm::ivec3& first, const glm::ivec3& last) {
      return boundsOnly_ && covered(inst.frame, {cellBox(block, tile, first).lo, cellBox(block, tile, last).hi});
    };
    const Box wholeTile = tileBox(block, tile);
    if (boundsOnly_ && covered(inst.frame, wholeTile)) return;
    const auto tilePlanes = cuttingPlanes(*inst.planes, inst.frame, wholeTile);
    if (!tilePlanes) return;
    for (int kz = 0; kz < n.z; ++kz) {
      const int z = static_cast<int>(visitOrder(kz, n.z));
      if (coveredCells({0, 0, z}, {n.x - 1, n.y - 1, z})) continue;
      for (int ky = 0; ky < n.y; ++ky) {
        const int y = static_cast<int>(visitOrder(ky, n.y));
        if (coveredCells({0, y, z}, {n.x - 1, y, z})) continue;
        for (int kx = 0; kx < n.x; ++kx) {
          if (++visits_ > options_.maxCellVisits) {
            fail("more than " + std::to_string(options_.maxCellVisits) + " cell visits (the limit)");
            return;
          }
          const glm::ivec3 c(static_cast<int>(visitOrder(kx, n.x)), y, z);
          const Cell& cell = block.cell(c.x, c.y, c.z);
          if (cell.kind == CellKind::Empty) continue;
          if (cell.kind == CellKind::Redirection && !hasSolid(block.redirections[cell.redirection].target)) continue;
          const Box box = cellBox(block, tile, c);
          if (boundsOnly_ && covered(inst.frame, box)) continue;
          const auto cutting = cuttingPlanes(*tilePlanes, inst.frame, box);
          if (!cutting) continue;
          if (cell.kind == CellKind::Redirection)
            redirect(inst, c, box, *cutting);
          else if (cell.kind == CellKind::Plane)
            emitPlaneCell(inst, cell, tile, box, *cutting);
          else if (cutting->empty())
            emitWhole(inst, tile, *tilePlanes, c, box);
          else
            emitCut(inst, cell, box, *cutting);
          if (failure_) return;
        }
      }
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
  TriangleMesh mesh_;
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

}  // namespace

Result<TriangleMesh> exportMesh(const Hierarchy& h, const glm::dvec3& originM, const MeshExportOptions& options) {
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

namespace {

// The MTL file: one material per HNI material, named m<index>.
std::string mtlText(const std::vector<Material>& materials) {
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
  return text;
}

// The OBJ file, written in pieces of about a megabyte: the vertices, then the triangles grouped
// by material, in their order within each group.
bool writeObjText(std::ofstream& out, const TriangleMesh& mesh, const std::string& mtlName) {
  std::string text = "# nut export-mesh: world coordinates in metres\nmtllib " + mtlName + "\n";
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
}

}  // namespace

Status writeObj(const std::string& objPath, const TriangleMesh& mesh) {
  const std::vector<Material>& materials = mesh.materials;
  for (std::uint16_t m : mesh.triangleMaterial)
    if (m >= materials.size())
      return Error{objPath + ": material " + std::to_string(m) + " out of range (" + std::to_string(materials.size()) +
                   " materials)"};
  const std::filesystem::path obj(objPath);
  const std::filesystem::path mtl = std::filesystem::path(obj).replace_extension(".mtl");
  if (mtl == obj) return Error{objPath + ": the OBJ file needs a name other than its MTL file's"};
  // Both files are written to temporaries first and renamed into place only when both are whole.
  auto mtlTemporary = files::writeTemporary(mtl, [&](std::ofstream& out) {
    const std::string text = mtlText(materials);
    return static_cast<bool>(out.write(text.data(), static_cast<std::streamsize>(text.size())));
  });
  if (!mtlTemporary) return mtlTemporary.error();
  auto objTemporary =
      files::writeTemporary(obj, [&](std::ofstream& out) { return writeObjText(out, mesh, mtl.filename().string()); });
  std::error_code error;
  if (!objTemporary) {
    std::filesystem::remove(*mtlTemporary, error);
    return objTemporary.error();
  }
  if (Status s = files::moveIntoPlace(*mtlTemporary, mtl); !s) {
    std::filesystem::remove(*objTemporary, error);
    return s;
  }
  return files::moveIntoPlace(*objTemporary, obj);
}

}  // namespace nut
