// Rendering a city on the CPU (scene::SceneRenderer, what `nut render city.json` draws): a
// 40 x 40 grid of the sample building, 1,600 HNIs sharing one image, from above the whole city and
// from a street inside it, at 640 x 360 on one thread. The scene walks a grid over the ground and
// casts each ray only into the HNIs it meets before its nearest hit; the baseline casts every ray
// into every HNI whose box it meets (a caster per HNI), which costs
// pixels times buildings. docs/BENCHMARKS.md records a run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/scene_render.hpp>

namespace {

constexpr int kWidth = 640, kHeight = 360;
constexpr int kThreads = 1;
constexpr int kSide = 40;          // buildings per row and column
constexpr double kSpacingM = 30;   // between building origins (the building is about 24 x 16 m)

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "scene_bench: %s\n", what.c_str());
  std::exit(1);
}

struct City {
  nut::PngFile png;
  std::vector<nut::scene::PlacedHni> placed;
  std::unique_ptr<nut::scene::SceneRenderer> scene;
  std::vector<std::unique_ptr<nut::HniRayCaster>> casters;  // the baseline: one per HNI
  std::vector<nut::WorldBox> boxes;                         // and its world box
  nut::Camera above, street;
};

const City& city() {
  static const std::unique_ptr<City> c = [] {
    auto city = std::make_unique<City>();
    auto png = nut::readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/building.png");
    if (!png) fail(png.error().message);
    city->png = std::move(*png);
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j) {
        const glm::dvec3 origin = city->png.text.originM + glm::dvec3(i * kSpacingM, 0, j * kSpacingM);
        city->placed.push_back({&city->png.image, origin, glm::dmat3(1.0)});
        city->casters.push_back(std::make_unique<nut::HniRayCaster>(city->png.image, origin));
        city->boxes.push_back(city->casters.back()->bounds());
      }
    city->scene = std::make_unique<nut::scene::SceneRenderer>(city->placed, nullptr);
    const double size = kSide * kSpacingM;
    city->above = nut::fitCamera({{0, 0, 0}, {size, 30, size}}, kWidth, kHeight);
    city->street = city->above;
    city->street.eye = {0.62 * size, 25, 0.66 * size};
    city->street.target = {0.4 * size, 8, 0.4 * size};
    return city;
  }();
  return *c;
}

const nut::Camera& view(const City& c, const std::string& name) { return name == "above" ? c.above : c.street; }

// Every HNI whose box the ray meets in front of the nearest hit so far, in the scene's order.
nut::RayResult everyHni(const City& c, const glm::dvec3& eye, const glm::dvec3& dir, double pixelAngle) {
  nut::RayResult nearest;
  nearest.distanceM = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.casters.size(); ++i) {
    const nut::WorldBox& box = c.boxes[i];
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3 && t0 <= t1; ++a) {
      double near = (box.min[a] - eye[a]) / dir[a], far = (box.max[a] - eye[a]) / dir[a];
      if (near > far) std::swap(near, far);
      t0 = std::max(t0, near), t1 = std::min(t1, far);
    }
    if (t0 > t1 || t0 >= nearest.distanceM) continue;
    const nut::RayResult r = c.casters[i]->trace(eye, dir, pixelAngle, {});
    nearest.iterations += r.iterations;
    if (r.hit && r.distanceM < nearest.distanceM) nearest = r;
  }
  if (!nearest.hit) nearest.distanceM = 0;
  return nearest;
}

void sceneRenderer(benchmark::State& state, const std::string& viewName) {
  const City& c = city();
  nut::RenderOutput out;
  for (auto _ : state) {
    out = c.scene->render(view(c, viewName), {}, kThreads);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
}

void baseline(benchmark::State& state, const std::string& viewName) {
  const City& c = city();
  nut::RenderOutput out;
  for (auto _ : state) {
    out = nut::renderRays(
        view(c, viewName),
        [&](const glm::dvec3& eye, const glm::dvec3& dir, double pixelAngle) { return everyHni(c, eye, dir, pixelAngle); },
        kThreads);
    benchmark::DoNotOptimize(out.colour.pixels.data());
  }
  state.SetItemsProcessed(state.iterations() * kWidth * kHeight);
  // The two must draw the same picture.
  const nut::RenderOutput grid = c.scene->render(view(c, viewName), {}, kThreads);
  auto diff = nut::compareImages(out.colour, grid.colour, 0);
  state.counters["pixels_differing_from_grid"] = diff ? static_cast<double>(diff->differing) : -1;
}

const bool registered = [] {
  for (const char* v : {"above", "street"}) {
    const std::string name = v;
    benchmark::RegisterBenchmark(("City1600/ground_grid/" + name).c_str(), [name](benchmark::State& st) { sceneRenderer(st, name); })
        ->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("City1600/every_hni/" + name).c_str(), [name](benchmark::State& st) { baseline(st, name); })
        ->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  return true;
}();

}  // namespace
