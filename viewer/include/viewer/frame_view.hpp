// viewer/frame_view.hpp — a nut::Camera as the GL programs take it: the ray basis the HNI ray
// caster rebuilds per pixel (exactly nut::RayGenerator's), the projections that rasterise meshes
// and proxy boxes, and the window-depth mapping of docs/RENDERING.md.
//
// Everything is relative to the eye: a program never sees a world coordinate, only differences
// computed in double on the CPU, so world coordinates near 10^6 m (city origins) cost no precision.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <nut/camera.hpp>

namespace nut::viewer {

struct FrameView {
  Camera camera;
  RayGenerator rays;
  glm::vec3 forward, right, up;  // unit basis of the view, float
  glm::vec2 tanHalf;             // tan of the half fields of view, x and y
  float pixelAngle;              // the angle one pixel subtends (radians), for level of detail
  // Eye-relative world point (metres) to clip space, with the camera's near and far planes: meshes.
  glm::mat4 clipFromEye;
  // The same with a 1 mm near plane and no far plane: proxy boxes, which must not be clipped
  // (their fragments compute their own depth).
  glm::mat4 proxyClipFromEye;
  // Window depth = 0.5 + 0.5 (x - y / z) of eye-space depth z: x = (f + n) / (f - n), y = 2 f n / (f - n).
  glm::vec2 depthFromEyeZ;

  explicit FrameView(const Camera& c);

  // The distance along the ray of pixel (x, y) (row 0 at the top) of the point at window depth
  // `depth`; +infinity for 1 (nothing drawn). Inverts RayGenerator::windowDepth.
  double distanceFromWindowDepth(int x, int y, float depth) const;
};

}  // namespace nut::viewer
