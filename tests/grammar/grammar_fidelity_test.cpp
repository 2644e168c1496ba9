// Every sample grammar's HNI against the derivation's own mesh (grammar/derive.hpp): the CPU ray
// caster and Embree, from the default camera and three more, 99.5 % of pixels within 8/255. The
// mesh is made from the derivation without the hierarchy, the blocks or the encoding, so it is the
// independent side. On failure the three images are written to the test output folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <grammar/compile.hpp>
#include <meshref/embree_renderer.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

#include "grammar_samples.hpp"
#include "test_files.hpp"

namespace nut::grammar {
namespace {

constexpr int kThreshold = 8;
constexpr double kMinWithinPct = 99.5;

// Share of pixels that show something: a comparison of two empty skies would pass.
double coveredPct(const Image& image) {
  long covered = 0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4)
    if (image.pixels[i] != kBackground[0] || image.pixels[i + 1] != kBackground[1] ||
        image.pixels[i + 2] != kBackground[2])
      ++covered;
  return 400.0 * static_cast<double>(covered) / static_cast<double>(image.pixels.size());
}

// The default camera fitted to the box and three more: behind on the left, high above, low along
// the side, each at the distance the default camera has.
std::vector<Camera> views(const WorldBox& box) {
  const Camera fitted = fitCamera(box, 640, 360);
  const double distance = glm::length(fitted.eye - fitted.target);
  std::vector<Camera> out{fitted};
  for (const glm::dvec3 from :
       {glm::dvec3(-0.7, 0.35, 1.0), glm::dvec3(0.25, 1.6, 0.35), glm::dvec3(1.0, 0.12, 0.45)}) {
    Camera c = fitted;
    c.eye = c.target + distance * glm::normalize(from);
    out.push_back(c);
  }
  return out;
}

TEST(GrammarFidelity, EverySampleRendersAsItsOwnMesh) {
  const std::vector<std::string> samples = testing::sampleGrammarNames();
  ASSERT_GE(samples.size(), 4u);
  for (const std::string& name : samples) {
    SCOPED_TRACE(name);
    auto g = readGrammar(testing::sampleGrammarPath(name));
    ASSERT_TRUE(g) << g.error().message;
    auto c = compileGrammar(*g, {.seed = 5});
    ASSERT_TRUE(c) << c.error().message;
    auto mesh = derivationMesh(c->derivation);
    ASSERT_TRUE(mesh) << mesh.error().message;
    auto tracer = meshref::EmbreeRenderer::create(*mesh);
    ASSERT_TRUE(tracer) << tracer.error().message;
    const HniRayCaster caster(c->image, c->originM);
    const std::vector<Camera> cameras = views(mesh->bounds());
    for (std::size_t v = 0; v < cameras.size(); ++v) {
      const Image nut = renderHni(caster, cameras[v], RayCastOptions{}).colour;
      const Image reference = tracer->render(cameras[v]).colour;
      EXPECT_GT(coveredPct(reference), 5.0) << "view " << v << " shows the building";
      auto diff = compareImages(nut, reference, kThreshold);
      ASSERT_TRUE(diff) << diff.error().message;
      const double within = 100.0 - diff->differingPct;
      EXPECT_GE(within, kMinWithinPct) << "view " << v;
      if (within < kMinWithinPct) {
        const auto stem = testing::testOutputDir("grammar") / (name + ".view" + std::to_string(v));
        (void)writePng(stem.string() + ".nut.png", nut);
        (void)writePng(stem.string() + ".mesh.png", reference);
        (void)writePng(stem.string() + ".diff.png", diff->diff);
      }
    }
  }
}

}  // namespace
}  // namespace nut::grammar
