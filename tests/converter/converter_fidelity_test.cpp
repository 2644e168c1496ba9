// Fidelity of the mesh converter: each sample OBJ (and each external mesh in ../shared/data when
// present) is converted, its HNI ray-cast on the CPU together with its complementary mesh (Embree),
// and compared with the Embree render of the source mesh from the default camera and three more
// views (converter_support.hpp). Tolerance: a pixel matches when every channel is within 8/255;
// the axis-aligned samples must match on at least 99 % of the pixels of every view, and so must the
// car park turned, rounded, opened and turned over as other tools hand buildings over. The diff
// images of a view below its bar are written to the test output folder (converter_fidelity/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <nut/hni.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string path;       // relative to the source tree
  double minWithinPct;    // every view
  bool perObject;         // one HNI per o/g object (as `nut convert IN.obj -o FOLDER`)
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.path; }

std::string stemOf(const std::string& path) { return fs::path(path).stem().string(); }

// Converts the file as `nut convert` would and measures the fidelity.
void checkFidelity(const std::string& path, double minWithinPct, bool perObject) {
  auto obj = scene::readObj(path);
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  const TriangleMesh source = mergeMeshes(obj->objects, stemOf(path)).value();
  std::vector<Conversion> conversions;
  if (perObject) {
    for (const TriangleMesh& object : obj->objects) {
      auto c = convertMesh(object);
      ASSERT_TRUE(c.ok()) << c.error().message;
      conversions.push_back(std::move(*c));
    }
  } else {
    auto c = convertMesh(source);
    ASSERT_TRUE(c.ok()) << c.error().message;
    conversions.push_back(std::move(*c));
  }
  std::vector<const Conversion*> pointers;
  long long pngBytes = 0;
  for (Conversion& c : conversions) {
    pointers.push_back(&c);
    const std::string png = testing::outputDir("converter_fidelity") + "/" + scene::safeFileStem(c.report.name) + ".png";
    ASSERT_TRUE(writeConversion(c, png, "").ok());
    pngBytes += static_cast<long long>(c.report.pngBytes);
  }
  const std::string stem = testing::outputDir("converter_fidelity") + "/" + stemOf(path) + (perObject ? "_per_object" : "");
  const testing::Fidelity f = testing::measureFidelity(source, pointers, stem, minWithinPct);
  std::printf("%s: %zu triangles, %zu HNIs, %lld bytes PNG; within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n",
              stemOf(path).c_str(), source.triangles.size(), conversions.size(), pngBytes, f.withinPct[0], f.withinPct[1],
              f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, minWithinPct) << path << ": see " << stem << ".view*.diff.png";
}

class SampleFidelity : public ::testing::TestWithParam<Case> {};

TEST_P(SampleFidelity, RendersLikeTheSourceMesh) {
  checkFidelity(std::string(NUT_SOURCE_DIR) + "/" + GetParam().path, GetParam().minWithinPct, GetParam().perObject);
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleFidelity,
                         ::testing::Values(Case{"samples/obj/highrise.obj", 99.0, false},
                                           Case{"samples/obj/street.obj", 99.0, true},
                                           Case{"samples/obj/street.obj", 99.0, false},
                                           Case{"samples/obj/residential.obj", 99.0, false},
                                           Case{"samples/obj/carpark.obj", 99.0, false},
                                           Case{"samples/obj/house.obj", 99.0, false}));

// Zurich LoD2 houses kept in the repository (tests/data, CC0). zurich_house.obj: walls 1-2
// degrees off square, so after the yaw alignment one is still 0.1 degrees off and spans two
// boundaries of its axis; the solid's face at the other boundary once took the ground plate's
// colour (93.09 % in the worst view). zurich_gable.obj: a roof sheet overhanging its gables; lines
// of cells crossing both pitches once counted the air under the overhang as inside, and the gable
// showed that air's roof-coloured boxes (98.46 %); then the triangular ends of the wedges under
// the pitches, each too small a conflict on its own, showed the roof's colour (99.50 %).
// zurich_dormers.obj: an open mesh whose winding number in front of its steep pitch is about
// -0.56 (it sees the outside of the walls, roof and dormers, and not enough of what would cancel
// them); taken as |w| >= 1/2, that air became a roof-coloured band across the dormers (99.55 %).
// zurich_roof_given_up.obj: a roof none of whose 31 planes comes out as wedges, left to the mesh.
INSTANTIATE_TEST_SUITE_P(Fixtures, SampleFidelity,
                         ::testing::Values(Case{"tests/data/zurich_house.obj", 99.0, false},
                                           Case{"tests/data/zurich_gable.obj", 99.8, false},
                                           Case{"tests/data/zurich_dormers.obj", 99.8, false},
                                           Case{"tests/data/zurich_roof_given_up.obj", 99.5, false}));

