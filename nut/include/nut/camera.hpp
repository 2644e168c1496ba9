// nut/camera.hpp — the camera and shading every renderer of the project shares (docs/RENDERING.md):
// the CPU ray caster, the mesh reference renderer and the GL back-ends must produce the same image
// of the same scene, so they all take their rays and colours from here.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace nut {

// An axis-aligned box in world coordinates (metres).
struct WorldBox {
  glm::dvec3 min{0.0}, max{0.0};
  glm::dvec3 centre() const { return 0.5 * (min + max); }
  glm::dvec3 size() const { return max - min; }
  friend bool operator==(const WorldBox&, const WorldBox&) = default;
};

// Pinhole camera: eye, target, up, vertical field of view; pixel centres are sampled.
struct Camera {
  glm::dvec3 eye{0.0, 0.0, 10.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovYDeg = 40.0;
  int width = 1280, height = 720;
  // Depth range for window-space depth, metres along the view axis.
  double nearM = 0.1, farM = 1000.0;
};

// The largest image side a renderer draws (`nut render --size`), and so the largest side of a
// PNG read as a render rather than an HNI (png_io.hpp): 16384 x 16384 is 1 GiB of RGBA8.
inline constexpr int kMaxRenderSize = 16384;

// The direction the default camera looks from: in front (+z), to the right (+x) and above (+y),
// the classic three-quarter view of a facade.
inline constexpr glm::dvec3 kDefaultViewFrom{0.55, 0.45, 1.0};

// The default camera for a box: looks at its centre from kDefaultViewFrom, far enough that the
// bounding sphere fits both fields of view with a 5 % margin; near and far bracket the sphere.
inline Camera fitCamera(const WorldBox& box, int width, int height, double fovYDeg = 40.0) {
  Camera c;
  c.width = width;
  c.height = height;
  c.fovYDeg = fovYDeg;
  c.target = box.centre();
  const double radius = std::max(0.5 * glm::length(box.size()), 1e-3);
  const double halfY = 0.5 * fovYDeg * 3.14159265358979323846 / 180.0;
  const double halfX = std::atan(std::tan(halfY) * width / height);
  const double distance = 1.05 * radius / std::sin(std::min(halfX, halfY));
  c.eye = c.target + distance * glm::normalize(kDefaultViewFrom);
  c.nearM = std::max(1e-3, distance - 1.5 * radius);
  c.farM = distance + 1.5 * radius;
  return c;
}

// Orthonormal view basis and the ray through a pixel centre.
struct RayGenerator {
  explicit RayGenerator(const Camera& c) : camera(c) {
    forward = glm::normalize(c.target - c.eye);
    right = glm::normalize(glm::cross(forward, c.up));
    upVector = glm::cross(right, forward);
    tanHalfY = std::tan(0.5 * c.fovYDeg * 3.14159265358979323846 / 180.0);
    tanHalfX = tanHalfY * c.width / c.height;
  }
  // Unit direction through the centre of pixel (x, y); row 0 is the top of the image.
  glm::dvec3 direction(int x, int y) const {
    const double u = (2.0 * (x + 0.5) / camera.width - 1.0) * tanHalfX;
    const double v = (1.0 - 2.0 * (y + 0.5) / camera.height) * tanHalfY;
    return glm::normalize(forward + u * right + v * upVector);
  }
  // Window-space depth in [0, 1] (OpenGL convention) of a point at distance t along direction dir.
  double windowDepth(double t, const glm::dvec3& dir) const {
    const double z = t * glm::dot(dir, forward);  // eye-space depth
    const double n = camera.nearM, f = camera.farM;
    const double ndc = (f + n) / (f - n) - 2.0 * f * n / ((f - n) * z);
    return std::clamp(0.5 * ndc + 0.5, 0.0, 1.0);
  }
  Camera camera;
  glm::dvec3 forward, right, upVector;
  double tanHalfX, tanHalfY;
};

// Shading shared by every renderer: albedo x (ambient + (1 - ambient) max(0, n.l)), with the
// normal turned to face the viewer, a fixed light and a fixed background. Colours are sRGB bytes
// and the product is taken on them directly (no linearisation), rounded to the nearest byte.
inline constexpr double kAmbient = 0.35;
inline const glm::dvec3 kLightDirection = glm::normalize(glm::dvec3(0.35, 0.8, 0.5));  // towards the light
inline constexpr std::array<std::uint8_t, 3> kBackground{214, 222, 230};

inline std::array<std::uint8_t, 3> shade(const std::array<std::uint8_t, 3>& albedo, glm::dvec3 normal,
                                         const glm::dvec3& rayDirection) {
  if (glm::dot(normal, rayDirection) > 0) normal = -normal;
  const double light = kAmbient + (1.0 - kAmbient) * std::max(0.0, glm::dot(normal, kLightDirection));
  std::array<std::uint8_t, 3> out{};
  for (int i = 0; i < 3; ++i)  // round half up; the product is never negative
    out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::min(255.0, albedo[static_cast<std::size_t>(i)] * light) + 0.5);
  return out;
}

}  // namespace nut
