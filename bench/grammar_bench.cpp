// Grammar producer speed (docs/GRAMMAR.md, "Speed"): distinct buildings compiled per second on one
// core, each iteration a new seed of the PGA thesis's complex house (so each building is its own
// derivation, not a cached one): the derivation alone, with the hierarchy and compile() to pixels,
// and with a PNG (zlib; `nut grammar` writes Zopfli, slower).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

#include <grammar/compile.hpp>
#include <nut/hni.hpp>
#include <nut/png_encode.hpp>

namespace {

const nut::grammar::Grammar& sample(const std::string& name) {
  static std::map<std::string, nut::grammar::Grammar> grammars;
  auto it = grammars.find(name);
  if (it == grammars.end()) {
    auto g = nut::grammar::readGrammar(std::string(NUT_SOURCE_DIR) + "/samples/grammars/" + name + ".grammar");
    if (!g) throw std::runtime_error(g.error().message);
    it = grammars.emplace(name, std::move(*g)).first;
  }
  return it->second;
}

void BM_Derive(benchmark::State& state, const std::string& name) {
  const auto& g = sample(name);
  std::uint64_t seed = 0;
  for (auto _ : state) benchmark::DoNotOptimize(nut::grammar::derive(g, {.seed = seed++}));
  state.SetItemsProcessed(state.iterations());
}

void BM_CompileToPixels(benchmark::State& state, const std::string& name) {
  const auto& g = sample(name);
  std::uint64_t seed = 0;
  for (auto _ : state) {
    auto c = nut::grammar::compileGrammar(g, {.seed = seed++});
    if (!c) state.SkipWithError(c.error().message.c_str());
    benchmark::DoNotOptimize(c);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_CompileToPng(benchmark::State& state, const std::string& name) {
  const auto& g = sample(name);
  std::uint64_t seed = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto c = nut::grammar::compileGrammar(g, {.seed = seed++});
    if (!c) {
      state.SkipWithError(c.error().message.c_str());
      break;
    }
    bytes += nut::encodePng(c->image, nullptr, nut::PngEffort::Small).size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["png_bytes"] =
      benchmark::Counter(static_cast<double>(bytes) / static_cast<double>(state.iterations()));
}

}  // namespace

BENCHMARK_CAPTURE(BM_Derive, complex_house, std::string("pga_complex_house"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CompileToPixels, complex_house, std::string("pga_complex_house"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CompileToPng, complex_house, std::string("pga_complex_house"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CompileToPng, random_rule, std::string("pga_random_rule"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CompileToPng, figure12, std::string("krecklau_figure12"))->Unit(benchmark::kMicrosecond);
