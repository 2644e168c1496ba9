// tests/mesh_export_test.cpp — NUT -> mesh export: exact corners and triangle counts for boxes,
// interior-face culling, the 69 solids (closed, vertices on the surface, volume within the
// tessellation tolerance of solidVolume), wrapping, rotations, clipping with caps, limits, the OBJ
// writer, and seeded random hierarchies checked point by point against the model's semantics.
//
// "Closed" has two strengths here. A single solid (or boxes whose shared faces are culled) is a
// closed 2-manifold: every undirected edge is used by exactly two triangles, once in each
// direction. A whole hierarchy keeps coplanar opposite faces where cells touch without a culled
// pair, so edges may be shared by four triangles; what holds is that every directed edge occurs
// exactly as often as its reverse ("balanced"), which is what makes the signed volume and the
// winding number meaningful.
#include <nut/mesh_export.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "plane_roofs.hpp"
#include "random_hierarchy.hpp"

namespace {

using glm::dvec3;
using nut::Block;
using nut::Cell;
using nut::TriangleMesh;
using nut::Hierarchy;
using nut::MeshExportOptions;
using nut::Redirection;
using nut::Solid;
using nut::SolidGroup;

Solid solidAt(int index) { return Solid{static_cast<std::uint8_t>(index)}; }

std::string str(const dvec3& p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Mesh properties

using Edge = std::pair<std::uint32_t, std::uint32_t>;

std::map<Edge, int> directedEdges(const TriangleMesh& m) {
  std::map<Edge, int> edges;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) ++edges[{t[static_cast<std::size_t>(i)], t[static_cast<std::size_t>((i + 1) % 3)]}];
  return edges;
}

// Every undirected edge used by exactly two triangles, in opposite directions.
testing::AssertionResult isClosedManifold(const TriangleMesh& m) {
  const auto edges = directedEdges(m);
  for (const auto& [e, count] : edges) {
    const auto reverse = edges.find({e.second, e.first});
    if (count != 1 || reverse == edges.end() || reverse->second != 1)
      return testing::AssertionFailure() << "edge " << e.first << "-" << e.second << " used " << count
                                         << " times, reverse " << (reverse == edges.end() ? 0 : reverse->second)
                                         << " times";
  }
  return testing::AssertionSuccess();
}

// Every directed edge as often as its reverse.
testing::AssertionResult isBalanced(const TriangleMesh& m) {
  const auto edges = directedEdges(m);
  for (const auto& [e, count] : edges) {
    const auto reverse = edges.find({e.second, e.first});
    const int back = reverse == edges.end() ? 0 : reverse->second;
    if (count != back)
      return testing::AssertionFailure() << "edge " << e.first << "-" << e.second << " (" << str(m.positions[e.first])
                                         << " to " << str(m.positions[e.second]) << ") used " << count
                                         << " times, reverse " << back;
  }
  return testing::AssertionSuccess();
}

double volume(const TriangleMesh& m) {
  if (m.positions.empty()) return 0.0;
  const dvec3 o = m.positions[0];  // relative coordinates keep precision far from the world origin
  double v = 0.0;
  for (const auto& t : m.triangles)
    v += glm::dot(m.positions[t[0]] - o, glm::cross(m.positions[t[1]] - o, m.positions[t[2]] - o));
  return v / 6.0;
}

// Generalised winding number: 1 inside a closed mesh, 0 outside (Van Oosterom & Strackee).
double windingNumber(const TriangleMesh& m, const dvec3& p) {
  double sum = 0.0;
  for (const auto& t : m.triangles) {
    const dvec3 a = m.positions[t[0]] - p, b = m.positions[t[1]] - p, c = m.positions[t[2]] - p;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    sum += 2.0 * std::atan2(glm::dot(a, glm::cross(b, c)),
                            la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la);
  }
  return sum / (4.0 * std::numbers::pi);
}

std::set<std::array<double, 3>> positionSet(const TriangleMesh& m) {
  std::set<std::array<double, 3>> s;
  for (const dvec3& p : m.positions) s.insert({p.x, p.y, p.z});
  return s;
}

double smallestTriangleSine(const TriangleMesh& m) {
  double worst = 1.0;
  for (const auto& t : m.triangles) {
    const dvec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    for (int i = 0; i < 3; ++i) {
      const dvec3 u = (i == 0 ? b - a : i == 1 ? c - b : a - c), v = (i == 0 ? c - a : i == 1 ? a - b : b - c);
      worst = std::min(worst, glm::length(glm::cross(u, v)) / (glm::length(u) * glm::length(v)));
    }
  }
  return worst;
}

// ---------------------------------------------------------------------------------------------
// Hierarchies

Hierarchy withMaterials(Hierarchy h) {
  h.materials = {{200, 100, 50, 255, 0}, {10, 20, 30, 255, 0}, {90, 90, 255, 128, 0}};
  return h;
}

// One block of the given per-axis cell sizes with the cells listed (x fastest).
Hierarchy oneBlock(const std::array<std::vector<double>, 3>& sizes, const std::vector<Cell>& cells) {
  Hierarchy h;
  Block b = Block::fromSizes(sizes);
  b.cells = cells;
  h.addBlock(b);
  return withMaterials(h);
}

// A root of one cell of size cellM redirecting to `target`.
Hierarchy redirected(const dvec3& cellM, const Block& target, const Redirection& r) {
  Hierarchy h;
  Block root = Block::fromSizes({{{cellM.x}, {cellM.y}, {cellM.z}}});
  root.redirections = {r};
  root.cells = {Cell::redirect(0)};
  h.addBlock(root);
  h.addBlock(target);
  return withMaterials(h);
}

Block singleCellBlock(const dvec3& sizeM, const Cell& cell) {
  Block b = Block::fromSizes({{{sizeM.x}, {sizeM.y}, {sizeM.z}}});
  b.cells = {cell};
  return b;
}

TriangleMesh exported(const Hierarchy& h, const MeshExportOptions& o = {}, const dvec3& origin = dvec3(0.0)) {
  auto m = nut::exportMesh(h, origin, o);
  EXPECT_TRUE(m.ok()) << m.error().message;
  return m.ok() ? *m : TriangleMesh{};
}

// The model's semantics straight from hierarchy.hpp, in double: the solid cell a block-local point
// falls in, if any, and where in that cell's unit cube.
struct Leaf {
  std::optional<Solid> solid;
  dvec3 unit{0.0};
  dvec3 sizeM{0.0};
  // A plane cell: its cut and the point in the block's frame of tile 0.
  const nut::PlaneCut* cut = nullptr;
  dvec3 blockPoint{0.0};
  bool inside() const {
    if (cut) return nut::cutContains(*cut, blockPoint);
    return solid && nut::solidContains(*solid, unit);
  }
};

Leaf leafAt(const Hierarchy& h, nut::BlockId id, dvec3 p, const std::array<bool, 3>& wrap) {
  const Block& block = h.blocks[id];
  glm::ivec3 c(0);
  dvec3 lo(0.0), hi(0.0);
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = block.boundsM[static_cast<std::size_t>(a)];
    const double size = bounds.back();
    if (wrap[static_cast<std::size_t>(a)])
      p[a] -= std::floor(p[a] / size) * size;
    else if (p[a] < 0 || p[a] >= size)
      return {};
    const auto cellIndex = std::upper_bound(bounds.begin(), bounds.end(), p[a]) - bounds.begin() - 1;
    c[a] = std::clamp(static_cast<int>(cellIndex), 0, block.cellCount(a) - 1);
    lo[a] = bounds[static_cast<std::size_t>(c[a])];
    hi[a] = bounds[static_cast<std::size_t>(c[a]) + 1];
  }
  const Cell& cell = block.cell(c.x, c.y, c.z);
  switch (cell.kind) {
    case nut::CellKind::Empty:
      return {};
    case nut::CellKind::Solid:
      return {cell.solid, (p - lo) / (hi - lo), hi - lo};
    case nut::CellKind::Plane:
      return {std::nullopt, (p - lo) / (hi - lo), hi - lo, &block.cuts[cell.cut], p};
    case nut::CellKind::Redirection: {
      const Redirection& r = block.redirections[cell.redirection];
      const dvec3 q = glm::transpose(nut::rotationMatrix(r.rotation)) * (p - lo - r.offsetM);
      return leafAt(h, r.target, q, r.wrap);
    }
  }
  return {};
}

