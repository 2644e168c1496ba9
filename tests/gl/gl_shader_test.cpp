// The GLSL building blocks against their C++ originals, value by value: the 69 solids
// (solids.glsl vs nut::intersectSolid<float>), the metadata lookups (hni_access.glsl vs
// nut::AxisView on every axis of the sample building), the yaw rotation (against double cos and
// sin). A probe fragment shader evaluates the GLSL function once per pixel of a float framebuffer,
// on inputs read from float textures. Also: every program compiles under GLSL 330 and under the
// context's own version, and a compile error names the program, the stage, the GLSL version, and
// the file and line of each message.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include <glm/geometric.hpp>

#include <nut/format.hpp>
#include <nut/hni_view.hpp>
#include <nut/plane_cells.hpp>
#include <nut/png_io.hpp>
#include <nut/solids.hpp>
#include <viewer/context.hpp>
#include <viewer/hni_renderer.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/render_target.hpp>
#include <viewer/shader_library.hpp>

namespace nut::gltest {
namespace {

using viewer::Gl;
using viewer::GlObject;

// A triangle that covers the viewport, from gl_VertexID alone.
constexpr const char* kFullscreenVertex = R"(
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)";

// Evaluates a probe fragment shader over width x height pixels; the inputs are float textures
// bound to uInput0, uInput1 (RGBA32F), the HNI atlas (if any) to uHni; returns RGBA32F texels.
class Probe {
 public:
  explicit Probe(std::unique_ptr<viewer::Context> context) : context_(std::move(context)), gl_(context_->gl()) {}

  GlObject floatTexture(int width, int height, const std::vector<float>& rgba) const {
    GlObject t = viewer::makeTexture(gl_);
    gl_.BindTexture(GL_TEXTURE_2D, t.get());
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, rgba.empty() ? nullptr : rgba.data());
    gl_.BindTexture(GL_TEXTURE_2D, 0);
    return t;
  }

  // Runs `fragmentFiles` (after the prelude) with the library's sources and `probeSource`.
  std::vector<float> run(const std::vector<std::string>& libraryFiles, const std::string& probeSource, int width,
                         int height, const std::vector<const GlObject*>& inputs, GLuint hniTexture = 0) const {
    viewer::ShaderLibrary library;
    library.add("probe.vert", kFullscreenVertex);
    library.add("probe.frag", probeSource);
    std::vector<std::string> files = libraryFiles;
    files.push_back("probe.frag");
    auto program = viewer::Program::build(gl_, library, {"probe", {"probe.vert"}, files}, 330);
    if (!program) {
      ADD_FAILURE() << program.error().message;
      return {};
    }
    const GlObject output = floatTexture(width, height, {});
    const GlObject framebuffer = viewer::makeFramebuffer(gl_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, output.get(), 0);
    EXPECT_EQ(gl_.CheckFramebufferStatus(GL_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
    gl_.Viewport(0, 0, width, height);
    gl_.UseProgram(program->id());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
      gl_.BindTexture(GL_TEXTURE_2D, inputs[i]->get());
      gl_.Uniform1i(program->uniform(("uInput" + std::to_string(i)).c_str()), static_cast<GLint>(i));
    }
    if (hniTexture) {
      gl_.ActiveTexture(GL_TEXTURE0 + 7);
      gl_.BindTexture(GL_TEXTURE_2D, hniTexture);
      gl_.Uniform1i(program->uniform("uHni"), 7);
    }
    const GlObject vertexArray = viewer::makeVertexArray(gl_);
    gl_.BindVertexArray(vertexArray.get());
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, out.data());
    EXPECT_EQ(gl_.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    return out;
  }

  const viewer::Context& context() const { return *context_; }

 private:
  std::unique_ptr<viewer::Context> context_;
  const Gl& gl_;
};

std::unique_ptr<Probe> openProbe() {
  auto context = viewer::createContext(viewer::Backend::OSMesa);
  if (!context) {
    ADD_FAILURE() << context.error().message;
    return nullptr;
  }
  return std::make_unique<Probe>(std::move(*context));
}

double ulpsApart(float a, float b) {
  if (a == b) return 0;
  return std::abs(static_cast<double>(a) - b) / (std::numeric_limits<float>::epsilon() * std::max(1.0f, std::max(std::abs(a), std::abs(b))));
}

TEST(ShaderSolids, MatchTheCppFloatIntersection) {
  auto probe = openProbe();
  ASSERT_TRUE(probe);
  // Random rays through the unit cube, from inside and outside, clipped to it in double; pixel x
  // takes solid x mod 69. Inputs and outputs are the floats both implementations see.
  constexpr int kWidth = kSolidCount * 4, kHeight = 64;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> position(-1.0, 2.0), axis(-1.0, 1.0);
  std::vector<float> rayOrigin, rayDirection;
  for (int i = 0; i < kWidth * kHeight; ++i) {
    while (true) {
      const glm::dvec3 o(position(rng), position(rng), position(rng));
      glm::dvec3 d(axis(rng), axis(rng), axis(rng));
      if (i % 7 == 0) d[i % 3] = 0.0;  // rays along the cube's faces and axes too
      if (glm::length(d) < 1e-3) continue;
      d = glm::normalize(d);
      double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
      bool inside = true;
      for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
          inside = inside && o[a] >= 0.0 && o[a] <= 1.0;
          continue;
        }
        double ta = -o[a] / d[a], tb = (1.0 - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
      }
      if (!inside || !(t0 < t1)) continue;
      rayOrigin.insert(rayOrigin.end(), {float(o.x), float(o.y), float(o.z), float(t0)});
      rayDirection.insert(rayDirection.end(), {float(d.x), float(d.y), float(d.z), float(t1)});
      break;
    }
  }
  const GlObject origins = probe->floatTexture(kWidth, kHeight, rayOrigin);
  const GlObject directions = probe->floatTexture(kWidth, kHeight, rayDirection);
  const std::vector<float> out = probe->run({"solids.glsl"}, R"(
uniform sampler2D uInput0;
uniform sampler2D uInput1;
out vec4 result;
void main() {
  ivec2 at = ivec2(gl_FragCoord.xy);
  vec4 o = texelFetch(uInput0, at, 0), d = texelFetch(uInput1, at, 0);
  SolidHit hit = intersectSolid(at.x % kSolidCount, o.xyz, d.xyz, o.w, d.w);
  result = hit.hit ? vec4(hit.t, hit.normal) : vec4(-1.0);
}
)", kWidth, kHeight, {&origins, &directions});
  ASSERT_EQ(out.size(), rayOrigin.size());