// The car park sample as other tools hand buildings over: turned about the vertical and written
// with a few decimals (its T-junctions then lie a few micrometres off the edges they meet), with a
// triangle of its outside missing (an open mesh), with a floor's quad or every face turned over.
// Each converts as well as the sample itself, and the repair turns exactly the faces that were
// turned over.
enum class TurnedOver { Nothing, LargestQuad, Everything };

struct Handling {
  const char* name;
  double yawDeg;
  int decimals;  // positions rounded to this many decimals of a metre
  bool missingTriangle;
  TurnedOver turned;
  bool unwelded = false;  // every triangle with its own copies of its corners, each moved by up to 2 µm
};

// The largest triangle and the one across its longest edge.
std::vector<std::size_t> largestQuad(const TriangleMesh& mesh) {
  const auto corner = [&](std::size_t t, int k) { return mesh.positions[mesh.triangles[t][static_cast<std::size_t>(k)]]; };
  const auto area = [&](std::size_t t) { return glm::length(glm::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0))); };
  std::size_t largest = 0;
  for (std::size_t t = 1; t < mesh.triangles.size(); ++t)
    if (area(t) > area(largest)) largest = t;
  int edge = 0;
  for (int k = 1; k < 3; ++k)
    if (glm::length(corner(largest, (k + 1) % 3) - corner(largest, k)) > glm::length(corner(largest, (edge + 1) % 3) - corner(largest, edge)))
      edge = k;
  const glm::dvec3 a = corner(largest, edge), b = corner(largest, (edge + 1) % 3);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (t != largest && corner(t, k) == b && corner(t, (k + 1) % 3) == a) return {largest, t};
  return {largest};
}

void PrintTo(const Handling& h, std::ostream* os) { *os << h.name; }

class HandedOver : public ::testing::TestWithParam<Handling> {};

TEST_P(HandedOver, ConvertsAsWellAsTheSample) {
  const Handling& h = GetParam();
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/samples/obj/carpark.obj");
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  TriangleMesh mesh = mergeMeshes(obj->objects, h.name).value();
  const double turn = h.yawDeg * std::numbers::pi / 180.0, scale = std::pow(10.0, h.decimals);
  for (glm::dvec3& p : mesh.positions) {
    p = {p.x * std::cos(turn) + p.z * std::sin(turn), p.y, -p.x * std::sin(turn) + p.z * std::cos(turn)};
    p = glm::round(p * scale) / scale;
  }
  if (h.unwelded) {
    std::mt19937 random(1);
    std::uniform_real_distribution<double> jitter(-2e-6, 2e-6);
    std::vector<glm::dvec3> copies;
    for (auto& t : mesh.triangles)
      for (std::uint32_t& corner : t) {
        copies.push_back(mesh.positions[corner] + glm::dvec3(jitter(random), jitter(random), jitter(random)));
        corner = static_cast<std::uint32_t>(copies.size() - 1);
      }
    mesh.positions = std::move(copies);
  }
  if (h.missingTriangle) {  // the outside of a parapet stripe
    mesh.triangles.erase(mesh.triangles.begin());
    mesh.triangleMaterial.erase(mesh.triangleMaterial.begin());
  }
  std::vector<std::size_t> turned;
  if (h.turned == TurnedOver::LargestQuad) turned = largestQuad(mesh);
  if (h.turned == TurnedOver::Everything)
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) turned.push_back(t);
  for (std::size_t t : turned) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);

  auto c = convertMesh(mesh);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->report.check.flippedTriangles, turned.size());
  EXPECT_EQ(c->report.check.closedSurface, !h.missingTriangle);
  const std::string stem = testing::outputDir("converter_fidelity") + "/carpark_" + h.name;
  const testing::Fidelity f = testing::measureFidelity(mesh, {&*c}, stem, 99.0);
  std::printf("carpark, %s: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %%\n", h.name, f.withinPct[0], f.withinPct[1],
              f.withinPct[2], f.withinPct[3]);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << stem << ".view*.diff.png";
}

INSTANTIATE_TEST_SUITE_P(CarPark, HandedOver,
                         ::testing::Values(Handling{"turned_37deg_micrometres", 37, 6, false, TurnedOver::Nothing},
                                           Handling{"turned_37deg_millimetres", 37, 3, false, TurnedOver::Nothing},
                                           Handling{"missing_a_triangle", 0, 6, true, TurnedOver::Nothing},
                                           Handling{"turned_37deg_missing_a_triangle", 37, 6, true, TurnedOver::Nothing},
                                           Handling{"a_floor_turned_over", 0, 6, false, TurnedOver::LargestQuad},
                                           Handling{"turned_over", 0, 6, false, TurnedOver::Everything},
                                           Handling{"unwelded_2um_apart", 0, 6, false, TurnedOver::Nothing, true}));

