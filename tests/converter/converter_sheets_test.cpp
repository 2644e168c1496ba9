// Open sheets peeled off a closed body (converter/sheets.hpp). A gable house made in the test, its
// roof overhanging the walls on all sides, splits into the closed house and the overhang, whose
// area is known from the dimensions; a closed mesh and a box without a floor have no sheets. On
// the Zurich house fixture (tests/data/zurich_house.obj: a roof overhanging two walls, a dormer
// standing on it, walls a millimetre off the edges they meet) the sheets are the two overhang
// strips, measured from the fixture's own vertices, and the body converts to more NUT surface than
// the open mesh. The conversion keeps whichever of the two makes the smaller files.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <converter/mesh_check.hpp>
#include <converter/mesh_size.hpp>
#include <converter/sheets.hpp>
#include <nut/png_io.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

constexpr std::uint16_t kWall = 0, kRoof = 1, kGround = 2;

// Adds triangle abc facing away from `centre`.
void addFacingOut(TriangleMesh& mesh, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, const glm::dvec3& centre,
                  std::uint16_t material) {
  if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre) < 0) std::swap(b, c);
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c});
  mesh.triangles.push_back({first, first + 1, first + 2});
  mesh.triangleMaterial.push_back(material);
}

void addQuad(TriangleMesh& mesh, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d, const glm::dvec3& centre,
             std::uint16_t material) {
  addFacingOut(mesh, a, b, c, centre, material);
  addFacingOut(mesh, a, c, d, centre, material);
}

// A house 10 x 6 x 8 m (x, y, z) under a gable roof along x, ridge 3 m above the eaves at z = 4.
// The roof's two pitches run `eaves` past the long walls and `gables` past the gable walls; each
// pitch is two triangles, so the walls' top edges lie inside the roof's faces.
constexpr double kLength = 10, kEaveHeight = 6, kDepth = 8, kRise = 3;
TriangleMesh gableHouse(double eaves, double gables, bool withGround = true) {
  TriangleMesh mesh;
  mesh.name = "house";
  mesh.materials = {{200, 190, 170, 255, 0}, {160, 60, 50, 255, 0}, {110, 110, 110, 255, 0}};
  const glm::dvec3 centre(kLength / 2, kEaveHeight / 2, kDepth / 2);
  const double slope = kRise / (kDepth / 2);
  for (double z : {0.0, kDepth})
    addQuad(mesh, {0, 0, z}, {kLength, 0, z}, {kLength, kEaveHeight, z}, {0, kEaveHeight, z}, centre, kWall);
  for (double x : {0.0, kLength}) {
    addQuad(mesh, {x, 0, 0}, {x, 0, kDepth}, {x, kEaveHeight, kDepth}, {x, kEaveHeight, 0}, centre, kWall);
    addFacingOut(mesh, {x, kEaveHeight, 0}, {x, kEaveHeight, kDepth}, {x, kEaveHeight + kRise, kDepth / 2}, centre,
                 kWall);
  }
  if (withGround) addQuad(mesh, {0, 0, 0}, {kLength, 0, 0}, {kLength, 0, kDepth}, {0, 0, kDepth}, centre, kGround);
  const double lowY = kEaveHeight - slope * eaves, ridgeY = kEaveHeight + kRise;
  for (double side : {-1.0, 1.0}) {
    const double eaveZ = side < 0 ? -eaves : kDepth + eaves;
    addQuad(mesh, {-gables, lowY, eaveZ}, {kLength + gables, lowY, eaveZ}, {kLength + gables, ridgeY, kDepth / 2},
            {-gables, ridgeY, kDepth / 2}, centre, kRoof);
  }
  return mesh;
}

