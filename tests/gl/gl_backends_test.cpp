// The other GL back-ends render what OSMesa renders: EGL (a GPU if there is one, else Mesa's
// surfaceless platform) and GLFW (a hidden window; ctest runs that case under xvfb-run). A
// back-end that cannot start here is skipped with its reason; OSMesa is what CI relies on.
#include <gtest/gtest.h>

#include <cstdlib>

#include "gl_scenes.hpp"
#include "gl_test_support.hpp"

namespace nut::gltest {
namespace {

// The facade through OSMesa and through `backend`, compared as the GL-vs-CPU tests compare; skips
// when `backend` cannot start here.
void expectSameAsOsMesa(viewer::Backend backend) {
  const Scene s = sampleScene("facade", 320, 180);
  ASSERT_GT(s.image.width, 0);
  viewer::GlFrame reference;
  {
    auto osmesa = openRenderer();
    ASSERT_TRUE(osmesa);
    ASSERT_TRUE(osmesa->addHni(s.image, s.originM).ok());
    auto frame = osmesa->render(s.camera, {});
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    reference = std::move(*frame);
  }
  viewer::OffscreenOptions options;
  options.backend = backend;
  auto other = viewer::OffscreenRenderer::create(options);
  if (!other) GTEST_SKIP() << viewer::backendName(backend) << " is unavailable here: " << other.error().message;
  std::printf("%s: %s\n", viewer::backendName(backend), (*other)->context().description().c_str());
  ASSERT_TRUE((*other)->addHni(s.image, s.originM).ok());
  auto frame = (*other)->render(s.camera, {});
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  const Agreement a = compareFrames(outputDir("backends"), std::string("facade-") + viewer::backendName(backend),
                                    reference.colour, reference.windowDepth, frame->colour, frame->windowDepth, 2, 99.9);
  EXPECT_GE(a.withinPct, 99.9);
  EXPECT_EQ(a.depthOutOfRange, 0);
}

TEST(Backend, EglRendersWhatOsMesaRenders) { expectSameAsOsMesa(viewer::Backend::Egl); }

TEST(Backend, GlfwRendersWhatOsMesaRenders) {
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
    GTEST_SKIP() << "no display: ctest runs this case again under xvfb-run (gl_backends_glfw_xvfb)";
  expectSameAsOsMesa(viewer::Backend::Glfw);
}

}  // namespace
}  // namespace nut::gltest
