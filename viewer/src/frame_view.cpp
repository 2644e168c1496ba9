// The camera in the form the GL programs take it.
#include <viewer/frame_view.hpp>

#include <limits>

#include <glm/geometric.hpp>

namespace nut::viewer {

namespace {

// A perspective projection of an eye-space frame (x right, y up, looking down -z) with the
// camera's own tan of the half fields of view, so that pixel centres fall on RayGenerator's rays.
// farM = infinity gives the limit of an infinitely distant far plane.
glm::dmat4 projection(double tanHalfX, double tanHalfY, double nearM, double farM) {
  glm::dmat4 p(0.0);
  p[0][0] = 1.0 / tanHalfX;
  p[1][1] = 1.0 / tanHalfY;
  p[2][3] = -1.0;
  if (farM == std::numeric_limits<double>::infinity()) {
    p[2][2] = -1.0;
    p[3][2] = -2.0 * nearM;
  } else {
    p[2][2] = -(farM + nearM) / (farM - nearM);
    p[3][2] = -2.0 * farM * nearM / (farM - nearM);
  }
  return p;
}

}  // namespace

FrameView::FrameView(const Camera& c) : camera(c), rays(c) {
  forward = glm::vec3(rays.forward);
  right = glm::vec3(rays.right);
  up = glm::vec3(rays.upVector);
  tanHalf = glm::vec2(rays.tanHalfX, rays.tanHalfY);
  pixelAngle = static_cast<float>(2.0 * rays.tanHalfY / c.height);
  // Rows of the rotation are the eye axes: right, up, backwards.
  glm::dmat4 eyeFromWorld(1.0);
  for (int i = 0; i < 3; ++i) {
    eyeFromWorld[i][0] = rays.right[i];
    eyeFromWorld[i][1] = rays.upVector[i];
    eyeFromWorld[i][2] = -rays.forward[i];
  }
  clipFromEye = glm::mat4(projection(rays.tanHalfX, rays.tanHalfY, c.nearM, c.farM) * eyeFromWorld);
  proxyClipFromEye = glm::mat4(
      projection(rays.tanHalfX, rays.tanHalfY, 1e-3, std::numeric_limits<double>::infinity()) * eyeFromWorld);
  const double n = c.nearM, f = c.farM;
  depthFromEyeZ = glm::vec2((f + n) / (f - n), 2.0 * f * n / (f - n));
}

double FrameView::distanceFromWindowDepth(int x, int y, float depth) const {
  if (depth >= 1.0f) return std::numeric_limits<double>::infinity();
  const double n = camera.nearM, f = camera.farM;
  const double ndc = 2.0 * depth - 1.0;
  const double eyeZ = 2.0 * f * n / ((f - n) * ((f + n) / (f - n) - ndc));
  return eyeZ / glm::dot(rays.direction(x, y), rays.forward);
}

}  // namespace nut::viewer