  long long hits = 0, hitMismatch = 0, tOff = 0, normalOff = 0;
  double worstT = 0, worstNormal = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x));
      const glm::vec3 o(rayOrigin[i], rayOrigin[i + 1], rayOrigin[i + 2]);
      const glm::vec3 d(rayDirection[i], rayDirection[i + 1], rayDirection[i + 2]);
      const auto cpu = intersectSolid<float>(Solid{static_cast<std::uint8_t>(x % kSolidCount)}, o, d, rayOrigin[i + 3],
                                             rayDirection[i + 3]);
      const bool glHit = out[i + 1] != -1.0f || out[i] != -1.0f;
      if (cpu.has_value() != glHit) {
        ++hitMismatch;
        continue;
      }
      if (!cpu) continue;
      ++hits;
      const double tUlps = ulpsApart(cpu->t, out[i]);
      worstT = std::max(worstT, tUlps);
      tOff += tUlps > 4;
      const double n = glm::length(cpu->normal - glm::vec3(out[i + 1], out[i + 2], out[i + 3]));
      worstNormal = std::max(worstNormal, n);
      normalOff += n > 1e-5;
    }
  std::printf("solids: %lld rays, %lld hits; hit/miss disagree on %lld; t worst %.1f ulps (%lld beyond 4); normal "
              "worst %.2g (%lld beyond 1e-5)\n",
              static_cast<long long>(kWidth) * kHeight, hits, hitMismatch, worstT, tOff, worstNormal, normalOff);
  // Float rounding may differ (fused multiply-adds, division): a ray grazing a surface may flip.
  EXPECT_LE(hitMismatch, kWidth * kHeight / 2000);
  EXPECT_LE(tOff, hits / 1000);
  EXPECT_LE(normalOff, hits / 1000);
}

