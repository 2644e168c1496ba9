// Measured level of detail on the sample grammars (nut grammar --lod): every sample becomes a
// valid version 2 HNI whose footprints decode as measured, and from afar `--lod auto` keeps the
// picture as close to a supersampled full render as the one-ray-per-pixel full render is.
#include <gtest/gtest.h>

#include <string>

#include <grammar/compile.hpp>
#include <nut/camera.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <nut/units.hpp>

#include "grammar_samples.hpp"

namespace nut::grammar {
namespace {

CompiledGrammar compiledWithLod(const std::string& name) {
  auto g = readGrammar(testing::sampleGrammarPath(name));
  EXPECT_TRUE(g) << g.error().message;
  auto c = compileGrammar(*g, {}, LodMeasureOptions{});
  EXPECT_TRUE(c) << c.error().message;
  return c ? std::move(*c) : CompiledGrammar{};
}

class GrammarLod : public ::testing::TestWithParam<std::string> {};

TEST_P(GrammarLod, IsAValidVersion2FileWhoseFootprintsDecodeAsMeasured) {
  const CompiledGrammar c = compiledWithLod(GetParam());
  ASSERT_TRUE(validate(c.image).ok()) << validate(c.image).error().message;
  EXPECT_EQ(c.image.at(0, 0)[3], format::kVersionLod);
  auto decoded = decode(c.image);
  ASSERT_TRUE(decoded) << decoded.error().message;
  int withFootprint = 0;
  for (std::size_t b = 0; b < c.hierarchy.blocks.size(); ++b) {
    const double measured = c.hierarchy.blocks[b].lodFootprintM;
    EXPECT_EQ(decoded->blocks[b].lodFootprintM, lodFootprintM(lodCode(measured))) << "block " << b;
    withFootprint += measured > 0;
  }
  EXPECT_GT(withFootprint, 0);
}

// Share of pixels more than 8/255 from a 4 x 4 supersampled full render, in percent of the frame:
// --lod auto may add at most this to what one ray per pixel at full detail already misses. Drawing
// every redirection as its summary adds 5 to 15 points from the fitted camera (the control below).
constexpr double kAutoMarginPct = 0.25;

TEST_P(GrammarLod, FromAfarAutoIsAsCloseToASupersampledRenderAsFullDetail) {
  const CompiledGrammar c = compiledWithLod(GetParam());
  const HniRayCaster caster(c.image, c.originM);
  RayCastOptions full, automatic, everywhere;
  full.lookup = automatic.lookup = everywhere.lookup = Lookup::Exact;
  automatic.lodAuto = true;
  everywhere.lodPx = 1e9;
  bool anySummary = false;
  for (double away : {1.0, 2.0, 4.0, 8.0, 16.0}) {
    Camera camera = fitCamera(caster.bounds(), 160, 90);
    camera.eye = camera.target + away * (camera.eye - camera.target);
    camera.farM *= away;
    Camera fine = camera;
    fine.width *= 4, fine.height *= 4;
    auto reference = boxFilter(renderHni(caster, fine, full, 1).colour, 4);
    ASSERT_TRUE(reference);
    const auto offPct = [&](const Image& image) { return compareImages(*reference, image)->differingPct; };
    const Image fullDetail = renderHni(caster, camera, full, 1).colour;
    const Image withLod = renderHni(caster, camera, automatic, 1).colour;
    anySummary = anySummary || withLod != fullDetail;
    EXPECT_LE(offPct(withLod), offPct(fullDetail) + kAutoMarginPct) << away << " times as far";
    if (away == 1.0) {
      EXPECT_GT(offPct(renderHni(caster, camera, everywhere, 1).colour), offPct(fullDetail) + kAutoMarginPct)
          << "summaries everywhere must break the margin, or the test cannot fail";
    }
  }
  EXPECT_TRUE(anySummary) << "no summary stood in at any distance";
}

INSTANTIATE_TEST_SUITE_P(Samples, GrammarLod, ::testing::ValuesIn(testing::sampleGrammarNames()));

}  // namespace
}  // namespace nut::grammar
