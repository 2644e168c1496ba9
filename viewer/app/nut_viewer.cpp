// nut-viewer CITY.json --headless: streams a city manifest into the GL ray caster along a camera
// path, frame by frame, and writes the last frame and per-frame statistics (docs/VIEWER.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <nut/camera.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>
#include <viewer/city_renderer.hpp>
#include <viewer/context.hpp>
#include <viewer/http_fetch.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/post_process.hpp>
#include <viewer/render_target.hpp>
#include <viewer/shader_library.hpp>
#include <viewer/web_export.hpp>

#include "viewer_window.hpp"

namespace {

constexpr int kOk = 0, kInvalid = 1, kUsage = 2;

int fail(const std::string& message, int code) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  return code;
}

struct ViewerOptions {
  std::string city, size = "1280x720", cameraPath, screenshot, stats, gl = "osmesa", lookup = "exact", exportWeb;
  int frames = 0, threads = 2, atlasPage = 4096, hold = 0;  // frames 0: one headless, until closed in a window
  double settleSeconds = 30, budgetMb = 1024, lodPx = 0, summaryPx = 0;
  std::string lod = "off";
  bool headless = false, fxaa = false, heatMap = false, noFrustumCulling = false, noOcclusionCulling = false,
       noFrontToBack = false, noProxies = false;
  std::optional<bool> ground;  // default: in the window, not headless
};

struct Keyframe {
  glm::dvec3 eye{0.0}, target{0.0};
};

// A camera path: {"fov_deg": 40, "keyframes": [{"eye": [x, y, z], "target": [x, y, z]}, ...]}.
nut::Result<std::pair<double, std::vector<Keyframe>>> readCameraPath(const std::string& path) {
  auto text = nut::readTextFile(path);
  if (!text) return text.error();
  const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return nut::Error{path + ": not a JSON object"};
  double fov = 40;
  if (j.contains("fov_deg")) {
    if (!j["fov_deg"].is_number() || !(j["fov_deg"].get<double>() > 1 && j["fov_deg"].get<double>() < 170))
      return nut::Error{path + ": \"fov_deg\" must be a number between 1 and 170"};
    fov = j["fov_deg"].get<double>();
  }
  if (!j.contains("keyframes") || !j["keyframes"].is_array() || j["keyframes"].empty())
    return nut::Error{path + ": \"keyframes\" must be a non-empty array"};
  std::vector<Keyframe> keys;
  for (const nlohmann::json& k : j["keyframes"]) {
    const std::string where = path + ": keyframe " + std::to_string(keys.size());
    Keyframe key;
    for (const auto& [name, out] : {std::pair<const char*, glm::dvec3*>{"eye", &key.eye}, {"target", &key.target}}) {
      if (!k.is_object() || !k.contains(name) || !k[name].is_array() || k[name].size() != 3)
        return nut::Error{where + ": \"" + name + "\" must be three numbers"};
      for (int a = 0; a < 3; ++a) {
        const nlohmann::json& v = k[name][static_cast<std::size_t>(a)];
        if (!v.is_number() || !std::isfinite(v.get<double>()))
          return nut::Error{where + ": \"" + name + "\" must be three finite numbers"};
        (*out)[a] = v.get<double>();
      }
    }
    if (glm::length(key.target - key.eye) <= 0) return nut::Error{where + ": eye and target coincide"};
    keys.push_back(key);
  }
  return std::make_pair(fov, keys);
}

// The city's box from the manifest: the bounds it gives, else the positions.
nut::WorldBox manifestBounds(const nut::scene::CityManifest& city) {
  nut::WorldBox box{glm::dvec3(1e300), glm::dvec3(-1e300)};
  for (const auto& b : city.buildings) {
    const nut::WorldBox one = b.boundsM ? *b.boundsM : nut::WorldBox{b.positionM, b.positionM + 10.0};
    box.min = glm::min(box.min, one.min);
    box.max = glm::max(box.max, one.max);
  }
  return box;
}