// Plane cells: the shader's octahedral decoding and plane span against nut::decodeNormalFloat and
// nut::intersectPlaneCut<float> on random codes, offsets and rays (one, both and either by column).
TEST(ShaderPlaneCells, MatchTheCppFloatDecodingAndSpan) {
  auto probe = openProbe();
  ASSERT_TRUE(probe);
  constexpr int kWidth = 192, kHeight = 96;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0), axis(-1.0, 1.0);
  std::uniform_int_distribution<std::uint32_t> code(1, format::kOctahedralMax);
  std::vector<float> rayOrigin, rayDirection, codes, offsets;
  for (int i = 0; i < kWidth * kHeight; ++i) {
    glm::dvec3 d;
    do d = {axis(rng), axis(rng), axis(rng)};
    while (glm::length(d) < 1e-3);
    d = glm::normalize(d);
    const float tEnter = static_cast<float>(unit(rng)), tExit = tEnter + static_cast<float>(unit(rng));
    rayOrigin.insert(rayOrigin.end(), {float(axis(rng)), float(axis(rng)), float(axis(rng)), tEnter});
    rayDirection.insert(rayDirection.end(), {float(d.x), float(d.y), float(d.z), tExit});
    // Codes below 2^24 are exact floats; offsets such that the planes pass near the ray's span.
    codes.insert(codes.end(), {float(code(rng)), float(code(rng)), float(code(rng)), float(code(rng))});
    offsets.insert(offsets.end(), {float(axis(rng)), float(axis(rng)), 0.0f, 0.0f});
  }
  const GlObject origins = probe->floatTexture(kWidth, kHeight, rayOrigin);
  const GlObject directions = probe->floatTexture(kWidth, kHeight, rayDirection);
  const GlObject codeTexture = probe->floatTexture(kWidth, kHeight, codes);
  const GlObject offsetTexture = probe->floatTexture(kWidth, kHeight, offsets);
  const std::vector<float> out = probe->run({"hni_access.glsl", "solids.glsl"}, R"(
uniform sampler2D uInput0;
uniform sampler2D uInput1;
uniform sampler2D uInput2;
uniform sampler2D uInput3;
out vec4 result;
void main() {
  ivec2 at = ivec2(gl_FragCoord.xy);
  vec4 o = texelFetch(uInput0, at, 0), d = texelFetch(uInput1, at, 0);
  uvec4 e = uvec4(texelFetch(uInput2, at, 0));
  vec4 offsets = texelFetch(uInput3, at, 0);
  vec3 n0 = decodeOctahedral(e.x, e.y), n1 = decodeOctahedral(e.z, e.w);
  vec3 span = intersectPlaneCut(n0, offsets.x, n1, offsets.y, 1 + at.x % 3, o.xyz, d.xyz, o.w, d.w);
  result = span.x <= span.y ? vec4(span, n0.x + n1.y) : vec4(-1.0);
}
)", kWidth, kHeight, {&origins, &directions, &codeTexture, &offsetTexture});
  ASSERT_EQ(out.size(), rayOrigin.size());
  long long hits = 0, hitMismatch = 0, tOff = 0, planeOff = 0, normalOff = 0;
  double worstT = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x));
      const std::array<glm::vec3, 2> normals{
          decodeNormalFloat(static_cast<std::uint32_t>(codes[i]), static_cast<std::uint32_t>(codes[i + 1])),
          decodeNormalFloat(static_cast<std::uint32_t>(codes[i + 2]), static_cast<std::uint32_t>(codes[i + 3]))};
      const auto cpu = intersectPlaneCut<float>(normals, {offsets[i], offsets[i + 1]},
                                                static_cast<PlaneCombine>(1 + x % 3),
                                                {rayOrigin[i], rayOrigin[i + 1], rayOrigin[i + 2]},
                                                {rayDirection[i], rayDirection[i + 1], rayDirection[i + 2]},
                                                rayOrigin[i + 3], rayDirection[i + 3]);
      const bool glHit = !(out[i] == -1.0f && out[i + 1] == -1.0f);
      if (cpu.has_value() != glHit) {
        ++hitMismatch;
        continue;
      }
      if (!cpu) continue;
      ++hits;
      const double tUlps = ulpsApart(cpu->tIn, out[i]);
      worstT = std::max(worstT, tUlps);
      tOff += tUlps > 4;
      planeOff += cpu->plane != static_cast<int>(out[i + 2]);
      normalOff += std::abs(normals[0].x + normals[1].y - out[i + 3]) > 1e-6f;
    }
  std::printf("plane cells: %d rays, %lld hits; hit/miss disagree on %lld; t worst %.1f ulps (%lld beyond 4); plane "
              "differs on %lld; decoded normals differ on %lld\n",
              kWidth * kHeight, hits, hitMismatch, worstT, tOff, planeOff, normalOff);
  EXPECT_GT(hits, kWidth * kHeight / 10);
  EXPECT_LE(hitMismatch, kWidth * kHeight / 2000);
  EXPECT_LE(tOff, hits / 1000);
  EXPECT_LE(planeOff, hits / 1000);
  EXPECT_EQ(normalOff, 0);
}

