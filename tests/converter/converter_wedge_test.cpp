// Wedge cells of the mesh converter on pitched roofs (converter/solid.hpp; fitWedges in
// solid_occupancy.cpp, crease points in solid_grid.cpp). A cell becomes a wedge of a roof plane
// only where the plane's faces cover its whole cross-section; where the plane's outline cuts
// through a cell diagonally (a hip, a valley) the cell holds a crease no solid has, and the faces'
// parts over it go to the complementary mesh. Each hip or valley is cut into a few steps whose end
// points become boundaries, so that the crease is one row of small cells and the rest of each
// pitch is wedges.
//
// A hip roof (10 x 8 m, eaves at 6 m, ridge at 9 m from x = 3 to 7), an L-shaped hip roof (two
// wings 8 m wide, four hips and a valley at the inner corner) and a gable roof are built as closed
// meshes with walls in one material and the roof in another, converted, and rendered with their
// complementary meshes against the source (at least 99 % of the pixels of every view within
// 8/255; the diff images go to the test output folder, converter_wedge/, when not). The hip and L
// roofs keep most of their roof surface as NUT wedges and show the hips' and the valley's parts in
// the complementary mesh, nothing else; the gable roof is all wedges with an empty complementary
// mesh, its gable triangles in the wall's material, in two materials and in one. A gable roof
// overhanging its walls leaves the overhang to the complementary mesh in a few pieces, however
// many boundaries cross its eaves. With only slopes that are wedges everywhere
// (the converter's coarser fallback) the hip roof's four slopes fail and are dropped, and it still
// renders like its source. A roof whose slopes all fail converts as if wedges were never tried.
// The meshes are also written to converter_wedge/*.obj for `nut convert`.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <converter/mesh_check.hpp>
#include <converter/solid.hpp>
#include <nut/format.hpp>
#include <nut/solids.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

using testing::cellsOf;

using glm::dvec3;

constexpr std::uint16_t kWall = 0, kRoof = 1;
// Roof pitches rise 0.75 m per metre (the hip ends of the hip roof 1 m per metre), eaves at 6 m.
constexpr double kEaves = 6, kRidge = 9;
// What the converter cuts a hip or valley into (kCreaseSteps in solid_builder.hpp): the expected
// figures below follow from it.
constexpr int kSteps = 4;

const dvec3 kUp(0, 1, 0), kDown(0, -1, 0), kWest(-1, 0, 0), kEast(1, 0, 0), kSouth(0, 0, -1), kNorth(0, 0, 1);

// A closed mesh put together from convex planar polygons with shared corners.
struct MeshBuilder {
  TriangleMesh mesh;
  std::map<std::array<double, 3>, std::uint32_t> index;

  explicit MeshBuilder(const std::string& name) {
    mesh.name = name;
    mesh.materials = {Material{220, 200, 170}, Material{170, 60, 50}};
    mesh.materialNames = {"wall", "roof"};
  }
  std::uint32_t at(const dvec3& q) {
    const auto [it, fresh] = index.emplace(std::array<double, 3>{q.x, q.y, q.z}, static_cast<std::uint32_t>(mesh.positions.size()));
    if (fresh) mesh.positions.push_back(q);
    return it->second;
  }
  // The polygon turned so that its normal points along `outward`, fanned from a corner that gives
  // no degenerate triangle (corners may lie on its sides, where a neighbour's corners are).
  void polygon(std::vector<dvec3> loop, const dvec3& outward, std::uint16_t material) {
    dvec3 normal(0.0);
    for (std::size_t i = 0; i < loop.size(); ++i) normal += glm::cross(loop[i], loop[(i + 1) % loop.size()]);
    if (glm::dot(normal, outward) < 0) std::reverse(loop.begin(), loop.end());
    const std::size_t n = loop.size();
    for (std::size_t s = 0; s < n; ++s) {
      bool ok = true;
      for (std::size_t i = 1; i + 1 < n && ok; ++i)
        ok = glm::length(glm::cross(loop[(s + i) % n] - loop[s], loop[(s + i + 1) % n] - loop[s])) > 1e-9;
      if (!ok) continue;
      for (std::size_t i = 1; i + 1 < n; ++i) {
        mesh.triangles.push_back({at(loop[s]), at(loop[(s + i) % n]), at(loop[(s + i + 1) % n])});
        mesh.triangleMaterial.push_back(material);
      }
      return;
    }
    ADD_FAILURE() << "polygon with no corner to fan from";
  }
};

// A hip roof over [0, 10] x [0, 8] (x, z): pitches facing -z and +z with the ridge from x = 3 to 7
// at z = 4, hip ends facing -x and +x.
TriangleMesh hipRoof() {
  MeshBuilder b("hip_roof");
  b.polygon({{0, 0, 0}, {10, 0, 0}, {10, 0, 8}, {0, 0, 8}}, kDown, kWall);
  b.polygon({{0, 0, 0}, {10, 0, 0}, {10, kEaves, 0}, {0, kEaves, 0}}, kSouth, kWall);
  b.polygon({{0, 0, 8}, {10, 0, 8}, {10, kEaves, 8}, {0, kEaves, 8}}, kNorth, kWall);
  b.polygon({{0, 0, 0}, {0, 0, 8}, {0, kEaves, 8}, {0, kEaves, 0}}, kWest, kWall);
  b.polygon({{10, 0, 0}, {10, 0, 8}, {10, kEaves, 8}, {10, kEaves, 0}}, kEast, kWall);
  b.polygon({{0, kEaves, 0}, {10, kEaves, 0}, {7, kRidge, 4}, {3, kRidge, 4}}, kUp, kRoof);
  b.polygon({{0, kEaves, 8}, {10, kEaves, 8}, {7, kRidge, 4}, {3, kRidge, 4}}, kUp, kRoof);
  b.polygon({{0, kEaves, 0}, {0, kEaves, 8}, {3, kRidge, 4}}, kUp, kRoof);
  b.polygon({{10, kEaves, 0}, {10, kEaves, 8}, {7, kRidge, 4}}, kUp, kRoof);
  return b.mesh;
}

