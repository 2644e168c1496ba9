// viewer/app/viewer_window.hpp — nut-viewer's window: a GLFW window with a fly camera and a Dear
// ImGui overlay over the streamed city (docs/VIEWER.md).
#pragma once

#include <string>

#include <nut/camera.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>
#include <viewer/city_loader.hpp>
#include <viewer/city_renderer.hpp>

namespace nut::viewer {

struct WindowRun {
  scene::CityManifest city;
  std::string base;
  Fetch fetch;
  CityRendererOptions options;
  RayCastOptions cast;
  Camera start;          // the window's size is the camera's
  int frames = 0;        // close after this many frames (0: when the window is closed)
  bool fxaa = false;     // FXAA on at the start (a toggle in the overlay)
  std::string screenshot;  // the last frame with its overlay, once the view has settled
  std::string stats;       // JSON: frames, and the overlay's rectangle in pixels
};

// Returns the exit status: 0, or 1 with one error line on stderr.
int runWindow(const WindowRun& run);

}  // namespace nut::viewer