// Primed coordinates of a unit-cube point for a solid (docs/FORMAT.md "Solids"): |q| = 1 on the
// quadric of quarter cylinders and octants.
dvec3 primed(Solid s, const dvec3& p) {
  const int o = nut::solidOrientation(s);
  dvec3 q(0.0);
  switch (nut::solidGroup(s)) {
    case SolidGroup::QuarterCylinder:
    case SolidGroup::InverseQuarterCylinder: {
      const int axis = o / 4, corner = o % 4, u = (axis + 1) % 3, v = (axis + 2) % 3;
      q[u] = (corner & 1) ? 1 - p[u] : p[u];
      q[v] = (corner & 2) ? 1 - p[v] : p[v];
      break;
    }
    default:
      for (int i = 0; i < 3; ++i) q[i] = ((o >> i) & 1) ? 1 - p[i] : p[i];
  }
  return q;
}

bool isQuadric(SolidGroup g) {
  return g == SolidGroup::QuarterCylinder || g == SolidGroup::InverseQuarterCylinder || g == SolidGroup::SphereOctant ||
         g == SolidGroup::InverseSphereOctant;
}

bool isInverse(SolidGroup g) { return g == SolidGroup::InverseQuarterCylinder || g == SolidGroup::InverseSphereOctant; }