// The hip roof's hips (ridge end to eaves corner).
const std::vector<std::array<dvec3, 2>> kHips{{dvec3(3, kRidge, 4), dvec3(0, kEaves, 0)},
                                              {dvec3(3, kRidge, 4), dvec3(0, kEaves, 8)},
                                              {dvec3(7, kRidge, 4), dvec3(10, kEaves, 0)},
                                              {dvec3(7, kRidge, 4), dvec3(10, kEaves, 8)}};

// An L-shaped hip roof: wing A over [0, 16] x [0, 8] (x, z), wing B over [8, 16] x [0, 18], both
// 8 m wide, every face rising 0.75 m per metre from its eaves (the roof a straight skeleton gives):
// ridges at z = 4 (x from 4 to 12) and x = 12 (z from 4 to 14), hips at the five outer corners and
// a valley from the inner corner (8, 8) up to where the ridges meet (12, 4): there the surface is
// the higher of two planes (solid = y' <= max), where a hip has the lower.
TriangleMesh lRoof() {
  MeshBuilder b("l_roof");
  const double e = kEaves, r = kRidge;
  b.polygon({{0, 0, 0}, {8, 0, 0}, {8, 0, 8}, {0, 0, 8}}, kDown, kWall);
  b.polygon({{8, 0, 0}, {16, 0, 0}, {16, 0, 8}, {8, 0, 8}}, kDown, kWall);
  b.polygon({{8, 0, 8}, {16, 0, 8}, {16, 0, 18}, {8, 0, 18}}, kDown, kWall);
  b.polygon({{0, 0, 0}, {8, 0, 0}, {16, 0, 0}, {16, e, 0}, {0, e, 0}}, kSouth, kWall);
  b.polygon({{16, 0, 0}, {16, 0, 8}, {16, 0, 18}, {16, e, 18}, {16, e, 0}}, kEast, kWall);
  b.polygon({{16, 0, 18}, {8, 0, 18}, {8, e, 18}, {16, e, 18}}, kNorth, kWall);
  b.polygon({{8, 0, 18}, {8, 0, 8}, {8, e, 8}, {8, e, 18}}, kWest, kWall);
  b.polygon({{8, 0, 8}, {0, 0, 8}, {0, e, 8}, {8, e, 8}}, kNorth, kWall);
  b.polygon({{0, 0, 8}, {0, 0, 0}, {0, e, 0}, {0, e, 8}}, kWest, kWall);
  b.polygon({{0, e, 0}, {16, e, 0}, {12, r, 4}, {4, r, 4}}, kUp, kRoof);      // facing -z
  b.polygon({{16, e, 0}, {16, e, 18}, {12, r, 14}, {12, r, 4}}, kUp, kRoof);  // facing +x
  b.polygon({{16, e, 18}, {8, e, 18}, {12, r, 14}}, kUp, kRoof);              // wing B's hip end, facing +z
  b.polygon({{8, e, 18}, {8, e, 8}, {12, r, 4}, {12, r, 14}}, kUp, kRoof);    // facing -x, down to the valley
  b.polygon({{8, e, 8}, {0, e, 8}, {4, r, 4}, {12, r, 4}}, kUp, kRoof);       // facing +z, down to the valley
  b.polygon({{0, e, 8}, {0, e, 0}, {4, r, 4}}, kUp, kRoof);                   // wing A's hip end, facing -x
  return b.mesh;
}

const std::vector<std::array<dvec3, 2>> kLCreases{{dvec3(4, kRidge, 4), dvec3(0, kEaves, 0)},   {dvec3(4, kRidge, 4), dvec3(0, kEaves, 8)},
                                                  {dvec3(12, kRidge, 4), dvec3(16, kEaves, 0)}, {dvec3(12, kRidge, 14), dvec3(16, kEaves, 18)},
                                                  {dvec3(12, kRidge, 14), dvec3(8, kEaves, 18)}, {dvec3(12, kRidge, 4), dvec3(8, kEaves, 8)}};

// A gable roof over [0, 10] x [0, 8]: two rectangular pitches, the ridge along x at z = 4, gable
// walls at x = 0 and 10.
TriangleMesh gableRoof() {
  MeshBuilder b("gable_roof");
  b.polygon({{0, 0, 0}, {10, 0, 0}, {10, 0, 8}, {0, 0, 8}}, kDown, kWall);
  b.polygon({{0, 0, 0}, {10, 0, 0}, {10, kEaves, 0}, {0, kEaves, 0}}, kSouth, kWall);
  b.polygon({{0, 0, 8}, {10, 0, 8}, {10, kEaves, 8}, {0, kEaves, 8}}, kNorth, kWall);
  b.polygon({{0, 0, 0}, {0, 0, 8}, {0, kEaves, 8}, {0, kRidge, 4}, {0, kEaves, 0}}, kWest, kWall);
  b.polygon({{10, 0, 0}, {10, 0, 8}, {10, kEaves, 8}, {10, kRidge, 4}, {10, kEaves, 0}}, kEast, kWall);
  b.polygon({{0, kEaves, 0}, {10, kEaves, 0}, {10, kRidge, 4}, {0, kRidge, 4}}, kUp, kRoof);
  b.polygon({{0, kEaves, 8}, {10, kEaves, 8}, {10, kRidge, 4}, {0, kRidge, 4}}, kUp, kRoof);
  return b.mesh;
}

