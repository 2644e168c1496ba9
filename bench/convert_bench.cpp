// Mesh-to-NUT conversion speed: each sample OBJ, read once, converted whole (checks and repairs,
// solid conversion, block extraction with every variant compiled, the chosen HNI compiled) per
// iteration, on one thread and on all cores. Results read as triangles/s (items); the OBJ
// parsing and the encoding of the HNI written are measured on their own. docs/CONVERTER.md records a run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include <converter/convert.hpp>
#include <converter/mesh.hpp>
#include <nut/png_encode.hpp>

namespace {

std::string samplePath(const std::string& name) { return std::string(NUT_SOURCE_DIR) + "/samples/obj/" + name + ".obj"; }

const nut::converter::Mesh& sample(const std::string& name) {
  static std::map<std::string, nut::converter::Mesh> meshes;
  auto it = meshes.find(name);
  if (it != meshes.end()) return it->second;
  auto obj = nut::converter::readObj(samplePath(name));
  if (!obj) {
    std::fprintf(stderr, "convert_bench: %s\n", obj.error().message.c_str());
    std::exit(1);
  }
  return meshes[name] = nut::converter::mergeObjects(obj->objects, name);
}

// state.range(0): worker threads (0: all cores).
void convert(benchmark::State& state, const std::string& name) {
  const nut::converter::Mesh& mesh = sample(name);
  nut::converter::ConvertOptions options;
  options.solid.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto result = nut::converter::convertMesh(mesh, options);
    if (!result) state.SkipWithError(result.error().message.c_str());
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.triangles.size()));
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
}

// Writing the HNI: the converted image encoded as `nut convert` writes it (PngEffort::Smallest:
// every filter strategy, Zopfli on all cores), per triangle of the source so the two add up.
void encodeHni(benchmark::State& state, const std::string& name) {
  const nut::converter::Mesh& mesh = sample(name);
  auto result = nut::converter::convertMesh(mesh);
  if (!result) {
    state.SkipWithError(result.error().message.c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(nut::encodePng(result->image, nullptr, nut::PngEffort::Smallest));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.triangles.size()));
}

void readObj(benchmark::State& state, const std::string& name) {
  for (auto _ : state) {
    auto obj = nut::converter::readObj(samplePath(name));
    benchmark::DoNotOptimize(obj);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sample(name).triangles.size()));
}

}  // namespace

BENCHMARK_CAPTURE(convert, highrise, std::string("highrise"))->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convert, street, std::string("street"))->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convert, residential, std::string("residential"))->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convert, house, std::string("house"))->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convert, carpark, std::string("carpark"))->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(encodeHni, highrise, std::string("highrise"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(readObj, highrise, std::string("highrise"))->Unit(benchmark::kMillisecond)->UseRealTime();