// ---------------------------------------------------------------------------------------------
// Boxes and culling

TEST(MeshExport, SingleBoxHasTwelveTrianglesOnItsExactCorners) {
  const Hierarchy h = oneBlock({{{2.0}, {3.0}, {4.0}}}, {Cell::box(1)});
  const dvec3 origin(10.0, 20.0, 30.0);
  const TriangleMesh m = exported(h, {}, origin);
  ASSERT_EQ(m.triangles.size(), 12u);
  std::set<std::array<double, 3>> corners;
  for (int i = 0; i < 8; ++i) corners.insert({i & 1 ? 12.0 : 10.0, i & 2 ? 23.0 : 20.0, i & 4 ? 34.0 : 30.0});
  EXPECT_EQ(positionSet(m), corners);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 24.0, 1e-12);  // positive: triangles are counter-clockwise seen from outside
  EXPECT_TRUE(
      std::all_of(m.triangleMaterial.begin(), m.triangleMaterial.end(), [](std::uint16_t x) { return x == 1; }));
}

TEST(MeshExport, SharedFaceOfTwoBoxesIsDropped) {
  const Hierarchy h = oneBlock({{{1.0, 1.0}, {1.0}, {1.0}}}, {Cell::box(0), Cell::box(1)});
  const TriangleMesh m = exported(h);
  EXPECT_EQ(m.triangles.size(), 20u);  // 2 x 12, less 2 triangles of each box's shared face
  EXPECT_EQ(m.positions.size(), 12u);
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 2.0, 1e-12);
  for (const auto& t : m.triangles)
    EXPECT_FALSE(m.positions[t[0]].x == 1.0 && m.positions[t[1]].x == 1.0 && m.positions[t[2]].x == 1.0)
        << "a face on x = 1 is left";
}

TEST(MeshExport, WallOfBoxesKeepsOnlyItsOutside) {
  // 4 x 3 x 1 boxes: only the outer faces of the 4 m x 3 m x 1 m slab remain, 2 triangles per cell face.
  const Hierarchy h = oneBlock({{{1, 1, 1, 1}, {1, 1, 1}, {1}}}, std::vector<Cell>(12, Cell::box(0)));
  const TriangleMesh m = exported(h);
  EXPECT_EQ(m.triangles.size(), 2u * (2 * 12 + 2 * 4 + 2 * 3));
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 12.0, 1e-12);
}

TEST(MeshExport, FacesNextToTranslucentCellsAreKept) {
  const Hierarchy h = oneBlock({{{1.0, 1.0}, {1.0}, {1.0}}}, {Cell::box(0), Cell::box(2)});  // material 2: opacity 128
  const TriangleMesh m = exported(h);
  EXPECT_EQ(m.triangles.size(), 24u);
  EXPECT_TRUE(isBalanced(m));
  EXPECT_NEAR(volume(m), 2.0, 1e-12);
}

// Whether solid s covers the face (axis a, side) of its cell completely, by solidContains on a grid.
bool coversFace(Solid s, int a, int side) {
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) {
      dvec3 p(0.0);
      p[a] = side;
      p[(a + 1) % 3] = i / 8.0;
      p[(a + 2) % 3] = j / 8.0;
      if (!nut::solidContains(s, p)) return false;
    }
  return true;
}

TEST(MeshExport, CullsExactlyTheFullFacesNextToABox) {
  // Solid s at cell 0 and a box at cell 1, along each axis: the shared face is culled iff s covers
  // it completely (checked independently with solidContains); then both sides' triangles go.
  const MeshExportOptions o;
  int culledPairs = 0;
  for (int s = 0; s < nut::kSolidCount; ++s) {
    const std::size_t alone =
        exported(oneBlock({{{1.0}, {1.0}, {1.0}}}, {Cell::solidCell(solidAt(s), 0)}), o).triangles.size();
    for (int a = 0; a < 3; ++a) {
      std::array<std::vector<double>, 3> sizes{{{1.0}, {1.0}, {1.0}}};
      sizes[static_cast<std::size_t>(a)] = {1.0, 1.0};
      const TriangleMesh m = exported(oneBlock(sizes, {Cell::solidCell(solidAt(s), 0), Cell::box(1)}), o);
      const bool full = coversFace(solidAt(s), a, 1);
      culledPairs += full;
      // A full face of any solid here is one square (two triangles).
      EXPECT_EQ(m.triangles.size(), alone + 12 - (full ? 4 : 0)) << nut::solidName(solidAt(s)) << " axis " << a;
      EXPECT_TRUE(isBalanced(m)) << nut::solidName(solidAt(s)) << " axis " << a;
    }
  }
  // Full faces on the +x, +y, +z sides: the box 3; wedges, inverse pyramids, quarter cylinders,
  // inverse quarter cylinders and inverse octants 12 each (half of their 24); pyramids and octants 0.
  EXPECT_EQ(culledPairs, 3 + 5 * 12);
}

