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

// Calls tile(x0, y0, x1, y1) for every 16x16 tile of a width x height image (the last row and
// column clipped: pixels x0 <= x < x1, y0 <= y < y1) from `threads` threads (0 = all cores),
// handing the tiles out in order. Each tile is drawn once by one thread, so the output does not
// depend on the thread count. Returns the number of threads used.
inline constexpr int kRenderTile = 16;
template <typename TileFunction>
int forEachTile(int width, int height, int threads, const TileFunction& tile) {
  const int tilesX = (width + kRenderTile - 1) / kRenderTile, tilesY = (height + kRenderTile - 1) / kRenderTile;
  std::atomic<int> nextTile{0};
  const auto work = [&] {
    for (int t = nextTile++; t < tilesX * tilesY; t = nextTile++) {
      const int x0 = t % tilesX * kRenderTile, y0 = t / tilesX * kRenderTile;
      tile(x0, y0, std::min(x0 + kRenderTile, width), std::min(y0 + kRenderTile, height));
    }
  };
  const int count = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int i = 1; i < count; ++i) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  return count;
}

// forEachTile, calling pixel(x, y) for each pixel of each tile, row by row.
template <typename PixelFunction>
int forEachPixelInTiles(int width, int height, int threads, const PixelFunction& pixel) {
  return forEachTile(width, height, threads, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) pixel(x, y);
  });
}

}  // namespace nut
