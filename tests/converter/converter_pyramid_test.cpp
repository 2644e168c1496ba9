// Pyramid cells of the mesh converter (converter/solid.hpp): a corner slope (a planar piece sloped
// along all three axes that is the triangle through the three corners of its bounding box next to
// one corner) becomes one Pyramid or InversePyramid cell, or a sub-block of one cell where
// boundaries from elsewhere cut its box. A box (10 x 6 x 8 m) with a chamfered top corner converts
// with the chamfer as one InversePyramid cell, none of it in the complementary mesh, and renders
// like its source (at least 99 % of the pixels of every view within 8/255; diff images in the test
// output folder, converter_pyramid/, when not); so do a box with all eight corners chamfered (some
// boxes cut by other chamfers' boundaries: sub-blocks), a chamfer whose box an annex's top cuts,
// and a notch (a corner cut inwards, solid on the corner's side: a Pyramid). A three-axis slope
// that is not a corner triangle (a quadrilateral) stays in the complementary mesh, so does a
// chamfer too small to pay for its boundaries, and a hip roof (its hip lines are creases no solid
// has) converts exactly as it does without pyramids (and renders like its source).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <converter/solid.hpp>
#include <nut/solids.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

using testing::cellsOf;
using testing::nutFraction;

constexpr double W = 10, H = 6, D = 8;  // x, y (up), z

using Loop = std::vector<glm::dvec3>;

// A convex polyhedron as its faces, each a convex loop counter-clockwise seen from outside.
struct Polytope {
  std::vector<Loop> faces;
};

Polytope boxPolytope(const glm::dvec3& lo, const glm::dvec3& hi) {
  Polytope p;
  for (int a = 0; a < 3; ++a)
    for (const bool high : {false, true}) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      Loop loop;
      for (const auto& [iu, iv] : {std::pair(0, 0), std::pair(1, 0), std::pair(1, 1), std::pair(0, 1)}) {
        glm::dvec3 q;
        q[a] = high ? hi[a] : lo[a];
        q[u] = iu ? hi[u] : lo[u];
        q[v] = iv ? hi[v] : lo[v];
        loop.push_back(q);
      }
      if (!high) std::reverse(loop.begin(), loop.end());  // (u, v) turn about +a
      p.faces.push_back(loop);
    }
  return p;
}

// Where segment ab crosses the plane n . x = d, the same point whichever way round it is taken
// (so that the two faces of an edge agree to the last bit).
glm::dvec3 crossing(glm::dvec3 a, glm::dvec3 b, const glm::dvec3& n, double d) {
  if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
  const double da = glm::dot(n, a) - d, db = glm::dot(n, b) - d;
  return a + (da / (da - db)) * (b - a);
}

// Keeps the part with n . x <= d and closes it with the cut (n points out of what is kept).
// Vertices within 1e-9 m of the plane count as on it (a hip roof's eaves corners).
void cut(Polytope& p, const glm::dvec3& n, double d) {
  std::vector<glm::dvec3> cap;
  std::vector<Loop> kept;
  const auto side = [&](const glm::dvec3& q) {
    const double s = glm::dot(n, q) - d;
    return s > 1e-9 ? 1 : s < -1e-9 ? -1 : 0;
  };
  for (const Loop& face : p.faces) {
    Loop out;
    for (std::size_t i = 0; i < face.size(); ++i) {
      const glm::dvec3 a = face[i], b = face[(i + 1) % face.size()];
      const int sideA = side(a), sideB = side(b);
      if (sideA <= 0) out.push_back(a);
      if (sideA == 0) cap.push_back(a);
      if (sideA * sideB < 0) {
        out.push_back(crossing(a, b, n, d));
        cap.push_back(out.back());
      }
    }
    if (out.size() >= 3) kept.push_back(out);
  }
  std::sort(cap.begin(), cap.end(), [](const glm::dvec3& a, const glm::dvec3& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); });
  cap.erase(std::unique(cap.begin(), cap.end()), cap.end());
  if (cap.size() >= 3) {
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& q : cap) centre += q;
    centre /= static_cast<double>(cap.size());
    const glm::dvec3 t1 = glm::normalize(cap.front() - centre), t2 = glm::cross(n, t1);
    std::sort(cap.begin(), cap.end(), [&](const glm::dvec3& a, const glm::dvec3& b) {
      return std::atan2(glm::dot(a - centre, t2), glm::dot(a - centre, t1)) < std::atan2(glm::dot(b - centre, t2), glm::dot(b - centre, t1));
    });
    kept.push_back(cap);
  }
  p.faces = kept;
}

