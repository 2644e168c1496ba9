// The city manifest (scene/city.hpp) and scene loading (scene/scene.hpp): the manifest round-trips
// and every rule of docs/CITY.md's schema is refused naming the field; a loaded scene places each
// building as the manifest says, reads a file placed twice once, and says which kind of failure
// stopped it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>

#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>
#include <scene/scene.hpp>

#include "test_files.hpp"

namespace nut::scene {
namespace {

namespace fs = std::filesystem;

fs::path outputDir() { return testing::testOutputDir("city"); }

std::string writeFile(const std::string& name, const std::string& text) {
  return testing::writeTestFile("city", name, text);
}

TEST(City, ManifestRoundTripsAndRejectsPathsOutside) {
  CityManifest city{"block", {{"a", "a.png", "a.complement.obj", {2678219.125, 395.5, -1243078.25}, 0},
                              {"b", "sub/b.png", "", {1, 2, 3}, 90, WorldBox{{1, 2, -7}, {11, 22, 3}}}}};
  const std::string path = writeFile("city.json", cityJson(city));
  auto back = readCityJson(path);
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_EQ(back->buildings.size(), 2u);
  EXPECT_EQ(back->buildings[0].positionM, city.buildings[0].positionM);
  EXPECT_EQ(back->buildings[1].hni, "sub/b.png");
  EXPECT_EQ(back->buildings[1].yawDeg, 90);
  EXPECT_TRUE(back->buildings[1].complement.empty());
  EXPECT_FALSE(back->buildings[0].boundsM);
  EXPECT_EQ(back->buildings[1].boundsM, city.buildings[1].boundsM);
  EXPECT_TRUE(back->buildings[0].complementLevels.empty());
  city.buildings[0].complementLevels = {{"a.complement.lod1.obj", 0.05}, {"a.complement.lod2.obj", 0.75}};
  auto levels = readCityJson(writeFile("levels.json", cityJson(city)));
  ASSERT_TRUE(levels.ok()) << levels.error().message;
  ASSERT_EQ(levels->buildings[0].complementLevels.size(), 2u);
  EXPECT_EQ(levels->buildings[0].complementLevels[1].path, "a.complement.lod2.obj");
  EXPECT_EQ(levels->buildings[0].complementLevels[1].errorM, 0.75);

  const std::string outside = writeFile("outside.json", R"({"format": "nut-city", "version": 1, "buildings": [
      {"name": "x", "hni": "../x.png", "position_m": [0, 0, 0]}]})");
  auto bad = readCityJson(outside);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("building 0 (x)"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(readCityJson(writeFile("notjson.json", "{")).ok());
  EXPECT_EQ(safeFileStem("UUID_2b58/..:x"), "UUID_2b58_.._x");
  EXPECT_EQ(safeFileStem(".hidden"), "_.hidden");
}

// Every rule of docs/CITY.md's schema, each broken alone in a one-building manifest, is refused
// naming the file, the building and the field.
TEST(City, EachBrokenFieldIsNamed) {
  const std::string good = R"("name": "a", "hni": "a.png", "position_m": [1, 2, 3])";
  const auto manifest = [](const std::string& version, const std::string& building) {
    return R"({"format": "nut-city", "version": )" + version + R"(, "buildings": [{)" + building + "}]}";
  };
  const std::pair<std::string, std::string> cases[] = {
      {R"({"format": "gltf", "version": 1, "buildings": []})", "not a nut city manifest"},
      {R"({"format": 1, "version": 1, "buildings": []})", "not a nut city manifest"},
      {manifest("2", good), "unsupported version (this reader knows version 1)"},
      {manifest("4294967297", good), "unsupported version"},  // 2^32 + 1, which an int cast makes 1
      {R"({"format": "nut-city", "version": 1, "name": ["a"], "buildings": []})", "\"name\" must be a string"},
      {R"({"format": "nut-city", "version": 1, "buildings": {}})", "\"buildings\" must be an array"},
      {R"({"format": "nut-city", "version": 1, "buildings": [7]})", "building 0: not an object"},
      {manifest("1", R"("hni": "a.png", "position_m": [1, 2, 3])"), "building 0: \"name\" must be a string"},
      {manifest("1", good + R"(, "complement": "/tmp/a.obj")"),
       "building 0 (a): \"complement\" must be a relative path inside the manifest's folder"},
      {manifest("1", R"("name": "a", "hni": "a.png", "position_m": [1, 2])"),
       "building 0 (a): \"position_m\" must be three numbers"},
      {manifest("1", R"("name": "a", "hni": "a.png", "position_m": [1, "2", 3])"),
       "building 0 (a): \"position_m\" must be three finite numbers"},
      {manifest("1", good + R"(, "yaw_deg": "north")"), "building 0 (a): \"yaw_deg\" must be a finite number"},
      {manifest("1", good + R"(, "bounds_m": [[0, 0, 0], [1, 1]])"),
       "building 0 (a): \"bounds_m\" must be two corners"},
      {manifest("1", good + R"(, "bounds_m": [[0, 5, 0], [1, 1, 1]])"), "min <= max"},
      {manifest("1", good + R"(, "complement_levels": [{"path": "a.lod1.obj", "error_m": 0.1}])"),
       "building 0 (a): \"complement_levels\" must be objects"},  // no complement
      {manifest("1", good + R"(, "complement": "a.obj", "complement_levels": [{"path": "../a.obj", "error_m": 1}])"),
       "\"complement_levels\" must be objects"},
      {manifest("1", good + R"(, "complement": "a.obj", "complement_levels": [{"path": "b.obj", "error_m": -1}])"),
       "\"complement_levels\" must be objects"},
      {manifest("1", good + R"(, "complement": "a.obj", "complement_levels": [{"path": "b.obj", "error_m": 2},
                                {"path": "c.obj", "error_m": 1}])"),
       "\"complement_levels\" must be objects"},
  };
  ASSERT_TRUE(readCityJson(writeFile("good-city.json", manifest("1", good))).ok());
  for (const auto& [text, message] : cases) {
    const std::string path = writeFile("broken-city.json", text);
    auto city = readCityJson(path);
    ASSERT_FALSE(city.ok()) << text;
    EXPECT_EQ(city.error().message.rfind(path + ": ", 0), 0u) << city.error().message;
    EXPECT_NE(city.error().message.find(message), std::string::npos) << city.error().message;
  }
}

