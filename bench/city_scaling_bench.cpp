// city_scaling_bench CITY.json --out RESULT.json — one city of the scaling benchmark
// (scripts/city-scaling.sh, docs/BENCHMARKS.md "City scaling"): the same views of it drawn by the
// streaming NUT renderer (viewer/city_renderer.hpp) and, in the same GL context, by rasterising
// the exported meshes of the same buildings, with the memory each needs.
//
// NUT: each view streams in what it sees, then `--hold` frames are timed, at full detail and with
// level of detail (whose frame is compared with full detail's), or fewer where the timed frames of
// a view pass `--hold-seconds` (frames of seconds vary less than the machine's noise); memory is the PNG bytes on disk,
// the texels of every HNI (what an atlas holding the whole city stores) and the atlas pages the
// run allocated. Mesh: every building's HNI exported as triangles (nut::exportMesh, placed and
// turned as the manifest says, on all cores) and uploaded as the renderer's vertex buffers; each
// view draws the buildings whose box meets the frustum (the same test as the NUT renderer),
// `--hold` frames timed (the same cap), after one untimed frame before the first view. A mesh
// city that would pass `--mesh-budget-mb` of vertex buffers is not drawn, and the result says so.
// Frames end with glFinish. Not a Google Benchmark: each run is one city, and the script compares
// the cities.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>
#include <scene/scene.hpp>
#include <viewer/city_loader.hpp>
#include <viewer/city_renderer.hpp>
#include <viewer/context.hpp>
#include <viewer/frame_view.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/render_target.hpp>
#include <viewer/shader_library.hpp>

namespace fs = std::filesystem;
using namespace nut;
using namespace nut::viewer;

namespace {

struct Options {
  std::string city, out, screenshots, gl = "osmesa";
  int width = 1280, height = 720, hold = 5;
  double holdSeconds = 0;  // 0: no cap
  double meshBudgetMb = 8192;
};

struct View {
  const char* name;
  glm::dvec3 eye, target;
};

// Fixed world positions, so every city of the grid layout (docs/CITY.md) is seen from the same
// place: its second street (z 56 to 72 m) at eye height looking along it, and its corner from 250 m
// up. A larger city adds buildings behind what the smaller one shows.
const View kViews[] = {{"street", {4.0, 1.7, 64.0}, {200.0, 8.0, 64.0}},
                       {"above", {-120.0, 250.0, -120.0}, {260.0, 0.0, 260.0}}};

// Full detail, and the level of detail a viewer of a large city would use: a building spanning
// fewer than 16 pixels drawn as its summary box, a redirection cell of fewer than 4 as its summary.
struct NutSetting {
  const char* name;  // of the screenshots
  const char* key;   // of the result
  double summaryBelowPx, lodPx;
};
const NutSetting kNutSettings[] = {{"nut", "views", 0.0, 0.0}, {"nut-lod", "lod_views", 16.0, 4.0}};

Camera cameraFor(const View& v, const Options& o) {
  Camera c;
  c.eye = v.eye, c.target = v.target;
  c.width = o.width, c.height = o.height;
  c.fovYDeg = 50.0;
  c.nearM = 0.5, c.farM = 6000.0;  // past the far corner of the largest city
  return c;
}

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "city_scaling_bench: %s\n", what.c_str());
  std::exit(1);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Whether a view has timed enough frames: `hold` of them, or at least one and `holdSeconds` of time.
