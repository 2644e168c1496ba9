#include "gl_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>

#include "../test_files.hpp"

namespace nut::gltest {

std::filesystem::path outputDir(const std::string& suite) { return testing::testOutputDir(suite); }

std::unique_ptr<viewer::OffscreenRenderer> openRenderer(viewer::Backend backend) {
  viewer::OffscreenOptions options;
  options.backend = backend;
  auto renderer = viewer::OffscreenRenderer::create(options);
  if (!renderer) {
    ADD_FAILURE() << renderer.error().message;
    return nullptr;
  }
  return std::move(*renderer);
}

Agreement compareFrames(const std::filesystem::path& dir, const std::string& name, const Image& reference,
                        const std::vector<float>& referenceDepth, const Image& actual,
                        const std::vector<float>& actualDepth, int threshold, double minWithinPct) {
  Agreement a;
  auto diff = nut::compareImages(reference, actual, threshold);
  if (!diff) {
    ADD_FAILURE() << name << ": " << diff.error().message;
    return a;
  }
  a.withinPct = 100.0 - diff->differingPct;
  a.maxDifference = diff->maxDifference;
  const int w = reference.width, h = reference.height;
  const auto index = [w](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x); };
  long long withinBound = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = index(x, y);
      if (referenceDepth[i] >= 1.0f || actualDepth[i] >= 1.0f) continue;
      const std::uint8_t* p = reference.at(x, y);
      const std::uint8_t* q = actual.at(x, y);
      if (std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) > threshold) continue;
      ++a.depthPixels;
      const double error = std::abs(static_cast<double>(actualDepth[i]) - referenceDepth[i]);
      a.worstDepthError = std::max(a.worstDepthError, error);
      if (error <= kWindowDepthBound) {
        ++withinBound;
        continue;
      }
      double lo = referenceDepth[i], hi = referenceDepth[i];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
          const float d = referenceDepth[index(x + dx, y + dy)];
          if (d < 1.0f) lo = std::min(lo, static_cast<double>(d)), hi = std::max(hi, static_cast<double>(d));
        }
      if (actualDepth[i] < lo - kWindowDepthBound || actualDepth[i] > hi + kWindowDepthBound) ++a.depthOutOfRange;
    }
  a.depthWithinBoundPct = a.depthPixels ? 100.0 * static_cast<double>(withinBound) / static_cast<double>(a.depthPixels) : 100.0;
  std::printf("%s: %.4f %% of %lld pixels within %d/255 (max difference %d); window depths of %lld pixels: %.4f %% "
              "within %.3g (worst %.3g), %lld outside their neighbourhood's range\n",
              name.c_str(), a.withinPct, static_cast<long long>(diff->pixels), threshold, a.maxDifference,
              a.depthPixels, a.depthWithinBoundPct, kWindowDepthBound, a.worstDepthError, a.depthOutOfRange);
  if (std::getenv("NUT_TEST_KEEP_IMAGES") || a.withinPct < minWithinPct || a.depthOutOfRange > 0) {
    const std::string stem = (dir / name).string();
    EXPECT_TRUE(writePng(stem + ".actual.png", actual).ok());
    EXPECT_TRUE(writePng(stem + ".expected.png", reference).ok());
    EXPECT_TRUE(writePng(stem + ".diff.png", diff->diff).ok());
  }
  return a;
}

}  // namespace nut::gltest
