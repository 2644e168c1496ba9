// `nut convert` as a user runs it: outputs (HNI with the world origin, complementary mesh, report
// JSON), one HNI per object and city.json with -o FOLDER, the progress bar's absence with --quiet,
// manual blocks, output names (a .png in any case is one HNI; another extension is refused), and
// the exit codes: 1 for invalid input, 2 for usage errors and unreadable input; and the
// commands users look at the result with: `nut render` (its default lookup, an HNI with its
// complementary mesh, a city manifest), `nut info --blocks --bytes`.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>
#include <scene/mesh_file.hpp>
#include <scene/scene.hpp>

#include "cli_support.hpp"
#include "converter/converter_support.hpp"

namespace nut::converter {
namespace {

namespace fs = std::filesystem;

using ::nut::testing::CliRun;

CliRun nut(const std::string& args) { return ::nut::testing::runNut(args, "converter_cli"); }

std::string out(const std::string& name) { return (fs::path(testing::outputDir("converter_cli")) / name).string(); }
std::string sample(const std::string& name) { return std::string(NUT_SOURCE_DIR) + "/samples/obj/" + name; }

TEST(ConvertCli, WritesTheHniComplementAndReport) {
  fs::remove(out("carpark.png"));
  const CliRun r = nut("convert " + sample("carpark.obj") + " -o " + out("carpark.png") + " --complement " + out("carpark-rest.obj") +
                    " --report " + out("carpark.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("surface"), std::string::npos) << r.stderrText;

  auto png = readPng(out("carpark.png"));
  ASSERT_TRUE(png.ok()) << png.error().message;
  EXPECT_TRUE(validate(png->image).ok());
  EXPECT_EQ(png->text.generator, "nut convert");
  EXPECT_NEAR(png->text.originM.y, 0.0, 1e-9);
  EXPECT_TRUE(fs::exists(out("carpark-rest.obj")));
  EXPECT_TRUE(fs::exists(out("carpark-rest.mtl")));

  std::ifstream in(out("carpark.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const char* key : {"phases_seconds", "input", "grid", "surface", "blocks", "hni"}) EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["hni"]["bytes_png"].get<long long>(), static_cast<long long>(fs::file_size(out("carpark.png"))));
  EXPECT_GT(report["surface"]["nut_fraction"].get<double>(), 0.9);
  EXPECT_GT(report["phases_seconds"]["solid"].get<double>(), 0.0);
}

// The complementary mesh as binary glTF: by its name with --complement, by default in a folder.
// Read back (the scene's GLB reader), each holds the triangles of its OBJ, at most one 16-bit
// quantization step of the mesh's bounds away.
TEST(ConvertCli, ComplementsAreBinaryGltfByNameAndInFolders) {
  CliRun r = nut("convert " + sample("carpark.obj") + " -o " + out("carpark-g.png") + " --complement " +
                 out("carpark-g-rest.glb") + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("convert " + sample("carpark.obj") + " -o " + out("carpark-o.png") + " --complement " +
          out("carpark-o-rest.obj") + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  std::vector<std::string> warnings;
  auto glb = scene::readMeshFile(out("carpark-g-rest.glb"), warnings);
  auto obj = scene::readMeshFile(out("carpark-o-rest.obj"), warnings);
  ASSERT_TRUE(glb.ok()) << glb.error().message;
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  ASSERT_EQ(glb->triangles.size(), obj->triangles.size());
  const WorldBox fromGlb = glb->bounds(), fromObj = obj->bounds();
  const glm::dvec3 extent = fromObj.max - fromObj.min;
  const double step = std::max({extent.x, extent.y, extent.z}) / 65535.0;
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(fromGlb.min[axis], fromObj.min[axis], step);
    EXPECT_NEAR(fromGlb.max[axis], fromObj.max[axis], step);
  }
  EXPECT_NEAR(glb->area(), obj->area(), 1e-3 * obj->area());

  for (const char* format : {"", "obj"}) {
    const std::string folder = out(std::string("street-complements-") + (*format ? format : "default"));
    fs::remove_all(folder);
    r = nut("convert " + sample("street.obj") + " -o " + folder + "/ --quiet --png-effort small" +
            (*format ? std::string(" --complement-format ") + format : std::string()));
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    auto city = scene::readCityJson(folder + "/city.json");
    ASSERT_TRUE(city.ok()) << city.error().message;
    std::size_t complements = 0;
    for (const scene::CityBuilding& b : city->buildings) {
      if (b.complement.empty()) continue;
      ++complements;
      EXPECT_EQ(fs::path(b.complement).extension(), *format ? ".obj" : ".glb") << b.complement;
      auto mesh = scene::readMeshFile(folder + "/" + b.complement, warnings);
      EXPECT_TRUE(mesh.ok()) << b.complement;
    }
    EXPECT_GT(complements, 0u);
    auto scene = scene::loadScene(folder + "/city.json", {});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->meshes.size(), complements);
  }
}

TEST(ConvertCli, QuietPrintsNothing) {
  const CliRun r = nut("convert " + sample("house.obj") + " -o " + out("house.png") + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(r.stderrText, "");
}

TEST(ConvertCli, AFolderGetsOneHniPerObjectAndACityManifest) {
  fs::remove_all(out("street"));
  const CliRun r = nut("convert " + sample("street.obj") + " -o " + out("street") + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto city = scene::readCityJson(out("street/city.json"));
  ASSERT_TRUE(city.ok()) << city.error().message;
  ASSERT_EQ(city->buildings.size(), 4u);
  for (const scene::CityBuilding& b : city->buildings) {
    auto png = readPng(out("street/" + b.hni));
    ASSERT_TRUE(png.ok()) << b.hni;
    EXPECT_EQ(png->text.originM, b.positionM) << b.name;  // the manifest places each HNI at its own origin
  }
}

// Buildings are converted side by side; the files do not depend on how many at once, the manifest
// keeps the objects' order, and an object that cannot be converted is named, with no manifest.
TEST(ConvertCli, AFolderIsTheSameWhateverTheThreadsAndNamesAFailingObject) {
  fs::remove_all(out("street1"));
  fs::remove_all(out("street2"));
  ASSERT_EQ(nut("convert " + sample("street.obj") + " -o " + out("street1") + " --quiet --png-effort small --threads 1").exitCode, 0);
  ASSERT_EQ(nut("convert " + sample("street.obj") + " -o " + out("street2") + " --quiet --png-effort small --threads 3").exitCode, 0);
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  auto city = scene::readCityJson(out("street2/city.json"));
  ASSERT_TRUE(city.ok()) << city.error().message;
  ASSERT_EQ(city->buildings.size(), 4u);
  EXPECT_EQ(city->buildings[0].name, "street_a");
  EXPECT_EQ(city->buildings[3].name, "street_d");
  EXPECT_EQ(bytes(out("street1/city.json")), bytes(out("street2/city.json")));
  for (const scene::CityBuilding& b : city->buildings) EXPECT_EQ(bytes(out("street1/" + b.hni)), bytes(out("street2/" + b.hni))) << b.hni;

  const std::string obj = out("two.obj");
  std::ofstream(obj) << "o good\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
                        "o sheet\nv 0 0 5\nv 1 0 5\nv 1 0 6\nf 9 10 11\n";
  fs::remove_all(out("two"));
  const CliRun r = nut("convert " + obj + " -o " + out("two") + " --quiet");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.stderrText.find("object 'sheet'"), std::string::npos) << r.stderrText;
  EXPECT_FALSE(fs::exists(out("two/city.json")));
}

TEST(ConvertCli, ManualBlocksAreReported) {
  // One window bay of the residential block's back facade, as a person would select it.
  const CliRun r = nut("convert " + sample("residential.obj") + " -o " + out("residential.png") + " --quiet --no-auto-blocks" +
                    " --block 1.03,4.13,-0.04:2.47,5.59,0.22 --report " + out("residential.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  std::ifstream in(out("residential.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_FALSE(report["blocks"]["found"].empty());
  EXPECT_TRUE(report["blocks"]["found"][0]["manual"].get<bool>());
  EXPECT_GE(report["blocks"]["found"][0]["instances"].get<int>(), 2);
}

TEST(ConvertCli, ExitCodes) {
  CliRun r = nut("convert /nonexistent/building.obj -o " + out("x.png"));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.stderrText.find("error: /nonexistent/building.obj: cannot open"), std::string::npos) << r.stderrText;

  {
    std::ofstream(out("nan.obj")) << "v 0 0 0\nv nan 1 0\nv 0 1 1\nf 1 2 3\n";
  }
  r = nut("convert " + out("nan.obj") + " -o " + out("nan.png"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.stderrText.find("nan.obj:2: vertex 2 has a non-finite coordinate"), std::string::npos) << r.stderrText;
  EXPECT_FALSE(fs::exists(out("nan.png")));

  {
    std::ofstream(out("empty.obj")) << "# nothing\n";
  }
  r = nut("convert " + out("empty.obj") + " -o " + out("empty.png"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.stderrText.find("no faces"), std::string::npos) << r.stderrText;

  r = nut("convert " + sample("house.obj") + " -o " + out("h.png") + " --block 1,2,3");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.stderrText.find("--block '1,2,3'"), std::string::npos) << r.stderrText;

  r = nut("convert " + sample("house.obj") + " -o " + out("h.png") + " --tolerance -1");
  EXPECT_EQ(r.exitCode, 2);
}

// `-o NAME.PNG` is one HNI, as `-o name.png` is, not a folder.
TEST(ConvertCli, AnUpperCaseDotPngIsOneHni) {
  fs::remove_all(out("HOUSE.PNG"));
  const CliRun r = nut("convert " + sample("house.obj") + " -o " + out("HOUSE.PNG") + " --quiet --png-effort small");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  ASSERT_TRUE(fs::is_regular_file(out("HOUSE.PNG")));
  auto png = readPng(out("HOUSE.PNG"));
  ASSERT_TRUE(png.ok()) << png.error().message;
  EXPECT_TRUE(validate(png->image).ok());
}

// An output name of another format is refused before the OBJ is read, naming the path and the
// extension written there, and nothing is written; a folder whose name has a dot ends in '/'.
TEST(ConvertCli, AnOutputNameOfAnotherFormatIsRefusedBeforeAnyWork) {
  const std::string house = sample("house.obj");
  for (const char* name : {"refused.jpg", "refused.png", "refused.ply", "refused.txt"}) fs::remove_all(out(name));
  const struct {
    std::string args, path, expected;
  } cases[] = {
      {" -o " + out("refused.jpg"), out("refused.jpg"), "a name ending in .png) or a folder"},
      {" -o " + out("refused.png") + " --complement " + out("refused.ply"), out("refused.ply"),
       "expected a name ending in .glb or .obj"},
      {" -o " + out("refused.png") + " --report " + out("refused.txt"), out("refused.txt"),
       "expected a name ending in .json"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const CliRun r = nut("convert " + house + c.args);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.stderrText.rfind("error: ", 0), 0u) << r.stderrText;
    EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
    EXPECT_NE(r.stderrText.find(c.path + ": "), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find(c.expected), std::string::npos) << r.stderrText;
  }
  for (const char* name : {"refused.jpg", "refused.png", "refused.ply", "refused.txt"})
    EXPECT_FALSE(fs::exists(out(name))) << name;

  fs::remove_all(out("house.v2"));
  const CliRun r = nut("convert " + house + " -o " + out("house.v2") + "/ --quiet --png-effort small");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_TRUE(fs::is_regular_file(out("house.v2/city.json")));
}

// `nut render`, with which users look at what `nut convert` wrote: both back-ends read the exact
// metadata rows unless told otherwise (the heuristic leaves holes along block seams).
TEST(RenderCli, DefaultLookupIsExactOnBothBackends) {
  const std::string hni = std::string(NUT_SOURCE_DIR) + "/samples/hni/building.png";
  const auto lookupOf = [](const std::string& statsPath) {
    std::ifstream in(statsPath);
    return nlohmann::json::parse(in).at("lookup").get<std::string>();
  };
  CliRun r = nut("render " + hni + " -o " + out("render-default.png") + " --size 160x90 --stats " + out("render-default.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(lookupOf(out("render-default.json")), "exact");
  r = nut("render " + hni + " -o " + out("render-exact.png") + " --size 160x90 --lookup exact");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(readPng(out("render-default.png"), PngKind::Render)->image,
            readPng(out("render-exact.png"), PngKind::Render)->image);
  r = nut("render " + hni + " -o " + out("render-gl.png") + " --size 160x90 --backend gl --stats " + out("render-gl.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(lookupOf(out("render-gl.json")), "exact");
  r = nut("render " + hni + " -o " + out("render-gl-heuristic.png") + " --size 160x90 --backend gl --lookup heuristic --stats " +
          out("render-gl-heuristic.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(lookupOf(out("render-gl-heuristic.json")), "heuristic");
}

// Percentage of pixels of two renders (PNG files) within 8/255.
double withinPct(const std::string& a, const std::string& b) {
  auto x = readPng(a, PngKind::Render), y = readPng(b, PngKind::Render);
  if (!x || !y) return 0.0;
  auto diff = nut::compareImages(x->image, y->image, 8);
  return diff ? 100.0 - diff->differingPct : 0.0;
}

// `nut render --mesh` on the CPU back-end: the complementary mesh is drawn with the HNI, nearest
// surface in front, so that the pair renders like the source mesh (the car park's ramps are in
// its complementary mesh).
TEST(RenderCli, AnHniWithItsComplementaryMeshRendersLikeTheSource) {
  CliRun r = nut("convert " + sample("carpark.obj") + " -o " + out("carpark-r.png") + " --complement " + out("carpark-r-rest.obj") + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("render-mesh " + sample("carpark.obj") + " -o " + out("carpark-r-source.png") + " --size 640x360");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("render " + out("carpark-r.png") + " -o " + out("carpark-r-alone.png") + " --size 640x360");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("render " + out("carpark-r.png") + " --mesh " + out("carpark-r-rest.obj") + " -o " + out("carpark-r-with.png") + " --size 640x360");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const double alone = withinPct(out("carpark-r-alone.png"), out("carpark-r-source.png"));
  const double with = withinPct(out("carpark-r-with.png"), out("carpark-r-source.png"));
  std::printf("carpark 640x360 within 8/255 of the source: HNI alone %.3f %%, with --mesh %.3f %%\n", alone, with);
  EXPECT_GE(with, 99.9);
  EXPECT_GT(100.0 - alone, 3 * (100.0 - with));  // the ramps are missing without the mesh
}

// `nut render city.json`: every building of a converted street with its complementary mesh, where
// the manifest puts it, like the source street; the GL back-end draws the same scene.
TEST(RenderCli, ACityManifestRendersLikeItsSourceOnBothBackends) {
  fs::remove_all(out("street-city"));
  CliRun r = nut("convert " + sample("street.obj") + " -o " + out("street-city") + "/ --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const std::string city = out("street-city") + "/city.json";
  {
    // Each building's box is in the manifest, as its placed HNI gives it, for a viewer to cull by.
    auto manifest = scene::readCityJson(city);
    auto placed = scene::loadScene(city, {});
    ASSERT_TRUE(manifest && placed);
    for (std::size_t i = 0; i < manifest->buildings.size(); ++i) {
      ASSERT_TRUE(manifest->buildings[i].boundsM) << i;
      const WorldBox box = HniRayCaster(*placed->hnis[i].image, placed->hnis[i].originM).bounds();
      for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(manifest->buildings[i].boundsM->min[a], box.min[a], 1e-9);
        EXPECT_NEAR(manifest->buildings[i].boundsM->max[a], box.max[a], 1e-9);
      }
    }
  }
  r = nut("render " + city + " -o " + out("street-city-cpu.png") + " --size 640x360");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("4 HNIs, 4 meshes"), std::string::npos) << r.stderrText;
  r = nut("render " + city + " -o " + out("street-city-gl.png") + " --size 640x360 --backend gl");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("render-mesh " + sample("street.obj") + " -o " + out("street-source.png") + " --size 640x360");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const double cpu = withinPct(out("street-city-cpu.png"), out("street-source.png"));
  const double gl = withinPct(out("street-city-gl.png"), out("street-city-cpu.png"));
  std::printf("street as a city, 640x360 within 8/255: CPU vs source %.3f %%, GL vs CPU %.3f %%\n", cpu, gl);
  EXPECT_GE(cpu, 99.9);
  EXPECT_GE(gl, 99.9);

  // A town of 10,000 buildings naming the street's four HNIs 2,500 times each: each file is read
  // once, and GL packs each image once into its atlas (a copy per building took 35 s to lay out,
  // and the atlas then placed them by another rule than the layout's and ran out of room).
  auto manifest = scene::readCityJson(city);
  ASSERT_TRUE(manifest.ok());
  scene::CityManifest town;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j)
      for (scene::CityBuilding b : manifest->buildings) {
        b.positionM += glm::dvec3(60.0 * i, 0.0, 60.0 * j);
        b.complement.clear();  // in world coordinates: it would not move with the copy
        town.buildings.push_back(b);
      }
  {
    std::ofstream(out("street-city") + "/town.json") << scene::cityJson(town);
  }
  r = nut("render " + out("street-city") + "/town.json -o " + out("town-cpu.png") + " --size 320x180");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("render " + out("street-city") + "/town.json -o " + out("town-gl.png") + " --size 320x180 --backend gl");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_GE(withinPct(out("town-gl.png"), out("town-cpu.png")), 99.9);
}

// An OBJ object that is a closed box from lo to hi; its vertices are numbered from `first`.
std::string boxObject(const std::string& name, const glm::dvec3& lo, const glm::dvec3& hi, int first) {
  std::string text = "o " + name + "\n";
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  }
  // Corners 0..7 as (x, y, z) bits; each face wound outwards.
  for (const std::array<int, 4>& f :
       {std::array<int, 4>{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}})
    text += "f " + std::to_string(first + f[0]) + " " + std::to_string(first + f[1]) + " " +
            std::to_string(first + f[2]) + " " + std::to_string(first + f[3]) + "\n";
  return text;
}

// Renders a city manifest and returns the percentage of pixels within 8/255 of `reference`.
double cityWithinPct(const std::string& city, const std::string& png, const std::string& reference,
                     const std::string& view) {
  const CliRun r = nut("render " + city + " -o " + png + view);
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  return withinPct(png, reference);
}

// --pack-atlases: the buildings of a converted file in district HNIs (docs/CITY.md, "Districts"),
// one complementary mesh per district. Buildings whose boxes overlap on the ground go to separate
// districts of the same square, boxes that touch share one; the report names each district's
// buildings; the packed city renders like the city of single buildings and like the source, and
// its files are fewer and smaller.
TEST(ConvertCli, PackAtlasesWritesADistrictHniAndComplementAndRendersLikeTheSource) {
  const std::string obj = out("overlap.obj");
  std::ofstream(obj) << boxObject("a", {0, 0, 0}, {10, 6, 8}, 1) << boxObject("b", {5, 0, 4}, {15, 9, 12}, 9)
                     << boxObject("c", {10, 0, 0}, {14, 4, 8}, 17);
  fs::remove_all(out("overlap"));
  CliRun r = nut("convert " + obj + " -o " + out("overlap") + " --quiet --pack-atlases --report " +
                 out("overlap-report.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const nlohmann::json report = nlohmann::json::parse(::nut::testing::fileText(out("overlap-report.json")));
  ASSERT_EQ(report.at("objects").size(), 3u);
  ASSERT_EQ(report.at("districts").size(), 2u) << report.at("districts").dump();
  EXPECT_EQ(report.at("districts")[0].at("buildings"), nlohmann::json({"a", "c"}));
  EXPECT_EQ(report.at("districts")[1].at("buildings"), nlohmann::json({"b"}));
  auto manifest = scene::readCityJson(out("overlap/city.json"));
  ASSERT_TRUE(manifest) << manifest.error().message;
  ASSERT_EQ(manifest->buildings.size(), 2u);
  EXPECT_EQ(manifest->buildings[0].hni, "d0000.png");
  EXPECT_EQ(manifest->buildings[1].hni, "d0001.png");
  EXPECT_FALSE(fs::exists(out("overlap/a.png")));
  const CliRun refused = nut("convert " + obj + " -o " + out("overlap.png") + " --pack-atlases");
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.stderrText.find("error: --pack-atlases packs the buildings written into a folder"),
            std::string::npos)
      << refused.stderrText;
  EXPECT_FALSE(fs::exists(out("overlap.png")));
  const std::string boxesView = " --size 480x270 --eye 30,25,-20 --target 7,3,6";
  r = nut("render-mesh " + obj + " -o " + out("overlap-source.png") + boxesView);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_GE(cityWithinPct(out("overlap/city.json"), out("overlap-packed.png"), out("overlap-source.png"), boxesView),
            99.9);

  // A generated LoD2 district with plane cells: its complementary meshes too become one.
  const std::string district = std::string(NUT_SOURCE_DIR) + "/tests/data/lod2_district_seed1.obj";
  const std::string single = out("lod2-single"), packed = out("lod2-packed");
  for (const std::string& dir : {single, packed}) fs::remove_all(dir);
  r = nut("convert " + district + " -o " + single + " --quiet --plane-cells");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("convert " + district + " -o " + packed + " --quiet --plane-cells --pack-atlases --report " +
          out("lod2-packed.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const auto folderBytes = [](const std::string& dir, std::size_t& files) {
    std::uintmax_t bytes = 0;
    files = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      if (e.path().filename() != "city.json") {
        bytes += e.file_size();
        ++files;
      }
    return bytes;
  };
  std::size_t singleFiles = 0, packedFiles = 0;
  const std::uintmax_t singleBytes = folderBytes(single, singleFiles), packedBytes = folderBytes(packed, packedFiles);
  std::printf("generated district, 30 buildings: %zu files, %ju B one per building; %zu files, %ju B packed\n",
              singleFiles, singleBytes, packedFiles, packedBytes);
  EXPECT_LE(packedFiles, 4u);
  EXPECT_LT(packedBytes, singleBytes * 3 / 4);
  const nlohmann::json lod2 = nlohmann::json::parse(::nut::testing::fileText(out("lod2-packed.json")));
  std::size_t members = 0;
  for (const nlohmann::json& d : lod2.at("districts")) {
    members += d.at("buildings").size();
    auto png = readPng(packed + "/" + d.at("name").get<std::string>() + ".png");
    ASSERT_TRUE(png) << png.error().message;
    EXPECT_TRUE(validate(png->image)) << d.at("name");
  }
  EXPECT_EQ(members, 30u);
  const std::string view = " --size 640x360 --eye -30,70,-40 --target 60,5,60";
  r = nut("render-mesh " + district + " -o " + out("lod2-source.png") + view);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const double one = cityWithinPct(single + "/city.json", out("lod2-single.png"), out("lod2-source.png"), view);
  const double both = cityWithinPct(packed + "/city.json", out("lod2-packed.png"), out("lod2-source.png"), view);
  std::printf("within 8/255 of the source: one HNI per building %.3f %%, districts %.3f %%\n", one, both);
  EXPECT_GE(both, 99.5);
  EXPECT_GE(both, one - 0.1);
}

// --district-size: two Zurich houses (tests/data/zurich_house.obj, its roof overhanging as a
// sheet the complementary mesh draws) 5 km apart are two districts of the default 256 m and one of
// 8 km: one HNI and one complementary mesh, fewer bytes, and near either house it renders like the
// source. (That the mesh keeps its 4 mm steps over 5 km is MeshSize's test.)
// A building whose roof waves 40 cm over 12 m: the roof is left to the complementary mesh, which
// --complement-levels decimates. city.json lists the levels with errors that grow, each file has
// fewer triangles, the scene loads them, and `nut render --lod auto` draws the same pixels close
// up and nearly the same from far away, on either back-end; with -o FILE.png the option is refused.
TEST(ConvertCli, ComplementLevelsAreListedLoadedAndDrawnFromFar) {
  std::ostringstream obj;
  obj << "o wavy\n";
  constexpr int n = 24;
  constexpr double size = 12.0;
  const auto roofY = [](double x, double z) { return 6.0 + 0.4 * std::sin(0.8 * x) * std::cos(0.6 * z); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      obj << "v " << size * i / n << " " << roofY(size * i / n, size * j / n) << " " << size * j / n << "\n";
  const auto roof = [](int i, int j) { return j * (n + 1) + i + 1; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      obj << "f " << roof(i, j) << " " << roof(i, j + 1) << " " << roof(i + 1, j) << "\nf " << roof(i + 1, j) << " "
          << roof(i, j + 1) << " " << roof(i + 1, j + 1) << "\n";
  // Walls from the ground up to the roof's edge, and the floor.
  int next = (n + 1) * (n + 1) + 1;
  const auto wall = [&](const std::vector<int>& edge) {
    for (int k : edge) {
      const int i = (k - 1) % (n + 1), j = (k - 1) / (n + 1);
      obj << "v " << size * i / n << " 0 " << size * j / n << "\n";
    }
    for (std::size_t t = 0; t + 1 < edge.size(); ++t) {
      const int g = next + static_cast<int>(t);
      obj << "f " << g << " " << g + 1 << " " << edge[t + 1] << "\nf " << g << " " << edge[t + 1] << " " << edge[t]
          << "\n";
    }
    next += static_cast<int>(edge.size());
  };
  std::vector<int> south, east, north, west;
  for (int k = 0; k <= n; ++k) south.push_back(roof(k, 0)), east.push_back(roof(n, k));
  for (int k = n; k >= 0; --k) north.push_back(roof(k, n)), west.push_back(roof(0, k));
  wall(south), wall(east), wall(north), wall(west);
  obj << "v 0 0 0\nv 12 0 0\nv 12 0 12\nv 0 0 12\nf " << next << " " << next + 1 << " " << next + 2 << "\nf " << next
      << " " << next + 2 << " " << next + 3 << "\n";
  const std::string input = out("wavy.obj");
  std::ofstream(input) << obj.str();

  fs::remove_all(out("wavy"));
  const CliRun r = nut("convert " + input + " -o " + out("wavy") + " --complement-levels 2 --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto city = scene::readCityJson(out("wavy/city.json"));
  ASSERT_TRUE(city.ok()) << city.error().message;
  const scene::CityBuilding& b = city->buildings.at(0);
  ASSERT_EQ(b.complementLevels.size(), 2u);
  std::vector<std::string> warnings;
  auto full = scene::readMeshFile(out("wavy/" + b.complement), warnings);
  ASSERT_TRUE(full.ok());
  std::size_t triangles = full->triangles.size();
  double error = 0;
  for (const scene::ComplementLevel& level : b.complementLevels) {
    auto mesh = scene::readMeshFile(out("wavy/" + level.path), warnings);
    ASSERT_TRUE(mesh.ok()) << level.path;
    EXPECT_LT(mesh->triangles.size(), triangles) << level.path;
    EXPECT_GT(level.errorM, error) << level.path;
    EXPECT_LT(level.errorM, 0.4) << level.path;  // the roof's waves are 40 cm high
    triangles = mesh->triangles.size(), error = level.errorM;
  }
  auto loaded = scene::loadScene(out("wavy/city.json"), {});
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->coarser.at(0).size(), 2u);

  const auto render = [&](const std::string& name, const std::string& eye, const std::string& lod,
                          const std::string& backend = "cpu") {
    const CliRun run = nut("render " + out("wavy/city.json") + " -o " + out(name) + " --eye " + eye +
                           " --target 6,4,6 --size 320x240 --lod " + lod + " --backend " + backend);
    EXPECT_EQ(run.exitCode, 0) << run.stderrText;
    return readPng(out(name), PngKind::Render)->image;
  };
  EXPECT_EQ(render("wavy-near-off.png", "20,14,20", "off"), render("wavy-near-auto.png", "20,14,20", "auto"));
  auto far =
      compareImages(render("wavy-far-off.png", "120,60,120", "off"), render("wavy-far-auto.png", "120,60,120", "auto"));
  ASSERT_TRUE(far.ok());
  EXPECT_LT(far->differingPct, 0.5);

  // The GL back-end draws the same levels.
  auto gl = compareImages(render("wavy-far-auto.png", "120,60,120", "auto"),
                          render("wavy-far-auto-gl.png", "120,60,120", "auto", "gl"));
  ASSERT_TRUE(gl.ok());
  EXPECT_LT(gl->differingPct, 0.5);

  const CliRun one = nut("convert " + input + " -o " + out("wavy-one.png") + " --complement-levels 1");
  EXPECT_EQ(one.exitCode, 2);
  EXPECT_NE(one.stderrText.find("--complement-levels"), std::string::npos) << one.stderrText;
}

TEST(ConvertCli, ALargerDistrictPacksBuildingsFarApartIntoOne) {
  const std::string house = ::nut::testing::fileText(std::string(NUT_SOURCE_DIR) + "/tests/data/zurich_house.obj");
  std::ostringstream pair;
  pair << "mtllib " << NUT_SOURCE_DIR << "/tests/data/zurich_house.mtl\n";
  for (int copy = 0; copy < 2; ++copy) {
    std::istringstream lines(house);
    pair << "o house" << copy << "\n";
    for (std::string line; std::getline(lines, line);) {
      std::istringstream fields(line);
      std::string tag;
      fields >> tag;
      if (tag == "v") {
        double x, y, z;
        fields >> x >> y >> z;
        pair << "v " << x + copy * 5000.0 << " " << y << " " << z << "\n";
      } else if (tag == "f") {
        pair << "f";
        for (int v; fields >> v;) pair << " " << v + copy * 22;
        pair << "\n";
      } else if (tag == "usemtl") {
        pair << line << "\n";
      }
    }
  }
  const std::string obj = out("far-apart.obj");
  std::ofstream(obj) << pair.str();
  const std::string small = out("far-small"), large = out("far-large");
  for (const std::string& dir : {small, large}) fs::remove_all(dir);
  CliRun r = nut("convert " + obj + " -o " + small + " --quiet --pack-atlases");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("convert " + obj + " -o " + large + " --quiet --pack-atlases --district-size 8192");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto smallCity = scene::readCityJson(small + "/city.json"), largeCity = scene::readCityJson(large + "/city.json");
  ASSERT_TRUE(smallCity && largeCity);
  EXPECT_EQ(smallCity->buildings.size(), 2u);
  ASSERT_EQ(largeCity->buildings.size(), 1u);
  EXPECT_FALSE(largeCity->buildings[0].complement.empty());
  std::uintmax_t smallBytes = 0, largeBytes = 0;
  for (const auto& [dir, bytes] : {std::pair{small, &smallBytes}, std::pair{large, &largeBytes}})
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      if (e.path().filename() != "city.json") *bytes += e.file_size();
  EXPECT_LT(largeBytes, smallBytes);
  for (int copy = 0; copy < 2; ++copy) {
    const double x = 3900 + copy * 5000.0;
    const std::string view =
        " --size 480x270 --eye " + std::to_string(x + 14) + ",86,-404 --target " + std::to_string(x) + ",75,-418";
    const std::string source = out("far-source" + std::to_string(copy) + ".png");
    r = nut("render-mesh " + obj + " -o " + source + view);
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_GE(cityWithinPct(large + "/city.json", out("far-large" + std::to_string(copy) + ".png"), source, view), 99.5)
        << "house " << copy;
  }
}

TEST(RenderCli, ABadManifestFailsNamingWhere) {
  fs::create_directories(out("bad-city"));
  {
    std::ofstream(out("bad-city/missing.json"))
        << R"({"format": "nut-city", "version": 1, "buildings": [{"name": "a", "hni": "a.png", "position_m": [0, 0, 0]}]})";
    std::ofstream(out("bad-city/empty.json")) << R"({"format": "nut-city", "version": 1, "buildings": []})";
    std::ofstream(out("bad-city/outside.json"))
        << R"({"format": "nut-city", "version": 1, "buildings": [{"name": "a", "hni": "../a.png", "position_m": [0, 0, 0]}]})";
    std::ofstream(out("bad-city/broken.json")) << R"({"format": "nut-city", )";
  }
  CliRun r = nut("render " + out("bad-city/missing.json") + " -o " + out("bad-city/x.png"));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.stderrText.find("error: " + out("bad-city") + "/a.png"), std::string::npos) << r.stderrText;
  r = nut("render " + out("bad-city/empty.json") + " -o " + out("bad-city/x.png"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.stderrText.find("empty.json: the manifest lists no buildings"), std::string::npos) << r.stderrText;
  r = nut("render " + out("bad-city/outside.json") + " -o " + out("bad-city/x.png"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.stderrText.find("outside.json: building 0 (a): \"hni\" must be a relative path inside"), std::string::npos) << r.stderrText;
  r = nut("render " + out("bad-city/broken.json") + " -o " + out("bad-city/x.png"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.stderrText.find("broken.json: not valid JSON"), std::string::npos) << r.stderrText;
  EXPECT_FALSE(fs::exists(out("bad-city/x.png")));
}

// `nut info --blocks --bytes`, with which users see where an HNI's bytes go.
TEST(InfoCli, ListsBlocksAndWhatEachKindOfRecordCosts) {
  const std::string hni = std::string(NUT_SOURCE_DIR) + "/samples/hni/facade.png";
  const CliRun r = nut("info " + hni + " --json --blocks --bytes > " + out("facade-info.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  std::ifstream in(out("facade-info.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("block_list").size(), j.at("blocks").get<std::size_t>());
  long long cells = 0;
  for (const auto& b : j.at("block_list")) cells += b.at("cells")[0].get<long long>() * b.at("cells")[1].get<long long>() * b.at("cells")[2].get<long long>();
  EXPECT_EQ(cells, j.at("cells").get<long long>());
  const auto& kinds = j.at("png_bytes_by_record").at("kinds");
  EXPECT_EQ(kinds.at("data components").at("pixels").get<long long>(), cells);
  // Every kind of record costs something, and no part costs more than the whole.
  const long long total = j.at("png_bytes_by_record").at("pixels_png_bytes").get<long long>();
  for (const auto& [name, kind] : kinds.items()) {
    EXPECT_GT(kind.at("png_bytes").get<long long>(), 0) << name;
    EXPECT_LT(kind.at("png_bytes").get<long long>(), total) << name;
  }
  EXPECT_LT(total, j.at("bytes_png").get<long long>());  // the file adds its chunks
}

}  // namespace
}  // namespace nut::converter
