// The commands users check and look at results with, run as a user runs them: `nut validate`,
// `nut compare`, `nut export-mesh`, `nut render-mesh`, `nut render --depth --stats --heat-map`
// and `nut info`; and what `nut` itself answers (unknown commands, --version, output names of
// another format). Each test knows its answer independently (images built here with known
// differences, the HNI's own decode, the PFM layout, the version in CMakeLists.txt), and bad input
// must give one `error:` line and the documented exit status: 1 invalid input, 2 usage error or
// unreadable file. (`nut convert` and the scene renders: converter_cli_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <regex>
#include <set>
#include <string_view>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <nut/camera.hpp>
#include <nut/heat_map.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>
#include <scene/scene.hpp>

#include "cli_support.hpp"
#include "test_files.hpp"
#include "declared_size_png.hpp"

namespace nut {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;

CliRun nut(const std::string& args) { return testing::runNut(args, "cli"); }

std::string out(const std::string& name) { return testing::outputPath("cli", name); }
std::string source(const std::string& path) { return std::string(NUT_SOURCE_DIR) + "/" + path; }

// An error is one line, `error: ` first, and says where.
void expectOneErrorLine(const CliRun& r, int exitCode, const std::string& saying) {
  EXPECT_EQ(r.exitCode, exitCode) << r.stderrText;
  EXPECT_EQ(r.stderrText.rfind("error: ", 0), 0u) << r.stderrText;
  EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
  EXPECT_NE(r.stderrText.find(saying), std::string::npos) << r.stderrText;
}

// An HNI of the repository read and decoded; the test fails where it cannot be.
struct DecodedHni {
  PngFile png;
  Hierarchy h;
};
DecodedHni decodeOrFail(const std::string& path) {
  DecodedHni out;
  auto png = readPng(path);
  EXPECT_TRUE(png.ok()) << png.error().message;
  if (!png) return out;
  out.png = std::move(*png);
  auto h = decode(out.png.image);
  EXPECT_TRUE(h.ok()) << h.error().message;
  if (h) out.h = std::move(*h);
  return out;
}

// A w x h image of one grey, opaque.
Image greyImage(int w, int h, std::uint8_t grey) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = p[1] = p[2] = grey, p[3] = 255;
    }
  return image;
}

TEST(ValidateCli, ExitStatusSaysValidInvalidOrUnreadable) {
  const std::string facade = source("samples/hni/facade.png");
  auto png = readPng(facade);
  ASSERT_TRUE(png.ok()) << png.error().message;
  const CliRun valid = nut("validate " + facade);
  EXPECT_EQ(valid.exitCode, 0) << valid.stderrText;
  EXPECT_NE(valid.stdoutText.find("valid HNI, " + std::to_string(png->image.width) + "x" +
                                  std::to_string(png->image.height) + " px"),
            std::string::npos)
      << valid.stdoutText;
  // A PNG that is not an HNI (no magic in its first pixel).
  ASSERT_TRUE(writePng(out("grey.png"), greyImage(16, 4, 128)).ok());
  expectOneErrorLine(nut("validate " + out("grey.png")), 1, out("grey.png") + ": invalid HNI: ");
  expectOneErrorLine(nut("validate " + out("missing.png")), 2, "missing.png");
  expectOneErrorLine(nut("validate " + source("README.md")), 2, "README.md");
}

// A 70-byte PNG whose IHDR declares 100000 x 100000 pixels: every command that reads it says so in
// one error line and exits 2 (unreadable), before allocating the pixels (png_io_test measures that).
TEST(ValidateCli, OversizedPngIsOneErrorLine) {
  const std::string huge = out("declares-100000x100000.png");
  testing::writePngDeclaringSize(huge, 100000, 100000);
  const std::string asHni = huge + ": the PNG declares 100000x100000 pixels; an HNI has at most 4096x4096";
  expectOneErrorLine(nut("info " + huge), 2, asHni);
  expectOneErrorLine(nut("validate " + huge), 2, asHni);
  expectOneErrorLine(nut("render " + huge + " -o " + out("huge-render.png")), 2, asHni);
  EXPECT_FALSE(fs::exists(out("huge-render.png")));
  const std::string asRender = huge + ": the PNG declares 100000x100000 pixels; a render has at most 16384x16384";
  expectOneErrorLine(nut("compare " + huge + " " + huge), 2, asRender);
}

