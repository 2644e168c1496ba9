// The OSMesa back-end: an OpenGL core context rendered by Mesa on the CPU (llvmpipe), no display
// needed. libepoxy does not work with OSMesa, so functions come from OSMesaGetProcAddress.
#include <array>
#include <cstdint>

#include <GL/glcorearb.h>  // before osmesa.h, which would otherwise pull in the legacy GL/gl.h
#include <GL/osmesa.h>

#include "backends.hpp"

namespace nut::viewer {

namespace {

class OSMesaBackend final : public Context {
 public:
  explicit OSMesaBackend(OSMesaContext context) : Context(Backend::OSMesa), context_(context) {}
  ~OSMesaBackend() override { OSMesaDestroyContext(context_); }

  Status makeCurrent() const override {
    // OSMesa needs a colour buffer to make a context current; rendering goes to framebuffer
    // objects, so one pixel is enough.
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) return Error{"OSMesaMakeCurrent failed"};
    return Ok{};
  }

  Status initialise() {
    return Context::initialise([](const char* name) { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); });
  }

 private:
  OSMesaContext context_;
  mutable std::array<std::uint8_t, 4> buffer_{};
};

}  // namespace

Result<std::unique_ptr<Context>> createOSMesaContext(const ContextOptions&) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context == nullptr) return Error{"OSMesa: cannot create an OpenGL 3.3 core context"};
  auto backend = std::make_unique<OSMesaBackend>(context);
  if (Status s = backend->makeCurrent(); !s) return Error{"OSMesa: " + s.error().message};
  if (Status s = backend->initialise(); !s) return Error{"OSMesa: " + s.error().message};
  return std::unique_ptr<Context>(std::move(backend));
}

}  // namespace nut::viewer
