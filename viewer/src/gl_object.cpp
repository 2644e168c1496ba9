// Creating GL objects owned by GlObject.
#include <viewer/gl_object.hpp>

namespace nut::viewer {

GlObject makeTexture(const Gl& gl) {
  GLuint name = 0;
  gl.GenTextures(1, &name);
  return {gl, name, [](const Gl& g, GLuint n) { g.DeleteTextures(1, &n); }};
}

Status checkTextureSize(const Gl& gl, const std::string& what, int width, int height) {
  GLint maxSize = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (width < 1 || height < 1 || width > maxSize || height > maxSize)
    return Error{what + " " + std::to_string(width) + "x" + std::to_string(height) + ": the GL context takes 1.." +
                 std::to_string(maxSize) + " per side"};
  return Ok{};
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

GlObject makeQuery(const Gl& gl) {
  GLuint name = 0;
  gl.GenQueries(1, &name);
  return {gl, name, [](const Gl& g, GLuint n) { g.DeleteQueries(1, &n); }};
}

}  // namespace nut::viewer
