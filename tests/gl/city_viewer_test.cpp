// The streaming city renderer (viewer/city_renderer.hpp) on OSMesa against the CPU scene renderer
// (scene/scene_render.hpp) of the same manifest and camera: a generated city of 60 buildings,
// streamed from its folder until settled, agrees with the CPU on at least 99.5 % of the pixels
// within 8/255 (docs/VIEWER.md); frustum culling and front-to-back order change no pixel; small
// atlas pages change no pixel; missing, truncated and foreign files are counted as failures while
// the rest of the city is drawn; the iteration heat-map agrees as the colours do. On failure
// <name>.diff.png is written to tests/gl/output/city.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <fstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <grammar/city.hpp>
#include <meshref/embree_renderer.hpp>
#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>
#include <scene/scene.hpp>
#include <scene/scene_render.hpp>
#include <viewer/city_renderer.hpp>
#include <viewer/http_fetch.hpp>
#include <viewer/render_target.hpp>

#include "gl_test_support.hpp"
#include "../glb_bytes.hpp"

namespace nut::viewer {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kBuildings = 60;
constexpr double kMinWithinPct = 99.5;

fs::path cityDir(std::size_t count = kBuildings) {
  return gltest::outputDir("city") / (count == kBuildings ? std::string("city") : "city" + std::to_string(count));
}

// The city `nut city --count N --seed 3` writes, with quick PNGs.
void writeCity(std::size_t count = kBuildings) {
  if (fs::exists(cityDir(count) / "city.json")) return;
  fs::create_directories(cityDir(count));
  std::vector<grammar::Grammar> grammars;
  std::vector<glm::dvec3> sizes;
  for (const char* name : {"marvie_building", "pga_complex_house", "pga_random_rule", "pga_random_windows"}) {
    auto g = grammar::readGrammar(std::string(NUT_SOURCE_DIR) + "/samples/grammars/" + name + ".grammar");
    ASSERT_TRUE(g) << g.error().message;
    sizes.push_back(*g->size);
    grammars.push_back(std::move(*g));
  }
  scene::CityManifest city{"city", {}};
  const auto plan = grammar::planCity(sizes, count, 3);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    auto built = grammar::buildCityBuilding(grammars[plan[i].source], plan[i]);
    ASSERT_TRUE(built) << built.error().message;
    std::string name = "b";
    name += std::to_string(i);  // not "b" + to_string: gcc 12's false -Wrestrict
    ASSERT_TRUE(writeHni((cityDir(count) / (name + ".png")).string(), built->compiled.image, {name}, PngEffort::Quick));
    city.buildings.push_back({name, name + ".png", "", built->placement.positionM, built->placement.yawDeg, built->placement.boundsM});
  }
  ASSERT_TRUE(scene::writeCityJson((cityDir(count) / "city.json").string(), city));
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
  std::vector<double> frameMs;       // every frame, the first (which builds the programs) included
  std::size_t settledAtFrame = 0;
  std::size_t maxAtlasBytes = 0;
  std::vector<std::string> failures;
  Image first;                 // the first frame, before anything is loaded
  CityFrameStats firstStats;
};

// What both renderers cast with: the exact lookup, as `nut render` by default.
RayCastOptions exactLookup() {
  RayCastOptions cast;
  cast.lookup = Lookup::Exact;
  return cast;
}