bool heldEnough(const std::vector<double>& ms, const Options& o) {
  double total = 0;
  for (double m : ms) total += m;
  return static_cast<int>(ms.size()) >= o.hold || (!ms.empty() && o.holdSeconds > 0 && total >= 1e3 * o.holdSeconds);
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json frameTimes(const std::vector<double>& ms) {
  return {{"median_ms", median(ms)},
          {"min_ms", *std::min_element(ms.begin(), ms.end())},
          {"max_ms", *std::max_element(ms.begin(), ms.end())},
          {"frames", ms.size()}};
}

// The exported mesh of each building, placed as the manifest places its HNI.
struct BuildingMesh {
  TriangleMesh mesh;
  std::string error;
};

BuildingMesh exportPlaced(const scene::PlacedHni& hni) {
  BuildingMesh out;
  auto model = decode(*hni.image);
  if (!model) return {{}, model.error().message};
  auto mesh = exportMesh(*model, hni.originM);
  if (!mesh) return {{}, mesh.error().message};
  for (glm::dvec3& p : mesh->positions) p = hni.originM + hni.worldFromRoot * (p - hni.originM);
  out.mesh = std::move(*mesh);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"city_scaling_bench: NUT streaming vs mesh rasterisation of one city, frame time and memory"};
  Options o;
  app.add_option("city", o.city, "City manifest (from nut city --layout grid)")->required();
  app.add_option("--out", o.out, "Result (JSON)")->required();
  app.add_option("--screenshots", o.screenshots, "Folder for each view's NUT and mesh frames (PNG)");
  app.add_option("--width", o.width)->capture_default_str();
  app.add_option("--height", o.height)->capture_default_str();
  app.add_option("--hold", o.hold, "Timed frames per view")->capture_default_str();
  app.add_option("--hold-seconds", o.holdSeconds, "Stop timing a view once its timed frames took this long (0: no cap)")
      ->capture_default_str();
  app.add_option("--mesh-budget-mb", o.meshBudgetMb, "Largest mesh city uploaded (vertex buffers)")->capture_default_str();
  app.add_option("--gl", o.gl, "osmesa or egl")->capture_default_str();
  app.footer("Example:\n  city_scaling_bench city225/city.json --out city225-result.json --screenshots shots/");
  CLI11_PARSE(app, argc, argv);

  auto manifest = scene::readCityJson(o.city);
  if (!manifest) fail(manifest.error().message);
  auto loaded = scene::loadScene(o.city, {});
  if (!loaded) fail(loaded.error().message);
  const scene::Scene& scene = *loaded;
  std::size_t pngBytes = 0, texelBytes = 0;
  const fs::path folder = fs::path(o.city).parent_path();
  for (const scene::CityBuilding& b : manifest->buildings) pngBytes += fs::file_size(folder / b.hni);
  for (const PngFile& f : scene.files) texelBytes += f.image.pixels.size();

  auto backend = parseBackend(o.gl);
  if (!backend) fail(backend.error().message);
  auto context = createContext(*backend);
  if (!context) fail(context.error().message);
  const Gl& gl = (*context)->gl();
  const ShaderLibrary library = ShaderLibrary::fromEnvironment();
  auto hniRenderer = HniRenderer::create(**context, library);
  if (!hniRenderer) fail(hniRenderer.error().message);
  auto meshRenderer = MeshRenderer::create(**context, library);
  if (!meshRenderer) fail(meshRenderer.error().message);
  auto target = RenderTarget::create(gl, o.width, o.height);
  if (!target) fail(target.error().message);
  if (!o.screenshots.empty()) fs::create_directories(o.screenshots);
  const auto screenshot = [&](const std::string& name) {
    if (o.screenshots.empty()) return;
    if (Status s = writePng((fs::path(o.screenshots) / (name + ".png")).string(), target->readColour()); !s)
      fail(s.error().message);
  };
  RayCastOptions cast;
  cast.lookup = Lookup::Exact;

  nlohmann::json result = {{"city", o.city},
                           {"buildings", manifest->buildings.size()},
                           {"width", o.width},
                           {"height", o.height},
                           {"gl", (*context)->description()}};
  result["nut"] = {{"png_bytes", pngBytes}, {"texel_bytes", texelBytes}};

  // NUT: a fresh renderer per view and setting, so each streams in what it sees, as a viewer
  // started there. The level-of-detail setting's frame is compared with full detail's.
  std::size_t atlasBytes = 0;
  for (const View& view : kViews) {
    const Camera camera = cameraFor(view, o);
    Image fullDetail;
    for (const NutSetting& setting : kNutSettings) {
      CityRendererOptions options;
      options.summaryBelowPx = setting.summaryBelowPx;
      RayCastOptions settingCast = cast;
      settingCast.lodPx = setting.lodPx;
      CityRenderer renderer(gl, *hniRenderer, &*meshRenderer, *manifest, folder.string(), localFiles(), options);
      CityFrameStats stats;
      // Streamed in without drawing (as `nut render --backend gl`): on llvmpipe a frame of the
      // whole city takes seconds, and a viewer streams a few buildings a frame.
      const auto start = std::chrono::steady_clock::now();
      if (Status s = renderer.streamIn(camera, 600.0); !s) fail(std::string(view.name) + ": " + s.error().message);
      const double streamSeconds = millisecondsSince(start) / 1e3;
      std::vector<double> ms;
      for (int f = 0; !heldEnough(ms, o); ++f) {  // occlusion answers a frame late: two untimed frames first
        const auto frameStart = std::chrono::steady_clock::now();
        target->bindCleared();
        if (Status s = renderer.drawFrame(camera, settingCast, stats); !s) fail(s.error().message);
        gl.Finish();
        if (f >= 2) ms.push_back(millisecondsSince(frameStart));
      }
      screenshot(std::string(view.name) + "-" + setting.name);
      atlasBytes = std::max(atlasBytes, stats.atlasBytes);
      nlohmann::json v = frameTimes(ms);
      v["drawn"] = stats.drawn;
      v["as_summary"] = stats.asSummary;
      v["culled_frustum"] = stats.culledByFrustum;
      v["culled_occlusion"] = stats.culledByOcclusion;
      v["loaded"] = stats.loaded;
      v["failed"] = stats.failed;
      v["stream_in_seconds"] = streamSeconds;
      const Image frame = target->readColour();
      if (fullDetail.pixels.empty()) {
        fullDetail = frame;
      } else {
        auto diff = compareImages(fullDetail, frame, 8);
        if (!diff) fail(diff.error().message);
        v["pixels_off_pct"] = diff->differingPct;  // more than 8/255 from full detail
      }
      result["nut"][setting.key][view.name] = v;
      std::fprintf(stderr, "city_scaling_bench: %zu buildings, %s: %s %.1f ms, %zu drawn\n",
                   manifest->buildings.size(), view.name, setting.name, median(ms), stats.drawn);
    }
  }
  result["nut"]["atlas_bytes"] = atlasBytes;

  // Meshes: exported on all cores a chunk at a time, each chunk uploaded on this thread and freed,
  // so the double-precision meshes of the whole city are never held at once.
  const std::size_t count = scene.hnis.size();
  constexpr std::size_t kChunk = 256;
  std::size_t triangles = 0, vertices = 0, bufferBytes = 0;
  bool overBudget = false;
  std::vector<GpuMesh> meshes;
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t end = std::min(count, first + kChunk);
    std::vector<BuildingMesh> exported(end - first);
    std::atomic<std::size_t> next{first};
    const auto work = [&] {
      for (std::size_t i; (i = next++) < end;) exported[i - first] = exportPlaced(scene.hnis[i]);
    };
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < std::max(1u, std::thread::hardware_concurrency()); ++t) threads.emplace_back(work);
    work();
    for (std::thread& t : threads) t.join();
    for (const BuildingMesh& m : exported) {
      if (!m.error.empty()) fail(m.error);
      triangles += m.mesh.triangles.size();
      vertices += m.mesh.positions.size();
      // 3 vertices of 28 bytes a triangle, as GpuMesh holds them.
      overBudget = overBudget || static_cast<double>(triangles) * 84.0 / (1 << 20) > o.meshBudgetMb;
      if (overBudget) continue;
      auto uploaded = GpuMesh::upload(gl, m.mesh);
      if (!uploaded) fail(uploaded.error().message);
      bufferBytes += uploaded->bufferBytes();
      meshes.push_back(std::move(*uploaded));
    }
    if (overBudget) meshes.clear();
    std::fprintf(stderr, "\rcity_scaling_bench: %zu of %zu meshes exported", end, count);
  }
  std::fprintf(stderr, "\n");
  result["mesh"] = {{"triangles", triangles},
                    {"vertices", vertices},
                    // float positions and 32-bit indices: a lower bound of any GPU layout
                    {"indexed_bytes", vertices * 12 + triangles * 12}};
  if (overBudget) {
    result["mesh"]["over_budget"] = true;
    std::fprintf(stderr, "city_scaling_bench: %zu buildings: the meshes need %.0f MiB, over the %.0f MiB budget\n",
                 count, static_cast<double>(triangles) * 84.0 / (1 << 20), o.meshBudgetMb);
  } else {
    result["mesh"]["buffer_bytes"] = bufferBytes;
    for (const View& view : kViews) {
      const FrameView frame(cameraFor(view, o));
      std::vector<double> ms;
      std::size_t drawn = 0;
      // One untimed frame before the first view (the shaders' first use), none after.
      for (int f = &view == kViews ? 0 : 1; !heldEnough(ms, o); ++f) {
        const auto frameStart = std::chrono::steady_clock::now();
        target->bindCleared();
        drawn = 0;
        for (const GpuMesh& mesh : meshes)
          if (mayBeVisible(mesh.bounds(), frame)) meshRenderer->drawOpaque(frame, mesh), ++drawn;
        for (GpuMesh& mesh : meshes)  // glass, if any, over everything opaque
          if (mayBeVisible(mesh.bounds(), frame)) meshRenderer->drawTranslucent(frame, mesh);
        gl.Finish();
        if (f >= 1) ms.push_back(millisecondsSince(frameStart));
      }
      screenshot(std::string(view.name) + "-mesh");
      nlohmann::json v = frameTimes(ms);
      v["drawn"] = drawn;
      result["mesh"]["views"][view.name] = v;
      std::fprintf(stderr, "city_scaling_bench: %zu buildings, %s: mesh %.1f ms, %zu drawn\n", count, view.name,
                   median(ms), drawn);
    }
  }
  if (Status s = writeTextFile(o.out, result.dump(2) + "\n"); !s) fail(s.error().message);
  return 0;
}