// Two images differing in known pixels: three by 9 (over the default threshold of 8), two by
// exactly 8 (not over it) and one by 155.
TEST(CompareCli, CountsThePixelsOverTheThresholdAndDrawsTheDiff) {
  const Image a = greyImage(8, 4, 100);
  Image b = a;
  for (int x : {0, 1, 2}) b.at(x, 0)[0] = 109;
  for (int x : {3, 4}) b.at(x, 1)[1] = 92;
  b.at(7, 3)[0] = 255;
  ASSERT_TRUE(writePng(out("a.png"), a).ok());
  ASSERT_TRUE(writePng(out("b.png"), b).ok());
  const CliRun r = nut("compare " + out("a.png") + " " + out("b.png") + " --json --diff " + out("ab-diff.png"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const nlohmann::json j = nlohmann::json::parse(r.stdoutText);
  EXPECT_EQ(j.at("width").get<int>(), 8);
  EXPECT_EQ(j.at("height").get<int>(), 4);
  EXPECT_EQ(j.at("pixels").get<long long>(), 32);
  EXPECT_EQ(j.at("differing").get<long long>(), 4);  // three by 9, one by 155; not the two by 8
  EXPECT_EQ(j.at("max_difference").get<int>(), 155);
  EXPECT_DOUBLE_EQ(j.at("differing_pct").get<double>(), 12.5);
  EXPECT_FALSE(j.at("psnr").is_null());
  auto diff = readPng(out("ab-diff.png"), PngKind::Render);
  ASSERT_TRUE(diff.ok()) << diff.error().message;
  EXPECT_EQ(diff->image.width, 8);
  EXPECT_EQ(diff->image.height, 4);

  const CliRun same = nut("compare " + out("a.png") + " " + out("a.png") + " --json");
  ASSERT_EQ(same.exitCode, 0) << same.stderrText;
  EXPECT_TRUE(nlohmann::json::parse(same.stdoutText).at("psnr").is_null());  // identical: no finite PSNR
  const CliRun text = nut("compare " + out("a.png") + " " + out("b.png") + " --threshold 10");
  EXPECT_NE(text.stdoutText.find("differing 3.1250% (1 of 32 pixels differ by more than 10"), std::string::npos)
      << text.stdoutText;

  ASSERT_TRUE(writePng(out("small.png"), greyImage(4, 4, 100)).ok());
  expectOneErrorLine(nut("compare " + out("a.png") + " " + out("small.png")), 1, "8x4");
  expectOneErrorLine(nut("compare " + out("a.png") + " " + out("missing.png")), 2, "missing.png");
}

// The exported mesh lies inside the HNI's root box and uses its materials.
TEST(ExportMeshCli, WritesAnObjInsideTheHnisBox) {
  const std::string facade = source("samples/hni/facade.png");
  const DecodedHni hni = decodeOrFail(facade);
  ASSERT_FALSE(hni.h.blocks.empty());
  const CliRun r = nut("export-mesh " + facade + " -o " + out("facade.obj"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  std::vector<std::string> warnings;
  auto mesh = scene::readObjMesh(out("facade.obj"), warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_FALSE(mesh->triangles.empty());
  EXPECT_NE(r.stderrText.find(std::to_string(mesh->triangles.size()) + " triangles"), std::string::npos)
      << r.stderrText;
  const glm::dvec3 lo = hni.png.text.originM, hi = lo + hni.h.blocks[hni.h.root].sizeM();
  for (const glm::dvec3& p : mesh->positions)
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], lo[a] - 1e-6);
      EXPECT_LE(p[a], hi[a] + 1e-6);
    }
  EXPECT_EQ(mesh->materials.size(), hni.h.materials.size());

  ASSERT_TRUE(writePng(out("not-an-hni.png"), greyImage(16, 4, 128)).ok());
  expectOneErrorLine(nut("export-mesh " + out("not-an-hni.png") + " -o " + out("grey.obj")), 1, "invalid HNI");
  EXPECT_FALSE(fs::exists(out("grey.obj")));
  const CliRun usage = nut("export-mesh " + facade + " -o " + out("x.obj") + " --tolerance 0");
  expectOneErrorLine(usage, 2, "must be a positive number");
}

TEST(RenderMeshCli, RendersTheSizeAskedAndRefusesBadCameras) {
  const std::string cube = source("tests/data/two_material_cube.obj");
  const CliRun r = nut("render-mesh " + cube + " -o " + out("cube.png") + " --size 64x48");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto png = readPng(out("cube.png"), PngKind::Render);
  ASSERT_TRUE(png.ok()) << png.error().message;
  EXPECT_EQ(png->image.width, 64);
  EXPECT_EQ(png->image.height, 48);
  const std::uint8_t* centre = png->image.at(32, 24);
  const std::uint8_t background[3] = {214, 222, 230};  // docs/RENDERING.md
  EXPECT_NE(std::memcmp(centre, background, 3), 0) << "the default camera looks at the cube";

  expectOneErrorLine(nut("render-mesh " + cube + " -o " + out("x.png") + " --eye 1,2"), 2,
                     "--eye '1,2': expected x,y,z in metres");
  expectOneErrorLine(nut("render-mesh " + cube + " -o " + out("x.png") + " --size 0x5"), 2, "--size '0x5'");
  expectOneErrorLine(nut("render-mesh " + cube + " -o " + out("x.png") + " --eye 0,5,0 --target 0,0,0"), 2,
                     "must not be collinear");
  expectOneErrorLine(nut("render-mesh " + source("README.md") + " -o " + out("x.png")), 1, "README.md");
  expectOneErrorLine(nut("render-mesh " + out("missing.obj") + " -o " + out("x.png")), 2, "missing.obj");
  EXPECT_FALSE(fs::exists(out("x.png")));
}

// --depth writes a PFM (docs: distance along each ray in metres, +inf for misses, bottom row
// first) of the image's size; --stats says the size and the lookup.
TEST(RenderCli, DepthIsAPfmOfTheImageAndStatsSayWhatRan) {
  const std::string facade = source("samples/hni/facade.png");
  const CliRun r = nut("render " + facade + " -o " + out("facade.png") + " --size 40x30 --depth " + out("facade.pfm") +
                       " --stats " + out("facade-stats.json") + " --lookup heuristic");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const std::string pfm = testing::fileText(out("facade.pfm"));
  const std::string header = "Pf\n40 30\n-1.0\n";
  ASSERT_EQ(pfm.size(), header.size() + 40 * 30 * sizeof(float));
  EXPECT_EQ(pfm.substr(0, header.size()), header);
  std::vector<float> depth(40 * 30);
  std::memcpy(depth.data(), pfm.data() + header.size(), depth.size() * sizeof(float));
  auto png = readPng(out("facade.png"), PngKind::Render);
  ASSERT_TRUE(png.ok()) << png.error().message;
  const std::uint8_t background[3] = {214, 222, 230};
  int hits = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const float d = depth[static_cast<std::size_t>((29 - y) * 40 + x)];  // bottom row first
      const bool hit = std::memcmp(png->image.at(x, y), background, 3) != 0;
      EXPECT_EQ(std::isfinite(d), hit) << "pixel " << x << "," << y;
      if (hit) {
        EXPECT_GT(d, 0.0f);
      }
      hits += hit;
    }
  EXPECT_GT(hits, 100);
  const nlohmann::json stats = nlohmann::json::parse(testing::fileText(out("facade-stats.json")));
  EXPECT_EQ(stats.at("width").get<int>(), 40);
  EXPECT_EQ(stats.at("height").get<int>(), 30);
  EXPECT_EQ(stats.at("lookup").get<std::string>(), "heuristic");
  EXPECT_EQ(stats.at("backend").get<std::string>(), "cpu");
}

// --heat-map draws every hit in a colour of the ramp (nut/heat_map.hpp) and nothing else: each
// pixel is the background, the ramp colour of some iteration count up to the cap, or the capped
// colour.
TEST(RenderCli, HeatMapDrawsOnlyRampColours) {
  const std::string building = source("samples/hni/building.png");
  const CliRun r = nut("render " + building + " -o " + out("heat.png") + " --size 64x36 --max-iter 40 --heat-map");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto png = readPng(out("heat.png"), PngKind::Render);
  ASSERT_TRUE(png.ok()) << png.error().message;
  std::set<int> ramp{kBackground[0] << 16 | kBackground[1] << 8 | kBackground[2],  // as 0xRRGGBB
                     kCappedColour[0] << 16 | kCappedColour[1] << 8 | kCappedColour[2]};
  for (int i = 0; i <= 40; ++i) {
    const auto c = heatColour(i, 40);
    ramp.insert(c[0] << 16 | c[1] << 8 | c[2]);
  }
  int hits = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 64; ++x) {
      const std::uint8_t* p = png->image.at(x, y);
      const int colour = p[0] << 16 | p[1] << 8 | p[2];
      EXPECT_TRUE(ramp.count(colour)) << "pixel " << x << "," << y;
      hits += std::memcmp(p, kBackground.data(), 3) != 0;
    }
  EXPECT_GT(hits, 200);
}

