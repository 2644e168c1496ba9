// nut/render_loop.hpp — what every CPU renderer of the project does the same way: front-to-back
// compositing of translucent surfaces (docs/RENDERING.md) and the tiled, multi-threaded pixel loop.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include <glm/vec3.hpp>

namespace nut {

// Front-to-back compositing: each translucent layer adds transmittance * alpha * colour.
struct Composite {
  glm::dvec3 colour{0.0};
  double transmittance = 1.0;
  void add(const std::array<std::uint8_t, 3>& c, double alpha) {
    colour += transmittance * alpha * glm::dvec3(c[0], c[1], c[2]);
    transmittance *= 1.0 - alpha;
  }
  std::array<std::uint8_t, 3> finish(const std::array<std::uint8_t, 3>& behind) const {
    const glm::dvec3 c = colour + transmittance * glm::dvec3(behind[0], behind[1], behind[2]);
    return {static_cast<std::uint8_t>(std::lround(std::min(255.0, c.x))),
            static_cast<std::uint8_t>(std::lround(std::min(255.0, c.y))),
            static_cast<std::uint8_t>(std::lround(std::min(255.0, c.z)))};
  }
};

// Calls pixel(x, y) for every pixel of a width x height image from `threads` threads (0 = all
// cores), handing out 16x16 tiles in order. Each pixel is computed once by one thread, so the
// output does not depend on the thread count. Returns the number of threads used.
template <typename PixelFunction>
int forEachPixelInTiles(int width, int height, int threads, const PixelFunction& pixel) {
  constexpr int kTile = 16;
  const int tilesX = (width + kTile - 1) / kTile, tilesY = (height + kTile - 1) / kTile;
  std::atomic<int> nextTile{0};
  const auto work = [&] {
    for (int tile = nextTile++; tile < tilesX * tilesY; tile = nextTile++) {
      const int x0 = tile % tilesX * kTile, y0 = tile / tilesX * kTile;
      for (int y = y0; y < std::min(y0 + kTile, height); ++y)
        for (int x = x0; x < std::min(x0 + kTile, width); ++x) pixel(x, y);
    }
  };
  const int count = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int i = 1; i < count; ++i) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  return count;
}

}  // namespace nut
