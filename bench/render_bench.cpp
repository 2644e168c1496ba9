// Ray casting speed: the NUT CPU ray caster against Embree on the mesh exported from the same HNI
// (same geometry, camera, resolution, thread count and shading), over the sample HNIs and the
// converted sample buildings, from the default camera and from a close-up that fills the screen
// (the paper's Table 5). Embree is measured one ray at a time (rtcIntersect1), in packets of 8 and
// 16 (rtcIntersect8/16) and as a coherent stream (rtcIntersect1M); the report takes the fastest
// as the peer. The NUT caster is measured one ray at a time with each lookup, and with the exact
// lookup in packets (HniRayCaster::traceMany). Then a generated LoD2 district converted with and without plane cells,
// drawn with its complementary meshes, against Embree on its source mesh; and the caster's level-of-detail settings
// against the error they cost (pixels differing from full detail). Results read as rays/s; make bench writes
// docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <converter/convert.hpp>
#include <converter/mesh_lod.hpp>
#include <meshref/embree_renderer.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/obj.hpp>
#include <scene/scene.hpp>
#include <scene/scene_render.hpp>

#include "lod2_district.hpp"

namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr int kThreads = 1;  // one thread for both renderers: the ratio, not the core count

// The sample HNIs (samples/hni) and the sample OBJs converted with the default options. The
// carpark is left out: part of it is the complementary mesh, which no caster here draws.
const char* const kSampleHnis[] = {"facade", "building", "solids"};
const char* const kConvertedObjs[] = {"house", "residential", "highrise"};

struct Scene {
  nut::Image image;
  glm::dvec3 originM{0.0};
  std::unique_ptr<nut::HniRayCaster> caster;
  nut::TriangleMesh mesh;
  std::unique_ptr<nut::meshref::EmbreeRenderer> embree;
  nut::Camera camera;       // fitted to the content, as `nut render` frames it
  nut::Camera closeCamera;  // nearer along the same line until the building fills the screen
  double closeCoverage = 0;  // its share of pixels that meet the building
  nut::Camera farCamera;  // six times further away: the building spans about 150 pixels
  nut::Image farFullDetail;  // the heuristic caster at full detail, the reference for LOD errors
};

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "render_bench: %s\n", what.c_str());
  std::exit(1);
}

template <typename T>
T orFail(nut::Result<T> result) {
  if (!result) fail(result.error().message);
  return std::move(*result);
}

// Share of the camera's pixels (drawn small) that meet the mesh.
double coverage(const nut::meshref::EmbreeRenderer& embree, nut::Camera camera) {
  camera.width = 160, camera.height = 90;
  const auto frame = embree.render(camera, kThreads);
  const auto hits =
      std::count_if(frame.distanceM.begin(), frame.distanceM.end(), [](float d) { return std::isfinite(d); });
  return static_cast<double>(hits) / static_cast<double>(frame.distanceM.size());
}

bool inside(const nut::WorldBox& box, const glm::dvec3& p) {
  for (int a = 0; a < 3; ++a)
    if (p[a] <= box.min[a] || p[a] >= box.max[a]) return false;
  return true;
}

const Scene& scene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Scene>> scenes;
  auto& slot = scenes[name];
  if (slot) return *slot;
  slot = std::make_unique<Scene>();
  Scene& s = *slot;
  const std::string samples = std::string(NUT_SOURCE_DIR) + "/samples/";
  if (std::find(std::begin(kSampleHnis), std::end(kSampleHnis), name) != std::end(kSampleHnis)) {
    nut::PngFile png = orFail(nut::readPng(samples + "hni/" + name + ".png"));
    s.image = std::move(png.image);
    s.originM = png.text.originM;
  } else {
    auto obj = orFail(nut::scene::readObj(samples + "obj/" + name + ".obj"));
    nut::converter::Conversion conversion =
        orFail(nut::converter::convertMesh(orFail(mergeMeshes(obj.objects, name))));
    s.image = std::move(conversion.image);
    s.originM = conversion.originM;
  }
  const nut::Hierarchy h = orFail(nut::decode(s.image));
  s.caster = std::make_unique<nut::HniRayCaster>(s.image, s.originM);
  s.mesh = orFail(nut::exportMesh(h, s.originM));
  const nut::WorldBox bounds = orFail(nut::contentBounds(h, s.originM));
  s.embree = std::make_unique<nut::meshref::EmbreeRenderer>(orFail(nut::meshref::EmbreeRenderer::create(s.mesh)));
  s.camera = nut::fitCamera(bounds, kWidth, kHeight);
  // The close-up: step towards the target until 99 % of the pixels meet the building, without
  // entering its box (a building with a courtyard or a low wing may never fill the screen).
  s.closeCamera = s.camera;
  s.closeCoverage = coverage(*s.embree, s.camera);
  for (int step = 0; step < 60 && s.closeCoverage < 0.99; ++step) {
    nut::Camera nearer = s.closeCamera;
    nearer.eye = nearer.target + 0.9 * (nearer.eye - nearer.target);
    if (inside(bounds, nearer.eye)) break;
    s.closeCamera = nearer;
    s.closeCoverage = coverage(*s.embree, nearer);
  }
  s.farCamera = s.camera;
  s.farCamera.eye = s.camera.target + 6.0 * (s.camera.eye - s.camera.target);
  s.farCamera.farM *= 6.0;
  s.farFullDetail = nut::renderHni(*s.caster, s.farCamera, {}, kThreads).colour;
  return s;
}