// The gable roof with its pitches carried 0.5 m past every wall as open sheets (eaves and
// overhanging gables, as most of Zurich's LoD2 roofs are), and `chimneys` chimneys 0.6 m square
// rising from inside the house through the -z pitch: each makes two boundaries along x, across
// the eaves. Each pitch is one quad, as LoD2 models draw it, or a grid of `tiles` x `tiles` quads,
// as tessellated meshes do.
constexpr double kOverhang = 0.5;
TriangleMesh overhangingGableRoof(int chimneys, int tiles = 1) {
  MeshBuilder b("overhanging_gable_roof_" + std::to_string(chimneys) + (tiles > 1 ? "_tiled" : ""));
  b.polygon({{0, 0, 0}, {10, 0, 0}, {10, 0, 8}, {0, 0, 8}}, kDown, kWall);
  b.polygon({{0, 0, 0}, {10, 0, 0}, {10, kEaves, 0}, {0, kEaves, 0}}, kSouth, kWall);
  b.polygon({{0, 0, 8}, {10, 0, 8}, {10, kEaves, 8}, {0, kEaves, 8}}, kNorth, kWall);
  b.polygon({{0, 0, 0}, {0, 0, 8}, {0, kEaves, 8}, {0, kRidge, 4}, {0, kEaves, 0}}, kWest, kWall);
  b.polygon({{10, 0, 0}, {10, 0, 8}, {10, kEaves, 8}, {10, kRidge, 4}, {10, kEaves, 0}}, kEast, kWall);
  const double x0 = -kOverhang, x1 = 10 + kOverhang, low = kEaves - 0.75 * kOverhang;
  for (const double eave : {-kOverhang, 8 + kOverhang}) {
    // Corner (i, j) of the tiling: i along x, j from the eave up to the ridge.
    const auto at = [&](int i, int j) {
      const double s = static_cast<double>(i) / tiles, t = static_cast<double>(j) / tiles;
      return dvec3(x0 + s * (x1 - x0), low + t * (kRidge - low), eave + t * (4 - eave));
    };
    for (int i = 0; i < tiles; ++i)
      for (int j = 0; j < tiles; ++j) b.polygon({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, kUp, kRoof);
  }
  for (int c = 0; c < chimneys; ++c) {
    const double a = 1.0 + 1.8 * c, z0 = 1.5, z1 = 2.1, y0 = 4, y1 = kRidge + 1;
    b.polygon({{a, y0, z0}, {a + 0.6, y0, z0}, {a + 0.6, y0, z1}, {a, y0, z1}}, kDown, kWall);
    b.polygon({{a, y1, z0}, {a + 0.6, y1, z0}, {a + 0.6, y1, z1}, {a, y1, z1}}, kUp, kWall);
    b.polygon({{a, y0, z0}, {a + 0.6, y0, z0}, {a + 0.6, y1, z0}, {a, y1, z0}}, kSouth, kWall);
    b.polygon({{a, y0, z1}, {a + 0.6, y0, z1}, {a + 0.6, y1, z1}, {a, y1, z1}}, kNorth, kWall);
    b.polygon({{a, y0, z0}, {a, y0, z1}, {a, y1, z1}, {a, y1, z0}}, kWest, kWall);
    b.polygon({{a + 0.6, y0, z0}, {a + 0.6, y0, z1}, {a + 0.6, y1, z1}, {a + 0.6, y1, z0}}, kEast, kWall);
  }
  return b.mesh;
}

// The mesh as OBJ + MTL in the test output folder (for `nut convert`, `nut render-mesh`).
void writeObj(const TriangleMesh& mesh) {
  const std::string stem = testing::outputDir("converter_wedge") + "/" + mesh.name;
  std::ofstream mtl(stem + ".mtl");
  for (std::size_t m = 0; m < mesh.materials.size(); ++m)
    mtl << "newmtl " << mesh.materialNames[m] << "\nKd " << mesh.materials[m].r / 255.0 << ' ' << mesh.materials[m].g / 255.0 << ' '
        << mesh.materials[m].b / 255.0 << "\n";
  std::ofstream obj(stem + ".obj");
  obj << "mtllib " << mesh.name << ".mtl\n";
  for (const dvec3& q : mesh.positions) obj << "v " << q.x << ' ' << q.y << ' ' << q.z << "\n";
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (t == 0 || mesh.triangleMaterial[t] != mesh.triangleMaterial[t - 1]) obj << "usemtl " << mesh.materialNames[mesh.triangleMaterial[t]] << "\n";
    obj << "f " << mesh.triangles[t][0] + 1 << ' ' << mesh.triangles[t][1] + 1 << ' ' << mesh.triangles[t][2] + 1 << "\n";
  }
}


dvec3 areaVector(const TriangleMesh& mesh, std::size_t t) {
  const auto& tri = mesh.triangles[t];
  return 0.5 * glm::cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
}

