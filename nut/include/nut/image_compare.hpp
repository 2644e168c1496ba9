// nut/image_compare.hpp — the numbers and the picture `nut compare` gives for two renders of
// the same view (typically an HNI ray cast against the mesh reference render).
#pragma once

#include <cstdint>

#include <nut/error.hpp>
#include <nut/image.hpp>

namespace nut {

struct ImageDiff {
  int width = 0, height = 0;
  double rms = 0;    // root mean square of the channel differences over R, G and B, 0..255 scale
  double psnr = 0;   // 20 log10(255 / rms) in dB; +infinity when the images are identical
  int maxDifference = 0;      // the largest channel difference of any pixel, 0..255
  std::int64_t pixels = 0;
  std::int64_t differing = 0;  // pixels whose largest channel difference exceeds the threshold
  double differingPct = 0;     // 100 * differing / pixels
  int threshold = 0;
  // What differs where, for a person to look at:
  //   equal pixels               grey of A, faded (so the scene stays recognisable)
  //   difference 1..threshold    blue, brighter with the difference
  //   difference > threshold     red, brighter with the difference (full red from 64 up)
  Image diff;
};

// Compares the RGB channels of two RGBA8 images of the same size (alpha is ignored: renders are
// opaque). A pixel differs when max(|ΔR|, |ΔG|, |ΔB|) > threshold (0..255).
// Error: "images differ in size: AxB vs CxD".
Result<ImageDiff> compareImages(const Image& a, const Image& b, int threshold = 8);

// The mean of each factor x factor square of pixels, rounded: a render made at factor times the
// size becomes a supersampled (anti-aliased) reference for a render at the smaller size.
// Error when the size is not a multiple of the factor.
Result<Image> boxFilter(const Image& image, int factor);

}  // namespace nut