// Draws a frame from each camera of the path, then frames of the last one until the city has
// streamed in from `base` through `fetch`, then `extraFrames` more.
Streamed stream(const scene::CityManifest& city, const std::string& base, const Fetch& fetch,
                const std::vector<Camera>& path, const CityRendererOptions& options, int extraFrames = 0,
                const RayCastOptions& cast = exactLookup()) {
  Streamed out;
  const Camera& camera = path.back();
  auto context = createContext(Backend::OSMesa);
  if (!context) {
    ADD_FAILURE() << context.error().message;
    return out;
  }
  const ShaderLibrary library = ShaderLibrary::fromEnvironment();
  auto hni = HniRenderer::create(**context, library);
  if (!hni) {
    ADD_FAILURE() << hni.error().message;
    return out;
  }
  auto meshes = MeshRenderer::create(**context, library);
  if (!meshes) {
    ADD_FAILURE() << meshes.error().message;
    return out;
  }
  const Gl& gl = (*context)->gl();
  auto target = RenderTarget::create(gl, camera.width, camera.height);
  CityRenderer renderer(gl, *hni, &*meshes, city, base, fetch, options);
  const auto frame = [&](const Camera& view) {
    const auto start = std::chrono::steady_clock::now();
    target->bindCleared();
    const Status s = renderer.drawFrame(view, cast, out.stats);
    EXPECT_TRUE(s) << s.error().message;
    gl.Finish();
    out.maxAtlasBytes = std::max(out.maxAtlasBytes, out.stats.atlasBytes);
    out.frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    out.failures.insert(out.failures.end(), out.stats.newFailures.begin(), out.stats.newFailures.end());
    if (out.frameMs.size() == 1) {
      out.first = target->readColour();
      out.firstStats = out.stats;
    }
  };
  for (std::size_t f = 0; f + 1 < path.size(); ++f) frame(path[f]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do frame(camera);
  while (!renderer.settled() && std::chrono::steady_clock::now() < deadline);
  EXPECT_TRUE(renderer.settled()) << "still streaming after " << out.frameMs.size() << " frames";
  out.settledAtFrame = out.frameMs.size();
  for (int f = 0; f < extraFrames; ++f) frame(camera);
  out.image = target->readColour();
  return out;
}

scene::CityManifest manifestAt(const fs::path& path) {
  auto city = scene::readCityJson(path.string());
  EXPECT_TRUE(city) << city.error().message;
  return city ? *city : scene::CityManifest{};
}

Streamed stream(const fs::path& manifest, const Camera& camera, const CityRendererOptions& options) {
  return stream(manifestAt(manifest), manifest.parent_path().string(), localFiles(), {camera}, options);
}

Image cpuRender(const fs::path& manifest, const Camera& camera, const RayCastOptions& cast = exactLookup()) {
  auto scene = scene::loadScene(manifest.string(), {});
  if (!scene) {
    ADD_FAILURE() << scene.error().message;
    return {};
  }
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

// The issue's city of a hundred buildings, all in view from here.
Camera hundredBuildingsView() {
  Camera camera = overview();
  camera.eye = {-90, 120, -100};
  camera.target = {110, 0, 90};
  return camera;
}

TEST_F(StreamedCity, AHundredBuildingsMatchTheCpuCity) {
  writeCity(100);
  const fs::path manifest = cityDir(100) / "city.json";
  const Camera camera = hundredBuildingsView();
  const Streamed gl = stream(manifest, camera, {});
  EXPECT_EQ(gl.stats.loaded, 100u);
  EXPECT_EQ(gl.stats.culledByFrustum, 0u) << "all in view";
  expectAgree("hundred", cpuRender(manifest, camera), gl.image, kMinWithinPct);
}

// The iteration heat-map of the same view: each pixel shows the iterations of the building seen.
TEST_F(StreamedCity, HeatMapMatchesTheCpuCity) {
  writeCity(100);
  const fs::path manifest = cityDir(100) / "city.json";
  const Camera camera = hundredBuildingsView();
  RayCastOptions cast = exactLookup();
  cast.heatMap = true;
  const Streamed gl = stream(manifestAt(manifest), manifest.parent_path().string(), localFiles(), {camera}, {}, 0, cast);
  const Image cpu = cpuRender(manifest, camera, cast);
  expectAgree("hundred-heat-map", cpu, gl.image, kMinWithinPct);
  EXPECT_NE(cpu, cpuRender(manifest, camera)) << "the heat-map is not the shaded image";
}

TEST_F(StreamedCity, MatchesTheCpuCity) {
  const fs::path manifest = cityDir() / "city.json";
  const Streamed gl = stream(manifest, overview(), {});
  EXPECT_EQ(gl.stats.loaded, kBuildings);
  EXPECT_EQ(gl.stats.failed, 0u);
  EXPECT_GT(gl.frameMs.size(), 1u) << "the uploads are spread over frames";
  expectAgree("overview", cpuRender(manifest, overview()), gl.image, kMinWithinPct);
}

// Each culling test, and the order, on or off: the settled street view is the same in every pixel.
// Occlusion answers a frame late, so each case draws two frames more after settling.
TEST_F(StreamedCity, CullingAndOrderChangeNoPixel) {
  const fs::path manifest = cityDir() / "city.json";
  const scene::CityManifest city = manifestAt(manifest);
  const auto streamed = [&](const CityRendererOptions& options) {
    return stream(city, cityDir().string(), localFiles(), {street()}, options, 2);
  };
  const Streamed culled = streamed({});
  EXPECT_GT(culled.stats.culledByFrustum, kBuildings / 2) << "the street view sees less than half the city";
  EXPECT_GT(culled.stats.culledByOcclusion, 0u) << "some buildings in the view hide behind the first row";
  EXPECT_LT(culled.stats.loaded, kBuildings) << "what no frame could see was never loaded";
  CityRendererOptions everything;
  everything.frustumCulling = false;
  everything.occlusionCulling = false;
  everything.frontToBack = false;
  const Streamed all = streamed(everything);
  EXPECT_EQ(all.stats.culledByFrustum + all.stats.culledByOcclusion, 0u);
  EXPECT_EQ(all.stats.drawn, kBuildings);
  EXPECT_EQ(culled.image, all.image);
  for (const auto& [name, change] : std::vector<std::pair<std::string, void (*)(CityRendererOptions&)>>{
           {"no frustum culling", [](CityRendererOptions& o) { o.frustumCulling = false; }},
           {"no occlusion culling", [](CityRendererOptions& o) { o.occlusionCulling = false; }},
           {"no front-to-back order", [](CityRendererOptions& o) { o.frontToBack = false; }}}) {
    CityRendererOptions one;
    change(one);
    EXPECT_EQ(streamed(one).image, culled.image) << name;
  }
  RecordProperty("drawn", std::to_string(culled.stats.drawn));
  RecordProperty("culled_frustum", std::to_string(culled.stats.culledByFrustum));
  RecordProperty("culled_occlusion", std::to_string(culled.stats.culledByOcclusion));
  expectAgree("street", cpuRender(manifest, street()), culled.image, kMinWithinPct);
}

bool isBackground(const std::uint8_t* p) { return p[0] == kBackground[0] && p[1] == kBackground[1] && p[2] == kBackground[2]; }

// Where the settled city shows a building, `image` shows something: its box contains it.
long long uncovered(const Image& settled, const Image& image) {
  long long n = 0;
  for (int y = 0; y < settled.height; ++y)
    for (int x = 0; x < settled.width; ++x) n += !isBackground(settled.at(x, y)) && isBackground(image.at(x, y));
  return n;
}

TEST_F(StreamedCity, UntilItIsLoadedABuildingIsItsGreyBox) {
  const Streamed gl = stream(cityDir() / "city.json", overview(), {});
  EXPECT_EQ(gl.firstStats.loaded, 0u) << "the first frame comes before any file";
  EXPECT_EQ(gl.firstStats.proxies, kBuildings);
  EXPECT_EQ(uncovered(gl.image, gl.first), 0) << "every building's pixels are covered by its proxy";
  EXPECT_EQ(gl.stats.proxies, 0u) << "none once settled";
}

TEST_F(StreamedCity, FarBuildingsAsTheirSummaryBoxes) {
  CityRendererOptions summaries;
  summaries.summaryBelowPx = 1e6;  // every building counts as far
  const Streamed gl = stream(cityDir() / "city.json", overview(), summaries);
  EXPECT_EQ(gl.stats.asSummary, kBuildings);
  EXPECT_EQ(gl.stats.drawn, 0u) << "no building is ray-cast";
  const Streamed full = stream(cityDir() / "city.json", overview(), {});
  EXPECT_EQ(uncovered(full.image, gl.image), 0) << "each building's pixels lie inside its summary box";
  EXPECT_NE(full.image, gl.image);
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

// A budget of six 128 x 128 pages (384 KiB) for a city of 60 HNIs (about 430 KiB of pixels, more
// with the pages' waste): standing in the street, turning from looking on along it to looking
// back and again on, the atlas never exceeds the budget, pages are emptied for what comes into
// view, the buildings seen again are fetched again, and the last view is the CPU's.
TEST_F(StreamedCity, ABudgetEvictsAndReloads) {
  const fs::path manifest = cityDir() / "city.json";
  CityRendererOptions budget;
  budget.atlasPageSize = 128;
  budget.maxAtlasPages = 6;
  std::vector<Camera> path;
  for (int step = 0; step <= 24; ++step) {
    Camera c = street();
    const double turn = std::numbers::pi * (step <= 12 ? step : 24 - step) / 12.0;  // 0 -> 180 -> 0 degrees
    c.target = c.eye + 170.0 * glm::dvec3(std::cos(turn), 0.02, std::sin(turn));
    path.push_back(c);
  }
  const Streamed flown = stream(manifestAt(manifest), cityDir().string(), localFiles(), path, budget);
  EXPECT_LE(flown.maxAtlasBytes, 6u * 128u * 128u * 4u);
  EXPECT_GT(flown.stats.evicted, 0u);
  EXPECT_GT(flown.stats.refetched, 0u) << "evicted buildings seen again are fetched again";
  expectAgree("budget", cpuRender(manifest, path.back()), flown.image, kMinWithinPct);
}

// tests/gl/http_server.py on loopback, started for a test and stopped after it.
class HttpServer {
 public:
  explicit HttpServer(const fs::path& directory, const std::vector<std::string>& extra = {}) {
    int out[2];
    if (pipe(out) != 0) return;
    pid_ = fork();
    if (pid_ == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      close(out[1]);
      std::vector<std::string> args = {"python3", std::string(NUT_SOURCE_DIR) + "/tests/gl/http_server.py",
                                       "--directory", directory.string()};
      args.insert(args.end(), extra.begin(), extra.end());
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execvp("python3", argv.data());
      _exit(127);
    }
    close(out[1]);
    // The port's line, once it listens; the pipe stays open while the server runs, which may write
    // the line in more than one piece.
    output_ = out[0];
    std::string line;
    char c = 0;
    while (read(output_, &c, 1) == 1 && c != '\n') line += c;
    port_ = std::atoi(line.c_str());
  }
  ~HttpServer() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    if (output_ >= 0) close(output_);
  }
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;
  std::string url(const std::string& path) const { return "http://127.0.0.1:" + std::to_string(port_) + "/" + path; }
  bool running() const { return port_ > 0; }

 private:
  pid_t pid_ = -1;
  int output_ = -1;
  int port_ = 0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0 : values[values.size() / 2];
}

TEST_F(StreamedCity, HttpAndLocalFilesGiveTheSameFrame) {
  const HttpServer server(cityDir().parent_path());
  ASSERT_TRUE(server.running());
  const scene::CityManifest city = manifestAt(cityDir() / "city.json");
  const Streamed local = stream(city, cityDir().string(), localFiles(), {overview()}, {});
  const Streamed http = stream(city, server.url("city"), httpFetch(), {overview()}, {});
  EXPECT_EQ(http.stats.loaded, kBuildings);
  EXPECT_EQ(http.stats.bytesStreamed, local.stats.bytesStreamed);
  EXPECT_EQ(http.image, local.image);
}

TEST_F(StreamedCity, HttpErrorsAreCountedAndTheRestIsDrawn) {
  const fs::path root = gltest::outputDir("city") / "http-broken";
  fs::remove_all(root);
  fs::create_directories(root);
  fs::copy(cityDir(), root / "city");
  fs::resize_file(root / "city" / "b6.png", 100);  // truncated
  fs::remove(root / "city" / "b7.png");            // 404 from the server itself
  const HttpServer server(root, {"--status", "/city/b4.png=404", "--status", "/city/b5.png=500"});
  ASSERT_TRUE(server.running());
  scene::CityManifest city = manifestAt(root / "city" / "city.json");
  const Streamed http = stream(city, server.url("city"), httpFetch(), {overview()}, {});
  EXPECT_EQ(http.stats.failed, 4u);
  EXPECT_EQ(http.stats.loaded, kBuildings - 4);
  const auto said = [&](const std::string& text) {
    return std::any_of(http.failures.begin(), http.failures.end(),
                       [&](const std::string& f) { return f.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(said("b4: " + server.url("city/b4.png") + ": HTTP 404"));
  EXPECT_TRUE(said("b5: " + server.url("city/b5.png") + ": HTTP 500"));
  EXPECT_TRUE(said("b7: " + server.url("city/b7.png") + ": HTTP 404"));
  EXPECT_TRUE(said("b6: "));
  city.buildings.erase(city.buildings.begin() + 4, city.buildings.begin() + 8);
  ASSERT_TRUE(scene::writeCityJson((root / "city" / "rest.json").string(), city));
  expectAgree("http-broken", cpuRender(root / "city" / "rest.json", overview()), http.image, kMinWithinPct);
}

// A server that waits half a second before each file, seen from the street (ten buildings to
// fetch): the frames while they stream in take at most twice the frames after (medians; the first
// frame, which builds the programs, left out), and nine in ten take less than one download's
// wait, which a frame that waited for a download could not.
TEST_F(StreamedCity, ASlowServerDoesNotSlowTheFrames) {
  constexpr double kDelaySeconds = 0.5;
  const HttpServer server(cityDir().parent_path(), {"--delay", std::to_string(kDelaySeconds)});
  ASSERT_TRUE(server.running());
  const Streamed http =
      stream(manifestAt(cityDir() / "city.json"), server.url("city"), httpFetch(), {street()}, {}, 10);
  ASSERT_GT(http.settledAtFrame, 10u) << "the downloads should take many frames";
  std::vector<double> streaming(http.frameMs.begin() + 1, http.frameMs.begin() + static_cast<std::ptrdiff_t>(http.settledAtFrame));
  const std::vector<double> loaded(http.frameMs.begin() + static_cast<std::ptrdiff_t>(http.settledAtFrame), http.frameMs.end());
  EXPECT_LE(median(streaming), 2.0 * median(loaded))
      << "streaming " << median(streaming) << " ms, loaded " << median(loaded) << " ms";
  std::sort(streaming.begin(), streaming.end());
  const double ninetieth = streaming[streaming.size() * 9 / 10];
  EXPECT_LT(ninetieth, 1000 * kDelaySeconds) << "frames wait for downloads";
  RecordProperty("streaming_median_ms", std::to_string(median(streaming)));
  RecordProperty("streaming_90th_ms", std::to_string(ninetieth));
  RecordProperty("loaded_median_ms", std::to_string(median(loaded)));
}

// A converted street (`nut convert samples/obj/street.obj -o DIR/ --complement-format obj`): four
// HNIs, each with its complementary mesh, which the viewer fetches with the HNI and draws in the
// same depth buffer; the settled frame agrees with the CPU scene render (Embree for the meshes),
// and with the frame of the same complements written as binary glTF.
TEST_F(StreamedCity, ComplementaryMeshesAreDrawnWithTheirBuildings) {
  if (!NUT_HAVE_CONVERTER) GTEST_SKIP() << "this build has no converter (NUT_BUILD_CONVERTER=OFF)";
  const fs::path dir = gltest::outputDir("city") / "street";
  fs::remove_all(dir);
  ASSERT_EQ(std::system((std::string(NUT_CLI_PATH) + " convert " + NUT_SOURCE_DIR + "/samples/obj/street.obj -o " +
                         dir.string() + "/ --quiet --png-effort small --complement-format obj")
                            .c_str()),
            0);
  const fs::path manifest = dir / "city.json";
  auto scene = scene::loadScene(manifest.string(), {});
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_FALSE(scene->meshes.empty());
  const Camera camera = fitCamera(scene->bounds, 480, 270);
  const Streamed gl = stream(manifest, camera, {});
  EXPECT_EQ(gl.stats.loaded, scene->hnis.size());
  auto traced = meshref::traceMeshes(scene->meshPointers());
  ASSERT_TRUE(traced) << traced.error().message;
  RayCastOptions cast;
  cast.lookup = Lookup::Exact;
  const Image cpu = scene::SceneRenderer(scene->hnis, std::move(*traced)).render(camera, cast).colour;
  expectAgree("street-complements", cpu, gl.image, kMinWithinPct);
  // The meshes are part of the picture: the HNIs alone give another one.
  EXPECT_NE(scene::SceneRenderer(scene->hnis, nullptr).render(camera, cast).colour, gl.image);

  // The same complements as binary glTF: the scene and the viewer read them by their extension.
  scene::CityManifest glbCity = manifestAt(manifest);
  for (scene::CityBuilding& b : glbCity.buildings) {
    if (b.complement.empty()) continue;
    std::vector<std::string> warnings;
    auto mesh = scene::readObjMesh((dir / b.complement).string(), warnings);
    ASSERT_TRUE(mesh) << mesh.error().message;
    b.complement = fs::path(b.complement).replace_extension(".glb").string();
    const std::vector<std::uint8_t> glb = testing::meshAsGlb(*mesh);
    std::ofstream(dir / b.complement, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()),
                                                              static_cast<std::streamsize>(glb.size()));
  }
  const fs::path glbManifest = dir / "city-glb.json";
  ASSERT_TRUE(scene::writeCityJson(glbManifest.string(), glbCity));
  auto glbScene = scene::loadScene(glbManifest.string(), {});
  ASSERT_TRUE(glbScene) << glbScene.error().message;
  ASSERT_EQ(glbScene->meshes.size(), scene->meshes.size());
  for (std::size_t m = 0; m < scene->meshes.size(); ++m)
    EXPECT_EQ(glbScene->meshes[m].triangles.size(), scene->meshes[m].triangles.size());
  const Streamed glbGl = stream(glbManifest, camera, {});
  EXPECT_EQ(glbGl.stats.failed, 0u);
  expectAgree("street-complements-glb", gl.image, glbGl.image, kMinWithinPct);
}

// The generated district converted with levels of its complements (`nut convert
// tests/data/lod2_district_seed1.obj -o DIR/ --complement-levels 3`). Under --lod auto the viewer
// draws each complement at the level `nut render --lod auto` picks on the cpu: from four times the
// fitted distance it fetches the coarse levels only, fewer bytes and triangles than at full detail,
// and agrees with the cpu scene at those levels; coming near after that, it fetches the finer
// levels the view wants and agrees with the cpu again.
TEST_F(StreamedCity, ComplementLevelsFollowTheCamera) {
  if (!NUT_HAVE_CONVERTER) GTEST_SKIP() << "this build has no converter (NUT_BUILD_CONVERTER=OFF)";
  const fs::path dir = gltest::outputDir("city") / "district-levels";
  fs::remove_all(dir);
  ASSERT_EQ(std::system((std::string(NUT_CLI_PATH) + " convert " + NUT_SOURCE_DIR +
                         "/tests/data/lod2_district_seed1.obj -o " + dir.string() +
                         "/ --quiet --png-effort small --complement-levels 3")
                            .c_str()),
            0);
  const fs::path manifest = dir / "city.json";
  auto scene = scene::loadScene(manifest.string(), {});
  ASSERT_TRUE(scene) << scene.error().message;
  std::size_t withLevels = 0;
  for (const auto& levels : scene->coarser) withLevels += levels.empty() ? 0 : 1;
  ASSERT_GE(withLevels, 3u);

  // Near: a third of the fitted distance, where most complements are drawn whole.
  const Camera fitted = fitCamera(scene->bounds, 480, 270);
  Camera near = fitted, far = fitted;
  near.eye = fitted.target + (fitted.eye - fitted.target) / 3.0;
  near.nearM = 0.5;
  far.eye = fitted.target + 4.0 * (fitted.eye - fitted.target);
  far.farM *= 4.0;
  RayCastOptions cast = exactLookup();
  cast.lodAuto = true;
  const auto cpu = [&](const Camera& camera) {
    auto traced = meshref::traceMeshes(scene->meshPointers(camera));
    EXPECT_TRUE(traced) << traced.error().message;
    return scene::SceneRenderer(scene->hnis, std::move(*traced)).render(camera, cast).colour;
  };
  // Every building drawn, so that a frame's complement triangles are the sum of the levels picked.
  const auto picked = [&](const std::vector<const TriangleMesh*>& meshes) {
    std::size_t triangles = 0;
    for (const TriangleMesh* mesh : meshes) triangles += mesh->triangles.size();
    return triangles;
  };
  const std::size_t full = picked(scene->meshPointers()), atFar = picked(scene->meshPointers(far)),
                    atNear = picked(scene->meshPointers(near));
  ASSERT_LT(atFar, atNear);
  CityRendererOptions all;
  all.frustumCulling = false;
  all.occlusionCulling = false;
  const scene::CityManifest city = manifestAt(manifest);
  const std::string base = dir.string();

  const Streamed farLevels = stream(city, base, localFiles(), {far}, all, 0, cast);
  const Streamed farFull = stream(city, base, localFiles(), {far}, all, 0, exactLookup());
  EXPECT_EQ(farLevels.stats.failed, 0u);
  expectAgree("district-levels-far", cpu(far), farLevels.image, kMinWithinPct);
  EXPECT_EQ(farLevels.stats.complementTriangles, atFar);
  EXPECT_EQ(farFull.stats.complementTriangles, full);
  EXPECT_LT(farLevels.stats.bytesStreamed, farFull.stats.bytesStreamed);
  RecordProperty("far_complement_triangles", std::to_string(atFar) + " of " + std::to_string(full));
  RecordProperty("far_bytes_streamed",
                 std::to_string(farLevels.stats.bytesStreamed) + " of " + std::to_string(farFull.stats.bytesStreamed));

  // From far, then near: the finer levels are fetched as the view wants them.
  const Streamed farThenNear = stream(city, base, localFiles(), {far, near}, all, 0, cast);
  expectAgree("district-levels-near", cpu(near), farThenNear.image, kMinWithinPct);
  EXPECT_EQ(farThenNear.stats.complementTriangles, atNear);
  RecordProperty("near_complement_triangles", std::to_string(atNear));
}

// Runs nut-viewer with `args`; its exit status.
int runViewer(const std::string& args) {
  return std::system((std::string(NUT_VIEWER_PATH) + " " + args + " 2>/dev/null").c_str());
}

// nut-viewer's window (GLFW, under xvfb-run in ctest: city_viewer_window_xvfb) shows the city as
// the headless viewer draws it, with the overlay over its corner: outside the overlay's rectangle
// (which the stats report) every pixel equals the headless screenshot's, and inside it most differ.
TEST_F(StreamedCity, TheWindowShowsTheCityAndTheOverlay) {
  if (std::getenv("DISPLAY") == nullptr)
    GTEST_SKIP() << "no display: ctest runs this case again under xvfb-run (city_viewer_window_xvfb)";
  const fs::path dir = gltest::outputDir("city");
  const std::string path = (dir / "overview.json").string();
  std::ofstream(path) << R"({"fov_deg": 40, "keyframes": [{"eye": [-60, 90, -70], "target": [110, 0, 70]}]})";
  const std::string common = (cityDir() / "city.json").string() + " --size 640x360 --camera-path " + path;
  ASSERT_EQ(runViewer(common + " --frames 2 --screenshot " + (dir / "window.png").string() + " --stats " +
                      (dir / "window.json").string()),
            0);
  ASSERT_EQ(runViewer(common + " --headless --screenshot " + (dir / "headless.png").string()), 0);
  auto window = readPng((dir / "window.png").string(), PngKind::Render);
  auto headless = readPng((dir / "headless.png").string(), PngKind::Render);
  ASSERT_TRUE(window && headless);
  const auto stats = readTextFile((dir / "window.json").string());
  ASSERT_TRUE(stats);
  const auto overlayAt = stats->find("\"overlay\"");
  ASSERT_NE(overlayAt, std::string::npos);
  double x = 0, y = 0, w = 0, h = 0;
  ASSERT_EQ(std::sscanf(stats->c_str() + stats->find('[', overlayAt), "[ %lf , %lf , %lf , %lf", &x, &y, &w, &h), 4);
  ASSERT_GT(w, 50);
  ASSERT_GT(h, 50);
  long long outsideDiffer = 0, inside = 0, insideDiffer = 0;
  for (int py = 0; py < 360; ++py)
    for (int px = 0; px < 640; ++px) {
      const bool differ = !std::equal(window->image.at(px, py), window->image.at(px, py) + 3, headless->image.at(px, py));
      const bool inOverlay = px >= x && px < x + w && py >= y && py < y + h;
      inside += inOverlay;
      (inOverlay ? insideDiffer : outsideDiffer) += differ;
    }
  EXPECT_EQ(outsideDiffer, 0);
  EXPECT_GT(insideDiffer, inside / 2);
}

}  // namespace
}  // namespace nut::viewer