// Whether a triangle is sloped (a roof face): its normal off every axis.
bool sloped(const TriangleMesh& mesh, std::size_t t) {
  const dvec3 a = areaVector(mesh, t);
  if (glm::length(a) <= 1e-9) return false;
  const dvec3 n = glm::abs(a / glm::length(a));
  return n.x < 0.999 && n.y < 0.999 && n.z < 0.999;
}

double slopedArea(const TriangleMesh& mesh) {
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (sloped(mesh, t)) area += glm::length(areaVector(mesh, t));
  return area;
}

// Distance in plan (x, z) from q to the segment ab.
double planDistance(const dvec3& q, const std::array<dvec3, 2>& ab) {
  const glm::dvec2 p(q.x, q.z), a(ab[0].x, ab[0].z), b(ab[1].x, ab[1].z);
  const double t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
  return glm::length(p - (a + t * (b - a)));
}


struct Figures {
  double roofArea = 0;            // the source's sloped faces
  double meshArea = 0, meshRoofArea = 0;  // the complementary mesh's faces, its sloped ones
  double roofNutPct = 0;          // of the roof's surface, shown by the HNI
  double farthestFromCrease = 0;  // of the complementary mesh's corners, in plan
  // In the mesh: all, in the wall's material, axis-aligned or degenerate.
  int meshTriangles = 0, meshWallTriangles = 0, meshFlatTriangles = 0;
  testing::Fidelity fidelity;
};

// Prints and measures a conversion: the roof's surface in the HNI and in the complementary mesh,
// where the complementary mesh lies, and the fidelity of every view (diff images for views below
// minPct).
Figures measure(const TriangleMesh& mesh, const Conversion& c, const std::vector<std::array<dvec3, 2>>& creases, const std::string& label,
                double minPct = 99.0) {
  Figures f;
  const SolidStats& s = c.report.solid;
  f.roofArea = slopedArea(mesh);
  f.meshTriangles = static_cast<int>(c.complement.triangles.size());
  for (std::size_t t = 0; t < c.complement.triangles.size(); ++t) {
    f.meshArea += glm::length(areaVector(c.complement, t));
    if (sloped(c.complement, t)) f.meshRoofArea += glm::length(areaVector(c.complement, t));
    f.meshWallTriangles += c.complement.triangleMaterial[t] != kRoof;
    f.meshFlatTriangles += !sloped(c.complement, t);
    for (const std::uint32_t k : c.complement.triangles[t]) {
      double nearest = 1e9;
      for (const auto& crease : creases) nearest = std::min(nearest, planDistance(c.complement.positions[k], crease));
      f.farthestFromCrease = std::max(f.farthestFromCrease, nearest);
    }
  }
  f.roofNutPct = 100 * (f.roofArea - f.meshRoofArea) / f.roofArea;
  const std::string path = testing::outputDir("converter_wedge") + "/" + label;
  f.fidelity = testing::measureFidelity(mesh, {&c}, path, minPct);
  std::printf("%s: %d slopes, %d as wedges, %lld wedge cells (%d in the HNI), grid %d x %d x %d, %lld slope boundaries; surface NUT %.2f %%, "
              "hidden %.2f %%, complementary mesh %.2f %% (%d triangles); roof %.2f m^2: NUT %.2f %%, mesh %.2f m^2 (%.2f m^2 sloped), its corners at most "
              "%.2f m from a hip or valley in plan; HNI %lld cells\n",
              label.c_str(), s.slopes, s.slopesAsWedges, s.wedgeCells, cellsOf(c, SolidGroup::Wedge), s.cells[0], s.cells[1], s.cells[2],
              s.slopeBoundaries, 100 * s.nutAreaM2 / s.areaM2, 100 * s.hiddenAreaM2 / s.areaM2, 100 * s.complementAreaM2 / s.areaM2,
              f.meshTriangles, f.roofArea, f.roofNutPct, f.meshArea, f.meshRoofArea, f.farthestFromCrease, c.report.hni.cells);
  std::printf("%s: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n", label.c_str(), f.fidelity.withinPct[0],
              f.fidelity.withinPct[1], f.fidelity.withinPct[2], f.fidelity.withinPct[3], f.fidelity.worstWithinPct);
  return f;
}

TEST(Wedges, HipRoofRendersLikeItsSource) {
  const TriangleMesh mesh = hipRoof();
  writeObj(mesh);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  const Figures f = measure(mesh, c, kHips, "hip_roof");
  EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/hip_roof.view*.diff.png";
  // All four faces stay slopes shown by wedges: each hip is cut into kSteps steps, so each pitch
  // has 16 whole cells (7 + 5 + 3 + 1 rows up to the ridge) and each hip end 12 (6 + 4 + 2).
  EXPECT_EQ(s.slopes, 4);
  EXPECT_EQ(s.slopesAsWedges, 4);
  EXPECT_EQ(s.wedgeCells, 2 * 16 + 2 * 12);
  // x: 0, 3, 7, 10 and 3 steps per hip; y: 0, 6, 3 steps, 9; z: 0 .. 8 in 1 m steps. The
  // slopes added all but the mesh's bounds: x = 3, 7 and 6 steps, y = 6 (the eaves) and 3, z = 4
  // (the ridge) and 6.
  EXPECT_EQ(s.cells, (std::array<int, 3>{9, 5, 8}));
  EXPECT_EQ(s.slopeBoundaries, 8 + 4 + 7);
  // The mesh holds the hips' crease cells and nothing else: per hip, kSteps cells of 0.75 x 1 m in
  // plan, half under the pitch (1.25 m^2 of surface per m^2 of plan) and half under the hip end
  // (sqrt 2).
  const double crease = 4 * kSteps * 0.5 * 0.75 * 1.0 * (1.25 + std::sqrt(2.0));
  EXPECT_NEAR(f.meshArea, crease, 0.01 * crease);
  EXPECT_NEAR(s.complementAreaM2, crease, 0.01 * crease);
  EXPECT_EQ(f.meshWallTriangles, 0);
  EXPECT_EQ(f.meshFlatTriangles, 0);
  EXPECT_LE(f.farthestFromCrease, 0.6 + 1e-6);  // within its crease cell: 0.75 x 1 m, across the diagonal 0.6 m
  EXPECT_GE(f.roofNutPct, 84.0);
  EXPECT_EQ(cellsOf(c, SolidGroup::Pyramid) + cellsOf(c, SolidGroup::InversePyramid), 0);
}