// ---------------------------------------------------------------------------------------------
// The 69 solids

void checkSolidAlone(Solid s, const dvec3& cellM, double tolerance) {
  SCOPED_TRACE(nut::solidName(s) + " in a cell of " + str(cellM));
  MeshExportOptions o;
  o.toleranceM = tolerance;
  const TriangleMesh m = exported(oneBlock({{{cellM.x}, {cellM.y}, {cellM.z}}}, {Cell::solidCell(s, 0)}), o);
  ASSERT_FALSE(m.triangles.empty());
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_GT(smallestTriangleSine(m), 1e-6);
  const SolidGroup g = nut::solidGroup(s);
  const double exact = nut::solidVolume(s) * cellM.x * cellM.y * cellM.z;
  const double v = volume(m);
  if (!isQuadric(g)) {
    EXPECT_NEAR(v, exact, 1e-12 * exact);
  } else {
    // Vertices on a convex surface: the chords lie inside it, so a convex quadric loses volume and
    // an inverse one gains; by at most the chord error times the curved area (< the box's area).
    const double area = 2 * (cellM.x * cellM.y + cellM.y * cellM.z + cellM.z * cellM.x);
    const double gained = isInverse(g) ? v - exact : exact - v;
    EXPECT_GE(gained, -1e-12);
    EXPECT_LE(gained, tolerance * area);
  }
  // Every vertex lies on the solid's boundary: on the quadric, or on a face of the cell.
  for (const dvec3& p : m.positions) {
    const dvec3 unit = p / cellM;
    const bool onQuadric = isQuadric(g) && std::abs(glm::length(primed(s, unit)) - 1.0) <= 1e-12;
    if (onQuadric) continue;
    EXPECT_TRUE(glm::any(glm::equal(unit, dvec3(0.0))) || glm::any(glm::equal(unit, dvec3(1.0)))) << str(p);
    EXPECT_TRUE(nut::solidContains(s, unit)) << str(p);
  }
  // Triangles of the curved surface (all three vertices on it, not on a cell face) stay within
  // the tolerance of it, checked at their centres.
  if (isQuadric(g))
    for (const auto& t : m.triangles) {
      std::array<double, 3> r;
      for (int i = 0; i < 3; ++i)
        r[static_cast<std::size_t>(i)] = glm::length(primed(s, m.positions[t[static_cast<std::size_t>(i)]] / cellM));
      if (std::any_of(r.begin(), r.end(), [](double x) { return std::abs(x - 1.0) > 1e-12; })) continue;
      bool onCellFace = false;  // an end face of a cylinder can have three vertices on the arc
      for (int a = 0; a < 3; ++a)
        onCellFace |= m.positions[t[0]][a] == m.positions[t[1]][a] && m.positions[t[1]][a] == m.positions[t[2]][a] &&
                      (m.positions[t[0]][a] == 0.0 || m.positions[t[0]][a] == cellM[a]);
      if (onCellFace) continue;
      const dvec3 centre = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0;
      // Along the ray from the edge or corner to the surface: q / |q| is on it (in metres: times the
      // cell size, as the primed axes are the cell's axes, possibly flipped).
      const dvec3 q = primed(s, centre / cellM);
      EXPECT_LE(glm::length(q), 1.0);
      EXPECT_LE(glm::length((q / glm::length(q) - q) * cellM), tolerance);
    }
}

TEST(MeshExport, EverySolidAloneIsClosedWithTheRightVolume) {
  for (int s = 0; s < nut::kSolidCount; ++s) {
    checkSolidAlone(solidAt(s), dvec3(1.0), 1e-3);
    checkSolidAlone(solidAt(s), dvec3(2.0, 0.5, 3.0), 1e-2);
  }
}

TEST(MeshExport, EverySegmentCountGivesClosedQuadrics) {
  // The pieces of a quadric share points only if they are computed bit for bit alike (the arcs'
  // end points on the cube's corners, for example), whatever the segment count.
  for (int n = 1; n <= 64; ++n) {
    MeshExportOptions o;
    o.minSegmentsPerQuarter = o.maxSegmentsPerQuarter = n;
    for (int s = 0; s < nut::kSolidCount; ++s) {
      if (!isQuadric(nut::solidGroup(solidAt(s)))) continue;
      const TriangleMesh m = exported(oneBlock({{{1.0}, {2.0}, {3.0}}}, {Cell::solidCell(solidAt(s), 0)}), o);
      EXPECT_TRUE(isClosedManifold(m)) << nut::solidName(solidAt(s)) << ", " << n << " segments";
      EXPECT_GT(smallestTriangleSine(m), 1e-6) << nut::solidName(solidAt(s)) << ", " << n << " segments";
    }
  }
}