// The external meshes are real models with open shells, tilted faces and non-axis-aligned parts:
// their figures are printed (docs/CONVERTER.md) and held to a looser bar, except Ingolstadt's:
// its facade turned 0.5 degrees is drawn in steps (converter_drift_test), and the bar holds it
// at the samples' 99 %. (Zurich's 49 buildings spread over 10 km, so each view
// is mostly background and its figure says little.)
class ExternalFidelity : public ::testing::TestWithParam<Case> {};

TEST_P(ExternalFidelity, RendersLikeTheSourceMesh) {
  const std::string path = std::string(NUT_SOURCE_DIR) + "/../shared/data/" + GetParam().path;
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  checkFidelity(path, GetParam().minWithinPct, GetParam().perObject);
}

INSTANTIATE_TEST_SUITE_P(SharedData, ExternalFidelity,
                         ::testing::Values(Case{"kenney_building_small_a.obj", 97.0, false},
                                           Case{"kenney_building_small_b.obj", 97.0, false},
                                           Case{"kenney_building_small_c.obj", 97.0, false},
                                           Case{"kenney_building_small_d.obj", 97.0, false},
                                           Case{"ingolstadt_lod3_4018210_aligned.obj", 99.0, false},
                                           Case{"zurich_subset_lod2.obj", 99.0, true}));

// Every material grey, opacity kept: what a conversion shows of shape alone.
void greyMaterials(std::vector<Material>& materials) {
  for (Material& m : materials) m.r = m.g = m.b = 200;
}

// What keeps the Kenney buildings from 99 % is colour, not shape: their colours come from a
// texture atlas sampled once per triangle, so the two triangles of a quad may differ and a flat
// wall shows a diagonal seam that a cell's one material cannot. The same conversion is measured
// again with every material grey on both sides (the HNI's, its complementary mesh's and the
// source's): what still differs is shape (a face elsewhere or at another angle), the rest of the
// difference is colour. Shape must stay under 1 % of the pixels in every view.
TEST(KenneyFidelity, WhatRemainsIsColourNotShape) {
  for (const char* name :
       {"kenney_building_small_a", "kenney_building_small_b", "kenney_building_small_c", "kenney_building_small_d"}) {
    const std::string path = std::string(NUT_SOURCE_DIR) + "/../shared/data/" + name + ".obj";
    if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
    auto obj = scene::readObj(path);
    ASSERT_TRUE(obj.ok()) << obj.error().message;
    TriangleMesh source = mergeMeshes(obj->objects, name).value();
    auto coloured = convertMesh(source);
    ASSERT_TRUE(coloured.ok()) << coloured.error().message;
    const std::string stem = testing::outputDir("converter_fidelity") + "/" + name;
    const testing::Fidelity whole = testing::measureFidelity(source, {&*coloured}, stem, 0.0);

    Conversion grey = *coloured;
    greyMaterials(grey.hierarchy.materials);
    auto image = compile(grey.hierarchy);
    ASSERT_TRUE(image.ok()) << image.error().message;
    grey.image = std::move(*image);
    greyMaterials(grey.complement.materials);
    greyMaterials(source.materials);
    const testing::Fidelity shape = testing::measureFidelity(source, {&grey}, stem + "_grey", 99.0);
    std::printf("%s: pixels beyond 8/255 per view: %.2f %.2f %.2f %.2f %%, of them shape %.2f %.2f %.2f %.2f %%\n",
                name, 100 - whole.withinPct[0], 100 - whole.withinPct[1], 100 - whole.withinPct[2],
                100 - whole.withinPct[3], 100 - shape.withinPct[0], 100 - shape.withinPct[1], 100 - shape.withinPct[2],
                100 - shape.withinPct[3]);
    EXPECT_LT(100 - shape.worstWithinPct, 1.0) << name << ": see " << stem << "_grey.view*.diff.png";
  }
}

// Zurich's district views are mostly background, so each building is also measured on its own,
// from the views fitted to it, as `nut convert zurich_subset_lod2.obj -o FOLDER` writes it: every
// building converted with `options` must have its worst view at least 97 % within 8/255. Prints
// the NUT share and the spread of the worst views.
void expectEachZurichBuildingRendersLikeItsSource(const ConvertOptions& options, const std::string& label) {
  const std::string path = std::string(NUT_SOURCE_DIR) + "/../shared/data/zurich_subset_lod2.obj";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  auto obj = scene::readObj(path);
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  constexpr double kBar = 97.0;
  std::vector<double> worst;
  double area = 0, nut = 0;
  for (const TriangleMesh& building : obj->objects) {
    auto c = convertMesh(building, options);
    ASSERT_TRUE(c.ok()) << c.error().message;
    area += c->report.solid.areaM2;
    nut += c->report.solid.nutAreaM2;
    const std::string stem =
        testing::outputDir("converter_fidelity") + "/" + label + "_" + scene::safeFileStem(c->report.name);
    const testing::Fidelity f = testing::measureFidelity(building, {&*c}, stem, kBar);
    EXPECT_GE(f.worstWithinPct, kBar) << building.name << ": see " << stem << ".view*.diff.png";
    worst.push_back(f.worstWithinPct);
  }
  std::sort(worst.begin(), worst.end());
  std::printf(
      "zurich_subset_lod2 (%s): %.1f %% NUT; each of %zu buildings on its own: worst view within 8/255: lowest "
      "%.2f %%, 10th percentile %.2f %%, median %.2f %%\n",
      label.c_str(), 100 * nut / area, worst.size(), worst.front(), worst[worst.size() / 10], worst[worst.size() / 2]);
}