// With only slopes that are wedges everywhere (the converter's coarser fallback), every face of the
// hip roof has cells its outline cuts, so all four are dropped and the grid is built again without
// their boundaries: one cell (no face is horizontal at the eaves), which the roof, now in the
// complementary mesh, cuts, so it is trimmed (it is not inside all over). A boundary at the eaves,
// where the roof's faces end inside that cell, keeps the house below them solid: the walls stay
// NUT cells and only the roof goes to the mesh.
TEST(Wedges, HipRoofWithoutPartialWedgesLeavesTheRoofToTheMesh) {
  const TriangleMesh mesh = hipRoof();
  ConvertOptions options;
  options.solid.partialWedges = false;
  const Conversion c = testing::convertOrFail(mesh, options);
  const SolidStats& s = c.report.solid;
  const Figures f = measure(mesh, c, kHips, "hip_roof_whole_wedges_only");
  EXPECT_GE(f.fidelity.worstWithinPct, 99.0);
  EXPECT_EQ(s.slopes, 4);
  EXPECT_EQ(s.slopesAsWedges, 0);
  EXPECT_EQ(s.wedgeCells, 0);
  EXPECT_EQ(s.slopeBoundaries, 0);
  EXPECT_EQ(s.trimBoundaries, 1);
  EXPECT_EQ(s.cells, (std::array<int, 3>{1, 2, 1}));
  EXPECT_EQ(s.trimmedCells, 1);  // the roof's cell, from the eaves to the ridge
  EXPECT_NEAR(s.complementAreaM2, f.roofArea, 1e-9 * s.areaM2);
  EXPECT_NEAR(f.meshArea, f.roofArea, 1e-9 * s.areaM2);
  EXPECT_EQ(f.meshWallTriangles, 0);
}

TEST(Wedges, LShapedHipRoofWithAValleyRendersLikeItsSource) {
  const TriangleMesh mesh = lRoof();
  writeObj(mesh);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  const Figures f = measure(mesh, c, kLCreases, "l_roof");
  EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/l_roof.view*.diff.png";
  EXPECT_EQ(s.slopes, 6);
  EXPECT_EQ(s.slopesAsWedges, 6);
  // Every hip and the valley run 4 m by 4 m in plan: kSteps crease cells of 1 x 1 m each, half
  // under each of the two faces (1.25 m^2 of surface per m^2 of plan): 6 * 4 * 1.25 m^2.
  const double crease = 6 * kSteps * 1.0 * 1.25;
  EXPECT_NEAR(f.meshArea, crease, 0.01 * crease);
  EXPECT_EQ(f.meshWallTriangles, 0);
  EXPECT_EQ(f.meshFlatTriangles, 0);
  EXPECT_LE(f.farthestFromCrease, std::sqrt(0.5) + 1e-6);  // within its 1 x 1 m crease cell
  EXPECT_GE(f.roofNutPct, 88.0);  // 230 of 260 m^2
}

