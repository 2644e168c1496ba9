// cli/camera_options.hpp — the camera flags shared by `nut render` and `nut render-mesh`, so that
// both fit the same default camera to a bounding box (docs/RENDERING.md).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>

namespace nut::cli {

struct CameraOptions {
  std::string size = "1280x720";
  std::string eye, target, up;
  double fovDeg = 40.0;

  void addTo(CLI::App& cmd);
  // The camera for a scene with these world bounds: flags given override the fitted default.
  Result<Camera> resolve(const WorldBox& bounds) const;
};

}  // namespace nut::cli