enum class View { Default, Close, Far };

const nut::Camera& cameraOf(const Scene& s, View view) {
  return view == View::Close ? s.closeCamera : view == View::Far ? s.farCamera : s.camera;
}

void setRate(benchmark::State& state, const Scene& s, View view) {
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
  if (view == View::Close) state.counters["coverage_pct"] = 100.0 * s.closeCoverage;
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

void nutCaster(benchmark::State& state, const std::string& name, View view, nut::Lookup lookup, double lodPx,
               bool packets = false) {
  const Scene& s = scene(name);
  nut::RayCastOptions options;
  options.lookup = lookup;
  options.lodPx = lodPx;
  options.packets = packets;
  nut::RenderStats stats;
  nut::RenderOutput out;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    out = nut::renderHni(*s.caster, cameraOf(s, view), options, kThreads, &stats);
    benchmark::DoNotOptimize(out.colour.pixels.data());
    if (slowdown() > 1) std::this_thread::sleep_for((slowdown() - 1) * (std::chrono::steady_clock::now() - start));
  }
  setRate(state, s, view);
  state.counters["iterations_mean"] = stats.iterationsMean;
  if (view == View::Far) {
    auto diff = nut::compareImages(out.colour, s.farFullDetail, 8);
    state.counters["differing_pct"] = diff ? diff->differingPct : -1;
  }
}

