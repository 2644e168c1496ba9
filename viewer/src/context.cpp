// The back-end-independent part of a context: names, the function table, the GLSL version.
#include <viewer/context.hpp>

#include <cstdio>

#include "backends.hpp"

namespace nut::viewer {

const char* backendName(Backend backend) {
  switch (backend) {
    case Backend::OSMesa: return "osmesa";
    case Backend::Egl: return "egl";
    case Backend::Glfw: return "glfw";
  }
  return "?";
}

Result<Backend> parseBackend(const std::string& name) {
  for (Backend b : {Backend::OSMesa, Backend::Egl, Backend::Glfw})
    if (name == backendName(b)) return b;
  return Error{"unknown GL back-end '" + name + "' (osmesa, egl or glfw)"};
}

std::string Context::description() const {
  const auto text = [this](GLenum name) {
    const GLubyte* s = gl_.GetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

Status Context::initialise(GlProcLoader loader) {
  auto gl = loadGl(loader);
  if (!gl) return gl.error();
  gl_ = *gl;
  GLint major = 0, minor = 0;
  gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
  gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 33)
    return Error{"OpenGL " + std::to_string(major) + "." + std::to_string(minor) + " (" + description() +
                 "); 3.3 core or later is needed"};
  // GL_SHADING_LANGUAGE_VERSION reads "4.50" (possibly followed by vendor text).
  const GLubyte* glsl = gl_.GetString(GL_SHADING_LANGUAGE_VERSION);
  int glslMajor = 0, glslMinor = 0;
  if (glsl == nullptr || std::sscanf(reinterpret_cast<const char*>(glsl), "%d.%d", &glslMajor, &glslMinor) != 2)
    return Error{"the context reports no GLSL version (" + description() + ")"};
  glslVersion_ = glslMajor * 100 + glslMinor;
  if (glslVersion_ < 330) return Error{"GLSL " + std::to_string(glslVersion_) + " (" + description() + "); 330 or later is needed"};
  return Ok{};
}

Result<std::unique_ptr<Context>> createContext(Backend backend, const ContextOptions& options) {
  switch (backend) {
#if NUT_HAVE_OSMESA
    case Backend::OSMesa: return createOSMesaContext(options);
#else
    case Backend::OSMesa: return Error{"osmesa: this nut was built without it (NUT_GL_OSMESA=OFF)"};
#endif
    case Backend::Egl: return createEglContext(options);
    case Backend::Glfw: return createGlfwContext(options);
  }
  return Error{"unknown GL back-end"};
}

}  // namespace nut::viewer
