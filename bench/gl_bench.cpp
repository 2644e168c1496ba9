// Frame time of one sample building at 1280x720, the same camera, measured in one run: the GLSL
// ray caster (OSMesa, and EGL: a GPU where there is one, else llvmpipe again), the CPU reference
// caster (all cores), the GL raster of the building's exported mesh (OSMesa), and Embree on that
// mesh (all cores); then the generated LoD2 district with and without plane cells, with its
// complementary meshes, against the raster of its source mesh. GL frames end with glFinish, so the
// time is the rendering's. Results read as frames' milliseconds and rays (pixels) per second;
// docs/BENCHMARKS.md records a run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <meshref/embree_renderer.hpp>
#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <viewer/offscreen.hpp>

#include "lod2_district.hpp"

namespace {

constexpr int kWidth = 1280, kHeight = 720;
constexpr const char* kSample = "building";

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "gl_bench: %s\n", what.c_str());
  std::exit(1);
}

struct Scene {
  nut::PngFile png;
  nut::Hierarchy model;
  nut::TriangleMesh mesh;
  nut::Camera camera;
};

const Scene& scene() {
  static const std::unique_ptr<Scene> s = [] {
    auto out = std::make_unique<Scene>();
    auto png = nut::readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/" + kSample + ".png");
    if (!png) fail(png.error().message);
    out->png = std::move(*png);
    auto h = nut::decode(out->png.image);
    if (!h) fail(h.error().message);
    out->model = std::move(*h);
    auto mesh = nut::exportMesh(out->model, out->png.text.originM);
    if (!mesh) fail(mesh.error().message);
    out->mesh = std::move(*mesh);
    auto bounds = nut::contentBounds(out->model, out->png.text.originM);
    if (!bounds) fail(bounds.error().message);
    out->camera = nut::fitCamera(*bounds, kWidth, kHeight);
    return out;
  }();
  return *s;
}

void setRate(benchmark::State& state) { state.SetItemsProcessed(state.iterations() * kWidth * kHeight); }

// An offscreen renderer of the back-end; null, with the benchmark skipped, when it cannot start.
std::unique_ptr<nut::viewer::OffscreenRenderer> offscreen(benchmark::State& state, nut::viewer::Backend backend) {
  nut::viewer::OffscreenOptions options;
  options.backend = backend;
  auto renderer = nut::viewer::OffscreenRenderer::create(options);
  if (!renderer) {
    state.SkipWithError(renderer.error().message.c_str());
    return nullptr;
  }
  return std::move(*renderer);
}

// Times the renderer's frames from the camera; the first frame, which compiles the shader
// variants, is drawn before timing.
void timeFrames(benchmark::State& state, nut::viewer::OffscreenRenderer& renderer, const nut::Camera& camera,
                const nut::RayCastOptions& cast) {
  if (nut::Status first = renderer.draw(camera, cast); !first) fail(first.error().message);
  for (auto _ : state)
    if (nut::Status drawn = renderer.draw(camera, cast); !drawn) fail(drawn.error().message);
  setRate(state);
  state.SetLabel(renderer.context().description());
}

// A renderer of the back-end holding the HNI (rayCast) or the exported mesh. `lookup` is the ray
// caster's.
void glFrame(benchmark::State& state, nut::viewer::Backend backend, bool rayCast,
             nut::Lookup lookup = nut::Lookup::Heuristic) {
  const Scene& s = scene();
  auto renderer = offscreen(state, backend);
  if (!renderer) return;
  const nut::Status added = rayCast ? renderer->addHni(s.png.image, s.png.text.originM) : renderer->addMesh(s.mesh);
  if (!added) fail(added.error().message);
  nut::RayCastOptions cast;
  cast.lookup = lookup;
  timeFrames(state, *renderer, s.camera, cast);
}

// The generated LoD2 district (bench/lod2_district.hpp) on the GL back-end: its HNIs, without or
// with plane cells, with their complementary meshes, exact lookup as `nut render`.
void glDistrict(benchmark::State& state, nut::viewer::Backend backend, int planes) {
  const nut::bench::Lod2District& d = nut::bench::lod2District(kWidth, kHeight);
  auto renderer = offscreen(state, backend);
  if (!renderer) return;
  const nut::bench::ConvertedDistrict& c = d.converted[planes];
  for (std::size_t i = 0; i < c.images.size(); ++i) {
    if (nut::Status added = renderer->addHni(c.images[i], c.originsM[i]); !added) fail(added.error().message);
    if (!c.complements[i].triangles.empty())
      if (nut::Status added = renderer->addMesh(c.complements[i]); !added) fail(added.error().message);
  }
  nut::RayCastOptions cast;
  cast.lookup = nut::Lookup::Exact;
  timeFrames(state, *renderer, d.camera, cast);
  state.counters["complement_triangles"] = static_cast<double>(c.complementTriangles);
  state.counters["plane_cells"] = static_cast<double>(c.planeCells);
}

// The district's source mesh rasterised on the GL back-end: the peer of glDistrict.
void glDistrictSource(benchmark::State& state, nut::viewer::Backend backend) {
  const nut::bench::Lod2District& d = nut::bench::lod2District(kWidth, kHeight);
  auto renderer = offscreen(state, backend);
  if (!renderer) return;
  if (nut::Status added = renderer->addMesh(d.source); !added) fail(added.error().message);
  timeFrames(state, *renderer, d.camera, {});
  state.counters["triangles"] = static_cast<double>(d.source.triangles.size());
}

void cpuCaster(benchmark::State& state) {
  const Scene& s = scene();
  const nut::HniRayCaster caster(s.png.image, s.png.text.originM);
  nut::RenderStats stats;
  for (auto _ : state) {
    auto out = nut::renderHni(caster, s.camera, {}, 0, &stats);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  setRate(state);
  state.counters["threads"] = stats.threads;
}

void embree(benchmark::State& state) {
  const Scene& s = scene();
  auto renderer = nut::meshref::EmbreeRenderer::create(s.mesh);
  if (!renderer) fail(renderer.error().message);
  nut::meshref::MeshRenderStats stats;
  for (auto _ : state) {
    auto out = renderer->render(s.camera, 0, &stats);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  setRate(state);
  state.counters["threads"] = stats.threads;
}

using nut::viewer::Backend;

BENCHMARK_CAPTURE(glFrame, gl_raycast/osmesa, Backend::OSMesa, true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glFrame, gl_raycast_exact/osmesa, Backend::OSMesa, true, nut::Lookup::Exact)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glFrame, gl_raycast/egl, Backend::Egl, true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glFrame, gl_raycast_exact/egl, Backend::Egl, true, nut::Lookup::Exact)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(cpuCaster)->Name("cpu_raycast")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glFrame, gl_mesh_raster/osmesa, Backend::OSMesa, false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glFrame, gl_mesh_raster/egl, Backend::Egl, false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(embree)->Name("embree_mesh")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glDistrict, district_boxes_wedges_mesh/osmesa, Backend::OSMesa, 0)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glDistrict, district_plane_cells/osmesa, Backend::OSMesa, 1)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glDistrictSource, district_source_raster/osmesa, Backend::OSMesa)
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glDistrict, district_boxes_wedges_mesh/egl, Backend::Egl, 0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glDistrict, district_plane_cells/egl, Backend::Egl, 1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(glDistrictSource, district_source_raster/egl, Backend::Egl)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
