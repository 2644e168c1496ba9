// bench/lookup_bench.cpp — the CPU analogue of the paper's Table 1 (Kuang et al. 2013, section
// 3.2): the cost of one random-access lookup into a 3D NUT of n x n x n cells, n = 4 .. 64, by
//   native     a uniform grid: per axis cell = x * (n / D), clamped and truncated, then the fetch
//   heuristic  per axis nut::AxisView::cellHeuristic (one metadata pixel), then the fetch
//   binary     per axis std::upper_bound over the interior boundaries (floats), then the fetch
//   exact      per axis nut::AxisView::cellExact (metadata pixel + exact row), then the fetch
// All four read the same RGBA8 data image ((n n) x n, z tiled along x: texel (cx + cz n, cy)) with
// the same fetch code, for the same precomputed query points, and add every fetched texel to a
// sum. One benchmark iteration is a batch of kQueries independent lookups: items_per_second reads
// as lookups/s and `per_lookup` is the time of one lookup (throughput, as a GPU measures it).
//
// The native grid is computed like AxisView's pixel (AxisView::pixelOf): a per-axis scale
// precomputed once, a float clamp, a truncation. It is as tuned as the NUT path, so the ratios
// measure the metadata, not a difference in arithmetic: the heuristic lookup does exactly this
// scale-clamp-truncate (in 1/256-pixel steps), the exact lookup the same four float operations in
// another order (clamp x, then scale and truncate) plus a truncation of x itself.
//
// The NUT's cells have random integer-mm widths in [kMinWidth, kMaxWidth] (fixed seeds); its
// metadata is built with nut::buildAxisIndex + nut::encodeAxisIndex and laid out like the HNI's
// metadata region (256 pixels wide, RGBA8): axis a's metadata row at v = 2a, its exact row at
// v = 2a + 1. The native grid spans the same D per axis. The scene is lookup_scene.hpp, shared with
// gl_lookup_bench.cpp (the same lookups in GLSL). Results: docs/BENCHMARKS.md.
#include "lookup_scene.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace nut::bench;  // the scene: lookup_scene.hpp

constexpr int kQueries = 1 << 16;

// The library's lookups behind the same cell(x) interface as UniformAxis and BoundaryAxis.
struct HeuristicAxis {
  nut::AxisView view;
  int cell(float x) const { return view.cellHeuristic(x); }
};
struct ExactAxis {
  nut::AxisView view;
  int cell(float x) const { return view.cellExact(x); }
};

// ---- The scene of one size n ------------------------------------------------------------------

struct Query {
  float x, y, z;
};

// The shared scene (metadata, data image, native grid) and this benchmark's own parts.
struct Scene : LookupScene {
  std::array<HeuristicAxis, 3> heuristic{};
  std::array<BoundaryAxis, 3> binary{};
  std::array<ExactAxis, 3> exact{};
  std::vector<Query> queries;
  double heuristicWrong = 0;  // fraction of per-axis heuristic answers that are not the exact cell
};

[[noreturn]] void fail(int n, const std::string& message) {
  std::fprintf(stderr, "lookup_bench: n = %d: %s\n", n, message.c_str());
  std::abort();
}