// With plane cells (SolidOptions::planeCells), the crease cells the wedges leave to the mesh
// become plane cells of the two faces meeting there: a ridge's for the hips, a valley's for the
// L's inner corner. The roofs are then NUT all over, and render like the source.
TEST(Wedges, PlaneCellsTakeTheHipsAndTheValleyFromTheMesh) {
  for (const bool l : {false, true}) {
    const TriangleMesh mesh = l ? lRoof() : hipRoof();
    ConvertOptions options;
    options.solid.planeCells = true;
    const Conversion c = testing::convertOrFail(mesh, options);
    const SolidStats& s = c.report.solid;
    const Figures f = measure(mesh, c, l ? kLCreases : kHips, l ? "l_roof_plane_cells" : "hip_roof_plane_cells");
    EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/*_plane_cells.view*.diff.png";
    // Every crease cell (kSteps per hip or valley) becomes a two-plane cell.
    const int creases = l ? 6 : 4;
    EXPECT_EQ(s.twoPlaneCells, creases * kSteps);
    EXPECT_GE(f.roofNutPct, 99.99);
    EXPECT_LE(f.meshArea, 1e-6);
    EXPECT_EQ(c.image.at(0, 0)[3], format::kVersionPlanes);
  }
}

// Roofs and walls at angles no wedge has, in one material: a shed roof sloped along both
// horizontal axes over a box (the plane corners of its roof become boundaries), and the same roof
// over a trapezoid whose two side walls stand at odd angles to the others. With plane cells, the
// roof's cells become one-plane cells, and where a side wall meets the roof two-plane cells; the
// faces the boxes already show leave the mesh too, and nothing is left to the complementary mesh.
TriangleMesh tiltedShed() {
  MeshBuilder b("tilted_shed");
  const auto top = [](double x, double z) { return dvec3(x, 6 + 0.3 * x + 0.2 * z, z); };
  b.polygon({{0, 0, 0}, {12, 0, 0}, {12, 0, 10}, {0, 0, 10}}, kDown, kWall);
  b.polygon({{0, 0, 0}, {12, 0, 0}, top(12, 0), top(0, 0)}, kSouth, kWall);
  b.polygon({{0, 0, 10}, {12, 0, 10}, top(12, 10), top(0, 10)}, kNorth, kWall);
  b.polygon({{0, 0, 0}, {0, 0, 10}, top(0, 10), top(0, 0)}, kWest, kWall);
  b.polygon({{12, 0, 0}, {12, 0, 10}, top(12, 10), top(12, 0)}, kEast, kWall);
  b.polygon({top(0, 0), top(12, 0), top(12, 10), top(0, 10)}, kUp, kWall);
  return b.mesh;
}

TriangleMesh trapezoidHouse() {
  MeshBuilder b("trapezoid_house");
  const std::array<dvec3, 4> foot{dvec3(0, 0, 0), dvec3(14, 0, 0), dvec3(11, 0, 9), dvec3(2, 0, 9)};
  const auto top = [](const dvec3& q) { return dvec3(q.x, 6 + 0.25 * q.x + 0.15 * q.z, q.z); };
  b.polygon({foot[0], foot[1], foot[2], foot[3]}, kDown, kWall);
  b.polygon({top(foot[0]), top(foot[1]), top(foot[2]), top(foot[3])}, kUp, kWall);
  for (std::size_t i = 0; i < 4; ++i) {
    const dvec3 a = foot[i], c = foot[(i + 1) % 4];
    const dvec3 outward = glm::normalize(dvec3(c.z - a.z, 0, a.x - c.x));
    b.polygon({a, c, top(c), top(a)}, outward, kWall);
  }
  return b.mesh;
}

TEST(Wedges, PlaneCellsTakeRoofsAndWallsAtAnyAngle) {
  for (const bool shed : {true, false}) {
    const TriangleMesh mesh = shed ? tiltedShed() : trapezoidHouse();
    ConvertOptions options;
    options.solid.planeCells = true;
    options.alignYaw = false;  // the trapezoid's odd walls stay odd in its own frame
    const Conversion c = testing::convertOrFail(mesh, options);
    const SolidStats& s = c.report.solid;
    const Figures f = measure(mesh, c, {}, mesh.name);
    std::printf("%s: %lld plane cells (%lld of two planes), %lld boundaries at plane corners\n", mesh.name.c_str(),
                s.planeCells, s.twoPlaneCells, s.planeBoundaries);
    EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/" << mesh.name << ".view*.diff.png";
    EXPECT_GT(s.planeCells, 0);
    if (!shed) {
      EXPECT_GT(s.twoPlaneCells, 0);
    }
    EXPECT_EQ(f.meshTriangles, 0);
    EXPECT_NEAR(s.nutAreaM2 + s.hiddenAreaM2, s.areaM2, 1e-6 * s.areaM2);
    EXPECT_EQ(c.image.at(0, 0)[3], format::kVersionPlanes);
    // Without plane cells the sloped roof and the odd walls are the mesh's.
    options.solid.planeCells = false;
    const Conversion without = testing::convertOrFail(mesh, options);
    const SolidStats& w = without.report.solid;
    std::printf("%s without plane cells: surface NUT %.2f %%, %zu triangles in the complementary mesh\n",
                mesh.name.c_str(), 100 * w.nutAreaM2 / w.areaM2, without.complement.triangles.size());
    EXPECT_GT(without.complement.triangles.size(), 0u);
  }
}

// Two rectangular pitches: every cell under them is covered whole, so the roof is wedges only, no
// crease points are added and nothing goes to the complementary mesh. Walls and roof differ in
// material: each gable end (6 m^2) is a small share of its cell (one wedge under a 50 m^2 pitch)
// but 1.8 % of the surface, so materialConflicts separates it by a boundary 2 mm inside the gable
// (the grid goes from 1 x 2 x 2 to 3 x 2 x 2 cells) and the gable triangles keep the wall's colour.
// In one material the grid stays 1 x 2 x 2.
TEST(Wedges, GableRoofIsAllWedges) {
  const TriangleMesh mesh = gableRoof();
  writeObj(mesh);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  const Figures two = measure(mesh, c, {}, "gable_roof");
  EXPECT_GE(two.fidelity.worstWithinPct, 99.0) << "see converter_wedge/gable_roof.view*.diff.png";
  EXPECT_EQ(s.slopes, 2);
  EXPECT_EQ(s.slopesAsWedges, 2);
  EXPECT_EQ(s.wedgeCells, 6);
  EXPECT_EQ(s.cells, (std::array<int, 3>{3, 2, 2}));
  EXPECT_EQ(s.slopeBoundaries, 2);  // the eaves (y = 6) and the ridge (z = 4)
  EXPECT_EQ(c.complement.triangles.size(), 0u);
  EXPECT_EQ(s.complementAreaM2, 0);
  EXPECT_EQ(s.trimmedCells, 0);
  EXPECT_NEAR(s.nutAreaM2 + s.hiddenAreaM2, s.areaM2, 1e-9 * s.areaM2);

  TriangleMesh plain = mesh;
  plain.name = "gable_roof_one_material";
  std::fill(plain.triangleMaterial.begin(), plain.triangleMaterial.end(), kWall);
  const Conversion one = testing::convertOrFail(plain);
  EXPECT_EQ(one.report.solid.wedgeCells, 2);
  EXPECT_EQ(one.report.solid.cells, (std::array<int, 3>{1, 2, 2}));
  EXPECT_EQ(one.complement.triangles.size(), 0u);
  const Figures f = measure(plain, one, {}, "gable_roof_one_material");
  EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/gable_roof_one_material.view*.diff.png";
}

// An eave is a sheet with no inside, so the cells under it fail and the roof's faces over them go
// to the complementary mesh: the overhang, a frame 0.5 m wide around the walls (9.5 m^2 in plan
// per pitch, 1.25 m^2 of surface per m^2 of plan). The boundaries that chimneys add across the
// eaves cut that frame into more cells, but not into more pieces: neighbouring cells are clipped
// as one rectangle, so the mesh is the same triangles with 3 chimneys as with 5 (cut cell by
// cell it grew with every chimney: 80 and 96 triangles with the pitches one quad each). The
// pitches are tiled 8 x 8 here, so that the overhang's pieces take fewer triangles than a pitch
// has and the pitches stay wedges (next test).
TEST(Wedges, AnOverhangGoesToTheMeshInPiecesThatDoNotMultiplyWithTheCells) {
  const double overhang = 2 * (11.0 * 4.5 - 10.0 * 4.0) * 1.25;
  const std::array<int, 2> chimneys{3, 5};
  constexpr int kTiles = 8;
  std::array<int, 2> triangles{}, cellsAlongX{};
  for (std::size_t n = 0; n < chimneys.size(); ++n) {
    const TriangleMesh mesh = overhangingGableRoof(chimneys[n], kTiles);
    writeObj(mesh);
    const Conversion c = testing::convertOrFail(mesh);
    const Figures f = measure(mesh, c, {}, mesh.name);
    EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/" << mesh.name << ".view*.diff.png";
    EXPECT_EQ(c.report.solid.slopesAsWedges, 2) << mesh.name;
    EXPECT_NEAR(f.meshArea, overhang, 0.01 * overhang) << mesh.name;
    EXPECT_EQ(f.meshWallTriangles, 0) << mesh.name;
    triangles[n] = f.meshTriangles;
    cellsAlongX[n] = c.report.solid.cells[0];
  }
  EXPECT_GE(cellsAlongX[1], cellsAlongX[0] + 4);  // the two more chimneys do cut the eaves
  EXPECT_EQ(triangles[1], triangles[0]);
  EXPECT_LE(triangles[0], 2 * 2 * kTiles * kTiles);  // fewer than the pitches' own triangles
}

// The same roof with each pitch one quad, as LoD2 models draw it (most of Zurich's): its overhang
// alone would take the mesh more triangles than the pitch has, so each pitch goes to the mesh whole
// and its wedges, which would save nothing, are not made; the house under it stays NUT.
TEST(Wedges, AnOverhangingPitchOfFewFacesGoesToTheMeshWhole) {
  const TriangleMesh mesh = overhangingGableRoof(3);
  writeObj(mesh);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  const Figures f = measure(mesh, c, {}, mesh.name);
  EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/" << mesh.name << ".view*.diff.png";
  EXPECT_EQ(s.slopes, 2);
  EXPECT_EQ(s.slopesAsWedges, 0);
  EXPECT_EQ(s.wedgeCells, 0);
  EXPECT_NEAR(f.meshRoofArea, f.roofArea, 1e-6 * f.roofArea);  // every pitch whole
  EXPECT_LE(f.meshTriangles, 4 + 2 * 3);                         // the pitches, and at most the gables' fans
  EXPECT_GE(s.solidCells, 1);
}

// Without chimneys nothing crosses the eaves, and each pitch has more cells where its sheet has no
// inside (the eave, the overhanging gables) than wedges, so both are dropped and the roof goes to
// the mesh whole. No face of the house ends at the eaves, so the house is then one cell up to the
// ridge, which the roof cuts; it is trimmed, and a boundary where the roof's faces end inside it
// (the eaves) keeps the house below solid; without that boundary the whole house would go to the
// mesh.
TEST(Wedges, AHouseUnderAnOverhangingRoofLeftToTheMeshStaysSolid) {
  const TriangleMesh mesh = overhangingGableRoof(0);
  writeObj(mesh);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  const Figures f = measure(mesh, c, {}, mesh.name);
  EXPECT_GE(f.fidelity.worstWithinPct, 99.0) << "see converter_wedge/" << mesh.name << ".view*.diff.png";
  EXPECT_EQ(s.slopesAsWedges, 0);
  EXPECT_EQ(s.trimBoundaries, 1);
  EXPECT_EQ(s.cells[1], 2);  // up to the eaves, and from there to the ridge
  EXPECT_GE(s.solidCells, 1);
  // The walls up to the eaves and the floor are NUT; the roof and the gables above the eaves are
  // mesh (a gable's triangles that reach below the eaves whole, drawn again over the wall there).
  const double walls = 2 * 10.0 * kEaves + 2 * 8.0 * kEaves + 10.0 * 8.0;
  EXPECT_NEAR(s.nutAreaM2, walls, 1e-6 * walls);
  EXPECT_NEAR(s.complementAreaM2, s.areaM2 - walls, 1e-6 * s.areaM2);
  EXPECT_NEAR(f.meshArea, s.areaM2 - walls + s.drawnTwiceAreaM2, 1e-6 * s.areaM2);
}

// Distance from q to triangle abc along its normal, when q's foot lies inside it; infinity when
// it lies outside (or the triangle is degenerate).
double distanceOnTriangle(const dvec3& q, const dvec3& a, const dvec3& b, const dvec3& c) {
  const dvec3 cross = glm::cross(b - a, c - a);
  const double length = glm::length(cross);
  if (length == 0) return std::numeric_limits<double>::infinity();
  const dvec3 n = cross / length;
  const double d = glm::dot(q - a, n);
  const dvec3 foot = q - d * n;
  const auto inside = [&](const dvec3& x, const dvec3& y) { return glm::dot(glm::cross(y - x, foot - x), n) >= -1e-9; };
  return inside(a, b) && inside(b, c) && inside(c, a) ? std::abs(d) : std::numeric_limits<double>::infinity();
}

// A wedge cell runs corner to corner, so its sloped face passes through its centre; a face of
// the complementary mesh through that point draws the same surface again. Only the faces' parts
// over failed cells go to the mesh, and a slope whose failed cells hold more than half of its
// cross-section is dropped (the car park's ramps: slabs thinner than the cells they cross, which
// fail in a few wide cells between many narrow wedges). The dormers' roof and the residential
// block's keep their wedges.
TEST(Wedges, NoWedgeCellDrawsWhatTheComplementaryMeshDraws) {
  for (const auto& [path, minWedges] : {std::pair<std::string, int>{"samples/obj/carpark.obj", 0},
                                        std::pair<std::string, int>{"tests/data/zurich_dormers.obj", 1},
                                        std::pair<std::string, int>{"samples/obj/residential.obj", 1}}) {
    auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/" + path);
    ASSERT_TRUE(obj.ok()) << obj.error().message;
    TriangleMesh mesh = mergeMeshes(obj->objects, path).value();
    checkAndRepair(mesh);
    auto grid = buildSolidGrid(mesh);
    ASSERT_TRUE(grid.ok()) << grid.error().message;
    const Block& block = grid->block;
    const TriangleMesh& complement = grid->complement;
    int wedges = 0, drawnTwice = 0;
    for (int z = 0; z < block.cellCount(2); ++z)
      for (int y = 0; y < block.cellCount(1); ++y)
        for (int x = 0; x < block.cellCount(0); ++x) {
          const Cell& cell = block.cell(x, y, z);
          if (cell.kind != CellKind::Solid || solidGroup(cell.solid) != SolidGroup::Wedge) continue;
          ++wedges;
          const std::array<int, 3> at{x, y, z};
          dvec3 centre = grid->originM;
          for (int a = 0; a < 3; ++a) {
            const auto& B = block.boundsM[static_cast<std::size_t>(a)];
            centre[a] += 0.5 * (B[static_cast<std::size_t>(at[static_cast<std::size_t>(a)])] + B[static_cast<std::size_t>(at[static_cast<std::size_t>(a)] + 1)]);
          }
          drawnTwice += std::any_of(complement.triangles.begin(), complement.triangles.end(), [&](const auto& t) {
            return distanceOnTriangle(centre, complement.positions[t[0]], complement.positions[t[1]], complement.positions[t[2]]) < 0.005;
          });
        }
    std::printf("%s: %d wedge cells, %d of them under a face of the complementary mesh\n", path.c_str(), wedges, drawnTwice);
    EXPECT_EQ(drawnTwice, 0) << path;
    EXPECT_GE(wedges, minWedges) << path;
  }
}

// A roof none of whose slopes comes out as wedges (tests/data/zurich_roof_given_up.obj, a LoD2
// house 23 m tall whose dormers and chimneys cut its 31 roof planes) leaves no trace of them: a
// grid that gives a slope up is built again without its boundaries before the occupancy of its
// other cells is computed, so the HNI and the complementary mesh are those of a conversion that
// never tried wedges: no material boundary its finer cells would propose goes into the next build.
TEST(Wedges, ARoofWhoseSlopesAllFailConvertsAsIfWedgesWereNeverTried) {
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/tests/data/zurich_roof_given_up.obj");
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  const TriangleMesh mesh = mergeMeshes(obj->objects, "zurich_roof_given_up").value();
  ConvertOptions withoutWedges;
  withoutWedges.solid.wedges = withoutWedges.solid.pyramids = false;
  auto tried = convertMesh(mesh);
  auto untried = convertMesh(mesh, withoutWedges);
  ASSERT_TRUE(tried.ok()) << tried.error().message;
  ASSERT_TRUE(untried.ok()) << untried.error().message;
  const SolidStats& stats = tried->report.solid;
  std::printf("%d slopes, %d as wedges; %d grids built, %d classified; %zu and %zu complementary triangles\n", stats.slopes,
              stats.slopesAsWedges, stats.gridBuilds, stats.gridsClassified, tried->complement.triangles.size(),
              untried->complement.triangles.size());
  EXPECT_GT(stats.slopes, 0);
  EXPECT_EQ(stats.slopesAsWedges, 0);
  EXPECT_LT(stats.gridsClassified, stats.gridBuilds);
  EXPECT_EQ(tried->report.solid.cells, untried->report.solid.cells);
  EXPECT_TRUE(tried->image.pixels == untried->image.pixels) << "the HNIs differ";
  EXPECT_EQ(tried->complement.positions, untried->complement.positions);
  EXPECT_EQ(tried->complement.triangles, untried->complement.triangles);
}

}  // namespace
}  // namespace nut::converter