TEST(Sheets, AnOverhangingGableRoofLeavesAClosedHouse) {
  const double eaves = 0.5, gables = 0.4;
  TriangleMesh mesh = gableHouse(eaves, gables);
  const MeshCheck check = checkAndRepair(mesh);
  ASSERT_FALSE(check.closedSurface);
  const std::optional<SheetSplit> split = detachSheets(mesh, 0.01);
  ASSERT_TRUE(split);
  // Each pitch: (length + 2 gables) x its slope's run to the ridge; over the walls, length x half
  // the depth. Slope lengths are runs times 5/4 (a 3-4-5 triangle).
  const double slopeFactor = 5.0 / 4.0;
  const double pitch = (kLength + 2 * gables) * (kDepth / 2 + eaves) * slopeFactor;
  const double overWalls = kLength * (kDepth / 2) * slopeFactor;
  EXPECT_NEAR(split->sheets.area(), 2 * (pitch - overWalls), 1e-6);
  const double walls = 2 * kLength * kEaveHeight + 2 * (kDepth * kEaveHeight + kDepth * kRise / 2);
  EXPECT_NEAR(split->body.area(), walls + kLength * kDepth + 2 * overWalls, 1e-6);
  EXPECT_TRUE(split->closed);
  EXPECT_TRUE(split->bodyCheck.closedSurface) << split->bodyCheck.summary();
  EXPECT_EQ(split->hiddenTriangles, 0u);
  for (std::uint16_t m : split->sheets.triangleMaterial) EXPECT_EQ(m, kRoof);
}

TEST(Sheets, AClosedHouseOrABoxWithoutAFloorHasNone) {
  TriangleMesh flush = gableHouse(0, 0);
  ASSERT_TRUE(checkAndRepair(flush).closedSurface);
  EXPECT_FALSE(detachSheets(flush, 0.01));
  // Without its ground the open edges are the walls' feet: peeling them takes everything.
  TriangleMesh bottomless = gableHouse(0.5, 0.4, false);
  checkAndRepair(bottomless);
  EXPECT_FALSE(detachSheets(bottomless, 0.01));
}

double quadArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  return 0.5 * glm::length(glm::cross(b - a, c - a)) + 0.5 * glm::length(glm::cross(c - a, d - a));
}

const std::string kZurichHouse = std::string(NUT_SOURCE_DIR) + "/tests/data/zurich_house.obj";

TriangleMesh zurichHouse() {
  auto obj = scene::readObj(kZurichHouse);
  EXPECT_TRUE(obj.ok()) << obj.error().message;
  return obj.ok() && obj->objects.size() == 1 ? obj->objects[0] : TriangleMesh{};
}

// The fixture's `v` lines in order, read here rather than through the OBJ reader, which keeps only
// the vertices faces use.
std::vector<glm::dvec3> fileVertices(const std::string& path) {
  std::ifstream in(path);
  std::vector<glm::dvec3> out;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string tag;
    glm::dvec3 p;
    if (fields >> tag && tag == "v" && fields >> p.x >> p.y >> p.z) out.push_back(p);
  }
  return out;
}

TEST(Sheets, TheZurichHousesOverhangsAreItsSheets) {
  TriangleMesh mesh = zurichHouse();
  ASSERT_FALSE(mesh.triangles.empty());
  const TriangleMesh source = mesh;
  checkAndRepair(mesh);
  const std::optional<SheetSplit> split = detachSheets(mesh, 0.01);
  ASSERT_TRUE(split);
  // The fixture's vertices (1-based in the file): the front eave 19-20 under the wall top 2-5, the
  // back eave 21-22 under the wall top 9-11.
  const std::vector<glm::dvec3> vertices = fileVertices(kZurichHouse);
  ASSERT_EQ(vertices.size(), 22u);
  const auto v = [&](int i) { return vertices[static_cast<std::size_t>(i - 1)]; };
  const double strips = quadArea(v(19), v(20), v(5), v(2)) + quadArea(v(21), v(22), v(11), v(9));
  EXPECT_NEAR(split->sheets.area(), strips, 0.02 * strips);
  // The roof under the dormer is inside the body and the dormer on it: dropped, not drawn.
  EXPECT_GT(split->hiddenTriangles, 0u);
  EXPECT_TRUE(split->closed);
  EXPECT_NEAR(split->body.area() + split->sheets.area(), mesh.area(), 0.02 * mesh.area());

  const Conversion open = testing::convertOrFail(source);
  const Conversion body = testing::convertOrFail(split->body);
  EXPECT_LT(testing::nutFraction(open), 0.8);
  EXPECT_GT(testing::nutFraction(body), 0.95);
}

