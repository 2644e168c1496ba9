// Yaw alignment of the mesh converter (converter/align.hpp): samples turned about +y in the test
// are found turned by the angle they were given (to the format's yaw step), convert to about as
// much NUT surface as the upright sample, and render like the turned source mesh (at least 99 % of
// the pixels of every view within 8/255; diff images in the test output folder, converter_align/,
// when not). An axis-aligned building, or one turned by less than the angle tolerance, is converted
// in the world frame. With ../shared/data present, Zurich's NUT surface fraction with and without alignment
// is printed, and its largest turned building is rendered against its source.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <sstream>

#include <converter/align.hpp>
#include <converter/convert.hpp>
#include <nut/format.hpp>
#include <nut/png_io.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

namespace fs = std::filesystem;

constexpr double kYawStepDeg = 360.0 / format::kYawSteps;

TriangleMesh sample(const std::string& name) {
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/samples/obj/" + name + ".obj");
  EXPECT_TRUE(obj.ok()) << obj.error().message;
  return obj.ok() ? mergeMeshes(obj->objects, name).value() : TriangleMesh{};
}

// The mesh turned by `degrees` about +y through `pivot`, as the format's yaw turns (x towards -z).
TriangleMesh turned(TriangleMesh mesh, double degrees, const glm::dvec3& pivot) {
  const double c = std::cos(degrees * std::numbers::pi / 180), s = std::sin(degrees * std::numbers::pi / 180);
  for (glm::dvec3& p : mesh.positions) {
    const glm::dvec3 d = p - pivot;
    p = pivot + glm::dvec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
  }
  return mesh;
}

double nutFraction(const ConvertReport& r) { return r.solid.areaM2 > 0 ? r.solid.nutAreaM2 / r.solid.areaM2 : 0; }

Conversion convert(const TriangleMesh& mesh, bool align) {
  ConvertOptions options;
  options.alignYaw = align;
  options.turnedWings = align;  // without alignment, a building turned whole would be found a wing
  auto c = convertMesh(mesh, options);
  EXPECT_TRUE(c.ok()) << c.error().message;
  return c.ok() ? std::move(*c) : Conversion{};
}

struct Case {
  std::string sample;
  double degrees;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.sample << " turned by " << c.degrees; }

class TurnedSample : public ::testing::TestWithParam<Case> {};

TEST_P(TurnedSample, IsAlignedAndRendersLikeTheSource) {
  const Case& param = GetParam();
  const TriangleMesh upright = sample(param.sample);
  ASSERT_FALSE(upright.triangles.empty());
  const TriangleMesh source = turned(upright, param.degrees, {3.0, 0.0, -2.0});
  const Conversion before = convert(source, false);
  Conversion after = convert(source, true);
  const Conversion reference = convert(upright, true);

  // (a) The orientation found is the one given, to the yaw step, and it is applied: the root is one
  // cell redirecting with that yaw.
  EXPECT_TRUE(after.report.yawApplied);
  EXPECT_NEAR(after.report.yawDeg, param.degrees, kYawStepDeg);
  const Block& root = after.hierarchy.blocks[after.hierarchy.root];
  ASSERT_EQ(root.cells.size(), 1u);
  ASSERT_EQ(root.redirections.size(), 1u);
  EXPECT_EQ(yawDegrees(root.redirections[0].rotation.yaw), after.report.yawDeg);
  EXPECT_EQ(after.hierarchy.blocks.size(), reference.hierarchy.blocks.size() + 1);

  // (b) About as much of the surface is NUT as on the upright sample.
  std::printf("%s turned by %.1f deg: yaw found %.4f deg; NUT surface %.2f %% without alignment, %.2f %% with "
              "(upright %.2f %%); HNI %lld bytes raw, complement %zu triangles\n",
              param.sample.c_str(), param.degrees, after.report.yawDeg, 100 * nutFraction(before.report),
              100 * nutFraction(after.report), 100 * nutFraction(reference.report), after.report.hni.bytesRaw,
              after.report.complementTriangles);
  EXPECT_NEAR(nutFraction(after.report), nutFraction(reference.report), 0.01);
  EXPECT_GT(nutFraction(after.report), nutFraction(before.report) + 0.1);

  // The complementary mesh is back in the world frame: inside the turned source's box.
  if (!after.complement.triangles.empty()) {
    const WorldBox box = source.bounds(), rest = after.complement.bounds();
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(rest.min[a], box.min[a] - 0.01) << "axis " << a;
      EXPECT_LE(rest.max[a], box.max[a] + 0.01) << "axis " << a;
    }
  }

  // (c) Fidelity against the turned source, from the same cameras. View 0 is written either way,
  // to look at.
  std::ostringstream name;
  name << param.sample << "_yaw" << param.degrees;
  const std::string stem = testing::outputDir("converter_align") + "/" + name.str();
  ASSERT_TRUE(writeConversion(after, stem + ".hni.png", "").ok());
  auto file = readPng(stem + ".hni.png");
  ASSERT_TRUE(file.ok()) << file.error().message;
  EXPECT_EQ(file->text.originM, after.originM);  // the PNG's origin is the new root's
  const testing::Fidelity f = testing::measureFidelity(source, {&after}, stem, 99.0);
  std::printf("%s turned by %.1f deg: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n",
              param.sample.c_str(), param.degrees, f.withinPct[0], f.withinPct[1], f.withinPct[2], f.withinPct[3],
              f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << stem << ".view*.diff.png";
  const Camera view = testing::fidelityViews(source.bounds(), 640, 360)[0];
  EXPECT_TRUE(writePng(stem + ".nut.png", testing::renderConversions({&after}, view)).ok());
  EXPECT_TRUE(writePng(stem + ".mesh.png", testing::renderMesh(source, view)).ok());
}