// The text summary and the block list agree with the HNI's own decode.
TEST(InfoCli, TextSummaryAndBlockListMatchTheDecode) {
  const std::string building = source("samples/hni/building.png");
  const DecodedHni hni = decodeOrFail(building);
  ASSERT_FALSE(hni.h.blocks.empty());
  const CliRun r = nut("info " + building + " --blocks");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stdoutText.find("blocks        " + std::to_string(hni.h.blocks.size()) + ", DAG depth"),
            std::string::npos)
      << r.stdoutText;
  EXPECT_NE(r.stdoutText.find("materials     " + std::to_string(hni.h.materials.size())), std::string::npos);
  // One line per block after the table's header, the root marked.
  const auto header = r.stdoutText.find("  block    cells");
  ASSERT_NE(header, std::string::npos) << r.stdoutText;
  const auto footer = r.stdoutText.find("  (* the root)");
  ASSERT_NE(footer, std::string::npos);
  const std::string table = r.stdoutText.substr(header, footer - header);
  EXPECT_EQ(static_cast<std::size_t>(std::count(table.begin(), table.end(), '\n')) - 1, hni.h.blocks.size());
  EXPECT_EQ(std::count(table.begin(), table.end(), '*'), 1);

  expectOneErrorLine(nut("info " + out("missing.png")), 2, "missing.png");
}

