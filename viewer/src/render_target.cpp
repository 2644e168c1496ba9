// Offscreen framebuffer and read-back.
#include <viewer/render_target.hpp>

#include <algorithm>
#include <cstring>
#include <string>

#include <nut/camera.hpp>

namespace nut::viewer {

namespace {

// Reverses the row order of a tightly packed image in place.
template <typename T>
void flipRows(std::vector<T>& values, std::size_t rowLength, int rows) {
  for (int y = 0; y < rows / 2; ++y)
    std::swap_ranges(values.begin() + static_cast<std::ptrdiff_t>(y * rowLength),
                     values.begin() + static_cast<std::ptrdiff_t>((y + 1) * rowLength),
                     values.begin() + static_cast<std::ptrdiff_t>((rows - 1 - y) * rowLength));
}

}  // namespace

Result<RenderTarget> RenderTarget::create(const Gl& gl, int width, int height) {
  if (Status s = checkTextureSize(gl, "render target", width, height); !s) return s.error();
  RenderTarget t(gl, width, height);
  t.colour_ = makeTexture(gl);
  gl.BindTexture(GL_TEXTURE_2D, t.colour_.get());
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  t.depth_ = makeTexture(gl);
  gl.BindTexture(GL_TEXTURE_2D, t.depth_.get());
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, width, height, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  t.framebuffer_ = makeFramebuffer(gl);
  gl.BindFramebuffer(GL_FRAMEBUFFER, t.framebuffer_.get());
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour_.get(), 0);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.depth_.get(), 0);
  const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) return Error{"render target: framebuffer incomplete (status " + std::to_string(status) + ")"};
  return t;
}

void RenderTarget::bind() const {
  gl_->BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  gl_->Viewport(0, 0, width_, height_);
}

void RenderTarget::bindCleared() const {
  bind();
  gl_->ClearColor(kBackground[0] / 255.0f, kBackground[1] / 255.0f, kBackground[2] / 255.0f, 1.0f);
  gl_->ClearDepth(1.0);
  gl_->DepthMask(GL_TRUE);
  gl_->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

Image RenderTarget::readColour() const {
  Image image(width_, height_);
  gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
  gl_->ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_->PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_->ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  flipRows(image.pixels, static_cast<std::size_t>(width_) * 4, height_);
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  return image;
}

std::vector<float> RenderTarget::readDepth() const {
  std::vector<float> depth(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
  gl_->PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl_->ReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  flipRows(depth, static_cast<std::size_t>(width_), height_);
  return depth;
}

}  // namespace nut::viewer