// Cuts p by the plane through a, b and c, keeping the side of `inside`.
void cutThrough(Polytope& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& inside) {
  glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  if (glm::dot(n, inside - a) > 0) n = -n;
  cut(p, n, glm::dot(n, a));
}

// Appends the polytope's faces (fans) with shared corners, all in material 0.
void addPolytope(TriangleMesh& mesh, const Polytope& p) {
  std::map<std::array<double, 3>, std::uint32_t> index;
  const auto at = [&](const glm::dvec3& q) {
    const auto [it, fresh] = index.emplace(std::array<double, 3>{q.x, q.y, q.z}, static_cast<std::uint32_t>(mesh.positions.size()));
    if (fresh) mesh.positions.push_back(q);
    return it->second;
  };
  for (const Loop& face : p.faces)
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      mesh.triangles.push_back({at(face[0]), at(face[i]), at(face[i + 1])});
      mesh.triangleMaterial.push_back(0);
    }
}

TriangleMesh emptyMesh(const std::string& name) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.materials = {Material{220, 200, 170}};
  mesh.materialNames = {"wall"};
  return mesh;
}

// A chamfer of the box corner with corner bits `corner` (bit 0: x = W, bit 1: y = H, bit 2: z = D),
// the cut running through the points `size` from the corner along its three edges.
struct Chamfer {
  int corner;
  glm::dvec3 size;
};

glm::dvec3 boxCorner(int corner) { return {corner & 1 ? W : 0, corner & 2 ? H : 0, corner & 4 ? D : 0}; }

// Cuts p by a chamfer of the W x H x D box's corner.
void chamfer(Polytope& p, const Chamfer& c) {
  const glm::dvec3 v = boxCorner(c.corner);
  std::array<glm::dvec3, 3> points;
  for (int a = 0; a < 3; ++a) {
    points[static_cast<std::size_t>(a)] = v;
    points[static_cast<std::size_t>(a)][a] += ((c.corner >> a) & 1 ? -1 : 1) * c.size[a];
  }
  cutThrough(p, points[0], points[1], points[2], glm::dvec3(W, H, D) / 2.0);
}

TriangleMesh chamferedBox(const std::vector<Chamfer>& chamfers, const std::string& name) {
  Polytope p = boxPolytope(glm::dvec3(0.0), glm::dvec3(W, H, D));
  for (const Chamfer& c : chamfers) chamfer(p, c);
  TriangleMesh mesh = emptyMesh(name);
  addPolytope(mesh, p);
  return mesh;
}

const Chamfer kTopChamfer{7, {1.5, 1.2, 2.0}};




// Whether a triangle's normal is clearly off all three axis planes (sloped along three axes).
bool threeAxis(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 normal = glm::cross(b - a, c - a);
  const glm::dvec3 n = glm::abs(normal) / glm::length(normal);
  return std::min({n.x, n.y, n.z}) > 0.02;
}