TEST(MeshExport, TighterToleranceGivesMoreTrianglesAndLessError) {
  const Solid octant = nut::makeSolid(SolidGroup::SphereOctant, 0);
  const Hierarchy h = oneBlock({{{1.0}, {1.0}, {1.0}}}, {Cell::solidCell(octant, 0)});
  MeshExportOptions coarse, fine;
  coarse.toleranceM = 1e-2;
  fine.toleranceM = 1e-4;
  const TriangleMesh a = exported(h, coarse), b = exported(h, fine);
  EXPECT_LT(a.triangles.size(), b.triangles.size());
  EXPECT_LT(nut::solidVolume(octant) - volume(b), nut::solidVolume(octant) - volume(a));
}

// ---------------------------------------------------------------------------------------------
// Redirections

TEST(MeshExport, WrappedTargetRepeatsAlongItsAxis) {
  // A 1 m block with a 0.5 m box, tiled along x in a 3 m cell: three boxes.
  Block target = Block::fromSizes({{{0.5, 0.5}, {1.0}, {1.0}}});
  target.cells = {Cell::box(0), Cell::empty()};
  Redirection r;
  r.target = 1;
  r.wrap = {true, false, false};
  TriangleMesh m = exported(redirected({3.0, 1.0, 1.0}, target, r));
  EXPECT_EQ(m.triangles.size(), 36u);
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 1.5, 1e-12);
  std::set<double> xs;
  for (const dvec3& p : m.positions) xs.insert(p.x);
  EXPECT_EQ(xs, (std::set<double>{0.0, 0.5, 1.0, 1.5, 2.0, 2.5}));

  // Without the wrap flag only [0, 1) exists.
  r.wrap = {false, false, false};
  m = exported(redirected({3.0, 1.0, 1.0}, target, r));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(volume(m), 0.5, 1e-12);

  // Shifted by 0.75 m: tiles -1 and 2 stick out of the cell and are cut and capped.
  r.wrap = {true, false, false};
  r.offsetM = {0.75, 0.0, 0.0};
  m = exported(redirected({3.0, 1.0, 1.0}, target, r));
  EXPECT_EQ(m.triangles.size(), 48u);
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 1.5, 1e-12);
  for (const dvec3& p : m.positions) EXPECT_TRUE(p.x >= 0.0 && p.x <= 3.0) << str(p);
}

TEST(MeshExport, WrapSeamsBetweenWholeBoxesAreCulled) {
  // A 1 m box block tiled three times (and twice along z): one 3 m x 1 m x 2 m box, seams culled.
  Redirection r;
  r.target = 1;
  r.wrap = {true, false, true};
  const TriangleMesh m = exported(redirected({3.0, 1.0, 2.0}, singleCellBlock(dvec3(1.0), Cell::box(0)), r));
  EXPECT_EQ(m.triangles.size(), 2u * (2 * 3 + 2 * 6 + 2 * 2));
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 6.0, 1e-12);
}

TEST(MeshExport, RotatedTargetLandsWhereTheRotationSays) {
  // A 1 x 2 x 3 m pyramid (its corner at the block origin) in a 10 m cell at offset 5 m: its four
  // vertices must be offset + R * vertex, for every cube rotation and some yaws.
  const Solid pyramid = nut::makeSolid(SolidGroup::Pyramid, 0);
  const Block target = singleCellBlock({1.0, 2.0, 3.0}, Cell::solidCell(pyramid, 0));
  const std::array<dvec3, 4> vertices{dvec3(0.0), dvec3(1, 0, 0), dvec3(0, 2, 0), dvec3(0, 0, 3)};
  for (int cube = 0; cube < 24; ++cube)
    for (std::uint16_t yaw : {0, 8192, 16384, 40000}) {
      Redirection r;
      r.target = 1;
      r.offsetM = dvec3(5.0);
      r.rotation = {static_cast<std::uint8_t>(cube), yaw};
      const TriangleMesh m = exported(redirected(dvec3(10.0), target, r));
      SCOPED_TRACE("cube " + std::to_string(cube) + " yaw " + std::to_string(yaw));
      ASSERT_EQ(m.triangles.size(), 4u);
      ASSERT_EQ(m.positions.size(), 4u);
      EXPECT_TRUE(isClosedManifold(m));
      EXPECT_NEAR(volume(m), 1.0, 1e-12);
      const glm::dmat3 R = nut::rotationMatrix(r.rotation);
      for (const dvec3& v : vertices) {
        const dvec3 expected = r.offsetM + R * v;
        const bool found = std::any_of(m.positions.begin(), m.positions.end(),
                                       [&](const dvec3& p) { return glm::length(p - expected) < 1e-12; });
        EXPECT_TRUE(found) << str(expected);
      }
    }
}

