// Hostile HNIs on the GLSL ray caster: the work a ray may do is bounded, so a file cannot hang the
// GPU. A thousand-fold wrap seen along its row needs thousands of cell visits per ray: the shader
// stops at its iteration cap and draws those rays magenta, as the CPU caster does; a chain of a
// thousand redirections (the deepest the metadata region holds; cycles are refused by validate)
// ends at the stack depth with visual summaries; a cyclic file never reaches the shader.
#include <gtest/gtest.h>

#include <chrono>

#include <nut/format.hpp>
#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/raycast.hpp>

#include "gl_scenes.hpp"
#include "gl_test_support.hpp"

namespace nut::gltest {
namespace {

// Generous for a 2-core CI machine: the slowest frame here, 160x90 pixels of which 56 % run to the
// cap of 512 cell visits, takes about 3 s on llvmpipe.
constexpr double kFrameSecondsLimit = 30.0;

long long countCapped(const Image& image) {
  long long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      n += p[0] == kCappedColour[0] && p[1] == kCappedColour[1] && p[2] == kCappedColour[2];
    }
  return n;
}

// Renders with both casters, checks that they agree and that the GL frame took bounded time;
// returns the number of capped (magenta) pixels of the GL frame.
long long renderBounded(Scene& s) {
  const HniRayCaster caster(s.image, s.originM);
  const RenderOutput cpu = renderHni(caster, s.camera, s.options);
  auto renderer = openRenderer();
  if (!renderer) return -1;
  EXPECT_TRUE(renderer->addHni(s.image, s.originM).ok());
  // Includes llvmpipe's compilation of the shader variant at the first draw (about 0.5 s).
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(renderer->draw(s.camera, s.options).ok());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const viewer::GlFrame gl = renderer->read(s.camera);
  const long long capped = countCapped(gl.colour);
  std::printf("%s, cap %d: GL frame %.3f s, %lld capped pixels (CPU %lld)\n", s.name.c_str(), s.options.maxIterations,
              seconds, capped, countCapped(cpu.colour));
  EXPECT_LT(seconds, kFrameSecondsLimit) << s.name;
  const Agreement a = compareFrames(outputDir("hostile"), s.name, cpu.colour, cpu.windowDepth, gl.colour,
                                    gl.windowDepth, 2, 99.9);
  EXPECT_GE(a.withinPct, 99.9) << s.name;
  EXPECT_EQ(a.depthOutOfRange, 0) << s.name;
  return capped;
}

TEST(Hostile, ThousandFoldWrapStopsAtTheIterationCap) {
  Scene s = compiledScene("wrap-1000", thousandFoldWrap(), glm::dvec3(0.0), 160, 90);
  // At one end of the 1000 m row, looking along it through a telephoto lens: most rays travel
  // hundreds of metres before they meet a post or a sill or leave the row.
  s.camera.eye = glm::dvec3(-1.0, 1.05, 0.95);
  s.camera.target = glm::dvec3(1000.0, 1.0, 1.0);
  s.camera.fovYDeg = 1.0;
  s.camera.nearM = 0.1;
  s.camera.farM = 1100.0;
  const long long cappedAt512 = renderBounded(s);
  EXPECT_GT(cappedAt512, 100) << "rays along the row need thousands of steps";
  s.name = "wrap-1000-cap-64";
  s.options.maxIterations = 64;
  EXPECT_GT(renderBounded(s), cappedAt512) << "a lower cap stops more rays";
}

// A chain of `levels` blocks of the same size: each block's second cell shows the next block,
// shifted so that the next block's second cell falls into it again.
Hierarchy sameSizeChain(int levels) {
  Hierarchy h;
  h.materials = {{200, 60, 40, 255, 0}, {60, 160, 90, 255, 0}};
  for (int k = 0; k < levels; ++k) {
    Block b = Block::fromSizes({{{1.0, 1.0}, {1.0, 1.0}, {1.0}}});
    b.cell(0, 0, 0) = Cell::box(static_cast<std::uint16_t>(k % 2));
    if (k + 1 < levels) {
      b.redirections.push_back({static_cast<BlockId>(k + 1), glm::dvec3(-1.0, -1.0, 0.0), {}, {false, false, false}});
      b.cell(1, 1, 0) = Cell::redirect(0);
    } else {
      b.cell(1, 1, 0) = Cell::box(1);
    }
    h.addBlock(std::move(b));
  }
  return h;
}

TEST(Hostile, ThousandLevelChainEndsAtTheStackDepth) {
  Scene s = compiledScene("chain-1000", sameSizeChain(1000), glm::dvec3(0.0), 320, 180);
  ASSERT_GT(s.image.width, 0);
  s.camera.eye = glm::dvec3(1.5, 1.5, 4.0);
  s.camera.target = glm::dvec3(1.5, 1.5, 0.5);
  s.camera.nearM = 0.5;
  s.camera.farM = 10.0;
  EXPECT_EQ(renderBounded(s), 0);
}

TEST(Hostile, CyclicHniNeverReachesTheShader) {
  // root -> block 1 -> block 2, then block 1's record is pointed back at the root.
  Hierarchy h = sameSizeChain(3);
  auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniView view(*image);
  const FileRecord file = view.fileRecord();
  const BlockHeader second = view.header(view.blockAddress(file, 1));
  const std::uint8_t* cell = view.cellTexel(second, {1, 1, 0});
  ASSERT_EQ(cell[3], format::kCellRedirection);
  const TexelAddress record{cell[0], cell[1]};
  std::uint8_t* target = image->at(record.u + 3, record.v);
  target[0] = static_cast<std::uint8_t>(file.root.u);
  target[1] = static_cast<std::uint8_t>(file.root.v);
  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  const Status added = renderer->addHni(*image, glm::dvec3(0.0));
  ASSERT_FALSE(added.ok());
  EXPECT_NE(added.error().message.find("cycle"), std::string::npos) << added.error().message;
}

}  // namespace
}  // namespace nut::gltest
