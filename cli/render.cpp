// `nut render IN.png -o OUT.png`: ray-casts an HNI with the CPU reference ray caster, or with the
// GLSL ray caster (`--backend gl`), optionally with a complementary mesh in the same image.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include <meshref/obj.hpp>
#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

#include "camera_options.hpp"
#include "commands.hpp"
#include "gl_backend.hpp"

namespace nut::cli {

namespace {

struct RenderOptions {
  std::string input, output, depth, stats, backend = "cpu", lookup = "exact", mesh;
  CameraOptions camera;
  GlOptions gl;
  double lodPx = 0;
  int maxIterations = 512;
  int threads = 0;
};

int run(RenderOptions o) {
  auto png = readPng(o.input);
  if (!png) {
    std::fprintf(stderr, "error: %s\n", png.error().message.c_str());
    return kUnreadable;
  }
  if (Status s = validate(png->image); !s) {
    std::fprintf(stderr, "error: %s: invalid HNI: %s\n", o.input.c_str(), s.error().message.c_str());
    return kInvalid;
  }
  const HniRayCaster caster(png->image, png->text.originM);
  // The default camera fits the solid content, as `nut render-mesh` fits the exported mesh.
  auto hierarchy = decode(png->image);
  auto bounds = hierarchy ? contentBounds(*hierarchy, png->text.originM) : Result<WorldBox>(hierarchy.error());
  if (!bounds) {
    std::fprintf(stderr, "error: %s: %s\n", o.input.c_str(), bounds.error().message.c_str());
    return kInvalid;
  }
  // A complementary mesh (--mesh) is part of the scene the default camera fits.
  std::optional<meshref::TriangleMesh> extra;
  if (!o.mesh.empty()) {
    auto mesh = meshref::readObj(o.mesh);
    if (!mesh) {
      std::fprintf(stderr, "error: %s\n", mesh.error().message.c_str());
      return kInvalid;
    }
    for (const std::string& warning : mesh->warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    bounds->min = glm::min(bounds->min, mesh->bounds.min);
    bounds->max = glm::max(bounds->max, mesh->bounds.max);
    extra = std::move(*mesh);
  }
  auto camera = o.camera.resolve(*bounds);
  if (!camera) {
    std::fprintf(stderr, "error: %s\n", camera.error().message.c_str());
    return kUsage;
  }
  RayCastOptions options;
  options.lookup = o.lookup == "exact" ? Lookup::Exact : Lookup::Heuristic;
  options.lodPx = o.lodPx;
  options.maxIterations = o.maxIterations;
  RenderStats stats;
  std::fprintf(stderr, "render: %s, %dx%d, %s lookup\n", o.input.c_str(), camera->width, camera->height, o.lookup.c_str());
  RenderOutput frame;
  if (o.backend == "gl") {
    auto gl = o.gl.open();
    if (!gl) {
      std::fprintf(stderr, "error: GL: %s\n", gl.error().message.c_str());
      return kUnreadable;
    }
    std::fprintf(stderr, "render: GL %s: %s\n", o.gl.context.c_str(), (*gl)->context().description().c_str());
    Status added = (*gl)->addHni(png->image, png->text.originM);
    if (added && extra) added = (*gl)->addMesh(toMeshData(*extra));
    if (!added) {
      std::fprintf(stderr, "error: %s\n", added.error().message.c_str());
      return kInvalid;
    }
    const auto start = std::chrono::steady_clock::now();
    if (Status drawn = (*gl)->draw(*camera, options); !drawn) {
      std::fprintf(stderr, "error: GL: %s\n", drawn.error().message.c_str());
      return kUnreadable;
    }
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.raysPerSecond = static_cast<double>(camera->width) * camera->height / stats.seconds;
    viewer::GlFrame gpu = (*gl)->read(*camera);
    frame.colour = std::move(gpu.colour);
    frame.distanceM = std::move(gpu.distanceM);
  } else {
    frame = renderHni(caster, *camera, options, o.threads, &stats);
  }
  if (Status s = writePng(o.output, frame.colour); !s) {
    std::fprintf(stderr, "error: %s\n", s.error().message.c_str());
    return kUnreadable;
  }
  if (!o.depth.empty())
    if (Status s = writePfm(o.depth, camera->width, camera->height, frame.distanceM); !s) {
      std::fprintf(stderr, "error: %s\n", s.error().message.c_str());
      return kUnreadable;
    }
  if (!o.stats.empty()) {
    nlohmann::json j = {{"seconds", stats.seconds},           {"rays_per_second", stats.raysPerSecond},
                        {"iterations_mean", stats.iterationsMean}, {"iterations_max", stats.iterationsMax},
                        {"capped_pct", stats.cappedPct},      {"threads", stats.threads},
                        {"width", camera->width},             {"height", camera->height},
                        {"lookup", o.lookup},                 {"lod_px", o.lodPx},
                        {"backend", o.backend}};
    // The GL caster keeps no per-ray counts.
    if (o.backend == "gl")
      for (const char* key : {"iterations_mean", "iterations_max", "capped_pct", "threads"}) j.erase(key);
    if (Status s = writeTextFile(o.stats, j.dump(2) + "\n"); !s) {
      std::fprintf(stderr, "error: %s\n", s.error().message.c_str());
      return kUnreadable;
    }
  }
  if (o.backend == "gl")
    std::fprintf(stderr, "render: wrote %s (%.3f s, %.2f Mrays/s)\n", o.output.c_str(), stats.seconds,
                 stats.raysPerSecond / 1e6);
  else
    std::fprintf(stderr, "render: wrote %s (%.3f s, %.2f Mrays/s, %.1f iterations per ray)\n", o.output.c_str(),
                 stats.seconds, stats.raysPerSecond / 1e6, stats.iterationsMean);
  return kOk;
}

}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Ray-cast an HNI into an image");
  cmd->add_option("input", o->input, "HNI image (PNG)")->required();
  cmd->add_option("-o,--output", o->output, "Output image (PNG)")->required();
  o->camera.addTo(*cmd);
  cmd->add_option("--backend", o->backend, "Renderer: cpu (the reference ray caster) or gl (the GLSL ray caster)")
      ->check(CLI::IsMember({"cpu", "gl"}))
      ->default_val("cpu");
  o->gl.addTo(*cmd);
  cmd->add_option("--mesh", o->mesh, "A complementary mesh (OBJ) drawn with the HNI in one depth-tested image (--backend gl)");
  cmd->add_option("--lod-px", o->lodPx, "Use visual summaries for redirection cells smaller than this many pixels (0: full detail)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-iter", o->maxIterations, "Iteration cap per ray (capped rays are magenta)")
      ->default_val(512)->check(CLI::Range(1, 1000000));
  // Exact by default on both back-ends: the heuristic places a sub-block up to 2 mm off its
  // neighbours, which leaves single-pixel holes along block seams, and the fetch it saves buys no
  // measurable time on a CPU or on llvmpipe (render_bench, gl_bench; docs/RENDERING.md).
  cmd->add_option("--lookup", o->lookup, "Metadata lookup: exact, or the paper's one-fetch heuristic (boundaries within 2 mm)")
      ->check(CLI::IsMember({"heuristic", "exact"}))
      ->default_val("exact");
  cmd->add_option("--depth", o->depth, "Also write the distance along each ray (metres, +inf for misses) as PFM");
  cmd->add_option("--stats", o->stats, "Write timing and iteration statistics as JSON");
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)")->check(CLI::NonNegativeNumber);
  cmd->footer("Examples:\n  nut render samples/hni/building.png -o building.png --size 1280x720 --stats stats.json\n"
              "  nut render samples/hni/building.png -o building-gl.png --backend gl --gl egl\n"
              "  nut render house.png -o house.png --backend gl --mesh house-complement.obj");
  cmd->callback([o, &exitCode] {
    if (!o->mesh.empty() && o->backend != "gl") {
      std::fprintf(stderr, "error: --mesh needs --backend gl (see nut render --help)\n");
      exitCode = kUsage;
      return;
    }
    exitCode = run(*o);
  });
}

}  // namespace nut::cli
