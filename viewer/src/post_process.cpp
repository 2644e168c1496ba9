// FXAA as a full-screen triangle over the frame's colour texture.
#include <viewer/post_process.hpp>

namespace nut::viewer {

Result<Fxaa> Fxaa::create(const Context& context, const ShaderLibrary& library, int glslVersion) {
  auto program = Program::build(context.gl(), library, {"FXAA", {"fullscreen.vert"}, {"fxaa.frag"}},
                                glslVersion ? glslVersion : context.glslVersion());
  if (!program) return program.error();
  Fxaa fxaa(context.gl(), std::move(*program));
  fxaa.vertexArray_ = makeVertexArray(context.gl());  // core profile: a draw needs one, even empty
  return fxaa;
}

void Fxaa::apply(const RenderTarget& source, const RenderTarget& destination) const {
  const Gl& gl = *gl_;
  destination.bind();
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_BLEND);
  gl.UseProgram(program_.id());
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, source.colourTexture());
  gl.Uniform1i(program_.uniform("uColour"), 0);
  gl.Uniform2f(program_.uniform("uTexelSize"), 1.0f / static_cast<float>(source.width()),
               1.0f / static_cast<float>(source.height()));
  gl.BindVertexArray(vertexArray_.get());
  gl.DrawArrays(GL_TRIANGLES, 0, 3);
  gl.BindVertexArray(0);
  gl.UseProgram(0);
}

}  // namespace nut::viewer
