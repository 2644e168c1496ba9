// viewer/render_target.hpp — an offscreen framebuffer: RGBA8 colour and 32-bit float depth, both
// textures (so a post-process can read them), and their read-back in nut's conventions.
#pragma once

#include <vector>

#include <nut/error.hpp>
#include <nut/image.hpp>

#include <viewer/gl.hpp>
#include <viewer/gl_object.hpp>

namespace nut::viewer {

class RenderTarget {
 public:
  // Errors: a size beyond GL_MAX_TEXTURE_SIZE, or an incomplete framebuffer.
  static Result<RenderTarget> create(const Gl& gl, int width, int height);

  // Binds the framebuffer for drawing and sets the viewport to the whole target.
  void bind() const;
  // bind(), then clears the colour to the background (docs/RENDERING.md) and the depth to 1: the
  // start of every frame.
  void bindCleared() const;
  // The colour, row 0 at the top (images are stored top first, GL reads bottom first), alpha
  // forced to 255: the HNI program leaves its transmittance there.
  Image readColour() const;
  // Window depth in [0, 1], row 0 at the top; 1 where nothing was drawn.
  std::vector<float> readDepth() const;

  int width() const { return width_; }
  int height() const { return height_; }
  GLuint framebuffer() const { return framebuffer_.get(); }
  GLuint colourTexture() const { return colour_.get(); }

 private:
  RenderTarget(const Gl& gl, int width, int height) : gl_(&gl), width_(width), height_(height) {}
  const Gl* gl_;
  int width_, height_;
  GlObject colour_, depth_, framebuffer_;
};

}  // namespace nut::viewer
