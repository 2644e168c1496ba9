// cli/parallel.hpp — the commands' one work loop over independent items (buildings, districts):
// each worker thread takes the next index until none is left.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace nut::cli {

// Runs work(i) for i in [0, count) on `workers` threads (the calling one among them), `done`
// called after each under a lock, for progress.
inline void forEachInParallel(std::size_t count, std::size_t workers, const std::function<void(std::size_t)>& work,
                              const std::function<void()>& done) {
  std::atomic<std::size_t> next{0};
  std::mutex doneMutex;
  const auto loop = [&] {
    for (std::size_t i; (i = next++) < count;) {
      work(i);
      const std::lock_guard lock(doneMutex);
      done();
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(loop);
  loop();
  for (std::thread& t : threads) t.join();
}

}  // namespace nut::cli
