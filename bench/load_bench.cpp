// Loading an HNI: what `nut render` (and a viewer that streams HNIs) does with a file before its
// first ray, stage by stage, for each sample HNI: read the PNG, validate it (untrusted input), decode
// it into a Hierarchy, find the content bounds the default camera is fitted to, and prepare the
// ray caster. The mesh export's walk (coarse quadrics, as the bounds use) is timed beside the
// bounds: the bounds walk skips what the bounds found so far already hold. docs/BENCHMARKS.md
// records a run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

namespace {

struct Loaded {
  std::string path;
  nut::PngFile png;
  nut::Hierarchy hierarchy;
};

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "load_bench: %s\n", what.c_str());
  std::exit(1);
}

const Loaded& sample(const std::string& name) {
  static std::map<std::string, Loaded> loaded;
  auto [it, added] = loaded.try_emplace(name);
  Loaded& l = it->second;
  if (!added) return l;
  l.path = std::string(NUT_SOURCE_DIR) + "/samples/hni/" + name + ".png";
  auto png = nut::readPng(l.path);
  if (!png) fail(png.error().message);
  l.png = std::move(*png);
  auto h = nut::decode(l.png.image);
  if (!h) fail(h.error().message);
  l.hierarchy = std::move(*h);
  return l;
}

void readPng(benchmark::State& state, const std::string& name) {
  const Loaded& l = sample(name);
  for (auto _ : state) benchmark::DoNotOptimize(nut::readPng(l.path));
}

void validate(benchmark::State& state, const std::string& name) {
  const Loaded& l = sample(name);
  for (auto _ : state) benchmark::DoNotOptimize(nut::validate(l.png.image));
}

void decode(benchmark::State& state, const std::string& name) {
  const Loaded& l = sample(name);
  for (auto _ : state) benchmark::DoNotOptimize(nut::decode(l.png.image));
}

void contentBounds(benchmark::State& state, const std::string& name) {
  const Loaded& l = sample(name);
  for (auto _ : state) benchmark::DoNotOptimize(nut::contentBounds(l.hierarchy, l.png.text.originM));
}

void exportCoarseMesh(benchmark::State& state, const std::string& name) {
  const Loaded& l = sample(name);
  nut::MeshExportOptions coarse;
  coarse.minSegmentsPerQuarter = coarse.maxSegmentsPerQuarter = 1;
  for (auto _ : state) benchmark::DoNotOptimize(nut::exportMesh(l.hierarchy, l.png.text.originM, coarse));
}

void prepareCaster(benchmark::State& state, const std::string& name) {
  const Loaded& l = sample(name);
  for (auto _ : state) {
    nut::HniRayCaster caster(l.png.image, l.png.text.originM);
    benchmark::DoNotOptimize(caster.bounds());
  }
}

const bool registered = [] {
  for (const char* name : {"building", "facade", "solids"}) {
    const std::string n = name;
    benchmark::RegisterBenchmark(("Load/read_png/" + n).c_str(), readPng, n)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Load/validate/" + n).c_str(), validate, n)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Load/decode/" + n).c_str(), decode, n)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Load/content_bounds/" + n).c_str(), contentBounds, n)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Load/export_coarse_mesh/" + n).c_str(), exportCoarseMesh, n)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Load/prepare_caster/" + n).c_str(), prepareCaster, n)
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
