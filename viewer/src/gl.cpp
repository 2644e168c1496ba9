// Loading the GL function table through a back-end's loader.
#include <viewer/gl.hpp>

namespace nut::viewer {

Result<Gl> loadGl(GlProcLoader loader) {
  Gl gl;
#define NUT_GL_LOAD(type, name)                                               \
  gl.name = reinterpret_cast<type>(loader("gl" #name));                       \
  if (gl.name == nullptr) return Error{"the context does not provide gl" #name};
  NUT_GL_FUNCTIONS(NUT_GL_LOAD)
#undef NUT_GL_LOAD
  return gl;
}

std::string glErrorName(GLenum error) {
  switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "GL error " + std::to_string(error);
  }
}

}  // namespace nut::viewer
