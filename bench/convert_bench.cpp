// Mesh-to-NUT conversion speed: each sample OBJ, read once, converted whole (checks and repairs,
// solid conversion, block extraction with every variant compiled, the chosen HNI compiled) per
// iteration, on one thread and on all cores. Results read as triangles/s (items); the OBJ
// parsing and the encoding of the HNI written are measured on their own. `convertAtTolerance`
// sweeps --tolerance: time against error, with the HNI's bytes (as written) and the fidelity of
// the converter tests (the worst of four views, share of pixels within 8/255) as counters.
// docs/CONVERTER.md records a run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>

#include <converter/convert.hpp>
#include <converter/mesh_size.hpp>
#include <nut/png_encode.hpp>
#include <scene/obj.hpp>

#include "converter_fidelity.hpp"

namespace {

std::string samplePath(const std::string& name) { return std::string(NUT_SOURCE_DIR) + "/samples/obj/" + name + ".obj"; }

const nut::TriangleMesh& sample(const std::string& name) {
  static std::map<std::string, nut::TriangleMesh> meshes;
  auto it = meshes.find(name);
  if (it != meshes.end()) return it->second;
  auto obj = nut::scene::readObj(samplePath(name));
  if (!obj) {
    std::fprintf(stderr, "convert_bench: %s\n", obj.error().message.c_str());
    std::exit(1);
  }
  return meshes[name] = mergeMeshes(obj->objects, name).value();
}

// state.range(0): worker threads (0: all cores).
void convert(benchmark::State& state, const std::string& name) {
  const nut::TriangleMesh& mesh = sample(name);
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
  const nut::TriangleMesh& mesh = sample(name);
  auto result = nut::converter::convertMesh(mesh);
  if (!result) {
    state.SkipWithError(result.error().message.c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(nut::encodePng(result->image, nullptr, nut::PngEffort::Smallest));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.triangles.size()));
}

// state.range(0): --tolerance in millimetres; all cores.
void convertAtTolerance(benchmark::State& state, const std::string& name) {
  const nut::TriangleMesh& mesh = sample(name);
  nut::converter::ConvertOptions options;
  options.solid.toleranceM = static_cast<double>(state.range(0)) / 1000.0;
  std::optional<nut::converter::Conversion> kept;
  for (auto _ : state) {
    auto result = nut::converter::convertMesh(mesh, options);
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      return;
    }
    kept = std::move(*result);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.triangles.size()));
  const nut::HniText text = nut::converter::hniText(*kept);  // the file as `nut convert` writes it
  const double png = static_cast<double>(nut::encodePng(kept->image, &text, nut::PngEffort::Smallest).size());
  state.counters["hni_bytes"] = png;
  state.counters["decoded_per_hni"] = static_cast<double>(nut::converter::measureMesh(mesh).decodedBytes) / png;
  state.counters["within_8_pct"] = nut::converter::testing::measureFidelity(mesh, {&*kept}, "", 0.0).worstWithinPct;
}

void readObj(benchmark::State& state, const std::string& name) {
  for (auto _ : state) {
    auto obj = nut::scene::readObj(samplePath(name));
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
BENCHMARK_CAPTURE(convertAtTolerance, highrise, std::string("highrise"))->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convertAtTolerance, street, std::string("street"))->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convertAtTolerance, residential, std::string("residential"))->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convertAtTolerance, house, std::string("house"))->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(convertAtTolerance, carpark, std::string("carpark"))->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(encodeHni, highrise, std::string("highrise"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(readObj, highrise, std::string("highrise"))->Unit(benchmark::kMillisecond)->UseRealTime();
