// viewer/gl_object.hpp — ownership of GL object names: one name and the call that deletes it.
#pragma once

#include <string>
#include <utility>

#include <nut/error.hpp>
#include <viewer/gl.hpp>

namespace nut::viewer {

// Move-only; deletes its object with the context's function table, which must outlive it.
class GlObject {
 public:
  using Deleter = void (*)(const Gl& gl, GLuint name);

  GlObject() = default;
  GlObject(const Gl& gl, GLuint name, Deleter deleter) : gl_(&gl), name_(name), deleter_(deleter) {}
  GlObject(GlObject&& other) noexcept
      : gl_(other.gl_), name_(std::exchange(other.name_, 0)), deleter_(other.deleter_) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      gl_ = other.gl_;
      name_ = std::exchange(other.name_, 0);
      deleter_ = other.deleter_;
    }
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;
  ~GlObject() { reset(); }

  GLuint get() const { return name_; }

 private:
  void reset() {
    if (name_ != 0) deleter_(*gl_, name_);
    name_ = 0;
  }
  const Gl* gl_ = nullptr;
  GLuint name_ = 0;
  Deleter deleter_ = nullptr;
};

GlObject makeTexture(const Gl& gl);
// Whether the context takes a 2D texture of width x height; the error names `what` and the limit.
Status checkTextureSize(const Gl& gl, const std::string& what, int width, int height);
GlObject makeBuffer(const Gl& gl);
GlObject makeVertexArray(const Gl& gl);
GlObject makeFramebuffer(const Gl& gl);
GlObject makeQuery(const Gl& gl);

}  // namespace nut::viewer
