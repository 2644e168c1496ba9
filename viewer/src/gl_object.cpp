// Creating GL objects owned by GlObject.
#include <viewer/gl_object.hpp>

namespace nut::viewer {

GlObject makeTexture(const Gl& gl) {
  GLuint name = 0;
  gl.GenTextures(1, &name);
  return {gl, name, [](const Gl& g, GLuint n) { g.DeleteTextures(1, &n); }};
}

GlObject makeBuffer(const Gl& gl) {
  GLuint name = 0;
  gl.GenBuffers(1, &name);
  return {gl, name, [](const Gl& g, GLuint n) { g.DeleteBuffers(1, &n); }};
}

GlObject makeVertexArray(const Gl& gl) {
  GLuint name = 0;
  gl.GenVertexArrays(1, &name);
  return {gl, name, [](const Gl& g, GLuint n) { g.DeleteVertexArrays(1, &n); }};
}

GlObject makeFramebuffer(const Gl& gl) {
  GLuint name = 0;
  gl.GenFramebuffers(1, &name);
  return {gl, name, [](const Gl& g, GLuint n) { g.DeleteFramebuffers(1, &n); }};
}

}  // namespace nut::viewer
