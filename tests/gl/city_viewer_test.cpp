// The streaming city renderer (viewer/city_renderer.hpp) on OSMesa against the CPU scene renderer
// (scene/scene_render.hpp) of the same manifest and camera: a generated city of 60 buildings,
// streamed from its folder until settled, agrees with the CPU on at least 99.5 % of the pixels
// within 8/255 (docs/VIEWER.md); frustum culling and front-to-back order change no pixel; small
// atlas pages change no pixel; missing, truncated and foreign files are counted as failures while
// the rest of the city is drawn. On failure <name>.diff.png is written to tests/gl/output/city.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <grammar/city.hpp>
#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>
#include <scene/scene.hpp>
#include <scene/scene_render.hpp>
#include <viewer/city_renderer.hpp>
#include <viewer/render_target.hpp>

#include "gl_test_support.hpp"

namespace nut::viewer {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kBuildings = 60;
constexpr double kMinWithinPct = 99.5;

fs::path cityDir() { return gltest::outputDir("city") / "city"; }

// The city `nut city --count 60 --seed 3` writes, with quick PNGs.
void writeCity() {
  if (fs::exists(cityDir() / "city.json")) return;
  fs::create_directories(cityDir());
  std::vector<grammar::Grammar> grammars;
  for (const char* name : {"marvie_building", "pga_complex_house", "pga_random_rule", "pga_random_windows"}) {
    auto g = grammar::readGrammar(std::string(NUT_SOURCE_DIR) + "/samples/grammars/" + name + ".grammar");
    ASSERT_TRUE(g) << g.error().message;
    grammars.push_back(std::move(*g));
  }
  scene::CityManifest city{"city", {}};
  const auto plan = grammar::planCity(grammars, kBuildings, 3);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    auto built = grammar::buildCityBuilding(grammars[plan[i].grammar], plan[i]);
    ASSERT_TRUE(built) << built.error().message;
    std::string name = "b";
    name += std::to_string(i);  // not "b" + to_string: gcc 12's false -Wrestrict
    ASSERT_TRUE(writeHni((cityDir() / (name + ".png")).string(), built->compiled.image, {name}, PngEffort::Quick));
    city.buildings.push_back({name, name + ".png", "", built->positionM, built->yawDeg, built->boundsM});
  }
  ASSERT_TRUE(scene::writeCityJson((cityDir() / "city.json").string(), city));
}

Camera overview() {
  Camera c;
  c.width = 320, c.height = 180;
  c.eye = {-60, 90, -70};
  c.target = {110, 0, 70};
  c.nearM = 0.5, c.farM = 1000;
  return c;
}

// At street level halfway along the first street, looking on along it: most of the city is
// behind or beside the view.
Camera street() {
  Camera c = overview();
  c.eye = {130, 3, 8};
  c.target = {300, 6, 8};
  return c;
}

struct Streamed {
  Image image;
  CityFrameStats stats;
  int frames = 0;
};

// Draws frames of one camera until the city has streamed in.
Streamed stream(const fs::path& manifest, const Camera& camera, const CityRendererOptions& options) {
  Streamed out;
  auto context = createContext(Backend::OSMesa);
  if (!context) {
    ADD_FAILURE() << context.error().message;
    return out;
  }
  const ShaderLibrary library = ShaderLibrary::fromEnvironment();
  auto hni = HniRenderer::create(**context, library);
  auto city = scene::readCityJson(manifest.string());
  if (!hni || !city) {
    ADD_FAILURE() << "renderer or manifest";
    return out;
  }
  const Gl& gl = (*context)->gl();
  auto target = RenderTarget::create(gl, camera.width, camera.height);
  CityRenderer renderer(gl, *hni, *city, manifest.parent_path().string(), localFiles(), options);
  RayCastOptions cast;
  cast.lookup = Lookup::Exact;
  do {
    target->bind();
    gl.ClearColor(kBackground[0] / 255.0f, kBackground[1] / 255.0f, kBackground[2] / 255.0f, 1.0f);
    gl.ClearDepth(1.0);
    gl.DepthMask(GL_TRUE);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const Status s = renderer.drawFrame(camera, cast, out.stats);
    EXPECT_TRUE(s) << s.error().message;
    ++out.frames;
  } while (!renderer.settled() && out.frames < 5000);
  EXPECT_TRUE(renderer.settled()) << "still streaming after " << out.frames << " frames";
  out.image = target->readColour();
  return out;
}

