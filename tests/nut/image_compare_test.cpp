// The image comparison behind `nut compare` (nut/image_compare.hpp): counts and the difference
// picture on images built with known differences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <nut/image_compare.hpp>

namespace nut {
namespace {

Image filled(int w, int h, std::uint8_t value) {
  Image image(w, h);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = (i % 4 == 3) ? 255 : value;
  return image;
}

TEST(CompareImages, IdenticalImages) {
  const Image a = filled(7, 5, 100);
  auto d = compareImages(a, a, 8);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->rms, 0.0);
  EXPECT_TRUE(std::isinf(d->psnr));
  EXPECT_EQ(d->pixels, 35);
  EXPECT_EQ(d->differing, 0);
  EXPECT_EQ(d->differingPct, 0.0);
  EXPECT_EQ(d->maxDifference, 0);
  // Equal pixels show A in faded grey: 96 + 100 / 2.
  EXPECT_EQ(d->diff.texel(3, 2), (Rgba8{146, 146, 146, 255}));
}

TEST(CompareImages, KnownDifferences) {
  const Image a = filled(10, 10, 100);
  Image b = a;
  b.at(0, 0)[0] = 120;  // +20 in R: differs
  b.at(1, 0)[1] = 108;  // +8 in G: equal to the threshold, does not differ
  b.at(2, 0)[2] = 91;   // -9 in B: differs
  b.at(3, 0)[3] = 0;    // alpha is ignored
  auto d = compareImages(a, b, 8);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->pixels, 100);
  EXPECT_EQ(d->differing, 2);
  EXPECT_DOUBLE_EQ(d->differingPct, 2.0);
  EXPECT_EQ(d->maxDifference, 20);
  EXPECT_DOUBLE_EQ(d->rms, std::sqrt((400.0 + 64.0 + 81.0) / 300.0));
  EXPECT_DOUBLE_EQ(d->psnr, 20.0 * std::log10(255.0 / d->rms));
  EXPECT_EQ(d->diff.texel(0, 0), (Rgba8{168, 0, 0, 255}));  // red: 128 + 127 * 20 / 64
  EXPECT_EQ(d->diff.texel(1, 0), (Rgba8{0, 0, 255, 255}));  // blue, full at the threshold
  EXPECT_EQ(d->diff.texel(2, 0), (Rgba8{146, 0, 0, 255}));  // red: 128 + 127 * 9 / 64
  EXPECT_EQ(d->diff.texel(3, 0), (Rgba8{146, 146, 146, 255}));

  // Threshold 0: every changed pixel differs.
  auto strict = compareImages(a, b, 0);
  ASSERT_TRUE(strict.ok());
  EXPECT_EQ(strict->differing, 3);
}

TEST(CompareImages, SizeMismatchAndBadThresholdAreErrors) {
  auto d = compareImages(filled(10, 10, 0), filled(10, 9, 0), 8);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.error().message, "images differ in size: 10x10 vs 10x9");
  auto t = compareImages(filled(2, 2, 0), filled(2, 2, 0), 256);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error().message, "threshold 256: expected 0..255");
}

TEST(BoxFilter, MeansOfSquaresRounded) {
  Image a = filled(4, 2, 0);
  // Left square: 0, 10, 20, 31 -> 15.25 -> 15; right square: 255 four times -> 255.
  a.at(0, 0)[0] = 0, a.at(1, 0)[0] = 10, a.at(0, 1)[0] = 20, a.at(1, 1)[0] = 31;
  for (int x = 2; x < 4; ++x)
    for (int y = 0; y < 2; ++y) a.at(x, y)[1] = 255;
  auto r = boxFilter(a, 2);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->width, 2);
  EXPECT_EQ(r->height, 1);
  EXPECT_EQ(r->texel(0, 0), (Rgba8{15, 0, 0, 255}));
  EXPECT_EQ(r->texel(1, 0), (Rgba8{0, 255, 0, 255}));
  auto one = boxFilter(a, 1);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(*one, a);
}

TEST(BoxFilter, RefusesASizeThatIsNoMultiple) {
  auto r = boxFilter(filled(5, 4, 0), 2);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("5x4 is not a multiple"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace nut
