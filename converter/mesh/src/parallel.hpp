// converter/mesh/src/parallel.hpp — a minimal parallel loop for the converter's independent
// work items (grid columns, cells): chunks handed out in order from an atomic counter; the calling
// thread works too and is the only one that reports progress.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace nut::converter {

inline int resolveThreads(int threads) {
  return threads > 0 ? threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Calls work(begin, end) for consecutive chunks of [0, count); progress(fraction) after each chunk
// the calling thread finishes. work must be safe to call concurrently on disjoint ranges.
inline void parallelFor(std::size_t count, std::size_t chunk, int threads,
                        const std::function<void(std::size_t, std::size_t)>& work,
                        const std::function<void(double)>& progress = {}) {
  std::atomic<std::size_t> next{0}, done{0};
  const auto loop = [&](bool caller) {
    for (;;) {
      const std::size_t begin = next.fetch_add(chunk);
      if (begin >= count) return;
      const std::size_t end = std::min(count, begin + chunk);
      work(begin, end);
      const std::size_t finished = done.fetch_add(end - begin) + (end - begin);
      if (caller && progress) progress(static_cast<double>(finished) / static_cast<double>(count));
    }
  };
  std::vector<std::thread> workers;
  const int n = std::min<int>(resolveThreads(threads), static_cast<int>((count + chunk - 1) / std::max<std::size_t>(chunk, 1)));
  for (int t = 1; t < n; ++t) workers.emplace_back(loop, false);
  loop(true);
  for (std::thread& w : workers) w.join();
}

}  // namespace nut::converter