Image cpuRender(const fs::path& manifest, const Camera& camera) {
  auto scene = scene::loadScene(manifest.string(), {});
  if (!scene) {
    ADD_FAILURE() << scene.error().message;
    return {};
  }
  RayCastOptions cast;
  cast.lookup = Lookup::Exact;
  return scene::SceneRenderer(scene->hnis, nullptr).render(camera, cast).colour;
}

void expectAgree(const std::string& name, const Image& expected, const Image& actual, double minWithinPct) {
  auto diff = compareImages(expected, actual, 8);
  ASSERT_TRUE(diff) << diff.error().message;
  EXPECT_GE(100.0 - diff->differingPct, minWithinPct) << name;
  if (100.0 - diff->differingPct < minWithinPct)
    (void)writePng((gltest::outputDir("city") / (name + ".diff.png")).string(), diff->diff);
}

struct StreamedCity : ::testing::Test {
  void SetUp() override { writeCity(); }
};

TEST_F(StreamedCity, MatchesTheCpuCity) {
  const fs::path manifest = cityDir() / "city.json";
  const Streamed gl = stream(manifest, overview(), {});
  EXPECT_EQ(gl.stats.loaded, kBuildings);
  EXPECT_EQ(gl.stats.failed, 0u);
  EXPECT_GT(gl.frames, 1) << "the uploads are spread over frames";
  expectAgree("overview", cpuRender(manifest, overview()), gl.image, kMinWithinPct);
}

TEST_F(StreamedCity, CullingAndOrderChangeNoPixel) {
  const fs::path manifest = cityDir() / "city.json";
  const Streamed culled = stream(manifest, street(), {});
  EXPECT_GT(culled.stats.culledByFrustum, kBuildings / 2) << "the street view sees less than half the city";
  EXPECT_LT(culled.stats.loaded, kBuildings) << "what no frame could see was never loaded";
  CityRendererOptions everything;
  everything.frustumCulling = false;
  everything.frontToBack = false;
  const Streamed all = stream(manifest, street(), everything);
  EXPECT_EQ(all.stats.culledByFrustum, 0u);
  EXPECT_EQ(all.stats.drawn, kBuildings);
  EXPECT_EQ(culled.image, all.image);
  expectAgree("street", cpuRender(manifest, street()), culled.image, kMinWithinPct);
}

TEST_F(StreamedCity, SmallAtlasPagesChangeNoPixel) {
  const fs::path manifest = cityDir() / "city.json";
  CityRendererOptions small;
  small.atlasPageSize = 256;
  small.maxAtlasPages = 64;
  const Streamed paged = stream(manifest, overview(), small);
  EXPECT_GT(paged.stats.atlasBytes, 256u * 256u * 4u) << "more than one page";
  EXPECT_EQ(paged.image, stream(manifest, overview(), {}).image);
}

TEST_F(StreamedCity, BrokenFilesAreCountedAndTheRestIsDrawn) {
  const fs::path broken = gltest::outputDir("city") / "broken";
  fs::remove_all(broken);
  fs::copy(cityDir(), broken);
  fs::remove(broken / "b1.png");                                     // missing
  fs::resize_file(broken / "b2.png", fs::file_size(broken / "b2.png") / 2);  // truncated
  ASSERT_TRUE(writePng((broken / "b3.png").string(), Image(8, 8)));  // a PNG, not an HNI
  const Streamed gl = stream(broken / "city.json", overview(), {});
  EXPECT_EQ(gl.stats.failed, 3u);
  EXPECT_EQ(gl.stats.loaded, kBuildings - 3);
  // The CPU draws the manifest without the three.
  auto city = scene::readCityJson((broken / "city.json").string());
  ASSERT_TRUE(city);
  city->buildings.erase(city->buildings.begin() + 1, city->buildings.begin() + 4);
  ASSERT_TRUE(scene::writeCityJson((broken / "rest.json").string(), *city));
  expectAgree("broken", cpuRender(broken / "rest.json", overview()), gl.image, kMinWithinPct);
}

}  // namespace
}  // namespace nut::viewer