std::unique_ptr<Scene> buildScene(int n) {
  auto scene = std::make_unique<Scene>();
  Scene& s = *scene;
  if (nut::Status built = buildLookupScene(n, s); !built) fail(n, built.error().message);
  for (std::size_t a = 0; a < 3; ++a) {
    s.heuristic[a] = {s.views[a]};
    s.binary[a] = {.interior = s.interior[a].data(), .count = n - 1};
    s.exact[a] = {s.views[a]};
  }
  s.queries.resize(kQueries);
  for (Query& q : s.queries) {
    float* c[3] = {&q.x, &q.y, &q.z};
    for (std::size_t a = 0; a < 3; ++a)
      *c[a] = std::min(randomUnit(s.rng) * s.size[a], std::nextafter(s.size[a], 0.0f));
  }
  // Correctness: every exact lookup agrees with the binary search; a heuristic answer that differs
  // is one cell off, for a coordinate within D / (512 M) of the boundary between the two cells
  // (plus a little float rounding of x * 256 M / D); the native cell is in [0, n).
  long wrong = 0;
  for (const Query& q : s.queries) {
    const float c[3] = {q.x, q.y, q.z};
    for (std::size_t a = 0; a < 3; ++a) {
      const float x = c[a];
      const int truth = s.binary[a].cell(x);
      if (s.exact[a].cell(x) != truth) fail(n, "an exact lookup disagrees with binary search");
      const int native = s.native[a].cell(x);
      if (native < 0 || native >= n) fail(n, "a native cell is outside the grid");
      const int h = s.heuristic[a].cell(x);
      if (h == truth) continue;
      if (std::abs(h - truth) != 1) fail(n, "a heuristic lookup is more than one cell off");
      const float boundary = s.interior[a][static_cast<std::size_t>(std::min(h, truth))];
      const float bound = s.size[a] / (512.0f * static_cast<float>(s.pixels[a]));
      if (std::abs(x - boundary) > 1.01f * bound) fail(n, "a heuristic lookup exceeds its error bound");
      ++wrong;
    }
  }
  s.heuristicWrong = static_cast<double>(wrong) / (3.0 * kQueries);
  return scene;
}

const Scene& scene(int n) {
  static std::map<int, std::unique_ptr<Scene>> scenes;
  auto& slot = scenes[n];
  if (!slot) slot = buildScene(n);
  return *slot;
}

// The timed loop: kQueries lookups, each three per-axis cell lookups and one data fetch.
template <class Axis>
void runLookups(benchmark::State& state, const Scene& s, const std::array<Axis, 3>& axes) {
  const std::uint8_t* data = s.data.data();
  const int n = s.n;
  const int width = n * n;
  const Axis ax = axes[0], ay = axes[1], az = axes[2];
  for (auto _ : state) {
    std::uint32_t sum = 0;
    for (const Query& q : s.queries) {
      const int cx = ax.cell(q.x), cy = ay.cell(q.y), cz = az.cell(q.z);
      sum += fetchTexel(data, width, cx + cz * n, cy);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kQueries);
  state.counters["per_lookup"] = benchmark::Counter(
      kQueries, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

enum class Method { kNative, kHeuristic, kBinary, kExact };

void lookupBenchmark(benchmark::State& state, Method method, int n) {
  const Scene& s = scene(n);
  switch (method) {
    case Method::kNative: runLookups(state, s, s.native); break;
    case Method::kHeuristic: runLookups(state, s, s.heuristic); break;
    case Method::kBinary: runLookups(state, s, s.binary); break;
    case Method::kExact: runLookups(state, s, s.exact); break;
  }
  // M: the metadata array's size, mean over the three axes; wrong_cells: the fraction of
  // per-axis heuristic answers that differ from the exact cell (within D / (512 M) of a boundary).
  if (method == Method::kHeuristic || method == Method::kExact)
    state.counters["M"] = (s.pixels[0] + s.pixels[1] + s.pixels[2]) / 3.0;
  if (method == Method::kHeuristic) state.counters["wrong_cells"] = s.heuristicWrong;
}

[[maybe_unused]] const bool kRegistered = [] {
  struct Entry {
    const char* name;
    Method method;
  };
  const Entry entries[] = {
      {"native", Method::kNative},
      {"heuristic", Method::kHeuristic},
      {"binary", Method::kBinary},
      {"exact", Method::kExact},
  };
  for (const Entry& e : entries)
    for (int n : kSizes)
      benchmark::RegisterBenchmark(("BM_Lookup/" + std::string(e.name) + "/" + std::to_string(n)).c_str(),
                                   lookupBenchmark, e.method, n);
  return true;
}();

}  // namespace