TEST(MeshExport, TargetBiggerThanItsCellIsClippedAndCapped) {
  Redirection r;
  r.target = 1;
  r.offsetM = dvec3(-0.5);
  // A 2 m box around a 1 m cell: the cell itself, all six faces caps.
  TriangleMesh m = exported(redirected(dvec3(1.0), singleCellBlock(dvec3(2.0), Cell::box(0)), r));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(positionSet(m).size(), 8u);
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 1.0, 1e-12);

  // A 2 m wedge x + y <= 2 (in its block): in the cell, x + y <= 1.
  m = exported(
      redirected(dvec3(1.0), singleCellBlock(dvec3(2.0), Cell::solidCell(nut::makeSolid(SolidGroup::Wedge, 8), 0)), r));
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_NEAR(volume(m), 0.5, 1e-12);
  for (const dvec3& p : m.positions) EXPECT_LE(p.x + p.y, 1.0 + 1e-12);
}

// Volume of {(x, y, z) in [0,1]^3 : (x+1)^2 + (y+1)^2 + (z+1)^2 >= 4}, by the midpoint rule over
// (x, y) of the exact extent in z.
double inverseBallInUnitCube() {
  constexpr int n = 2000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = (i + 0.5) / n + 1, y = (j + 0.5) / n + 1, rest = 4 - x * x - y * y;
      const double zMin = rest <= 1 ? 0.0 : std::min(1.0, std::sqrt(rest) - 1);
      sum += 1 - zMin;
    }
  return sum / (static_cast<double>(n) * n);
}

TEST(MeshExport, CutQuadricsAreCappedWithTheClippedVolume) {
  MeshExportOptions o;
  o.toleranceM = 1e-4;
  Redirection r;
  r.target = 1;
  // Quarter cylinder of radius 2 about the z axis through (-1, -1): area of the disc in the unit square.
  r.offsetM = {-1.0, -1.0, -0.5};
  const Solid cylinder = nut::makeSolid(SolidGroup::QuarterCylinder, 8);  // axis z, edge at x = y = 0
  TriangleMesh m = exported(redirected(dvec3(1.0), singleCellBlock(dvec3(2.0), Cell::solidCell(cylinder, 0)), r), o);
  double area = 0.0;
  constexpr int n = 1'000'000;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) / n + 1;
    area += std::clamp(std::sqrt(std::max(0.0, 4 - x * x)) - 1, 0.0, 1.0) / n;
  }
  EXPECT_TRUE(isClosedManifold(m));
  EXPECT_GE(area - volume(m), -1e-9);
  EXPECT_LE(area - volume(m), o.toleranceM * 6);

  // Inverse octant of radius 2 at (-1, -1, -1).
  r.offsetM = dvec3(-1.0);
  const Solid inverseOctant = nut::makeSolid(SolidGroup::InverseSphereOctant, 0);
  m = exported(redirected(dvec3(1.0), singleCellBlock(dvec3(2.0), Cell::solidCell(inverseOctant, 0)), r), o);
  EXPECT_TRUE(isClosedManifold(m));
  const double exact = inverseBallInUnitCube();
  EXPECT_GE(volume(m) - exact, -1e-6);
  EXPECT_LE(volume(m) - exact, o.toleranceM * 6);
  // Caps lie on the cell's faces up to the rounding of the crossing points.
  for (const dvec3& p : m.positions)
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, dvec3(-1e-15))) &&
                glm::all(glm::lessThanEqual(p, dvec3(1.0 + 1e-15))))
        << str(p);
}

TEST(MeshExport, TargetOutsideItsCellLeavesNothing) {
  Redirection r;
  r.target = 1;
  r.offsetM = {1.5, 0.0, 0.0};
  const TriangleMesh m = exported(redirected(dvec3(1.0), singleCellBlock(dvec3(1.0), Cell::box(0)), r));
  EXPECT_TRUE(m.triangles.empty());
  EXPECT_TRUE(m.positions.empty());
}

// ---------------------------------------------------------------------------------------------
// Limits and errors

TEST(MeshExport, TriangleLimitFailsNamingTheCount) {
  Redirection r;
  r.target = 1;
  r.wrap = {true, true, true};
  Block target = singleCellBlock(dvec3(0.5), Cell::solidCell(nut::makeSolid(SolidGroup::Pyramid, 0), 0));
  MeshExportOptions o;
  o.maxTriangles = 100;
  const auto m = nut::exportMesh(redirected(dvec3(10.0), target, r), dvec3(0.0), o);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("100 triangles"), std::string::npos) << m.error().message;
}

