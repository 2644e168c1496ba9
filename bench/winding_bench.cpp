// bench/winding_bench.cpp — the fast generalized winding number (converter/winding.hpp): time per
// query near a building's surface, the tree's construction, and the error against the exact sum.
// The meshes are read, merged and repaired as `nut convert` does; the query points are triangle
// centroids (triangles picked uniformly, seed fixed) moved by N(0, 5 cm) along each axis, where
// the converter asks (cell centres and corners next to faces) and where the far field is hardest.
// One iteration evaluates all kQueries points: items_per_second reads as queries/s. Counters:
// `max_error` and `mean_error` of |fast - exact| over the first kErrorPoints points, `flips` how
// many of those the fast value puts on the other side of |w| = 1/2. The argument is beta times 10
// (the library's default is 2.2). The external meshes (../shared/data) are skipped when absent.
// Results: docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <converter/mesh_check.hpp>
#include <converter/winding.hpp>
#include <scene/obj.hpp>

namespace {

using nut::converter::WindingNumber;

constexpr int kQueries = 1000;
constexpr int kErrorPoints = 500;

struct Scene {
  nut::TriangleMesh mesh;
  std::vector<glm::dvec3> points;
};

std::string meshPath(const std::string& name) {
  const std::string sample = std::string(NUT_SOURCE_DIR) + "/samples/obj/" + name + ".obj";
  return std::filesystem::exists(sample) ? sample : std::string(NUT_SOURCE_DIR) + "/../shared/data/" + name + ".obj";
}

// nullptr when the file is absent or unreadable.
const Scene* scene(const std::string& name) {
  static std::map<std::string, Scene> scenes;
  if (auto it = scenes.find(name); it != scenes.end()) return &it->second;
  auto obj = nut::scene::readObj(meshPath(name));
  if (!obj) return nullptr;
  Scene& s = scenes[name];
  s.mesh = mergeMeshes(obj->objects, name).value();
  nut::converter::checkAndRepair(s.mesh);
  std::mt19937 rng(2018);
  std::uniform_int_distribution<std::size_t> pick(0, s.mesh.triangles.size() - 1);
  std::normal_distribution<double> offset(0.0, 0.05);
  for (int i = 0; i < kQueries; ++i) {
    const auto& t = s.mesh.triangles[pick(rng)];
    const glm::dvec3 centroid = (s.mesh.positions[t[0]] + s.mesh.positions[t[1]] + s.mesh.positions[t[2]]) / 3.0;
    s.points.push_back(centroid + glm::dvec3(offset(rng), offset(rng), offset(rng)));
  }
  return &s;
}

// state.range(0): beta * 10.
void query(benchmark::State& state, const std::string& name) {
  const Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((meshPath(name) + ": not found").c_str());
    return;
  }
  const WindingNumber w(s->mesh.positions, s->mesh.triangles, static_cast<double>(state.range(0)) / 10.0);
  for (auto _ : state)
    for (const glm::dvec3& q : s->points) benchmark::DoNotOptimize(w(q));
  state.SetItemsProcessed(state.iterations() * kQueries);
  double maxError = 0, sumError = 0;
  int flips = 0;
  for (int i = 0; i < kErrorPoints; ++i) {
    const double fast = w(s->points[static_cast<std::size_t>(i)]), exact = w.exact(s->points[static_cast<std::size_t>(i)]);
    maxError = std::max(maxError, std::abs(fast - exact));
    sumError += std::abs(fast - exact);
    flips += (std::abs(fast) >= 0.5) != (std::abs(exact) >= 0.5);
  }
  state.counters["max_error"] = maxError;
  state.counters["mean_error"] = sumError / kErrorPoints;
  state.counters["flips"] = flips;
  state.counters["triangles"] = static_cast<double>(w.triangleCount());
}

// Building the tree (triangles split, sorted, expansions), per source triangle.
void build(benchmark::State& state, const std::string& name) {
  const Scene* s = scene(name);
  if (!s) {
    state.SkipWithError((meshPath(name) + ": not found").c_str());
    return;
  }
  for (auto _ : state) {
    const WindingNumber w(s->mesh.positions, s->mesh.triangles);
    benchmark::DoNotOptimize(&w);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s->mesh.triangles.size()));
}

}  // namespace

BENCHMARK_CAPTURE(query, ingolstadt, std::string("ingolstadt_lod3_4018210_aligned"))->Arg(22)->Arg(30)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(query, kenney_a, std::string("kenney_building_small_a"))->Arg(22)->Arg(30)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(query, highrise, std::string("highrise"))->Arg(22)->Arg(30)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(build, ingolstadt, std::string("ingolstadt_lod3_4018210_aligned"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(build, highrise, std::string("highrise"))->Unit(benchmark::kMillisecond);
