#include "camera_options.hpp"

#include <cstdio>

namespace nut::cli {

namespace {

Result<glm::dvec3> parseVector(const std::string& text, const char* flag) {
  glm::dvec3 v;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &tail) != 3)
    return Error{std::string("--") + flag + " '" + text + "': expected x,y,z in metres"};
  return v;
}

}  // namespace

void CameraOptions::addTo(CLI::App& cmd) {
  cmd.add_option("--size", size, "Image size WxH")->default_val("1280x720");
  cmd.add_option("--eye", eye, "Camera position x,y,z (metres, world frame); default: fitted to the bounds");
  cmd.add_option("--target", target, "Point looked at x,y,z; default: centre of the bounds");
  cmd.add_option("--up", up, "Up vector x,y,z; default 0,1,0");
  cmd.add_option("--fov", fovDeg, "Vertical field of view in degrees")->default_val(40.0)->check(CLI::Range(1.0, 170.0));
}

Result<Camera> CameraOptions::resolve(const WorldBox& bounds) const {
  int width = 0, height = 0;
  char tail = 0;
  if (std::sscanf(size.c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 1 || height < 1 ||
      width > kMaxRenderSize || height > kMaxRenderSize)
    return Error{"--size '" + size + "': expected WxH, each 1.." + std::to_string(kMaxRenderSize)};
  Camera camera = fitCamera(bounds, width, height, fovDeg);
  if (!eye.empty()) {
    auto v = parseVector(eye, "eye");
    if (!v) return v.error();
    camera.eye = *v;
  }
  if (!target.empty()) {
    auto v = parseVector(target, "target");
    if (!v) return v.error();
    camera.target = *v;
  }
  if (!up.empty()) {
    auto v = parseVector(up, "up");
    if (!v) return v.error();
    camera.up = *v;
  }
  if (glm::length(camera.target - camera.eye) == 0 || glm::length(glm::cross(camera.target - camera.eye, camera.up)) == 0)
    return Error{"camera: eye, target and up must not be collinear"};
  if (!eye.empty() || !target.empty()) {
    // Depth range around the bounds as seen from this eye.
    const double distance = glm::length(bounds.centre() - camera.eye);
    const double radius = 0.5 * glm::length(bounds.size());
    camera.nearM = std::max(1e-3, distance - 1.5 * radius);
    camera.farM = distance + 1.5 * radius;
  }
  return camera;
}

}  // namespace nut::cli