// A street of the facade sample placed twice (once turned) with a complementary mesh: the file is
// read once, each placement is the manifest's, the bounds hold both, and the mesh's missing MTL
// is a warning naming it.
TEST(LoadScene, PlacesEachBuildingAsTheManifestSays) {
  const std::string facade = std::string(NUT_SOURCE_DIR) + "/samples/hni/facade.png";
  fs::create_directories(outputDir() / "street");
  fs::copy_file(facade, outputDir() / "street" / "facade.png", fs::copy_options::overwrite_existing);
  writeFile("street/rest.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CityManifest city{"street", {{"one", "facade.png", "rest.obj", {100, 0, 0}, 0}, {"two", "facade.png", "", {200, 0, 0}, 90}}};
  const std::string path = (outputDir() / "street" / "city.json").string();
  ASSERT_TRUE(writeCityJson(path, city).ok());

  auto scene = loadScene(path, {});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->files.size(), 1u);
  ASSERT_EQ(scene->hnis.size(), 2u);
  EXPECT_EQ(scene->hnis[0].image, &scene->files[0].image);
  EXPECT_EQ(scene->hnis[1].image, &scene->files[0].image);
  EXPECT_EQ(scene->hnis[0].originM, glm::dvec3(100, 0, 0));
  EXPECT_EQ(scene->hnis[1].originM, glm::dvec3(200, 0, 0));
  EXPECT_EQ(scene->hnis[1].worldFromRoot, yawRotation(90));
  ASSERT_EQ(scene->meshes.size(), 1u);
  ASSERT_EQ(scene->warnings.size(), 1u);
  EXPECT_NE(scene->warnings[0].find("missing.mtl"), std::string::npos) << scene->warnings[0];
  // A quarter turn takes the building's +z to +x, so the turned one reaches past x = 200; the
  // mesh's triangle lies at x in [0, 1].
  EXPECT_LE(scene->bounds.min.x, 0.0);
  EXPECT_GT(scene->bounds.max.x, 200.0);
}

