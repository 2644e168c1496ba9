// viewer/post_process.hpp — optional full-screen passes over a finished frame (shaders/fxaa.frag).
// Not for frames compared with the CPU renderers, which do not anti-alias.
#pragma once

#include <nut/error.hpp>

#include <viewer/context.hpp>
#include <viewer/gl_object.hpp>
#include <viewer/render_target.hpp>
#include <viewer/shader_library.hpp>

namespace nut::viewer {

class Fxaa {
 public:
  static Result<Fxaa> create(const Context& context, const ShaderLibrary& library, int glslVersion = 0);

  // Writes the anti-aliased colour of `source` into `destination` (same size); depth is untouched.
  void apply(const RenderTarget& source, const RenderTarget& destination) const;

 private:
  Fxaa(const Gl& gl, Program program) : gl_(&gl), program_(std::move(program)) {}
  const Gl* gl_;
  Program program_;
  GlObject vertexArray_;
};

}  // namespace nut::viewer
