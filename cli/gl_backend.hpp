// cli/gl_backend.hpp — the GL side of `nut render` and `nut render-mesh` (`--backend gl`): the flags
// that pick the context and the shader sources, and opening the offscreen renderer.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include <nut/error.hpp>
#include <viewer/offscreen.hpp>

namespace nut::cli {

struct GlOptions {
  std::string context = "osmesa";
  std::string shaderDir;
  bool fxaa = false;

  void addTo(CLI::App& cmd);
  // The renderer on the chosen back-end; the error names the back-end and why it is unavailable.
  Result<std::unique_ptr<viewer::OffscreenRenderer>> open() const;
};

}  // namespace nut::cli