// A complement with two coarser levels: the camera gets the coarsest level whose error spans under
// a pixel at the mesh's nearest point, worked out here from the camera's pixel angle.
TEST(LoadScene, AFarCameraGetsTheCoarsestLevelItCannotTellApart) {
  writeFile("levels/h.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 10 10 0\nf 1 2 3\nf 2 4 3\n");
  writeFile("levels/h.lod1.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n");
  writeFile("levels/h.lod2.obj", "v 0 0 0\nv 10 0 0\nv 5 10 0\nf 1 2 3\n");
  const std::string facade = std::string(NUT_SOURCE_DIR) + "/samples/hni/facade.png";
  fs::copy_file(facade, outputDir() / "levels" / "facade.png", fs::copy_options::overwrite_existing);
  CityBuilding building{"one", "facade.png", "h.obj", {100, 0, 0}, 0};
  building.complementLevels = {{"h.lod1.obj", 0.1}, {"h.lod2.obj", 1.0}};
  const std::string path = (outputDir() / "levels" / "city.json").string();
  ASSERT_TRUE(writeCityJson(path, CityManifest{"levels", {building}}).ok());
  auto scene = loadScene(path, {});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->coarser.size(), 1u);
  ASSERT_EQ(scene->coarser[0].size(), 2u);
  EXPECT_EQ(scene->coarser[0][1].mesh.triangles.size(), 1u);
  EXPECT_EQ(scene->meshPointers()[0], &scene->meshes[0]);

  Camera camera;  // looking down -z at the mesh in the plane z = 0, from distance d
  camera.width = 1000, camera.height = 1000, camera.fovYDeg = 40;
  const double pixelAngle = 2 * std::tan(20 * std::numbers::pi / 180) / 1000;
  const auto at = [&](double distance) {
    camera.eye = {5, 5, distance};
    camera.target = {5, 5, 0};
    return scene->meshPointers(camera)[0];
  };
  EXPECT_EQ(at(0.5 * 0.1 / pixelAngle), &scene->meshes[0]);         // 0.1 m spans 2 pixels
  EXPECT_EQ(at(2 * 0.1 / pixelAngle), &scene->coarser[0][0].mesh);  // half a pixel; 1 m spans 5
  EXPECT_EQ(at(2 * 1.0 / pixelAngle), &scene->coarser[0][1].mesh);  // 1 m spans half a pixel
}

TEST(LoadScene, SaysWhichKindOfFailureStoppedIt) {
  LoadFailure failure = LoadFailure::invalid;
  auto missing = loadScene((outputDir() / "nowhere.png").string(), {}, &failure);
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(failure, LoadFailure::unreadable) << missing.error().message;

  failure = LoadFailure::unreadable;
  const std::string empty = writeFile("empty.json", R"({"format": "nut-city", "version": 1, "buildings": []})");
  auto none = loadScene(empty, {}, &failure);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(failure, LoadFailure::invalid);
  EXPECT_EQ(none.error().message, empty + ": the manifest lists no buildings");

  failure = LoadFailure::unreadable;
  const std::string broken = writeFile("broken-building.json", R"({"format": "nut-city", "version": 1, "buildings": [
      {"name": "x", "hni": "not-an-hni.png", "position_m": [0, 0, 0]}]})");
  writeFile("not-an-hni.png", "these bytes are no PNG");
  auto bad = loadScene(broken, {}, &failure);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(failure, LoadFailure::unreadable);
  EXPECT_NE(bad.error().message.find("not-an-hni.png"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace nut::scene
