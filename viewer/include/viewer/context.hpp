// viewer/context.hpp — an OpenGL 3.3+ core context from one of three back-ends, behind one
// interface:
//
//   OSMesa  headless, Mesa's llvmpipe on the CPU: what the tests and CI use
//   EGL     headless: a GPU through EGL devices, else Mesa's surfaceless platform (llvmpipe)
//   GLFW    a window (GLX or Wayland; under `xvfb-run` on a machine without a display)
//
// Rendering never touches the default framebuffer of the headless back-ends: it goes to a
// RenderTarget (render_target.hpp). A context is current on the thread that created it; the GL
// objects made with it must be destroyed before it.
#pragma once

#include <memory>
#include <string>

#include <nut/error.hpp>

#include <viewer/gl.hpp>

struct GLFWwindow;

namespace nut::viewer {

enum class Backend { OSMesa, Egl, Glfw };

// "osmesa", "egl", "glfw".
const char* backendName(Backend backend);
Result<Backend> parseBackend(const std::string& name);

struct ContextOptions {
  // GLFW only: the window's size and title, and whether it is shown (hidden windows still render).
  int windowWidth = 1280, windowHeight = 720;
  std::string windowTitle = "nut";
  bool visible = false;
};

class Context {
 public:
  virtual ~Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  Backend backend() const { return backend_; }
  const Gl& gl() const { return gl_; }
  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
  std::string description() const;
  // The highest GLSL version the context takes, as in "#version 450 core": 330 or more.
  int glslVersion() const { return glslVersion_; }

  // Makes the context current on this thread: needed before drawing when a program uses several.
  virtual Status makeCurrent() const = 0;

  // The GLFW window, or nullptr for the headless back-ends.
  virtual GLFWwindow* window() const { return nullptr; }

 protected:
  explicit Context(Backend backend) : backend_(backend) {}
  // Loads the function table and checks the version; called by each back-end once, when current.
  Status initialise(GlProcLoader loader);

 private:
  Backend backend_;
  Gl gl_;
  int glslVersion_ = 0;
};

// Creates a context of the back-end and makes it current on this thread. Errors say which
// back-end failed and why ("EGL: no display: ...", "GLFW: no display (run under xvfb-run)"), or
// that the back-end was not built into this program.
Result<std::unique_ptr<Context>> createContext(Backend backend, const ContextOptions& options = {});

}  // namespace nut::viewer