TEST(MeshExport, HugeTilingFailsInsteadOfRunningForever) {
  Redirection r;
  r.target = 1;
  r.wrap = {true, true, true};
  const auto m =
      nut::exportMesh(redirected(dvec3(1000.0), singleCellBlock(dvec3(0.001), Cell::box(0)), r), dvec3(0.0), {});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("repeats block 1 1000"), std::string::npos) << m.error().message;
}

TEST(MeshExport, NestingDeeperThanTheLimitFails) {
  Hierarchy h;
  for (int b = 0; b < 4; ++b) {
    Block block = Block::fromSizes({{{1.0}, {1.0}, {1.0}}});
    if (b < 3) {
      Redirection r;
      r.target = static_cast<nut::BlockId>(b + 1);
      block.redirections = {r};
      block.cells = {Cell::redirect(0)};
    } else {
      block.cells = {Cell::box(0)};
    }
    h.addBlock(block);
  }
  h = withMaterials(h);
  MeshExportOptions o;
  EXPECT_EQ(exported(h, o).triangles.size(), 12u);
  o.maxDepth = 2;
  const auto m = nut::exportMesh(h, dvec3(0.0), o);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("deeper than 2 levels"), std::string::npos) << m.error().message;
}

TEST(MeshExport, InvalidHierarchyIsAnError) {
  Hierarchy h = oneBlock({{{1.0}, {1.0}, {1.0}}}, {Cell::box(7)});  // no material 7
  const auto m = nut::exportMesh(h, dvec3(0.0), {});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("material 7"), std::string::npos) << m.error().message;
}

// ---------------------------------------------------------------------------------------------
// OBJ / MTL

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(MeshExport, WritesObjWithMaterials) {
  const std::filesystem::path dir = std::filesystem::path(NUT_TEST_OUTPUT_DIR) / "mesh_export";
  std::filesystem::create_directories(dir);
  const Hierarchy h = oneBlock({{{1.0, 1.0}, {1.0}, {1.0}}}, {Cell::box(2), Cell::box(0)});
  const TriangleMesh m = exported(h, {}, {1e6, 0.25, -3.0});
  EXPECT_EQ(m.materials, h.materials);  // the mesh carries the hierarchy's materials
  const std::filesystem::path obj = dir / "two.obj";
  ASSERT_TRUE(nut::writeObj(obj.string(), m).ok());
  const std::string text = readText(obj), mtl = readText(dir / "two.mtl");
  EXPECT_NE(text.find("mtllib two.mtl\n"), std::string::npos);
  EXPECT_NE(text.find("v 1000001 1.25 -2\n"), std::string::npos);  // world coordinates, shortest exact form
  // Triangles grouped by material: m0 first, then m2.
  const auto m0 = text.find("usemtl m0\n"), m2 = text.find("usemtl m2\n");
  ASSERT_NE(m0, std::string::npos);
  ASSERT_NE(m2, std::string::npos);
  EXPECT_LT(m0, m2);
  std::istringstream lines(text);
  int vertices = 0, faces = 0;
  for (std::string line; std::getline(lines, line);) {
    vertices += line.rfind("v ", 0) == 0;
    faces += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(vertices, 12);
  EXPECT_EQ(faces, 24);  // material 2 is translucent: the shared face stays on both sides
  EXPECT_NE(mtl.find("newmtl m2\nKd 0.35294117647058826 0.35294117647058826 1\nd 0.5019607843137255\n"),
            std::string::npos)
      << mtl;
  EXPECT_NE(mtl.find("newmtl m0\n"), std::string::npos);
  // No temporary files are left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();

  TriangleMesh bad = m;
  bad.triangleMaterial[0] = 9;
  EXPECT_FALSE(nut::writeObj((dir / "bad.obj").string(), bad).ok());
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.obj"));
}

TEST(MeshExport, ContentBoundsAreTheVertexBoundsOfTheCoarseMesh) {
  // contentBounds walks the hierarchy as the export does but keeps only the extremes of the
  // vertices: the same box, to the bit, as the exported mesh's vertices (quadrics at one segment
  // per quarter), whatever the wraps, rotations and clips.
  MeshExportOptions coarse;
  coarse.minSegmentsPerQuarter = coarse.maxSegmentsPerQuarter = 1;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Hierarchy h = nut::testing::randomHierarchy(seed);
    const dvec3 origin(2.5e5 * static_cast<double>(seed), -31.25, 1e6 / static_cast<double>(seed));
    auto mesh = nut::exportMesh(h, origin, coarse);
    ASSERT_TRUE(mesh.ok()) << mesh.error().message;
    auto box = nut::contentBounds(h, origin);
    ASSERT_TRUE(box.ok()) << box.error().message;
    if (mesh->positions.empty()) {
      EXPECT_EQ(box->min, origin);
      EXPECT_EQ(box->max, origin + h.blocks[h.root].sizeM());
      continue;
    }
    dvec3 lo = mesh->positions.front(), hi = lo;
    for (const dvec3& p : mesh->positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    EXPECT_EQ(box->min, lo) << str(box->min - lo);
    EXPECT_EQ(box->max, hi) << str(box->max - hi);
  }
}

// ---------------------------------------------------------------------------------------------
// Random hierarchies against the model's semantics

// At random points of the root box the mesh's winding number must say what the model says,
// except between a curved surface and its chords: such a point must lie in a quadric cell,
// within the tolerance of the quadric, on the side the chords give away (convex solids lose the
// gap, inverse ones gain it). Plane cells are exact: no gap.
void checkRandomHierarchiesPointByPoint(const nut::testing::RandomHierarchyOptions& options) {
  MeshExportOptions o;
  o.toleranceM = 0.01;
  constexpr int kSeeds = 40, kPoints = 200;
  int gapPoints = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Hierarchy h = nut::testing::randomHierarchy(seed, options);
    const dvec3 origin(1000.0 * static_cast<double>(seed), -50.0, 7.0);
    auto result = nut::exportMesh(h, origin, o);
    ASSERT_TRUE(result.ok()) << result.error().message;
    const TriangleMesh& m = *result;
    EXPECT_TRUE(isBalanced(m));
    const dvec3 size = h.blocks[h.root].sizeM();
    for (const dvec3& p : m.positions) {
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(p - origin, dvec3(-1e-6))) &&
                  glm::all(glm::lessThanEqual(p - origin, size + 1e-6)))
          << str(p - origin);
    }
    for (std::uint16_t mat : m.triangleMaterial) ASSERT_LT(mat, h.materials.size());
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < kPoints; ++i) {
      const dvec3 local = dvec3(unit(rng), unit(rng), unit(rng)) * size;
      const Leaf leaf = leafAt(h, h.root, local, {false, false, false});
      const double w = windingNumber(m, origin + local);
      ASSERT_TRUE(std::abs(w - std::round(w)) < 1e-6 && (std::round(w) == 0 || std::round(w) == 1)) << w;
      if (leaf.inside() == (w > 0.5)) continue;
      SCOPED_TRACE("point " + str(local) + ", model " + (leaf.inside() ? "inside" : "outside"));
      ASSERT_TRUE(leaf.solid && isQuadric(nut::solidGroup(*leaf.solid)));
      const dvec3 q = primed(*leaf.solid, leaf.unit);
      EXPECT_LE(glm::length((q / glm::length(q) - q) * leaf.sizeM), o.toleranceM);
      EXPECT_EQ(leaf.inside(), !isInverse(nut::solidGroup(*leaf.solid)));
      ++gapPoints;
    }
  }
  std::fprintf(stderr, "%d of %d points in the tessellation gap\n", gapPoints, kSeeds * kPoints);
}

