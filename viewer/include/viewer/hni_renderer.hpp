// viewer/hni_renderer.hpp — HNIs on the GPU: an atlas texture that holds one or many HNIs, and
// the ray-casting program drawn as one proxy box per instance (shaders/hni_proxy.vert,
// shaders/hni_raycast.frag), all instances of an atlas in one instanced draw.
//
// The program is a port of the CPU reference caster (nut/raycast.hpp) and takes the same options;
// it renders the same image (docs/GL.md gives the measured agreement) and writes depth, so HNIs and
// meshes mix in one depth-tested frame.
#pragma once

#include <span>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/raycast.hpp>

#include <viewer/context.hpp>
#include <viewer/frame_view.hpp>
#include <viewer/gl_object.hpp>
#include <viewer/shader_library.hpp>

namespace nut::viewer {

// A GL_RGBA8UI texture read with texelFetch (integer texels, no filtering). Every address inside
// an HNI is relative to its origin, so HNIs are packed anywhere (MaxRects: OffscreenRenderer lays
// them out with the packer's width search).
class HniAtlas {
 public:
  // An empty atlas; errors when the size exceeds GL_MAX_TEXTURE_SIZE.
  static Result<HniAtlas> create(const Gl& gl, int width, int height);

  // Uploads an HNI (validate() it first) with its origin at `at`, a place the caller's layout gave
  // it (packer::packSearchWidth); fails when it does not lie inside the atlas.
  Status put(const Image& hni, glm::ivec2 at);

  GLuint texture() const { return texture_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  HniAtlas(const Gl& gl, int width, int height) : gl_(&gl), width_(width), height_(height) {}
  const Gl* gl_;
  int width_, height_;
  GlObject texture_;
};

// One building: an HNI of the atlas placed in the world.
struct HniInstance {
  glm::ivec2 atlasOrigin{0};
  glm::dvec3 originM{0.0};         // world position of the root block's minimum corner
  glm::dmat3 worldFromRoot{1.0};   // rotation of the root block's axes (as for nut::HniRayCaster)
};

// The ray caster's program, one per lookup mode: the files and the NUT_EXACT_LOOKUP define that
// HniRenderer builds, and the browser viewer's export assembles as GLSL ES (docs/WEB.md).
ProgramSpec hniRayCasterSpec(Lookup lookup);

class HniRenderer {
 public:
  // Builds the program under the context's GLSL version, or `glslVersion` when non-zero.
  static Result<HniRenderer> create(const Context& context, const ShaderLibrary& library, int glslVersion = 0);

  // Draws the instances into the bound framebuffer: depth test (GL_LEQUAL) and write, front faces
  // culled, blending GL_ONE, GL_SRC_ALPHA (hni_raycast.frag). Opaque meshes should be drawn first,
  // so that what shows through translucent cells is there.
  void draw(const FrameView& view, const HniAtlas& atlas, std::span<const HniInstance> instances,
            const RayCastOptions& options) const;

 private:
  HniRenderer(const Gl& gl, Program heuristic, Program exact)
      : gl_(&gl), heuristic_(std::move(heuristic)), exact_(std::move(exact)) {}
  const Gl* gl_;
  // One program per lookup mode (NUT_EXACT_LOOKUP): a uniform would keep both lookups in the
  // traversal loop, which costs llvmpipe about 15 %.
  Program heuristic_, exact_;
  GlObject vertexArray_, instanceBuffer_;
};

}  // namespace nut::viewer