// --export-web DIR: the browser viewer written beside a city (docs/WEB.md).
int exportWebPage(const std::string& dir) {
  auto written = nut::viewer::exportWeb(dir, nut::viewer::ShaderLibrary::fromEnvironment());
  if (!written) return fail(written.error().message, kUsage);
  std::fprintf(stderr, "nut-viewer: wrote the browser viewer (%d files) to %s\n", *written, dir.c_str());
  if (!std::filesystem::exists(std::filesystem::path(dir) / "city.json"))
    std::fprintf(stderr, "nut-viewer: %s has no city.json: open index.html?city=URL, or put a city there\n", dir.c_str());
  std::fprintf(stderr, "serve it with:  cd %s && python3 -m http.server 8000   then open http://localhost:8000/\n",
               dir.c_str());
  return kOk;
}

int run(const ViewerOptions& o) {
  if (!o.exportWeb.empty()) return exportWebPage(o.exportWeb);
  if (o.city.empty()) return fail("a city manifest is required (or --export-web DIR; see nut-viewer --help)", kUsage);
  int width = 0, height = 0;
  char tail = 0;
  if (std::sscanf(o.size.c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 1 || height < 1 || width > 16384 ||
      height > 16384)
    return fail("--size '" + o.size + "': expected WxH, 1 to 16384 each", kUsage);
  // A path or a URL: the manifest through the same fetch as its buildings.
  const nut::viewer::Fetch fetch = nut::viewer::fetchFor(o.city);
  auto manifestBytes = fetch(o.city);
  if (!manifestBytes) return fail(manifestBytes.error().message, kUsage);
  auto city = nut::scene::parseCityJson(std::string(manifestBytes->begin(), manifestBytes->end()), o.city);
  if (!city) return fail(city.error().message, kInvalid);
  const std::size_t slash = o.city.rfind('/');
  const std::string base = slash == std::string::npos ? "." : o.city.substr(0, slash);
  if (city->buildings.empty()) return fail(o.city + ": no buildings", kInvalid);

  std::vector<Keyframe> keys;
  double fov = 40;
  if (!o.cameraPath.empty()) {
    auto path = readCameraPath(o.cameraPath);
    if (!path) return fail(path.error().message, kInvalid);
    fov = path->first;
    keys = path->second;
  }
  const nut::WorldBox box = manifestBounds(*city);
  const nut::Camera fitted = nut::fitCamera(box, width, height, fov);
  if (keys.empty()) keys.push_back({fitted.eye, fitted.target});
  const double reach = glm::length(box.size()) + 1.0;
  const auto cameraAt = [&](double s) {  // s in [0, 1] along the path
    const double k = s * static_cast<double>(keys.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(k), keys.size() - 1);
    const std::size_t j = std::min(i + 1, keys.size() - 1);
    const double f = k - static_cast<double>(i);
    nut::Camera c = fitted;
    c.eye = glm::mix(keys[i].eye, keys[j].eye, f);
    c.target = glm::mix(keys[i].target, keys[j].target, f);
    const double far = glm::length(c.eye - box.centre()) + reach;
    c.nearM = std::max(0.05, far * 1e-5);
    c.farM = far;
    return c;
  };

  nut::viewer::CityRendererOptions options;
  options.frustumCulling = !o.noFrustumCulling;
  options.frontToBack = !o.noFrontToBack;
  options.occlusionCulling = !o.noOcclusionCulling;
  options.loaderThreads = std::max(1, o.threads);
  options.atlasPageSize = o.atlasPage;
  const double pageMb = 4.0 * o.atlasPage * o.atlasPage / (1 << 20);
  options.maxAtlasPages = std::max(1, static_cast<int>(o.budgetMb / pageMb));
  options.proxies = !o.noProxies;
  options.summaryBelowPx = o.summaryPx;
  options.ground = o.ground.value_or(!o.headless);
  nut::RayCastOptions cast;
  cast.lookup = o.lookup == "exact" ? nut::Lookup::Exact : nut::Lookup::Heuristic;
  cast.lodPx = o.lodPx;
  cast.lodAuto = o.lod == "auto";
  cast.heatMap = o.heatMap;
  if (!o.headless)
    return nut::viewer::runWindow(
        {*city, base, fetch, options, cast, cameraAt(0.0), o.frames, o.fxaa, o.screenshot, o.stats});

  auto backend = nut::viewer::parseBackend(o.gl);
  if (!backend) return fail(backend.error().message, kUsage);
  auto context = nut::viewer::createContext(*backend);
  if (!context) return fail("GL: " + context.error().message, kUsage);
  const nut::viewer::ShaderLibrary library = nut::viewer::ShaderLibrary::fromEnvironment();
  auto hni = nut::viewer::HniRenderer::create(**context, library);
  if (!hni) return fail(hni.error().message, kInvalid);
  const nut::viewer::Gl& gl = (*context)->gl();
  auto target = nut::viewer::RenderTarget::create(gl, width, height);
  if (!target) return fail(target.error().message, kInvalid);
  // --fxaa: the screenshot is the last frame anti-aliased into a second target.
  std::optional<nut::viewer::Fxaa> fxaa;
  std::optional<nut::viewer::RenderTarget> smoothed;
  if (o.fxaa) {
    auto created = nut::viewer::Fxaa::create(**context, library);
    if (!created) return fail(created.error().message, kInvalid);
    fxaa.emplace(std::move(*created));
    auto second = nut::viewer::RenderTarget::create(gl, width, height);
    if (!second) return fail(second.error().message, kInvalid);
    smoothed.emplace(std::move(*second));
  }

  auto meshes = nut::viewer::MeshRenderer::create(**context, library);
  if (!meshes) return fail(meshes.error().message, kInvalid);
  nut::viewer::CityRenderer renderer(gl, *hni, &*meshes, *city, base, fetch, options);

  nlohmann::json frames = nlohmann::json::array();
  std::vector<std::string> failures;
  nut::viewer::CityFrameStats stats;
  const auto drawOne = [&](const nut::Camera& camera, const char* phase) -> nut::Status {
    const auto start = std::chrono::steady_clock::now();
    target->bindCleared();
    if (nut::Status s = renderer.drawFrame(camera, cast, stats); !s) return s;
    gl.Finish();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    for (const std::string& f : stats.newFailures) {
      std::fprintf(stderr, "warning: %s\n", f.c_str());
      failures.push_back(f);
    }
    frames.push_back({{"ms", ms},
                      {"phase", phase},
                      {"drawn", stats.drawn},
                      {"culled_frustum", stats.culledByFrustum},
                      {"culled_occlusion", stats.culledByOcclusion},
                      {"waiting", stats.waiting},
                      {"proxies", stats.proxies},
                      {"as_summary", stats.asSummary},
                      {"complement_triangles", stats.complementTriangles},
                      {"uploaded", stats.uploaded},
                      {"evicted", stats.evicted},
                      {"refetched", stats.refetched},
                      {"over_budget", stats.overBudget},
                      {"loaded", stats.loaded},
                      {"bytes_streamed", stats.bytesStreamed}});
    return nut::Ok{};
  };
  const int pathFrames = std::max(1, o.frames);
  for (int f = 0; f < pathFrames; ++f)
    if (nut::Status s = drawOne(cameraAt(pathFrames > 1 ? f / double(pathFrames - 1) : 1.0), "path"); !s)
      return fail(s.error().message, kInvalid);
  // The last view until everything it needs has streamed in, so the screenshot is complete.
  const auto settleStart = std::chrono::steady_clock::now();
  while (!renderer.settled()) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - settleStart).count() > o.settleSeconds)
      return fail("the city did not finish streaming in " + std::to_string(o.settleSeconds) + " s", kInvalid);
    if (nut::Status s = drawOne(cameraAt(1.0), "settling"); !s) return fail(s.error().message, kInvalid);
  }
  for (int f = 0; f < o.hold; ++f)
    if (nut::Status s = drawOne(cameraAt(1.0), "holding"); !s) return fail(s.error().message, kInvalid);
  if (fxaa) fxaa->apply(*target, *smoothed);
  if (!o.screenshot.empty())
    if (nut::Status s = nut::writePng(o.screenshot, (fxaa ? *smoothed : *target).readColour()); !s)
      return fail(s.error().message, kUsage);
  if (!o.stats.empty()) {
    const nlohmann::json j = {{"city", o.city},
                              {"width", width},
                              {"height", height},
                              {"known", stats.known},
                              {"loaded", stats.loaded},
                              {"failed", stats.failed},
                              {"failures", failures},
                              {"bytes_streamed", stats.bytesStreamed},
                              {"atlas_bytes", stats.atlasBytes},
                              {"frames", frames}};
    if (nut::Status s = nut::writeTextFile(o.stats, j.dump(2) + "\n"); !s) return fail(s.error().message, kUsage);
  }
  std::fprintf(stderr, "nut-viewer: %zu of %zu buildings loaded, %zu failed, %zu bytes streamed, %zu frames\n",
               stats.loaded, stats.known, stats.failed, stats.bytesStreamed, frames.size());
  return kOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nut-viewer: stream a PNG city (city.json) into the GL ray caster"};
  ViewerOptions o;
  app.add_option("city", o.city, "City manifest: a path, or an http(s):// URL (its buildings are fetched beside it)");
  app.add_option("--export-web", o.exportWeb,
                 "Write the browser viewer (an HTML page and its modules, docs/WEB.md) into this folder, usually "
                 "the city's, and exit");
  app.add_flag("--headless", o.headless, "Render offscreen (OSMesa or EGL) instead of in a window");
  app.add_option("--size", o.size, "Frame size WxH")->capture_default_str();
  app.add_option("--camera-path", o.cameraPath, "Camera path JSON (docs/VIEWER.md); default: the city fitted");
  app.add_option("--frames", o.frames,
                 "Frames along the camera path (headless; default 1), or before the window closes itself")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--screenshot", o.screenshot,
                 "Write the last frame (PNG), once its view has streamed in; in a window, with the overlay");
  app.add_option("--stats", o.stats, "Write per-frame statistics (JSON)");
  app.add_option("--gl", o.gl, "Headless GL: osmesa (CPU, llvmpipe) or egl (a GPU)")
      ->check(CLI::IsMember({"osmesa", "egl"}))
      ->capture_default_str();
  app.add_option("--lookup", o.lookup, "Metadata lookup: exact or heuristic")
      ->check(CLI::IsMember({"exact", "heuristic"}))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "Loader threads")->capture_default_str()->check(CLI::Range(1, 64));
  app.add_option("--hold", o.hold, "Headless: frames of the last view drawn after it has settled (timing)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--settle-seconds", o.settleSeconds, "Longest wait for the last view to stream in")
      ->capture_default_str();
  app.add_option("--budget", o.budgetMb,
                 "Atlas memory in MiB: whole pages, at least one; the least recently seen are emptied when full")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--atlas-page", o.atlasPage, "Atlas page side in texels")
      ->capture_default_str()
      ->check(CLI::Range(64, 16384));
  app.add_option("--lod", o.lod,
                 "auto: summaries where the HNIs' measured footprints allow (nut grammar --lod), and each "
                 "complementary mesh as the coarsest of its levels (nut convert --complement-levels) whose error "
                 "spans under a pixel, each level fetched when first wanted")
      ->check(CLI::IsMember({"off", "auto"}))
      ->capture_default_str();
  app.add_option("--lod-px", o.lodPx, "Summaries for redirection cells below this many pixels (0: full detail)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--summary-px", o.summaryPx,
                 "Draw a building whose largest side spans fewer pixels as its summary box (0: never)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--fxaa", o.fxaa, "Anti-alias the frame with FXAA (a toggle in the window)");
  app.add_flag("--heat-map", o.heatMap,
               "Draw each surface in the colour of the traversal iterations its ray took (a toggle in the window)");
  app.add_flag("--ground,!--no-ground", o.ground, "A ground plane under the city (default: in the window only)");
  app.add_flag("--no-proxies", o.noProxies, "Draw nothing for buildings not loaded yet (default: a grey box)");
  app.add_flag("--no-frustum-culling", o.noFrustumCulling, "Draw buildings outside the view too");
  app.add_flag("--no-occlusion-culling", o.noOcclusionCulling, "Draw buildings hidden behind others too");
  app.add_flag("--no-front-to-back", o.noFrontToBack, "Draw in manifest order instead of nearest first");
  app.footer(
      "Examples:\n  nut city --count 100 --out city100 && nut-viewer city100/city.json\n"
      "  nut-viewer city100/city.json --headless --size 1280x720 --screenshot shot.png --stats stats.json\n"
      "  nut-viewer --export-web city100 && cd city100 && python3 -m http.server 8000   # a browser at :8000\n\n"
      "Exit status: 0 success, 1 invalid input, 2 usage error or a file that cannot be read or written.");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return kOk;
  } catch (const CLI::ParseError& e) {
    return fail(std::string(e.what()) + " (see nut-viewer --help)", kUsage);
  }
  return run(o);
}
