// `nut render IN.png -o OUT.png`: ray-casts an HNI, or the buildings of a city manifest, with the
// CPU reference ray caster or the GLSL ray caster (`--backend gl`), with their complementary meshes
// and any --mesh in the same image.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

#include <scene/city.hpp>
#include <scene/scene.hpp>
#include <scene/scene_render.hpp>
#if NUT_HAVE_EMBREE
#include <meshref/embree_renderer.hpp>
#endif

#include "camera_options.hpp"
#include "commands.hpp"
#if NUT_HAVE_GL
#include "gl_backend.hpp"
#endif

namespace nut::cli {

namespace {

struct RenderOptions {
  std::string input, output, depth, stats, backend = "cpu", lookup = "exact", lod = "off";
  std::vector<std::string> meshes;
  CameraOptions camera;
#if NUT_HAVE_GL
  GlOptions gl;
#endif
  double lodPx = 0;
  int maxIterations = 512;
  int threads = 0;
  int frames = 1;  // timed frames; stats.seconds is their median
  bool heatMap = false;
};

// The median of the frames' times.
double medianSeconds(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  const std::size_t n = seconds.size();
  return n % 2 == 1 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
}

#if NUT_HAVE_GL
// The scene through the GLSL ray caster; `frame` and `stats` are filled. Returns an exit code.
int renderWithGl(const RenderOptions& o, const scene::Scene& scene, const Camera& camera, const RayCastOptions& options,
                 RenderOutput& frame, RenderStats& stats) {
  auto gl = o.gl.open();
  if (!gl) return fail("GL: " + gl.error().message, kUnreadable);
  std::fprintf(stderr, "render: GL %s: %s\n", o.gl.context.c_str(), (*gl)->context().description().c_str());
  Status added = Ok{};
  if (lowerExtension(o.input) == ".json") {
    // A city streams through the viewer's renderer: atlas pages, culling, front-to-back order.
    auto city = scene::readCityJson(o.input);
    if (!city) return fail(city.error().message, kInvalid);
    (*gl)->setCity(std::move(*city), std::filesystem::path(o.input).parent_path().string());
  } else {
    // One shared image per file: the buildings that name it are instances of one atlas entry.
    std::map<const Image*, std::shared_ptr<const Image>> images;
    for (const PngFile& file : scene.files) images[&file.image] = std::make_shared<const Image>(file.image);
    for (const scene::PlacedHni& hni : scene.hnis)
      if (added) added = (*gl)->addHni(images.at(hni.image), hni.originM, hni.worldFromRoot);
  }
  // --lod auto: each complement as the coarsest level whose error spans under a pixel, as on the cpu.
  for (const TriangleMesh* mesh : options.lodAuto ? scene.meshPointers(camera) : scene.meshPointers())
    if (added) added = (*gl)->addMesh(*mesh);
  if (!added) return fail(added.error().message, kInvalid);
  // With --frames, a first frame (shader compilation, streaming, upload) is drawn untimed.
  std::vector<double> seconds;
  for (int i = o.frames > 1 ? -1 : 0; i < o.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    if (Status drawn = (*gl)->draw(camera, options); !drawn) return fail("GL: " + drawn.error().message, kUnreadable);
    if (i >= 0) seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  stats.seconds = medianSeconds(seconds);
  stats.raysPerSecond = static_cast<double>(camera.width) * camera.height / stats.seconds;
  viewer::GlFrame gpu = (*gl)->read(camera);
  frame.colour = std::move(gpu.colour);
  frame.distanceM = std::move(gpu.distanceM);
  return kOk;
}
#endif

// The scene through the CPU ray caster (and Embree for its meshes). Returns an exit code.
int renderOnCpu(const RenderOptions& o, const scene::Scene& scene, const Camera& camera, const RayCastOptions& options,
                RenderOutput& frame, RenderStats& stats) {
  if (scene.hnis.size() == 1 && scene.meshes.empty()) {
    // One HNI alone keeps its translucent cells' tint over the background, which a scene of
    // several objects does not (scene/scene_render.hpp).
    const scene::PlacedHni& hni = scene.hnis.front();
    const HniRayCaster caster(*hni.image, hni.originM, hni.worldFromRoot);
    std::vector<double> seconds;
    for (int i = 0; i < o.frames; ++i) {
      frame = renderHni(caster, camera, options, o.threads, &stats);
      seconds.push_back(stats.seconds);
    }
    stats.seconds = medianSeconds(seconds);
    stats.raysPerSecond = static_cast<double>(camera.width) * camera.height / stats.seconds;
    return kOk;
  }
#if NUT_HAVE_EMBREE
  // --lod auto draws each complement at the coarsest level whose error spans under a pixel.
  auto traced = meshref::traceMeshes(options.lodAuto ? scene.meshPointers(camera) : scene.meshPointers());
  if (!traced) return fail(traced.error().message, kUnreadable);
  std::unique_ptr<const scene::MeshTracer> meshes = std::move(*traced);
#else
  if (!scene.meshes.empty())
    return fail(o.input +
                    ": this nut was built without the Embree mesh reference (NUT_BUILD_EMBREE=OFF), so the cpu "
                    "back-end cannot draw meshes",
                kUsage);
  std::unique_ptr<const scene::MeshTracer> meshes;
#endif
  const scene::SceneRenderer renderer(scene.hnis, std::move(meshes));
  std::vector<double> seconds;
  for (int i = 0; i < o.frames; ++i) {
    frame = renderer.render(camera, options, o.threads, &stats);
    seconds.push_back(stats.seconds);
  }
  stats.seconds = medianSeconds(seconds);
  stats.raysPerSecond = static_cast<double>(camera.width) * camera.height / stats.seconds;
  return kOk;
}

// --stats: the timing and, on the CPU, the per-ray counts (the GL caster keeps none).
Status writeStats(const RenderOptions& o, const Camera& camera, const RenderStats& stats) {
  nlohmann::json j = {{"seconds", stats.seconds},
                      {"rays_per_second", stats.raysPerSecond},
                      {"iterations_mean", stats.iterationsMean},
                      {"iterations_max", stats.iterationsMax},
                      {"capped_pct", stats.cappedPct},
                      {"threads", stats.threads},
                      {"width", camera.width},
                      {"height", camera.height},
                      {"lookup", o.lookup},
                      {"lod", o.lod},
                      {"lod_px", o.lodPx},
                      {"backend", o.backend}};
  if (o.backend == "gl")
    for (const char* key : {"iterations_mean", "iterations_max", "capped_pct", "threads"}) j.erase(key);
  return writeTextFile(o.stats, j.dump(2) + "\n");
}

int run(const RenderOptions& o) {
  scene::LoadFailure failure = scene::LoadFailure::invalid;
  auto loaded = scene::loadScene(o.input, o.meshes, &failure);
  if (!loaded) return fail(loaded.error().message, failure == scene::LoadFailure::unreadable ? kUnreadable : kInvalid);
  for (const std::string& warning : loaded->warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
  const scene::Scene& scene = *loaded;
  // The default camera fits the solid content and the meshes, as `nut render-mesh` fits a mesh.
  auto camera = o.camera.resolve(scene.bounds);
  if (!camera) return fail(camera.error().message, kUsage);
  RayCastOptions options;
  options.lookup = o.lookup == "exact" ? Lookup::Exact : Lookup::Heuristic;
  options.lodPx = o.lodPx;
  options.lodAuto = o.lod == "auto";
  options.maxIterations = o.maxIterations;
  options.heatMap = o.heatMap;
  std::fprintf(stderr, "render: %s (%zu HNI%s, %zu mesh%s), %dx%d, %s lookup\n", o.input.c_str(), scene.hnis.size(),
               scene.hnis.size() == 1 ? "" : "s", scene.meshes.size(), scene.meshes.size() == 1 ? "" : "es",
               camera->width, camera->height, o.lookup.c_str());
  RenderOutput frame;
  RenderStats stats;
  const bool gl = o.backend == "gl";
#if NUT_HAVE_GL
  const int code = gl ? renderWithGl(o, scene, *camera, options, frame, stats)
                      : renderOnCpu(o, scene, *camera, options, frame, stats);
#else
  const int code = renderOnCpu(o, scene, *camera, options, frame, stats);
#endif
  if (code != kOk) return code;
  if (Status s = writePng(o.output, frame.colour); !s) return fail(s.error().message, kUnreadable);
  if (!o.depth.empty())
    if (Status s = writePfm(o.depth, camera->width, camera->height, frame.distanceM); !s)
      return fail(s.error().message, kUnreadable);
  if (!o.stats.empty())
    if (Status s = writeStats(o, *camera, stats); !s) return fail(s.error().message, kUnreadable);
  if (gl)
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
  CLI::App* cmd = app.add_subcommand("render", "Ray-cast an HNI, or every building of a city manifest, into an image");
  cmd->add_option("input", o->input,
                  "HNI image (PNG), or a city manifest (city.json: every building with its complementary mesh)")
      ->required();
  cmd->add_option("-o,--output", o->output, "Output image (PNG)")->required()->check(outputExtension(".png", "PNG"));
  o->camera.addTo(*cmd);
#if NUT_HAVE_GL
  cmd->add_option("--backend", o->backend, "Renderer: cpu (the reference ray caster) or gl (the GLSL ray caster)")
      ->check(CLI::IsMember({"cpu", "gl"}))
      ->default_val("cpu");
  o->gl.addTo(*cmd);
#else
  cmd->add_option("--backend", o->backend, "Renderer: cpu (the reference ray caster; built without GL)")
      ->check(CLI::IsMember({"cpu"}))
      ->default_val("cpu");
#endif
  cmd->add_option(
      "--mesh", o->meshes,
      "A mesh (OBJ or GLB; a complementary mesh) drawn with the HNI in one image, nearest surface in front "
      "(repeatable)");
  cmd->add_option("--lod", o->lod,
                  "auto: draw a sub-block as its visual summary where one pixel spans more than the footprint "
                  "measured for it (HNIs from `nut grammar --lod`), and each complementary mesh as the coarsest "
                  "of its levels (`nut convert --complement-levels`) whose error spans under a pixel; off: full "
                  "detail")
      ->check(CLI::IsMember({"off", "auto"}))
      ->capture_default_str();
  cmd->add_option("--lod-px", o->lodPx,
                  "Use visual summaries for redirection cells smaller than this many pixels (0: full detail)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-iter", o->maxIterations, "Iteration cap per ray (capped rays are magenta)")
      ->default_val(512)
      ->check(CLI::Range(1, 1000000));
  cmd->add_flag("--heat-map", o->heatMap,
                "Draw each surface in the colour of the traversal iterations its ray took, dark blue (few) to red "
                "(the cap), log scale (docs/RENDERING.md)");
  // Exact by default on both back-ends: the heuristic places a sub-block up to 2 mm off its
  // neighbours, which leaves single-pixel holes along block seams, and the fetch it saves buys no
  // measurable time on a CPU or on llvmpipe (render_bench, gl_bench; docs/RENDERING.md).
  cmd->add_option("--lookup", o->lookup,
                  "Metadata lookup: exact, or the paper's one-fetch heuristic (boundaries within 2 mm)")
      ->check(CLI::IsMember({"heuristic", "exact"}))
      ->default_val("exact");
  cmd->add_option("--depth", o->depth, "Also write the distance along each ray (metres, +inf for misses) as PFM")
      ->check(outputExtension(".pfm", "PFM"));
  cmd->add_option("--stats", o->stats, "Write timing and iteration statistics as JSON")
      ->check(outputExtension(".json", "JSON"));
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--frames", o->frames,
                  "Draw the frame N times and report the median time (--stats seconds); on the gl back-end a first "
                  "frame, which compiles the shaders and streams the scene in, is drawn untimed before them")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->footer(
      "Examples:\n  nut render samples/hni/building.png -o building.png --size 1280x720 --stats stats.json\n"
      "  nut render samples/hni/building.png -o building-gl.png --backend gl --gl egl\n"
      "  nut render grid/city.json -o grid.png --lod auto   # after nut grammar --lod\n"
      "  nut render samples/hni/building.png -o heat.png --heat-map   # where the iterations go\n"
      "  nut render carpark.png -o carpark-render.png --mesh carpark-rest.obj\n"
      "  nut render street/city.json -o street.png        # after nut convert street.obj -o street/\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
