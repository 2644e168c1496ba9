// `nut render-mesh IN.obj -o OUT.png`: renders an OBJ or GLB mesh with the Embree reference
// renderer, or rasterises it with OpenGL (`--backend gl`), with the same camera flags and default
// camera as `nut render`, so the images compare.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include <meshref/embree_renderer.hpp>
#include <nut/png_io.hpp>
#include <scene/mesh_file.hpp>

#include "camera_options.hpp"
#include "commands.hpp"
#if NUT_HAVE_GL
#include "gl_backend.hpp"
#endif

namespace nut::cli {

namespace {

struct RenderMeshOptions {
  std::string input, output, depth, stats, backend = "cpu";
  CameraOptions camera;
#if NUT_HAVE_GL
  GlOptions gl;
#endif
  int threads = 0;
};

int writeOutputs(const RenderMeshOptions& o, const Camera& camera, const Image& colour,
                 const std::vector<float>& distanceM, const nlohmann::json& stats) {
  if (Status s = writePng(o.output, colour); !s) return fail(s.error().message, kUnreadable);
  if (!o.depth.empty())
    if (Status s = writePfm(o.depth, camera.width, camera.height, distanceM); !s)
      return fail(s.error().message, kUnreadable);
  if (!o.stats.empty())
    if (Status s = writeTextFile(o.stats, stats.dump(2) + "\n"); !s) return fail(s.error().message, kUnreadable);
  return kOk;
}

#if NUT_HAVE_GL
// Rasterises the mesh with OpenGL: the camera is fitted to the same bounds as Embree's.
int runGl(const RenderMeshOptions& o, const TriangleMesh& mesh) {
  auto camera = o.camera.resolve(mesh.bounds());
  if (!camera) return fail(camera.error().message, kUsage);
  auto gl = o.gl.open();
  if (!gl) return fail("GL: " + gl.error().message, kUnreadable);
  if (Status s = (*gl)->addMesh(mesh); !s) return fail(o.input + ": " + s.error().message, kInvalid);
  std::fprintf(stderr, "render-mesh: %s, %zu triangle%s, %dx%d, GL %s: %s\n", o.input.c_str(), mesh.triangles.size(),
               mesh.triangles.size() == 1 ? "" : "s", camera->width, camera->height, o.gl.context.c_str(),
               (*gl)->context().description().c_str());
  const auto start = std::chrono::steady_clock::now();
  if (Status s = (*gl)->draw(*camera, RayCastOptions{}); !s) return fail("GL: " + s.error().message, kUnreadable);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const viewer::GlFrame frame = (*gl)->read(*camera);
  const nlohmann::json stats = {{"seconds", seconds},
                                {"triangles", mesh.triangles.size()},
                                {"width", camera->width},
                                {"height", camera->height},
                                {"backend", o.backend}};
  if (const int code = writeOutputs(o, *camera, frame.colour, frame.distanceM, stats); code != kOk) return code;
  std::fprintf(stderr, "render-mesh: wrote %s (%.3f s)\n", o.output.c_str(), seconds);
  return kOk;
}
#endif

int run(const RenderMeshOptions& o) {
  std::vector<std::string> warnings;
  auto mesh = scene::readMeshFile(o.input, warnings);
  if (!mesh) {
    // A file that opens but does not hold a usable mesh is invalid input, not unreadable.
    std::error_code ec;
    const bool readable = std::filesystem::is_regular_file(o.input, ec) && std::ifstream(o.input).good();
    return fail(mesh.error().message, readable ? kInvalid : kUnreadable);
  }
  for (const std::string& warning : warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
#if NUT_HAVE_GL
  if (o.backend == "gl") return runGl(o, *mesh);
#endif
  auto renderer = meshref::EmbreeRenderer::create(*mesh);
  if (!renderer) return fail(o.input + ": " + renderer.error().message, kInvalid);
  auto camera = o.camera.resolve(renderer->bounds());
  if (!camera) return fail(camera.error().message, kUsage);
  std::fprintf(stderr, "render-mesh: %s, %zu triangle%s, %dx%d (scene built in %.3f s)\n", o.input.c_str(),
               mesh->triangles.size(), mesh->triangles.size() == 1 ? "" : "s", camera->width, camera->height,
               renderer->buildSeconds());
  meshref::MeshRenderStats stats;
  const meshref::MeshRenderOutput frame = renderer->render(*camera, o.threads, &stats);
  const nlohmann::json j = {{"seconds", stats.seconds},
                            {"rays_per_second", stats.raysPerSecond},
                            {"build_seconds", renderer->buildSeconds()},
                            {"triangles", mesh->triangles.size()},
                            {"threads", stats.threads},
                            {"width", camera->width},
                            {"height", camera->height},
                            {"backend", o.backend}};
  if (const int code = writeOutputs(o, *camera, frame.colour, frame.distanceM, j); code != kOk) return code;
  std::fprintf(stderr, "render-mesh: wrote %s (%.3f s, %.2f Mrays/s, %d thread%s)\n", o.output.c_str(), stats.seconds,
               stats.raysPerSecond / 1e6, stats.threads, stats.threads == 1 ? "" : "s");
  return kOk;
}

}  // namespace

void addRenderMeshCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<RenderMeshOptions>();
  CLI::App* cmd =
      app.add_subcommand("render-mesh", "Render an OBJ or GLB mesh with the reference renderer (Embree) or OpenGL");
  cmd->add_option("input", o->input,
                  "Mesh: OBJ (materials from the MTL files it names: Kd colour, d opacity) or binary glTF (.glb: "
                  "base colour factors)")
      ->required();
  cmd->add_option("-o,--output", o->output, "Output image (PNG)")->required()->check(outputExtension(".png", "PNG"));
  o->camera.addTo(*cmd);
#if NUT_HAVE_GL
  cmd->add_option("--backend", o->backend, "Renderer: cpu (Embree ray tracing) or gl (OpenGL rasterisation)")
      ->check(CLI::IsMember({"cpu", "gl"}))
      ->default_val("cpu");
  o->gl.addTo(*cmd);
#else
  cmd->add_option("--backend", o->backend, "Renderer: cpu (Embree ray tracing; built without GL)")
      ->check(CLI::IsMember({"cpu"}))
      ->default_val("cpu");
#endif
  cmd->add_option("--depth", o->depth, "Also write the distance along each ray (metres, +inf for misses) as PFM")
      ->check(outputExtension(".pfm", "PFM"));
  cmd->add_option("--stats", o->stats, "Write timing statistics as JSON")->check(outputExtension(".json", "JSON"));
  cmd->add_option("--threads", o->threads, "Worker threads of the cpu back-end (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->footer(
      "With no camera flags the camera is fitted to the mesh's bounding box exactly as `nut render` fits it to an\n"
      "HNI's root block, so a mesh and its HNI render from the same view.\n\n"
      "Example:\n  nut render-mesh building.obj -o building-mesh.png --size 1280x720 --stats stats.json\n"
      "  nut compare building-hni.png building-mesh.png --diff diff.png\n"
      "  nut render-mesh building.obj -o building-raster.png --backend gl\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