TEST(ShaderLookups, MatchAxisViewOnTheSampleBuilding) {
  auto probe = openProbe();
  ASSERT_TRUE(probe);
  auto png = readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/building.png");
  ASSERT_TRUE(png.ok());
  const Image& image = png->image;
  auto atlas = viewer::HniAtlas::create(probe->context().gl(), image.width, image.height);
  ASSERT_TRUE(atlas.ok());
  ASSERT_TRUE(atlas->put(image, {0, 0}).ok());

  // Per query: header (u, v), axis, coordinate. Coordinates: every boundary (heuristic and exact
  // position, and the floats beside them), random ones, and some outside the block.
  const HniView view(image);
  const FileRecord file = view.fileRecord();
  struct Query {
    TexelAddress header;
    int axis;
    float x;
  };
  std::vector<Query> queries;
  std::mt19937_64 rng(5);
  for (int b = 0; b < file.blockCount; ++b) {
    const TexelAddress at = view.blockAddress(file, b);
    const BlockHeader h = view.header(at);
    for (int a = 0; a < 3; ++a) {
      const AxisView axis = view.axis(h, a);
      for (int k = 0; k < axis.pixels; ++k) {
        if (axis.meta[4 * k + 1] == 0) continue;
        for (float x : {axis.boundaryHeuristic(k), axis.exactPosition(k)})
          for (float near : {std::nextafter(x, 0.0f), x, std::nextafter(x, 1e9f)}) queries.push_back({at, a, near});
      }
      std::uniform_real_distribution<float> inside(-0.01f * axis.size, 1.01f * axis.size);
      for (int i = 0; i < 64; ++i) queries.push_back({at, a, inside(rng)});
    }
  }
  const int width = 256, height = static_cast<int>((queries.size() + 255) / 256);
  std::vector<float> input(static_cast<std::size_t>(width) * height * 4, 0.0f);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    input[4 * i] = static_cast<float>(queries[i].header.u);
    input[4 * i + 1] = static_cast<float>(queries[i].header.v);
    input[4 * i + 2] = static_cast<float>(queries[i].axis);
    input[4 * i + 3] = queries[i].x;
  }
  const GlObject inputs = probe->floatTexture(width, height, input);
  const std::vector<float> out = probe->run({"hni_access.glsl"}, R"(
uniform sampler2D uInput0;
out vec4 result;
void main() {
  gHniOrigin = ivec2(0);
  vec4 q = texelFetch(uInput0, ivec2(gl_FragCoord.xy), 0);
  BlockInfo b = loadBlock(ivec2(q.xy));
  int a = int(q.z);
  int k = pixelOf(b, a, q.w);
  int step = stepOf(b, a, q.w);
  uvec4 p = metaTexel(b, a, k);
  // The heuristic lookup reads pixel step >> 8: a different pixel than pixelOf shows as -1.
  result = vec4(step >> 8 == k ? float(cellHeuristic(p, step)) : -1.0, float(cellExact(b, a, q.w, k, p)), float(k),
                boundaryHeuristic(b, a, k));
}
)", width, height, {&inputs}, atlas->texture());
  ASSERT_EQ(out.size(), input.size());
  long long heuristicOff = 0, exactOff = 0, pixelOff = 0, positionOff = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    const AxisView axis = view.axis(view.header(q.header), q.axis);
    const int k = axis.pixelOf(q.x);
    heuristicOff += out[4 * i] != static_cast<float>(axis.cellHeuristic(q.x));
    exactOff += out[4 * i + 1] != static_cast<float>(axis.cellExact(q.x));
    pixelOff += out[4 * i + 2] != static_cast<float>(k);
    positionOff += out[4 * i + 3] != axis.boundaryHeuristic(k);
  }
  std::printf("lookups: %zu queries; differing: heuristic cell %lld, exact cell %lld, pixel %lld, boundary position %lld\n",
              queries.size(), heuristicOff, exactOff, pixelOff, positionOff);
  EXPECT_EQ(heuristicOff, 0);
  EXPECT_EQ(exactOff, 0);
  EXPECT_EQ(pixelOff, 0);
  EXPECT_EQ(positionOff, 0);
}