TEST(MainCli, NoCommandIsAUsageErrorAndEveryHelpHasAnExample) {
  expectOneErrorLine(nut(""), 2, "see nut --help");
  const CliRun help = nut("--help");
  EXPECT_EQ(help.exitCode, 0);
  for (const char* command : {"info", "validate", "render", "export-mesh", "render-mesh", "compare", "grammar", "city", "convert"}) {
    EXPECT_NE(help.stdoutText.find(std::string("  ") + command + " "), std::string::npos) << command;
    // Every command's help ends with an example of itself.
    const CliRun own = nut(std::string(command) + " --help");
    EXPECT_EQ(own.exitCode, 0) << command;
    const auto example = own.stdoutText.find("Example");
    ASSERT_NE(example, std::string::npos) << command;
    EXPECT_NE(own.stdoutText.find(std::string("nut ") + command + " ", example), std::string::npos) << command;
  }
}


// `nut grammar` writes the HNI, the mesh and the report it is asked for; the HNI carries the
// origin the report gives and validates. A broken grammar is one error line naming file, line and
// column, exit 1, and writes nothing; a malformed --size is a usage error.
TEST(GrammarCli, WritesWhatItIsAskedForAndNothingOnError) {
  const std::string grammar = source("samples/grammars/pga_simple_house.grammar");
  for (const char* name : {"house.png", "house.obj", "house.mtl", "house.json"}) fs::remove(out(name));
  const CliRun r = nut("grammar " + grammar + " -o " + out("house.png") + " --seed 3 --mesh " + out("house.obj") +
                       " --report " + out("house.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto png = readPng(out("house.png"));
  ASSERT_TRUE(png) << png.error().message;
  EXPECT_TRUE(validate(png->image).ok());
  EXPECT_EQ(png->text.generator, "nut grammar");
  const auto report = nlohmann::json::parse(testing::fileText(out("house.json")));
  EXPECT_EQ(report["seed"], 3);
  EXPECT_EQ(report["png_bytes"], fs::file_size(out("house.png")));
  EXPECT_DOUBLE_EQ(report["origin_m"][2].get<double>(), png->text.originM.z);
  std::vector<std::string> warnings;
  auto mesh = scene::readObjMesh(out("house.obj"), warnings);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->triangles.size(), report["mesh"]["triangles"].get<std::size_t>());

  const std::string broken = testing::writeTestFile("cli", "broken.grammar", "@size 4, 3\nA -> SplitX(Abs, 5, B)\nB -> Mat(Color, 0, 1, 0, 0, 1)\n");
  fs::remove(out("broken.png"));
  expectOneErrorLine(nut("grammar " + broken + " -o " + out("broken.png")), 1, "broken.grammar:2:1: rule 'A': parts of 5 m");
  EXPECT_FALSE(fs::exists(out("broken.png")));
  expectOneErrorLine(nut("grammar " + grammar + " -o " + out("broken.png") + " --size 4"), 2, "--size '4'");
  expectOneErrorLine(nut("grammar " + grammar + " -o " + out("broken.obj")), 2, "expected a name ending in .png");
  EXPECT_FALSE(fs::exists(out("broken.png")));
}

// `nut grammar --lod` writes a version 2 HNI and the footprints in the report; `nut render --lod
// auto` draws it, and any other --lod value is a usage error.
TEST(GrammarCli, MeasuredLevelOfDetailIsWrittenAndRendered) {
  const std::string grammar = source("samples/grammars/krecklau_figure12.grammar");
  const CliRun r = nut("grammar " + grammar + " -o " + out("lod.png") + " --lod --report " + out("lod.json"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto png = readPng(out("lod.png"));
  ASSERT_TRUE(png) << png.error().message;
  EXPECT_TRUE(validate(png->image).ok());
  EXPECT_EQ(png->image.at(0, 0)[3], 2) << "version";
  const auto report = nlohmann::json::parse(testing::fileText(out("lod.json")));
  ASSERT_EQ(report["lod_footprint_m"].size(), report["blocks"].get<std::size_t>());
  EXPECT_GT(report["lod_footprint_m"][0].get<double>(), 0.0);
  const CliRun render = nut("render " + out("lod.png") + " -o " + out("lod-render.png") + " --size 64x36 --lod auto");
  EXPECT_EQ(render.exitCode, 0) << render.stderrText;
  expectOneErrorLine(nut("render " + out("lod.png") + " -o " + out("lod-render.png") + " --lod sometimes"), 2,
                     "--lod");
}

// `nut city`: N distinct valid buildings and a manifest that places them on lots that do not
// overlap, on the ground; the same seed gives the same bytes whatever the thread count, another
// seed another city; a facade grammar or a zero count is refused with one line.
TEST(CityCli, DistinctValidBuildingsOnLotsThatDoNotOverlap) {
  constexpr int kCount = 24;
  // The manifest names the city after its folder: the runs compared write folders of one name.
  const std::string a = out("city-a") + "/city", b = out("city-b") + "/city", c = out("city-c") + "/city";
  for (const char* dir : {"city-a", "city-b", "city-c"}) fs::remove_all(out(dir));
  const CliRun r = nut("city --count 24 --out " + a + " --seed 5 --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(r.stderrText, "");
  auto scene = scene::loadScene(a + "/city.json", {});
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_EQ(scene->hnis.size(), static_cast<std::size_t>(kCount));
  auto manifest = scene::readCityJson(a + "/city.json");
  ASSERT_TRUE(manifest) << manifest.error().message;
  std::set<std::size_t> distinct;  // hashes of the pixels
  std::vector<WorldBox> boxes;
  for (const scene::PlacedHni& hni : scene->hnis) {
    EXPECT_TRUE(validate(*hni.image).ok());
    distinct.insert(std::hash<std::string_view>{}(std::string_view(
        reinterpret_cast<const char*>(hni.image->pixels.data()), hni.image->pixels.size())));
    boxes.push_back(HniRayCaster(*hni.image, hni.originM, hni.worldFromRoot).bounds());
    // The manifest's box is the placed root block's, known before the image is read.
    const auto& written = manifest->buildings[boxes.size() - 1].boundsM;
    ASSERT_TRUE(written);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(written->min[axis], boxes.back().min[axis], 1e-6);
      EXPECT_NEAR(written->max[axis], boxes.back().max[axis], 1e-6);
    }
  }
  EXPECT_EQ(distinct.size(), static_cast<std::size_t>(kCount)) << "every building its own HNI";
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_NEAR(boxes[i].min.y, 0.0, 1e-3) << "building " << i << " stands on the ground";
    for (std::size_t j = 0; j < i; ++j) {
      bool apart = false;
      for (int axis : {0, 2})
        apart = apart || boxes[i].min[axis] >= boxes[j].max[axis] || boxes[j].min[axis] >= boxes[i].max[axis];
      EXPECT_TRUE(apart) << "buildings " << j << " and " << i << " overlap";
    }
  }
  ASSERT_EQ(nut("city --count 24 --out " + b + " --seed 5 --quiet --threads 1").exitCode, 0);
  for (const char* file : {"city.json", "b00000.png", "b00023.png"})
    EXPECT_EQ(testing::fileText(a + "/" + file), testing::fileText(b + "/" + file)) << file;
  ASSERT_EQ(nut("city --count 24 --out " + c + " --seed 6 --quiet").exitCode, 0);
  EXPECT_NE(testing::fileText(a + "/b00000.png"), testing::fileText(c + "/b00000.png"));

  expectOneErrorLine(nut("city --count 2 --out " + out("city-d") + " --grammar " +
                         source("samples/grammars/gbef_m1.grammar")),
                     1, "needs a mass");
  EXPECT_FALSE(fs::exists(out("city-d") + "/city.json"));
  expectOneErrorLine(nut("city --count 0 --out " + out("city-d")), 2, "--count");
  expectOneErrorLine(nut("city --count 2 --out " + out("city-d") + " --mix converted --grammar " +
                         source("samples/grammars/pga_simple_house.grammar")),
                     2, "--grammar");
}

// --layout grid places the same buildings (the same PNG bytes as the streets layout of the seed) on
// a square of 30 m lots: 25 buildings make 5 rows of 5, each centred on its lot, a row's lots 30 m
// apart, rows of a block back to back 20 m apart and a 16 m street between blocks. --report counts
// what was written.
TEST(CityCli, GridLayoutIsASquareOfLotsAndTheReportCountsTheCity) {
  const std::string streets = out("city-streets") + "/city", grid = out("city-grid") + "/city";
  for (const char* dir : {"city-streets", "city-grid"}) fs::remove_all(out(dir));
  ASSERT_EQ(nut("city --count 25 --out " + streets + " --seed 3 --quiet").exitCode, 0);
  const CliRun r = nut("city --count 25 --out " + grid + " --seed 3 --quiet --layout grid --report " +
                       out("city-grid") + "/report.json");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto manifest = scene::readCityJson(grid + "/city.json");
  ASSERT_TRUE(manifest) << manifest.error().message;
  ASSERT_EQ(manifest->buildings.size(), 25u);
  std::size_t pngBytes = 0;
  for (std::size_t i = 0; i < 25; ++i) {
    const scene::CityBuilding& b = manifest->buildings[i];
    EXPECT_EQ(testing::fileText(grid + "/" + b.hni), testing::fileText(streets + "/" + b.hni)) << b.hni;
    pngBytes += fs::file_size(grid + "/" + b.hni);
    ASSERT_TRUE(b.boundsM);
    const glm::dvec3 centre = 0.5 * (b.boundsM->min + b.boundsM->max);
    const std::size_t column = i % 5, row = i / 5;
    EXPECT_NEAR(centre.x, 15.0 + 30.0 * static_cast<double>(column), 1e-6) << b.name;
    const double rowZ = 16.0 + static_cast<double>(row / 2) * 56.0 + (row % 2 == 1 ? 30.0 : 10.0);
    EXPECT_NEAR(centre.z, rowZ, 1e-6) << b.name;
    EXPECT_EQ(b.yawDeg, row % 2 == 1 ? 180.0 : 0.0) << b.name;
  }
  const nlohmann::json report = nlohmann::json::parse(testing::fileText(out("city-grid") + "/report.json"));
  EXPECT_EQ(report.at("buildings").get<std::size_t>(), 25u);
  EXPECT_EQ(report.at("png_bytes").get<std::size_t>(), pngBytes);
  EXPECT_EQ(report.at("layout").get<std::string>(), "grid");
  EXPECT_GT(report.at("buildings_per_second").get<double>(), 0.0);
  // Boxes of at least 4 x 6 x 4 m: twelve triangles a building at the very least.
  EXPECT_GE(report.at("grammar_mesh").at("triangles").get<std::size_t>(), 25u * 12u);
}

// --mix grammar,converted takes the converted samples in turn with the grammars, each building
// its own stretched HNI; --pack-atlases writes the same city as district HNIs. Each district
// validates, they are smaller than the buildings' PNGs together, the buildings' PNGs are gone, and
// the packed city renders as the city of single buildings: the buildings placed by the manifest
// (an independent placement) against the buildings placed inside the districts' root blocks.
TEST(CityCli, AMixedCityPackedIntoDistrictsRendersAsItsBuildings) {
  const std::string single = out("city-mixed") + "/city", packed = out("city-packed") + "/city";
  for (const char* dir : {"city-mixed", "city-packed"}) fs::remove_all(out(dir));
  const std::string args = " --count 36 --seed 2 --layout grid --mix grammar,converted --quiet --report ";
  CliRun r = nut("city --out " + single + args + out("city-mixed") + "/report.json");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  r = nut("city --out " + packed + args + out("city-packed") + "/report.json --pack-atlases");
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;

  const nlohmann::json report = nlohmann::json::parse(testing::fileText(out("city-packed") + "/report.json"));
  for (const char* name : {"house", "residential", "highrise", "marvie_building", "pga_random_windows"})
    EXPECT_GE(report.at("sources").value(name, 0), 5) << name;
  EXPECT_GT(report.at("converted_mesh").at("triangles").get<std::size_t>(), 0u);
  auto buildings = scene::loadScene(single + "/city.json", {});
  ASSERT_TRUE(buildings) << buildings.error().message;
  ASSERT_EQ(buildings->hnis.size(), 36u);
  std::set<std::size_t> distinct;
  for (const scene::PlacedHni& hni : buildings->hnis)
    distinct.insert(std::hash<std::string_view>{}(std::string_view(
        reinterpret_cast<const char*>(hni.image->pixels.data()), hni.image->pixels.size())));
  EXPECT_EQ(distinct.size(), 36u) << "every building its own HNI";

  auto districts = scene::readCityJson(packed + "/city.json");
  ASSERT_TRUE(districts) << districts.error().message;
  EXPECT_LT(districts->buildings.size(), 36u);
  std::size_t pngBytes = 0;
  for (const scene::CityBuilding& d : districts->buildings) {
    auto png = readPng(packed + "/" + d.hni);
    ASSERT_TRUE(png) << png.error().message;
    EXPECT_TRUE(validate(png->image).ok()) << d.hni;
    pngBytes += fs::file_size(packed + "/" + d.hni);
  }
  EXPECT_FALSE(fs::exists(packed + "/b00000.png"));
  EXPECT_EQ(report.at("districts").at("png_bytes").get<std::size_t>(), pngBytes);
  EXPECT_LT(pngBytes, report.at("png_bytes").get<std::size_t>());
  EXPECT_GT(report.at("districts").at("merged_blocks").get<std::size_t>(), 0u);

  const std::string view = " --size 480x270 --eye -40,60,-60 --target 90,5,90";
  for (const std::string& city : {single, packed}) {
    r = nut("render " + city + "/city.json -o " + city + ".png" + view);
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  }
  auto a = readPng(single + ".png", PngKind::Render), b = readPng(packed + ".png", PngKind::Render);
  ASSERT_TRUE(a && b);
  auto diff = compareImages(a->image, b->image, 8);
  ASSERT_TRUE(diff) << diff.error().message;
  // Positions in the districts are whole millimetres: a window edge may move by a pixel.
  EXPECT_LT(diff->differingPct, 0.1);
  if (diff->differingPct >= 0.1) {
    EXPECT_TRUE(writePng(out("city-packed") + "/diff.png", diff->diff));
  }
}

// A misspelt command is named, with the commands there are, on one line.
TEST(MainCli, AnUnknownCommandIsNamedWithTheCommandsThereAre) {
  const CliRun r = nut("rendr samples/hni/building.png -o x.png");
  expectOneErrorLine(r, 2, "unknown command 'rendr'");
  EXPECT_NE(r.stderrText.find("info, validate, render, export-mesh, render-mesh, compare, grammar, city, convert"), std::string::npos)
      << r.stderrText;
  expectOneErrorLine(nut("--json rendr"), 2, "unknown command 'rendr'");
}

// The version is the one the project declares in its CMakeLists.txt.
TEST(MainCli, VersionIsTheProjects) {
  const std::string cmake = testing::fileText(source("CMakeLists.txt"));
  std::smatch version;
  ASSERT_TRUE(std::regex_search(cmake, version, std::regex(R"(project\(nut VERSION ([0-9.]+))"))) << cmake;
  const CliRun r = nut("--version");
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_EQ(r.stdoutText, "nut " + version[1].str() + "\n");
  EXPECT_EQ(r.stderrText, "");
}

// Usage errors exit 2, whatever the command; input that is read but invalid exits 1.
TEST(MainCli, UsageErrorsExitTwoAndInvalidInputOne) {
  const std::string facade = source("samples/hni/facade.png");
  expectOneErrorLine(nut("info"), 2, "file is required");
  expectOneErrorLine(nut("info " + facade + " --colour"), 2, "--colour");
  expectOneErrorLine(nut("render " + facade), 2, "--output is required");
  expectOneErrorLine(nut("compare " + facade + " " + facade + " --threshold 300"), 2, "--threshold");
  expectOneErrorLine(nut("render " + facade + " -o " + out("x.png") + " --size 5"), 2, "--size '5'");
  ASSERT_TRUE(writePng(out("plain.png"), greyImage(16, 4, 128)).ok());
  expectOneErrorLine(nut("info " + out("plain.png")), 1, "invalid HNI");
}

// A file is never written under a name that says another format: the command refuses the name
// before it reads anything, naming the path and the extension it writes, and writes nothing.
TEST(OutputNamesCli, ANameOfAnotherFormatIsRefusedBeforeAnyWork) {
  const std::string facade = source("samples/hni/facade.png");
  const std::string cube = source("tests/data/two_material_cube.obj");
  for (const char* name : {"refused.png", "refused.jpg", "refused.txt", "refused.stl", "refused.mtl"})
    fs::remove(out(name));
  const std::string png = " -o " + out("refused.png") + " --size 8x6";
  const struct {
    std::string args, path, expected;
  } cases[] = {
      {"render " + facade + " -o " + out("refused.jpg"), out("refused.jpg"), ".png"},
      {"render " + facade + png + " --depth " + out("refused.txt"), out("refused.txt"), ".pfm"},
      {"render " + facade + png + " --stats " + out("refused.txt"), out("refused.txt"), ".json"},
      {"render-mesh " + cube + " -o " + out("refused.jpg"), out("refused.jpg"), ".png"},
      {"render-mesh " + cube + png + " --depth " + out("refused.txt"), out("refused.txt"), ".pfm"},
      {"render-mesh " + cube + png + " --stats " + out("refused.txt"), out("refused.txt"), ".json"},
      {"compare " + facade + " " + facade + " --diff " + out("refused.jpg"), out("refused.jpg"), ".png"},
      {"export-mesh " + facade + " -o " + out("refused.stl"), out("refused.stl"), ".obj"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const CliRun r = nut(c.args);
    expectOneErrorLine(r, 2, c.path + ": ");
    EXPECT_NE(r.stderrText.find("expected a name ending in " + c.expected), std::string::npos) << r.stderrText;
    EXPECT_EQ(r.stdoutText, "");
  }
  for (const char* name : {"refused.png", "refused.jpg", "refused.txt", "refused.stl", "refused.mtl"})
    EXPECT_FALSE(fs::exists(out(name))) << name;
}

// Extensions are compared in any case: upper-case names are written as the lower-case ones are.
TEST(OutputNamesCli, ExtensionsInUpperCaseAreAccepted) {
  const std::string facade = source("samples/hni/facade.png");
  CliRun r = nut("render " + facade + " -o " + out("UPPER.PNG") + " --size 8x6 --depth " + out("UPPER.PFM") +
                 " --stats " + out("UPPER.JSON"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  auto png = readPng(out("UPPER.PNG"), PngKind::Render);
  ASSERT_TRUE(png.ok()) << png.error().message;
  EXPECT_EQ(png->image.width, 8);
  EXPECT_EQ(testing::fileText(out("UPPER.PFM")).substr(0, 7), "Pf\n8 6\n");
  EXPECT_EQ(nlohmann::json::parse(testing::fileText(out("UPPER.JSON"))).at("width").get<int>(), 8);
  r = nut("export-mesh " + facade + " -o " + out("UPPER.OBJ"));
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_TRUE(scene::readObj(out("UPPER.OBJ")).ok());
}

}  // namespace
}  // namespace nut