TEST(MeshExport, RandomHierarchiesMatchTheModelPointByPoint) { checkRandomHierarchiesPointByPoint({}); }

TEST(MeshExport, RandomHierarchiesWithPlaneCellsMatchTheModelPointByPoint) {
  nut::testing::RandomHierarchyOptions options;
  options.planeCellShare = 0.5;
  checkRandomHierarchiesPointByPoint(options);
}

// The roof houses: closed, and the volume of the model, integrated independently over the
// footprint (midpoint rule on a 2000 x 1500 grid; the kink of the ridge or valley line costs less
// than 1e-5 of the volume).
TEST(MeshExport, PlaneRoofHousesAreClosedWithTheRightVolume) {
  for (const nut::PlaneCombine combine : {nut::PlaneCombine::Both, nut::PlaneCombine::Either}) {
    const nut::testing::PlaneRoof roof = nut::testing::planeRoofHouse(combine);
    const TriangleMesh m = exported(roof.h);
    EXPECT_TRUE(isBalanced(m));
    const auto height = [&](const nut::CutPlane& p, double x, double z) {
      return (p.offsetM - p.normal.x * x - p.normal.z * z) / p.normal.y;
    };
    constexpr int kNx = 2000, kNz = 1500;
    const double dx = (roof.hi.x - roof.lo.x) / kNx, dz = (roof.hi.z - roof.lo.z) / kNz;
    double expected = 0;
    for (int i = 0; i < kNx; ++i)
      for (int k = 0; k < kNz; ++k) {
        const double x = roof.lo.x + (i + 0.5) * dx, z = roof.lo.z + (k + 0.5) * dz;
        const double a = height(roof.cut.planes[0], x, z), b = height(roof.cut.planes[1], x, z);
        expected += (combine == nut::PlaneCombine::Both ? std::min(a, b) : std::max(a, b)) - roof.lo.y;
      }
    expected *= dx * dz;
    EXPECT_NEAR(volume(m), expected, 1e-5 * expected) << (combine == nut::PlaneCombine::Both ? "ridge" : "valley");
  }
}

}  // namespace