INSTANTIATE_TEST_SUITE_P(Samples, TurnedSample,
                         ::testing::Values(Case{"carpark", 30.0}, Case{"carpark", 17.3}, Case{"house", -30.0}));

TEST(YawAlignment, LeavesAnAxisAlignedBuildingAsItIs) {
  const TriangleMesh upright = sample("carpark");
  const Conversion aligned = convert(upright, true), plain = convert(upright, false);
  EXPECT_FALSE(aligned.report.yawApplied);
  EXPECT_EQ(aligned.report.yawDeg, 0.0);
  EXPECT_EQ(aligned.hierarchy, plain.hierarchy);  // no wrapping block
  EXPECT_EQ(aligned.originM, plain.originM);
}

TEST(YawAlignment, LeavesATurnWithinTheAngleToleranceAlone) {
  const Conversion c = convert(turned(sample("carpark"), 0.5, {0.0, 0.0, 0.0}), true);
  EXPECT_FALSE(c.report.yawApplied);
  EXPECT_NEAR(c.report.yawDeg, 0.5, kYawStepDeg);
}

TEST(YawAlignment, IsNotAppliedWithManualBlocks) {
  ConvertOptions options;
  options.blocks.manual.push_back({{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}});
  auto c = convertMesh(turned(sample("carpark"), 30.0, {0.0, 0.0, 0.0}), options);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_FALSE(c->report.yawApplied);
  EXPECT_FALSE(c->report.warnings.empty());
}

// Zurich's LoD2 buildings have real orientations: the share of their surface that becomes NUT,
// one HNI per building as `nut convert zurich_subset_lod2.obj -o FOLDER`.
TEST(YawAlignment, Zurich) {
  const std::string path = std::string(NUT_SOURCE_DIR) + "/../shared/data/zurich_subset_lod2.obj";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  auto obj = scene::readObj(path);
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  double area = 0, nutBefore = 0, nutAfter = 0;
  int turnedBuildings = 0;
  std::optional<Conversion> largest;  // the largest turned building, to render up close
  const TriangleMesh* largestSource = nullptr;
  for (const TriangleMesh& building : obj->objects) {
    Conversion before = convert(building, false), after = convert(building, true);
    area += after.report.solid.areaM2;
    nutBefore += before.report.solid.nutAreaM2;
    nutAfter += after.report.solid.nutAreaM2;
    turnedBuildings += after.report.yawApplied ? 1 : 0;
    if (after.report.yawApplied && (!largest || after.report.solid.areaM2 > largest->report.solid.areaM2)) {
      largest = std::move(after);
      largestSource = &building;
    }
  }
  std::printf("zurich_subset_lod2: %zu buildings, %d turned; NUT surface %.2f %% without alignment, %.2f %% with\n",
              obj->objects.size(), turnedBuildings, 100 * nutBefore / area, 100 * nutAfter / area);
  EXPECT_GT(nutAfter, nutBefore);
  // The whole district's views are mostly background: the largest turned building is rendered on
  // its own, held to the external meshes' bar (converter_fidelity_test).
  ASSERT_TRUE(largest.has_value());
  const std::string stem = testing::outputDir("converter_align") + "/zurich_largest";
  const testing::Fidelity f = testing::measureFidelity(*largestSource, {&*largest}, stem, 97.0);
  std::printf("zurich_subset_lod2, largest turned building (yaw %.2f deg, %.0f m2, NUT %.1f %%): within 8/255: %.2f %% "
              "%.2f %% %.2f %% %.2f %% (worst %.2f %%)\n",
              largest->report.yawDeg, largest->report.solid.areaM2, 100 * nutFraction(largest->report), f.withinPct[0],
              f.withinPct[1], f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 97.0) << "see " << stem << ".view*.diff.png";
  const Camera view = testing::fidelityViews(largestSource->bounds(), 640, 360)[0];
  EXPECT_TRUE(writePng(stem + ".nut.png", testing::renderConversions({&*largest}, view)).ok());
  EXPECT_TRUE(writePng(stem + ".mesh.png", testing::renderMesh(*largestSource, view)).ok());
}

}  // namespace
}  // namespace nut::converter