std::uint64_t filesBytes(const Conversion& c) {
  return encodePng(c.image, nullptr, PngEffort::Small).size() +
         (c.complement.triangles.empty() ? 0 : measureMesh(c.complement).glbGzipBytes);
}

// For the most surface, the Zurich house is converted as its body; for the smallest files, as it
// is, without trying the body.
TEST(Sheets, TheMostSurfaceConvertsTheBody) {
  const TriangleMesh source = zurichHouse();
  ConvertOptions most;
  most.objective = ConvertOptions::Objective::MostSurface;
  const Conversion kept = testing::convertOrFail(source, most);
  const SheetReport& sheets = kept.report.sheets;
  ASSERT_TRUE(sheets.found);
  EXPECT_TRUE(sheets.applied);
  EXPECT_TRUE(sheets.bodyClosed);
  EXPECT_GT(sheets.nutShareWith, sheets.nutShareWithout + 0.15);
  EXPECT_NEAR(testing::nutFraction(kept), sheets.nutShareWith, 1e-9);
  EXPECT_EQ(filesBytes(kept), sheets.bytesWith);
  const Conversion smallest = testing::convertOrFail(source);
  EXPECT_FALSE(smallest.report.sheets.found);
  EXPECT_EQ(filesBytes(smallest), sheets.bytesWithout);
  EXPECT_NEAR(testing::nutFraction(smallest), sheets.nutShareWithout, 1e-9);
}

// The Zurich fixtures (tests/data) for the most surface, with and without plane cells: each takes
// at least the surface and at most the files' bytes the smallest files do not, and renders like
// its source (at least 99 % of the pixels of every view within 8/255; diff images in the test
// output folder, converter_sheets/, when not).
struct Fixture {
  const char* file;
  bool planeCells;
};

class ObjectiveOnZurich : public ::testing::TestWithParam<Fixture> {};

TEST_P(ObjectiveOnZurich, EachObjectiveWinsItsMeasureAndRendersLikeTheSource) {
  const std::string path = std::string(NUT_SOURCE_DIR) + "/tests/data/" + GetParam().file;
  auto obj = scene::readObj(path);
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  const TriangleMesh source = mergeMeshes(obj->objects, "source").value();
  ConvertOptions files, most;
  files.solid.planeCells = most.solid.planeCells = GetParam().planeCells;
  most.objective = ConvertOptions::Objective::MostSurface;
  const Conversion smallest = testing::convertOrFail(source, files);
  const Conversion surface = testing::convertOrFail(source, most);
  EXPECT_GE(testing::nutFraction(surface), testing::nutFraction(smallest) - 1e-3);
  EXPECT_LE(filesBytes(smallest), filesBytes(surface));
  const std::string stem = testing::outputDir("converter_sheets") + "/" + std::filesystem::path(path).stem().string() +
                           (GetParam().planeCells ? "_planes" : "");
  const testing::Fidelity f = testing::measureFidelity(source, {&surface}, stem, 99.0);
  std::printf("%s%s: NUT %.1f %% (smallest files %.1f %%), %ju B (%ju B); worst view %.2f %% within 8/255\n",
              GetParam().file, GetParam().planeCells ? " (plane cells)" : "", 100 * testing::nutFraction(surface),
              100 * testing::nutFraction(smallest), static_cast<std::uintmax_t>(filesBytes(surface)),
              static_cast<std::uintmax_t>(filesBytes(smallest)), f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << stem << ".view*.diff.png";
}

INSTANTIATE_TEST_SUITE_P(Fixtures, ObjectiveOnZurich,
                         ::testing::Values(Fixture{"zurich_house.obj", false}, Fixture{"zurich_house.obj", true},
                                           Fixture{"zurich_gable.obj", false}, Fixture{"zurich_gable.obj", true},
                                           Fixture{"zurich_dormers.obj", false}, Fixture{"zurich_dormers.obj", true},
                                           Fixture{"zurich_roof_given_up.obj", true}));

}  // namespace
}  // namespace nut::converter
