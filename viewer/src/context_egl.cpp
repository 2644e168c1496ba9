// The EGL back-end: a headless OpenGL core context without any window system. It prefers a
// hardware EGL device (EGL_EXT_device_enumeration, e.g. an NVIDIA GPU), and falls back to Mesa's
// surfaceless platform (llvmpipe on a machine without a GPU). No surface: rendering goes to
// framebuffer objects (EGL_KHR_surfaceless_context).
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "backends.hpp"

namespace nut::viewer {

namespace {

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t length = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + length, name))
    if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0')) return true;
  return false;
}

std::string eglErrorText() {
  char text[32];
  std::snprintf(text, sizeof text, "EGL error 0x%04x", static_cast<unsigned>(eglGetError()));
  return text;
}

class EglBackend final : public Context {
 public:
  EglBackend(EGLDisplay display, EGLContext context) : Context(Backend::Egl), display_(display), context_(context) {}
  // The display stays initialised: EGL displays are shared by the whole process, and terminating
  // it would destroy the contexts of anyone else using it.
  ~EglBackend() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }

  Status makeCurrent() const override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      return Error{"eglMakeCurrent without a surface failed (" + eglErrorText() + ")"};
    return Ok{};
  }

  Status initialise() {
    return Context::initialise([](const char* name) { return reinterpret_cast<GlProc>(eglGetProcAddress(name)); });
  }

 private:
  EGLDisplay display_;
  EGLContext context_;
};

// An OpenGL 3.3 core context on an initialised display, or EGL_NO_CONTEXT.
EGLContext createCoreContext(EGLDisplay display) {
  if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, wanted, &config, 1, &count) || count < 1) return EGL_NO_CONTEXT;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  return eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
}

// The displays to try, best first: hardware devices, software devices, the surfaceless platform.
std::vector<EGLDisplay> candidateDisplays(std::string& notes) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (getPlatformDisplay == nullptr || !hasExtension(client, "EGL_EXT_platform_base")) {
    notes = "EGL_EXT_platform_base is missing";
    return {};
  }
  std::vector<EGLDisplay> hardware, software;
  const auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  const auto queryDeviceString =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (queryDevices && queryDeviceString && hasExtension(client, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices(16, devices, &count))
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY) continue;
        const bool isSoftware = hasExtension(queryDeviceString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software");
        (isSoftware ? software : hardware).push_back(d);
      }
  }
  std::vector<EGLDisplay> out = hardware;
  out.insert(out.end(), software.begin(), software.end());
  if (hasExtension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back(d);
  }
  if (out.empty()) notes = "no EGL device and no surfaceless platform";
  return out;
}

}  // namespace

Result<std::unique_ptr<Context>> createEglContext(const ContextOptions&) {
  std::string notes;
  for (EGLDisplay display : candidateDisplays(notes)) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      notes = "eglInitialize failed (" + eglErrorText() + ")";
      continue;
    }
    EGLContext context = createCoreContext(display);
    if (context == EGL_NO_CONTEXT) {
      notes = "no OpenGL 3.3 core context (" + eglErrorText() + ")";
      continue;
    }
    auto backend = std::make_unique<EglBackend>(display, context);
    Status current = backend->makeCurrent();
    if (current) current = backend->initialise();
    if (!current) {
      notes = current.error().message;
      continue;
    }
    return std::unique_ptr<Context>(std::move(backend));
  }
  return Error{"EGL: no usable display: " + notes};
}

}  // namespace nut::viewer