void embree(benchmark::State& state, const std::string& name, View view, nut::meshref::EmbreeRays rays) {
  const Scene& s = scene(name);
  for (auto _ : state) {
    auto out = s.embree->render(cameraOf(s, view), kThreads, nullptr, rays);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  setRate(state, s, view);
  state.counters["triangles"] = static_cast<double>(s.mesh.triangles.size());
}

// The generated LoD2 district drawn as `nut render city.json` draws a converted folder: the HNIs
// with their complementary meshes (scene::SceneRenderer, Embree for the meshes), without and with
// plane cells. The peer is Embree on the source mesh.
struct District {
  std::unique_ptr<nut::scene::SceneRenderer> renderers[2];
  std::unique_ptr<nut::meshref::EmbreeRenderer> embree;
  // The default conversion seen from four times as far, its complements at full detail and at
  // the levels that camera picks (converter/mesh_lod.hpp, as `nut render --lod auto` picks them).
  nut::Camera farCamera;
  std::unique_ptr<nut::scene::SceneRenderer> far[2];
  std::size_t farTriangles[2] = {0, 0};
  nut::Image farFull;
};

const District& district() {
  static const std::unique_ptr<District> d = [] {
    const nut::bench::Lod2District& source = nut::bench::lod2District(kWidth, kHeight);
    auto out = std::make_unique<District>();
    out->embree =
        std::make_unique<nut::meshref::EmbreeRenderer>(orFail(nut::meshref::EmbreeRenderer::create(source.source)));
    for (int planes = 0; planes < 2; ++planes) {
      const nut::bench::ConvertedDistrict& c = source.converted[planes];
      std::vector<nut::scene::PlacedHni> placed;
      for (std::size_t i = 0; i < c.images.size(); ++i) placed.push_back({&c.images[i], c.originsM[i]});
      std::vector<const nut::TriangleMesh*> meshes;
      for (const nut::TriangleMesh& m : c.complements)
        if (!m.triangles.empty()) meshes.push_back(&m);
      out->renderers[planes] =
          std::make_unique<nut::scene::SceneRenderer>(placed, orFail(nut::meshref::traceMeshes(meshes)));
    }
    const nut::bench::ConvertedDistrict& c = source.converted[0];
    out->farCamera = source.camera;
    out->farCamera.eye = source.camera.target + 4.0 * (source.camera.eye - source.camera.target);
    out->farCamera.farM *= 4.0;
    nut::scene::Scene levels;
    for (const nut::TriangleMesh& m : c.complements) {
      if (m.triangles.empty()) continue;
      levels.meshes.push_back(m);
      levels.coarser.emplace_back();
      for (nut::converter::MeshLevel& level : nut::converter::meshLevels(m))
        levels.coarser.back().push_back({std::move(level.mesh), level.errorM});
    }
    std::vector<nut::scene::PlacedHni> placed;
    for (std::size_t i = 0; i < c.images.size(); ++i) placed.push_back({&c.images[i], c.originsM[i]});
    for (int lod = 0; lod < 2; ++lod) {
      const auto meshes = lod ? levels.meshPointers(out->farCamera) : levels.meshPointers();
      for (const nut::TriangleMesh* m : meshes) out->farTriangles[lod] += m->triangles.size();
      out->far[lod] = std::make_unique<nut::scene::SceneRenderer>(placed, orFail(nut::meshref::traceMeshes(meshes)));
    }
    nut::RayCastOptions exact;
    exact.lookup = nut::Lookup::Exact;
    out->farFull = out->far[0]->render(out->farCamera, exact, kThreads).colour;
    return out;
  }();
  return *d;
}

// Render/district/{nut_boxes_wedges_mesh, nut_plane_cells}: the CPU caster (exact lookup, as `nut
// render`) with the complementary meshes; Render/district/embree_source: the source mesh.
void districtNut(benchmark::State& state, int planes) {
  const District& d = district();
  const nut::bench::Lod2District& source = nut::bench::lod2District(kWidth, kHeight);
  nut::RayCastOptions options;
  options.lookup = nut::Lookup::Exact;
  for (auto _ : state) {
    auto out = d.renderers[planes]->render(source.camera, options, kThreads);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
  state.counters["complement_triangles"] = static_cast<double>(source.converted[planes].complementTriangles);
  state.counters["plane_cells"] = static_cast<double>(source.converted[planes].planeCells);
}

// Render/district/far_complements_{full,levels}: the district from four times as far, its
// complements at full detail or at the levels the camera picks; differing_pct against full detail.
void districtFar(benchmark::State& state, int lod) {
  const District& d = district();
  nut::RayCastOptions options;
  options.lookup = nut::Lookup::Exact;
  nut::RenderOutput out;
  for (auto _ : state) {
    out = d.far[lod]->render(d.farCamera, options, kThreads);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
  state.counters["complement_triangles"] = static_cast<double>(d.farTriangles[lod]);
  auto diff = nut::compareImages(out.colour, d.farFull, 8);
  state.counters["differing_pct"] = diff ? diff->differingPct : -1;
}

void districtEmbree(benchmark::State& state, nut::meshref::EmbreeRays rays) {
  const District& d = district();
  const nut::bench::Lod2District& source = nut::bench::lod2District(kWidth, kHeight);
  for (auto _ : state) {
    auto out = d.embree->render(source.camera, kThreads, nullptr, rays);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
  state.counters["triangles"] = static_cast<double>(source.source.triangles.size());
}

const bool registered = [] {
  using nut::meshref::EmbreeRays;
  const std::pair<const char*, EmbreeRays> embreeModes[] = {{"embree", EmbreeRays::Single},
                                                            {"embree_packet8", EmbreeRays::Packet8},
                                                            {"embree_packet16", EmbreeRays::Packet16},
                                                            {"embree_stream", EmbreeRays::Stream}};
  std::vector<std::string> names(std::begin(kSampleHnis), std::end(kSampleHnis));
  names.insert(names.end(), std::begin(kConvertedObjs), std::end(kConvertedObjs));
  const auto add = [](const std::string& label, auto run) {
    benchmark::RegisterBenchmark(label.c_str(), run)->Unit(benchmark::kMillisecond)->UseRealTime();
  };
  // Render/METHOD/NAME from the default camera, Render/METHOD/close/NAME from the close-up.
  for (const std::string& n : names)
    for (const View view : {View::Default, View::Close}) {
      const std::string suffix = (view == View::Close ? "/close/" : "/") + n;
      for (const auto& [method, rays] : embreeModes)
        add("Render/" + std::string(method) + suffix,
            [n, view, rays = rays](benchmark::State& st) { embree(st, n, view, rays); });
      add("Render/nut_heuristic" + suffix,
          [n, view](benchmark::State& st) { nutCaster(st, n, view, nut::Lookup::Heuristic, 0); });
      add("Render/nut_exact" + suffix,
          [n, view](benchmark::State& st) { nutCaster(st, n, view, nut::Lookup::Exact, 0); });
      add("Render/nut_packets" + suffix,
          [n, view](benchmark::State& st) { nutCaster(st, n, view, nut::Lookup::Exact, 0, true); });
    }
  add("Render/district/nut_boxes_wedges_mesh", [](benchmark::State& st) { districtNut(st, 0); });
  add("Render/district/nut_plane_cells", [](benchmark::State& st) { districtNut(st, 1); });
  add("Render/district/far_complements_full", [](benchmark::State& st) { districtFar(st, 0); });
  add("Render/district/far_complements_levels", [](benchmark::State& st) { districtFar(st, 1); });
  for (const auto& [method, rays] : embreeModes)
    add("Render/district/" + std::string(method) + "_source",
        [rays = rays](benchmark::State& st) { districtEmbree(st, rays); });
  // Level of detail on the building seen from six times the default distance.
  for (double lod : {0.0, 1.0, 2.0, 4.0, 8.0, 16.0})
    add("Render/far_lod" + std::to_string(static_cast<int>(lod)) + "px/building",
        [lod](benchmark::State& st) { nutCaster(st, "building", View::Far, nut::Lookup::Heuristic, lod); });
  return true;
}();

}  // namespace