int threeAxisFaces(const TriangleMesh& mesh) {
  int count = 0;
  for (const auto& t : mesh.triangles) count += threeAxis(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  return count;
}

// The solid grid's cells of a group (before blocks and axis order), with their orientations.
std::vector<int> gridOrientations(const TriangleMesh& mesh, SolidGroup group) {
  auto grid = buildSolidGrid(mesh);
  EXPECT_TRUE(grid.ok()) << grid.error().message;
  std::vector<int> out;
  if (!grid.ok()) return out;
  for (const Block* block : {&grid->block})
    for (const Cell& cell : block->cells)
      if (cell.kind == CellKind::Solid && solidGroup(cell.solid) == group) out.push_back(solidOrientation(cell.solid));
  for (const Block& block : grid->subBlocks)
    for (const Cell& cell : block.cells)
      if (cell.kind == CellKind::Solid && solidGroup(cell.solid) == group) out.push_back(solidOrientation(cell.solid));
  std::sort(out.begin(), out.end());
  return out;
}

struct Expected {
  int pieces = 0;      // corner slopes found and shown
  int subBlocks = 0;   // of those, by a sub-block
  int pyramids = 0;    // Pyramid cells in the HNI
  int inverse = 0;     // InversePyramid cells in the HNI
  int turned = 0;      // sub-blocks that are another's turned, shown by that one's block
};

void expectPyramids(const TriangleMesh& mesh, const Expected& e, const std::string& stem) {
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("%s: %d corner slopes, %d as cells (%d as sub-blocks), %lld pyramid cells (%d pyramid, %d inverse in the HNI), "
              "%zu blocks, NUT %.2f %% (+ %.2f %% hidden), complement %zu triangles\n",
              stem.c_str(), s.cornerSlopes, s.cornerSlopesAsCells, s.cornerSlopesAsSubBlocks, s.pyramidCells,
              cellsOf(c, SolidGroup::Pyramid), cellsOf(c, SolidGroup::InversePyramid), c.hierarchy.blocks.size(), 100 * nutFraction(c),
              100 * s.hiddenAreaM2 / s.areaM2, c.complement.triangles.size());
  EXPECT_EQ(s.cornerSlopes, e.pieces);
  EXPECT_EQ(s.cornerSlopesAsCells, e.pieces);
  EXPECT_EQ(s.cornerSlopesAsSubBlocks, e.subBlocks);
  EXPECT_EQ(s.pyramidCells, e.pyramids + e.inverse + e.turned);
  EXPECT_EQ(cellsOf(c, SolidGroup::Pyramid), e.pyramids);
  EXPECT_EQ(cellsOf(c, SolidGroup::InversePyramid), e.inverse);
  EXPECT_EQ(c.hierarchy.blocks.size() > 1, e.subBlocks > 0);
  EXPECT_NE(reportJson(c.report).find("\"pyramid_cells\": " + std::to_string(e.pyramids + e.inverse + e.turned)), std::string::npos);
  EXPECT_EQ(threeAxisFaces(c.complement), 0);
  EXPECT_EQ(s.complementAreaM2, 0);
  const std::string path = testing::outputDir("converter_pyramid") + "/" + stem;
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 99.0);
  std::printf("%s: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n", stem.c_str(), f.withinPct[0], f.withinPct[1],
              f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << path << ".view*.diff.png";
}

TEST(Pyramids, ChamferedCornerBecomesOneInversePyramidCell) {
  const TriangleMesh mesh = chamferedBox({kTopChamfer}, "chamfer");
  // The removed corner (x = W, y = H, z = D: corner bits 7) is empty: InversePyramid there.
  EXPECT_EQ(gridOrientations(mesh, SolidGroup::InversePyramid), std::vector<int>{7});
  EXPECT_TRUE(gridOrientations(mesh, SolidGroup::Pyramid).empty());
  expectPyramids(mesh, {1, 0, 0, 1}, "chamfer");
}

// The chamfer split into three coplanar triangles (its centroid a vertex) is one piece.
TEST(Pyramids, ChamferOfSeveralTrianglesIsOnePiece) {
  TriangleMesh mesh = chamferedBox({kTopChamfer}, "chamfer_split");
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    if (!threeAxis(a, b, c)) {
      kept.push_back(t);
      continue;
    }
    const auto centre = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back((a + b + c) / 3.0);
    for (int k = 0; k < 3; ++k) kept.push_back({t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)], centre});
  }
  mesh.triangles = kept;
  mesh.triangleMaterial.assign(kept.size(), 0);
  EXPECT_EQ(threeAxisFaces(mesh), 3);
  expectPyramids(mesh, {1, 0, 0, 1}, "chamfer_split");
}

