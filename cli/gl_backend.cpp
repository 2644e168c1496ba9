// The GL flags of `nut render` and `nut render-mesh`, and OBJ meshes for the GL layer.
#include "gl_backend.hpp"

namespace nut::cli {

void GlOptions::addTo(CLI::App& cmd) {
  cmd.add_option("--gl", context, "GL back-end for --backend gl: osmesa (headless, CPU), egl (headless, GPU if any), "
                                  "glfw (a window; use xvfb-run without a display)")
      ->check(CLI::IsMember({"osmesa", "egl", "glfw"}))
      ->default_val("osmesa");
  cmd.add_flag("--fxaa", fxaa, "Anti-alias the GL frame with FXAA (not for comparisons: the cpu renderers do not)");
  cmd.add_option("--shader-dir", shaderDir,
                 "Load the GLSL sources from this folder instead of the embedded ones (development; also NUT_SHADER_DIR)");
}

Result<std::unique_ptr<viewer::OffscreenRenderer>> GlOptions::open() const {
  auto backend = viewer::parseBackend(context);
  if (!backend) return backend.error();
  viewer::OffscreenOptions options;
  options.backend = *backend;
  options.shaderDirectory = shaderDir;
  auto renderer = viewer::OffscreenRenderer::create(options);
  if (renderer && fxaa)
    if (Status s = (*renderer)->setFxaa(true); !s) return s.error();
  return renderer;
}

}  // namespace nut::cli
