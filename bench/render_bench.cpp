// Ray casting speed: the NUT CPU ray caster over each sample HNI against Embree (rtcIntersect1)
// on the mesh exported from it, same default camera, resolution and thread count; and the ray
// caster's level-of-detail settings against the error they cost (pixels differing from full detail).
// Results read as rays/s; docs/BENCHMARKS.md records a run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include <meshref/embree_renderer.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr int kThreads = 1;  // one thread for both renderers: the ratio, not the core count

struct Scene {
  nut::PngFile png;
  std::unique_ptr<nut::HniRayCaster> caster;
  nut::TriangleMesh mesh;
  std::unique_ptr<nut::meshref::EmbreeRenderer> embree;
  nut::Camera camera;
  nut::Camera farCamera;  // six times further away: the building spans about 150 pixels
  nut::Image farFullDetail;  // the heuristic caster at full detail, the reference for LOD errors
};

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "render_bench: %s\n", what.c_str());
  std::exit(1);
}

const Scene& scene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Scene>> scenes;
  auto& slot = scenes[name];
  if (slot) return *slot;
  slot = std::make_unique<Scene>();
  Scene& s = *slot;
  auto png = nut::readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/" + name + ".png");
  if (!png) fail(png.error().message);
  s.png = std::move(*png);
  auto h = nut::decode(s.png.image);
  if (!h) fail(h.error().message);
  s.caster = std::make_unique<nut::HniRayCaster>(s.png.image, s.png.text.originM);
  auto exported = nut::exportMesh(*h, s.png.text.originM);
  if (!exported) fail(exported.error().message);
  s.mesh = std::move(*exported);
  auto bounds = nut::contentBounds(*h, s.png.text.originM);
  if (!bounds) fail(bounds.error().message);
  auto embree = nut::meshref::EmbreeRenderer::create(s.mesh);
  if (!embree) fail(embree.error().message);
  s.embree = std::make_unique<nut::meshref::EmbreeRenderer>(std::move(*embree));
  s.camera = nut::fitCamera(*bounds, kWidth, kHeight);
  s.farCamera = s.camera;
  s.farCamera.eye = s.camera.target + 6.0 * (s.camera.eye - s.camera.target);
  s.farCamera.farM *= 6.0;
  s.farFullDetail = nut::renderHni(*s.caster, s.farCamera, {}, kThreads).colour;
  return s;
}

void setRate(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
}

// Test-only: NUT_BENCH_SLOWDOWN=k makes each frame of the NUT caster take k times as long (a sleep
// after it), so that a test can show the guard of make bench-quick catching a slower caster.
double slowdown() {
  static const double k = [] {
    const char* text = std::getenv("NUT_BENCH_SLOWDOWN");
    return text ? std::max(1.0, std::atof(text)) : 1.0;
  }();
  return k;
}

void nutCaster(benchmark::State& state, const std::string& name, nut::Lookup lookup, double lodPx, bool far) {
  const Scene& s = scene(name);
  const nut::Camera& camera = far ? s.farCamera : s.camera;
  nut::RayCastOptions options;
  options.lookup = lookup;
  options.lodPx = lodPx;
  nut::RenderStats stats;
  nut::RenderOutput out;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    out = nut::renderHni(*s.caster, camera, options, kThreads, &stats);
    benchmark::DoNotOptimize(out.colour.pixels.data());
    if (slowdown() > 1) std::this_thread::sleep_for((slowdown() - 1) * (std::chrono::steady_clock::now() - start));
  }
  setRate(state);
  state.counters["iterations_mean"] = stats.iterationsMean;
  if (far) {
    auto diff = nut::compareImages(out.colour, s.farFullDetail, 8);
    state.counters["differing_pct"] = diff ? diff->differingPct : -1;
  }
}

void embree(benchmark::State& state, const std::string& name) {
  const Scene& s = scene(name);
  for (auto _ : state) {
    auto out = s.embree->render(s.camera, kThreads);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  setRate(state);
  state.counters["triangles"] = static_cast<double>(s.mesh.triangles.size());
}

const bool registered = [] {
  for (const char* name : {"facade", "building", "solids"}) {
    const std::string n = name;
    benchmark::RegisterBenchmark(("Render/embree/" + n).c_str(), [n](benchmark::State& st) { embree(st, n); })
        ->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("Render/nut_heuristic/" + n).c_str(),
                                 [n](benchmark::State& st) { nutCaster(st, n, nut::Lookup::Heuristic, 0, false); })
        ->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("Render/nut_exact/" + n).c_str(),
                                 [n](benchmark::State& st) { nutCaster(st, n, nut::Lookup::Exact, 0, false); })
        ->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  // Level of detail on the building seen from six times the default distance.
  for (double lod : {0.0, 1.0, 2.0, 4.0, 8.0, 16.0}) {
    const std::string label = "Render/far_lod" + std::to_string(static_cast<int>(lod)) + "px/building";
    benchmark::RegisterBenchmark(label.c_str(), [lod](benchmark::State& st) {
      nutCaster(st, "building", nut::Lookup::Heuristic, lod, true);
    })->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  return true;
}();

}  // namespace
