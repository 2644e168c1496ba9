// The GLFW back-end: an OpenGL core context with a window (GLX or Wayland). On a machine without a
// display run the program under `xvfb-run`. The window is hidden unless asked for; rendering goes
// to framebuffer objects either way, and an application presents by blitting to the window.
#include <string>

#define GLFW_INCLUDE_NONE  // glcorearb.h (viewer/gl.hpp) declares what GL is needed
#include <GLFW/glfw3.h>

#include "backends.hpp"

namespace nut::viewer {

namespace {

// glfwInit and glfwTerminate are process-wide: the library stays initialised while a window lives.
int gLiveWindows = 0;

std::string glfwErrorText() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "no description";
}

class GlfwBackend final : public Context {
 public:
  explicit GlfwBackend(GLFWwindow* window) : Context(Backend::Glfw), window_(window) { ++gLiveWindows; }
  ~GlfwBackend() override {
    glfwDestroyWindow(window_);
    if (--gLiveWindows == 0) glfwTerminate();
  }

  GLFWwindow* window() const override { return window_; }

  Status makeCurrent() const override {
    glfwMakeContextCurrent(window_);
    if (glfwGetCurrentContext() != window_) return Error{"glfwMakeContextCurrent failed (" + glfwErrorText() + ")"};
    return Ok{};
  }

  Status initialise() {
    return Context::initialise([](const char* name) { return reinterpret_cast<GlProc>(glfwGetProcAddress(name)); });
  }

 private:
  GLFWwindow* window_;
};

}  // namespace

Result<std::unique_ptr<Context>> createGlfwContext(const ContextOptions& options) {
  if (!glfwInit())
    return Error{"GLFW: cannot initialise (" + glfwErrorText() + "); without a display, run under xvfb-run"};
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  GLFWwindow* window =
      glfwCreateWindow(options.windowWidth, options.windowHeight, options.windowTitle.c_str(), nullptr, nullptr);
  if (window == nullptr) {
    const std::string why = glfwErrorText();
    if (gLiveWindows == 0) glfwTerminate();
    return Error{"GLFW: cannot create a window with an OpenGL 3.3 core context (" + why + ")"};
  }
  auto backend = std::make_unique<GlfwBackend>(window);
  Status current = backend->makeCurrent();
  if (current) current = backend->initialise();
  if (!current) return Error{"GLFW: " + current.error().message};
  return std::unique_ptr<Context>(std::move(backend));
}

}  // namespace nut::viewer