TEST(ExternalFidelityEachBuilding, Zurich) { expectEachZurichBuildingRendersLikeItsSource({}, "zurich"); }

// The same for the most surface with plane cells (`nut convert zurich_subset_lod2.obj -o FOLDER
// --plane-cells --prefer surface`): bodies under their roofs' sheets become cells (sheets.hpp).
// UUID_c383c4f4's walls, 0.85 degrees off the axes, stay mesh in front of boxes reaching from the
// ground to the eaves; those boxes must take the walls' colour, not the ground plate's under them.
TEST(ExternalFidelityEachBuilding, ZurichForTheMostSurface) {
  ConvertOptions most;
  most.solid.planeCells = true;
  most.objective = ConvertOptions::Objective::MostSurface;
  expectEachZurichBuildingRendersLikeItsSource(most, "zurich_most");
}

// A generated LoD2 district (tests/data/lod2_district_seed1.obj, from `python3
// scripts/lod2-district.py --seed 1 --buildings 30`): footprints with walls at odd angles, roofs
// at any pitch and direction. Each building is converted on its own with plane cells, for the
// smallest files and for the most surface, and must render like its source from the views fitted
// to it both ways; plane cells take most of what the wedges leave to the complementary mesh, and
// for the most surface all but 1 %: where a gable's ridge ends in a wall at an odd angle, three
// planes meet in a cell and only the faces' parts in those cells stay mesh (the complementary
// mesh's own area, summed from its triangles, is under 1 % of the surface).
TEST(GeneratedDistrict, PlaneCellsTakeMostOfTheSurfaceAndRenderLikeTheSource) {
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/tests/data/lod2_district_seed1.obj");
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  ConvertOptions planes;
  planes.solid.planeCells = true;
  ConvertOptions most = planes;
  most.objective = ConvertOptions::Objective::MostSurface;
  double area = 0, nutOff = 0, nutOn = 0, nutMost = 0, complementMost = 0;
  std::size_t trianglesOff = 0, trianglesOn = 0, trianglesMost = 0;
  double lowest = 100;
  for (const TriangleMesh& building : obj->objects) {
    auto off = convertMesh(building);
    auto on = convertMesh(building, planes);
    auto surface = convertMesh(building, most);
    ASSERT_TRUE(off.ok() && on.ok() && surface.ok()) << building.name;
    area += on->report.solid.areaM2;
    nutOff += off->report.solid.nutAreaM2;
    nutOn += on->report.solid.nutAreaM2;
    nutMost += surface->report.solid.nutAreaM2;
    complementMost += surface->complement.area();
    trianglesOff += off->complement.triangles.size();
    trianglesOn += on->complement.triangles.size();
    trianglesMost += surface->complement.triangles.size();
    for (const auto& [label, c] : {std::pair{"", &*on}, std::pair{"_most", &*surface}}) {
      const std::string stem = testing::outputDir("converter_fidelity") + "/district_" + building.name + label;
      const testing::Fidelity f = testing::measureFidelity(building, {c}, stem, 99.0);
      EXPECT_GE(f.worstWithinPct, 99.0) << building.name << label << ": see " << stem << ".view*.diff.png";
      lowest = std::min(lowest, f.worstWithinPct);
    }
  }
  std::printf(
      "generated district, %zu buildings: NUT surface %.1f %% -> %.1f %% with plane cells (%.1f %% for the "
      "most surface), complementary triangles %zu -> %zu (%zu), the most surface's complementary mesh "
      "%.2f %% of the surface; worst view of any building within 8/255: %.2f %%\n",
      obj->objects.size(), 100 * nutOff / area, 100 * nutOn / area, 100 * nutMost / area, trianglesOff, trianglesOn,
      trianglesMost, 100 * complementMost / area, lowest);
  EXPECT_GE(nutOn, 0.90 * area);
  EXPECT_LE(trianglesOn, trianglesOff / 3);
  EXPECT_GE(nutMost, 0.99 * area);
  EXPECT_LT(complementMost, 0.01 * area);
}

}  // namespace
}  // namespace nut::converter
