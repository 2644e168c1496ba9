// Image comparison for `nut compare`: plain loops over the bytes, so every count is exact.
#include <nut/image_compare.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace nut {

namespace {

// Red saturates at this difference, so a difference of 30 and one of 200 still look different.
constexpr int kFullRedDifference = 64;

std::uint8_t toByte(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); }

}  // namespace

Result<ImageDiff> compareImages(const Image& a, const Image& b, int threshold) {
  if (a.width != b.width || a.height != b.height)
    return Error{"images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                 std::to_string(b.width) + "x" + std::to_string(b.height)};
  if (threshold < 0 || threshold > 255) return Error{"threshold " + std::to_string(threshold) + ": expected 0..255"};
  ImageDiff d;
  d.width = a.width;
  d.height = a.height;
  d.threshold = threshold;
  d.pixels = static_cast<std::int64_t>(a.width) * a.height;
  d.diff = Image(a.width, a.height);
  std::uint64_t sumSquares = 0;  // at most 3 * 255^2 per pixel: exact for any image that fits in memory
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::uint8_t* p = a.at(x, y);
      const std::uint8_t* q = b.at(x, y);
      int most = 0;
      for (int c = 0; c < 3; ++c) {
        const int delta = std::abs(p[c] - q[c]);
        sumSquares += static_cast<std::uint64_t>(delta * delta);
        most = std::max(most, delta);
      }
      d.maxDifference = std::max(d.maxDifference, most);
      std::uint8_t* out = d.diff.at(x, y);
      out[3] = 255;
      if (most == 0) {
        const double luma = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
        out[0] = out[1] = out[2] = toByte(96.0 + 0.5 * luma);
      } else if (most <= threshold) {
        out[0] = out[1] = 0;
        out[2] = toByte(128.0 + 127.0 * most / threshold);
      } else {
        ++d.differing;
        out[0] = toByte(128.0 + 127.0 * std::min(most, kFullRedDifference) / kFullRedDifference);
        out[1] = out[2] = 0;
      }
    }
  if (d.pixels > 0) {
    d.rms = std::sqrt(static_cast<double>(sumSquares) / (3.0 * static_cast<double>(d.pixels)));
    d.differingPct = 100.0 * static_cast<double>(d.differing) / static_cast<double>(d.pixels);
  }
  d.psnr = d.rms > 0 ? 20.0 * std::log10(255.0 / d.rms) : std::numeric_limits<double>::infinity();
  return d;
}

Result<Image> boxFilter(const Image& image, int factor) {
  if (factor < 1 || image.width % factor != 0 || image.height % factor != 0)
    return Error{"image " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                 " is not a multiple of the box filter's " + std::to_string(factor) + " pixels"};
  Image out(image.width / factor, image.height / factor);
  const int area = factor * factor;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int dy = 0; dy < factor; ++dy)
          for (int dx = 0; dx < factor; ++dx) sum += image.at(factor * x + dx, factor * y + dy)[c];
        out.at(x, y)[c] = static_cast<std::uint8_t>((sum + area / 2) / area);
      }
  return out;
}

}  // namespace nut