TEST(ShaderYaw, CosAndSinOfEveryYawToAnUlp) {
  auto probe = openProbe();
  ASSERT_TRUE(probe);
  const std::vector<float> out = probe->run({"hni_access.glsl"}, R"(
out vec4 result;
void main() {
  uint yaw = uint(gl_FragCoord.y) * 256u + uint(gl_FragCoord.x);
  result = vec4(yawCosSin(yaw), 0.0, 0.0);
}
)", 256, 256, {});
  ASSERT_EQ(out.size(), std::size_t{256 * 256 * 4});
  double worst = 0;
  for (int yaw = 0; yaw < 65536; ++yaw) {
    const double angle = 2.0 * 3.14159265358979323846 * yaw / 65536.0;
    worst = std::max({worst, std::abs(out[4 * static_cast<std::size_t>(yaw)] - std::cos(angle)),
                      std::abs(out[4 * static_cast<std::size_t>(yaw) + 1] - std::sin(angle))});
  }
  std::printf("yaw: worst |error| of cos and sin over 65536 angles: %.3g\n", worst);
  EXPECT_LE(worst, 1.2e-7);  // one float ulp at 1
}

TEST(ShaderPrograms, CompileUnderGlsl330AndTheContextsVersion) {
  auto context = viewer::createContext(viewer::Backend::OSMesa);
  ASSERT_TRUE(context.ok()) << context.error().message;
  std::printf("%s, GLSL %d\n", (*context)->description().c_str(), (*context)->glslVersion());
  EXPECT_GE((*context)->glslVersion(), 330);
  const viewer::ShaderLibrary library;
  for (int version : {330, (*context)->glslVersion()}) {
    auto hni = viewer::HniRenderer::create(**context, library, version);
    EXPECT_TRUE(hni.ok()) << hni.error().message;
    auto mesh = viewer::MeshRenderer::create(**context, library, version);
    EXPECT_TRUE(mesh.ok()) << mesh.error().message;
  }
}

TEST(ShaderPrograms, CompileErrorsNameProgramStageVersionFileAndLine) {
  auto context = viewer::createContext(viewer::Backend::OSMesa);
  ASSERT_TRUE(context.ok()) << context.error().message;
  viewer::ShaderLibrary library;
  library.add("mesh.frag", "out vec4 colour;\nvoid main() { colour = vec4(undeclared); }\n");
  auto mesh = viewer::MeshRenderer::create(**context, library, 330);
  ASSERT_FALSE(mesh.ok());
  const std::string& message = mesh.error().message;
  std::printf("%s\n", message.c_str());
  for (const char* part : {"mesh: fragment shader, GLSL 330:", "mesh.frag:2(", "undeclared"})
    EXPECT_NE(message.find(part), std::string::npos) << part;
  // A missing file is named too.
  auto missing = viewer::HniRenderer::create(**context, viewer::ShaderLibrary("/nonexistent"), 330);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/common.glsl"), std::string::npos) << missing.error().message;
}

TEST(Backends, UnknownNamesAreRefused) {
  EXPECT_TRUE(viewer::parseBackend("osmesa").ok());
  auto bad = viewer::parseBackend("vulkan");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("osmesa, egl or glfw"), std::string::npos);
}

TEST(GlTextures, SizesOutsideTheContextsLimitAreRefusedNamingIt) {
  auto probe = openProbe();
  ASSERT_TRUE(probe);
  const viewer::Gl& gl = probe->context().gl();
  GLint maxSize = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  const std::string limit = "the GL context takes 1.." + std::to_string(maxSize) + " per side";
  for (const auto& [w, h] : {std::pair{0, 4}, std::pair{4, -1}, std::pair{static_cast<int>(maxSize) + 1, 4}}) {
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    auto atlas = viewer::HniAtlas::create(gl, w, h);
    ASSERT_FALSE(atlas.ok()) << size;
    EXPECT_EQ(atlas.error().message, "HNI atlas " + size + ": " + limit);
    auto target = viewer::RenderTarget::create(gl, w, h);
    ASSERT_FALSE(target.ok()) << size;
    EXPECT_EQ(target.error().message, "render target " + size + ": " + limit);
  }
  EXPECT_TRUE(viewer::HniAtlas::create(gl, 4, 4).ok());
  EXPECT_TRUE(viewer::RenderTarget::create(gl, 4, 4).ok());
}

}  // namespace
}  // namespace nut::gltest