// All eight corners chamfered, each differently: the planes of one chamfer's box cut the boxes of
// others (x = 9 from corners 3 and 5 runs through the boxes of corners 1 and 7, which reach to
// x = 8.5, and so on), which become sub-blocks. Corner 7's chamfer has corner 1's sizes and is
// corner 1's turned by half a turn about x: one sub-block shows both.
TEST(Pyramids, EightChamferedCornersBecomeInversePyramids) {
  const std::vector<Chamfer> chamfers{{0, {1.0, 1.0, 1.0}}, {1, {1.5, 1.2, 2.0}}, {2, {1.2, 1.5, 1.0}}, {3, {1.0, 1.2, 1.5}},
                                      {4, {2.0, 1.0, 1.2}}, {5, {1.0, 1.0, 1.0}}, {6, {1.5, 1.2, 2.0}}, {7, {1.5, 1.2, 2.0}}};
  const TriangleMesh mesh = chamferedBox(chamfers, "eight_chamfers");
  EXPECT_EQ(gridOrientations(mesh, SolidGroup::InversePyramid), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  expectPyramids(mesh, {8, 6, 0, 7, 1}, "eight_chamfers");
}

// The closed box [lo, hi] (a convex polytope of its own).
void addBox(TriangleMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi) { addPolytope(mesh, boxPolytope(lo, hi)); }

// The chamfered box with an annex against its +x wall, 5.4 m high: its roof's plane y = 5.4 runs
// through the chamfer's box (y from 4.8 to 6), which becomes a sub-block of one cell.
TEST(Pyramids, ChamferCutByABoundaryBecomesASubBlock) {
  TriangleMesh mesh = chamferedBox({kTopChamfer}, "chamfer_annex");
  addBox(mesh, glm::dvec3(W, 0, 1), glm::dvec3(W + 2, 5.4, 3));
  expectPyramids(mesh, {1, 1, 0, 1}, "chamfer_annex");
}

// A notch: the corner cell [8.5, 10] x [4.8, 6] x [6, 8] of the box taken out but for the
// tetrahedron at its inner corner (8.5, 4.8, 6), whose slope faces the open corner: solid on the
// corner's side of the plane, a Pyramid at corner bits 0. Built from touching convex pieces.
TEST(Pyramids, NotchBecomesOnePyramidCell) {
  TriangleMesh mesh = emptyMesh("notch");
  const glm::dvec3 inner(W - 1.5, H - 1.2, D - 2);
  addBox(mesh, glm::dvec3(0.0), glm::dvec3(W, H, inner.z));
  addBox(mesh, glm::dvec3(0, 0, inner.z), glm::dvec3(inner.x, H, D));
  addBox(mesh, glm::dvec3(inner.x, 0, inner.z), glm::dvec3(W, inner.y, D));
  Polytope tetra = boxPolytope(inner, glm::dvec3(W, H, D));
  cutThrough(tetra, glm::dvec3(W, inner.y, inner.z), glm::dvec3(inner.x, H, inner.z), glm::dvec3(inner.x, inner.y, D), inner);
  addPolytope(mesh, tetra);
  EXPECT_EQ(gridOrientations(mesh, SolidGroup::Pyramid), std::vector<int>{0});
  EXPECT_TRUE(gridOrientations(mesh, SolidGroup::InversePyramid).empty());
  expectPyramids(mesh, {1, 0, 1, 0}, "notch");
}

// A cut through the top edge along z, leaning along z too: a quadrilateral from (8.5, 6, 8) and
// (10, 4.8, 8) to (10, 5.4, 0) and (9.25, 6, 0), sloped along all three axes but not the corner
// triangle of its box. It stays in the complementary mesh, and no pyramid appears.
TEST(Pyramids, OtherThreeAxisSlopesStayInTheComplementaryMesh) {
  Polytope p = boxPolytope(glm::dvec3(0.0), glm::dvec3(W, H, D));
  cutThrough(p, glm::dvec3(8.5, H, D), glm::dvec3(W, 4.8, D), glm::dvec3(W, 5.4, 0), glm::dvec3(W, H, D) / 2.0);
  TriangleMesh mesh = emptyMesh("quad_cut");
  addPolytope(mesh, p);
  ASSERT_EQ(threeAxisFaces(mesh), 2);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("quad cut: %d corner slopes, %lld pyramid cells, complement %zu triangles (%d sloped along three axes)\n", s.cornerSlopes,
              s.pyramidCells, c.complement.triangles.size(), threeAxisFaces(c.complement));
  EXPECT_EQ(s.cornerSlopes, 0);
  EXPECT_EQ(s.pyramidCells, 0);
  EXPECT_EQ(cellsOf(c, SolidGroup::Pyramid) + cellsOf(c, SolidGroup::InversePyramid), 0);
  EXPECT_EQ(threeAxisFaces(c.complement), 2);
}

// A chamfer 30 cm along each edge (0.08 m^2, 0.02 % of the surface) is a corner triangle, but like
// a slope below 0.2 % of the surface it is not worth three boundaries across the whole grid: it
// stays in the complementary mesh. The box's one cell, which the chamfer cuts, is not inside at its
// corner sample beyond the chamfer, so it is trimmed; one boundary where the chamfer ends keeps the
// rest of the box solid (Builder::proposeTrimSplits), and only the 30 cm slab beside the chamfer
// goes to the mesh with it, across the box's smallest side (without that boundary the whole box
// did).
TEST(Pyramids, SmallChamferStaysInTheComplementaryMesh) {
  const TriangleMesh mesh = chamferedBox({{7, {0.3, 0.3, 0.3}}}, "small_chamfer");
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("small chamfer: %d corner slopes, %lld pyramid cells, grid %d x %d x %d, complement %zu triangles, NUT %.2f %% of the surface\n",
              s.cornerSlopes, s.pyramidCells, s.cells[0], s.cells[1], s.cells[2], c.complement.triangles.size(), 100 * s.nutAreaM2 / s.areaM2);
  EXPECT_EQ(s.cornerSlopes, 0);
  EXPECT_EQ(s.pyramidCells, 0);
  EXPECT_EQ(s.trimBoundaries, 1);
  EXPECT_EQ(s.trimmedCells, 1);
  // The slab is 0.3 m of the 10 x 6 x 8 m box along x: its end (48 m^2) and 0.3 m strips of four
  // sides (8.4 m^2) of the 376 m^2 go to the mesh.
  EXPECT_EQ(s.cells, (std::array<int, 3>{2, 1, 1}));
  EXPECT_NEAR(s.nutAreaM2, 376 - 48 - 8.4, 0.5);
  EXPECT_EQ(threeAxisFaces(c.complement), 1);
}

// A hip roof (eaves at 6 m, ridge at 9 m from x = 3 to 7): its four faces are sloped along one
// axis each, so no corner slope; the cells under the hip lines hold a crease that no solid has.
// Pyramids change nothing: the HNI, the complementary mesh and the fidelity are the same with them
// or without. (The wedge code leaves those crease cells to the complementary mesh and makes the
// rest of the roof wedges: converter_wedge_test checks how, and the fidelity here is held to the
// samples' bar too.)
TEST(Pyramids, HipRoofConvertsAsBefore) {
  TriangleMesh mesh = emptyMesh("hip_roof");
  Polytope p = boxPolytope(glm::dvec3(0.0), glm::dvec3(W, H + 4, D));
  const glm::dvec3 inside(W / 2, 1, D / 2);
  cutThrough(p, glm::dvec3(0, H, 0), glm::dvec3(W, H, 0), glm::dvec3(W, H + 3, 4), inside);      // pitch facing -z
  cutThrough(p, glm::dvec3(0, H, D), glm::dvec3(W, H, D), glm::dvec3(W, H + 3, 4), inside);      // pitch facing +z
  cutThrough(p, glm::dvec3(0, H, 0), glm::dvec3(0, H, D), glm::dvec3(3, H + 3, 1), inside);      // hip end facing -x
  cutThrough(p, glm::dvec3(W, H, 0), glm::dvec3(W, H, D), glm::dvec3(W - 3, H + 3, 1), inside);  // hip end facing +x
  addPolytope(mesh, p);
  const Conversion c = testing::convertOrFail(mesh);
  ConvertOptions without;
  without.solid.pyramids = false;
  const Conversion before = testing::convertOrFail(mesh, without);
  const SolidStats& s = c.report.solid;
  std::printf("hip roof: %d slopes, %d as wedges, %lld wedge cells, %d corner slopes, %lld pyramid cells, NUT %.2f %%, complement %zu "
              "triangles (%zu without pyramids)\n",
              s.slopes, s.slopesAsWedges, s.wedgeCells, s.cornerSlopes, s.pyramidCells, 100 * nutFraction(c), c.complement.triangles.size(),
              before.complement.triangles.size());
  EXPECT_EQ(s.cornerSlopes, 0);
  EXPECT_EQ(s.pyramidCells, 0);
  EXPECT_EQ(cellsOf(c, SolidGroup::Pyramid) + cellsOf(c, SolidGroup::InversePyramid), 0);
  EXPECT_GT(s.wedgeCells, 0);
  EXPECT_TRUE(c.image == before.image);
  EXPECT_TRUE(c.complement.positions == before.complement.positions);
  EXPECT_TRUE(c.complement.triangles == before.complement.triangles);
  const std::string path = testing::outputDir("converter_pyramid") + "/hip_roof";
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 0.0);
  const testing::Fidelity fBefore = testing::measureFidelity(mesh, {&before}, path, 0.0);
  std::printf("hip roof: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%; without pyramids %.2f %%)\n", f.withinPct[0],
              f.withinPct[1], f.withinPct[2], f.withinPct[3], f.worstWithinPct, fBefore.worstWithinPct);
  EXPECT_EQ(f.withinPct, fBefore.withinPct);
  EXPECT_GE(f.worstWithinPct, 99.0);
  EXPECT_GT(c.complement.triangles.size(), 0u);  // the hips' crease cells
}

}  // namespace
}  // namespace nut::converter
