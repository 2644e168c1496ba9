// `nut convert IN.obj -o OUT.png`: converts an OBJ building into an HNI (converter/convert.hpp);
// `-o FOLDER` converts each object of the file into its own HNI and writes a city manifest.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <converter/convert.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>

#include "commands.hpp"
#include "progress.hpp"

namespace nut::cli {

namespace {

namespace fs = std::filesystem;

struct ConvertCliOptions {
  std::string input, output, complement, report;
  double toleranceM = 0.01;
  double angleDeg = 1.0;
  bool zUp = false, quiet = false, noAutoBlocks = false, noWedges = false, noAlign = false, noAxisOrder = false,
       noWings = false, planeCells = false;
  std::vector<std::string> blocks;
  int threads = 0;
  std::string pngEffort = "smallest";
  std::string complementFormat = "glb";  // of the complements written into a folder
};

// -o names one HNI when it ends in .png (any case); otherwise a folder.
bool writesOneHni(const std::string& output) { return lowerExtension(output) == ".png"; }

// -o is an HNI or a folder. A name with another extension is refused rather than made a folder:
// it most likely asks for a file of another format. A folder whose name has a dot is given with a
// trailing slash (its extension is then empty), or exists already.
CLI::Validator hniOrFolder() {
  return CLI::Validator(
      [](std::string& path) {
        std::error_code ec;
        if (writesOneHni(path) || lowerExtension(path).empty() || fs::is_directory(path, ec)) return std::string();
        return path + ": writes an HNI (a name ending in .png) or a folder (no extension, or a name ending in /)";
      },
      "");
}

PngEffort effortOf(const ConvertCliOptions& o) {
  return o.pngEffort == "small" ? PngEffort::Small : PngEffort::Smallest;
}

Result<WorldBox> parseBox(const std::string& text) {
  WorldBox b;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf:%lf,%lf,%lf%c", &b.min.x, &b.min.y, &b.min.z, &b.max.x, &b.max.y, &b.max.z,
                  &tail) != 6)
    return Error{"--block '" + text + "': expected x0,y0,z0:x1,y1,z1 in metres"};
  for (int a = 0; a < 3; ++a)
    if (!(b.max[a] > b.min[a]))
      return Error{"--block '" + text + "': the second corner must exceed the first on every axis"};
  return b;
}

void printSummary(const converter::ConvertReport& r, const std::string& output) {
  const auto& s = r.solid;
  std::fprintf(stderr, "convert: %s: %s\n", r.name.c_str(), r.check.summary().c_str());
  std::fprintf(
      stderr,
      "convert: %s: yaw %.2f deg (%s); grid %dx%dx%d, %lld solid cells (%lld wedges, %lld plane cells), %d blocks; "
      "surface %.1f %% NUT, %.1f %% complementary mesh (%zu triangles)\n",
      r.name.c_str(), r.yawDeg, r.yawApplied ? "converted in that frame" : "not aligned", s.cells[0], s.cells[1],
      s.cells[2], s.solidCells, s.wedgeCells, s.planeCells, r.hni.blocks, s.areaM2 > 0 ? 100 * s.nutAreaM2 / s.areaM2 : 0.0,
      s.areaM2 > 0 ? 100 * s.complementAreaM2 / s.areaM2 : 0.0, r.complementTriangles);
  std::fprintf(stderr, "convert: wrote %s (%dx%d, %lld bytes raw, %ju bytes PNG) in %.2f s\n", output.c_str(),
               r.hni.width, r.hni.height, r.hni.bytesRaw, r.pngBytes, r.seconds());
}

Result<converter::ConvertOptions> convertOptionsOf(const ConvertCliOptions& o) {
  converter::ConvertOptions options;
  options.solid.toleranceM = o.toleranceM;
  options.solid.angleToleranceDeg = o.angleDeg;
  options.solid.wedges = !o.noWedges;
  options.solid.pyramids = !o.noWedges;
  options.solid.planeCells = o.planeCells;
  options.solid.threads = o.threads;
  options.alignYaw = !o.noAlign;
  options.turnedWings = !o.noWings;
  options.blocks.automatic = !o.noAutoBlocks;
  options.axisOrder = !o.noAxisOrder;
  for (const std::string& text : o.blocks) {
    auto box = parseBox(text);
    if (!box) return box.error();
    options.blocks.manual.push_back(*box);
  }
  return options;
}

// The whole file as one building: one HNI, its complementary mesh and report where asked.
int convertOneBuilding(const ConvertCliOptions& o, scene::ObjContents& obj, converter::ConvertOptions options) {
  const std::string name = fs::path(o.input).stem().string();
  auto merged = obj.objects.size() == 1 ? Result<TriangleMesh>(std::move(obj.objects[0])) : mergeMeshes(obj.objects, name);
  if (!merged) return fail(o.input + ": " + merged.error().message, kInvalid);
  TriangleMesh mesh = std::move(*merged);
  mesh.name = name;
  ProgressBar bar(!o.quiet, "convert", name);
  options.progress = [&](std::string_view phase, double f) { bar.update(phase, f); };
  auto conversion = converter::convertMesh(std::move(mesh), options);
  if (conversion) bar.update("write", 0);  // Zopfli takes about a second per 150 KB of pixels
  bar.finish();
  if (!conversion) {
    const std::string hint = obj.objects.size() > 1 ? " (the file holds " + std::to_string(obj.objects.size()) +
                                                          " objects: -o FOLDER converts each on its own)"
                                                    : "";
    return fail(o.input + ": " + conversion.error().message + hint, kInvalid);
  }
  if (Status s = converter::writeConversion(*conversion, o.output, o.complement, effortOf(o)); !s)
    return fail(s.error().message, kUnreadable);
  if (!o.report.empty())
    if (Status s = writeTextFile(o.report, converter::reportJson(conversion->report)); !s)
      return fail(s.error().message, kUnreadable);
  if (!o.quiet) printSummary(conversion->report, o.output);
  return kOk;
}

// File names for the objects, in their order: a name used twice gets _2, _3, ...
std::vector<std::string> fileStems(const std::vector<TriangleMesh>& objects) {
  std::vector<std::string> stems;
  std::set<std::string> used;
  for (const TriangleMesh& object : objects) {
    std::string stem = scene::safeFileStem(object.name);
    for (int k = 2; used.count(stem); ++k) stem = scene::safeFileStem(object.name) + "_" + std::to_string(k);
    used.insert(stem);
    stems.push_back(stem);
  }
  return stems;
}

// What is kept of each building's conversion: what the manifest, the report and the summary need.
struct ConvertedBuilding {
  std::string name, hni, complement, error;
  int exitCode = kOk;
  glm::dvec3 originM{0.0};
  WorldBox boundsM;  // the placed root block's, for the manifest
  converter::ConvertReport report;
};

// Converts and writes each object into the folder, side by side, one per worker, each on one
// thread (most of a small building's conversion keeps one core busy); the results come in the
// objects' order whatever the timing.
std::vector<ConvertedBuilding> convertSideBySide(const ConvertCliOptions& o, std::vector<TriangleMesh>& objects,
                                                 converter::ConvertOptions perBuilding, ProgressBar& bar) {
  const std::size_t count = objects.size();
  const std::vector<std::string> stems = fileStems(objects);
  std::vector<ConvertedBuilding> buildings(count);
  perBuilding.solid.threads = 1;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min<std::size_t>(count, o.threads > 0 ? static_cast<std::size_t>(o.threads) : cores);
  std::atomic<std::size_t> next{0}, finished{0};
  std::mutex progressMutex;
  const auto work = [&] {
    for (std::size_t i; (i = next++) < count;) {
      ConvertedBuilding& b = buildings[i];
      b.name = objects[i].name;
      auto conversion = converter::convertMesh(std::move(objects[i]), perBuilding);
      if (!conversion) {
        b.error = o.input + ": object '" + b.name + "': " + conversion.error().message;
        b.exitCode = kInvalid;
      } else {
        const bool hasComplement = !conversion->complement.triangles.empty();
        b.hni = stems[i] + ".png";
        b.complement = hasComplement ? stems[i] + ".complement." + o.complementFormat : "";
        if (Status s = converter::writeConversion(*conversion, (fs::path(o.output) / b.hni).string(),
                                                  hasComplement ? (fs::path(o.output) / b.complement).string() : "",
                                                  effortOf(o));
            !s) {
          b.error = s.error().message;
          b.exitCode = kUnreadable;
        }
        b.originM = conversion->originM;
        b.boundsM = HniRayCaster(conversion->image, conversion->originM).bounds();
        b.report = std::move(conversion->report);
      }
      const std::lock_guard lock(progressMutex);
      bar.update("buildings", static_cast<double>(++finished) / static_cast<double>(count));
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  return buildings;
}

// One HNI per object, a complementary mesh beside each that has one, and city.json.
int convertCity(const ConvertCliOptions& o, scene::ObjContents& obj, const converter::ConvertOptions& options) {
  if (!o.complement.empty())
    return fail(
        "--complement names one file; with -o FOLDER each building's complementary mesh is written into the folder",
        kUsage);
  std::error_code ec;
  fs::create_directories(o.output, ec);
  if (ec) return fail(o.output + ": cannot create folder (" + ec.message() + ")", kUnreadable);
  scene::CityManifest city;
  city.name = fs::path(o.input).stem().string();
  ProgressBar bar(!o.quiet, "convert", city.name);
  const std::vector<ConvertedBuilding> buildings = convertSideBySide(o, obj.objects, options, bar);
  bar.finish();
  nlohmann::json reports = nlohmann::json::array();
  for (const ConvertedBuilding& b : buildings) {
    if (b.exitCode != kOk) return fail(b.error, b.exitCode);
    // Yaw 0: a turned building carries its yaw inside its HNI, which is in the world frame.
    city.buildings.push_back({b.name, b.hni, b.complement, b.originM, 0.0, b.boundsM});
    reports.push_back(nlohmann::json::parse(converter::reportJson(b.report)));
    if (!o.quiet) printSummary(b.report, (fs::path(o.output) / b.hni).string());
  }
  const std::string manifest = (fs::path(o.output) / "city.json").string();
  if (Status s = scene::writeCityJson(manifest, city); !s) return fail(s.error().message, kUnreadable);
  if (!o.report.empty())
    if (Status s = writeTextFile(o.report, nlohmann::json{{"objects", reports}}.dump(2) + "\n"); !s)
      return fail(s.error().message, kUnreadable);
  if (!o.quiet) std::fprintf(stderr, "convert: wrote %s (%zu buildings)\n", manifest.c_str(), city.buildings.size());
  return kOk;
}

int run(const ConvertCliOptions& o) {
  {
    std::ifstream probe(o.input, std::ios::binary);
    std::error_code ec;
    if (!probe || fs::is_directory(o.input, ec)) return fail(o.input + ": cannot open", kUnreadable);
  }
  auto options = convertOptionsOf(o);
  if (!options) return fail(options.error().message, kUsage);
  auto obj = scene::readObj(o.input, {o.zUp});
  if (!obj) return fail(obj.error().message, kInvalid);
  if (!o.quiet)
    for (const std::string& w : obj->warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return writesOneHni(o.output) ? convertOneBuilding(o, *obj, *options) : convertCity(o, *obj, *options);
}

}  // namespace

void addConvertCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<ConvertCliOptions>();
  CLI::App* cmd = app.add_subcommand("convert", "Convert an OBJ building (or a file of buildings) into HNI");
  cmd->add_option("input", o->input, "OBJ file (its MTL files beside it)")->required();
  cmd->add_option(
         "-o,--output", o->output,
         "Output HNI (.png: the whole file as one building), or a folder (no extension, or a name ending in /: "
         "one HNI per o/g object and city.json)")
      ->required()
      ->check(hniOrFolder());
  cmd->add_option("--tolerance", o->toleranceM,
                  "Planes closer than this merge; slopes within it become wedges (metres)")
      ->default_val(0.01)
      ->check(CLI::Range(0.001, 10.0));
  cmd->add_option("--angle-tolerance", o->angleDeg, "Faces within this many degrees of an axis count as axis-aligned")
      ->default_val(1.0)
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_flag("--z-up", o->zUp, "The OBJ is z-up (turned to the y-up world frame)");
  cmd->add_option("--complement", o->complement,
                  "Write the faces the HNI does not show (world coordinates): a binary glTF compressed with "
                  "meshoptimizer (.glb) or OBJ + MTL (.obj)")
      ->check(CLI::Validator(
          [](std::string& path) {
            const std::string extension = lowerExtension(path);
            if (extension == ".glb" || extension == ".obj") return std::string();
            return path + ": writes a mesh; expected a name ending in .glb or .obj";
          },
          ""));
  cmd->add_option("--complement-format", o->complementFormat,
                  "With -o FOLDER: write each building's complementary mesh as glb (binary glTF, meshoptimizer) "
                  "or obj (OBJ + MTL)")
      ->check(CLI::IsMember({"glb", "obj"}))
      ->capture_default_str();
  cmd->add_option("--report", o->report,
                  "Write the conversion report as JSON (timings, grid, blocks, bytes, surface fractions)")
      ->check(outputExtension(".json", "JSON"));
  cmd->add_flag("--quiet", o->quiet, "No progress bar, summary or warnings on stderr");
  cmd->add_flag("--no-auto-blocks", o->noAutoBlocks, "Do not search for repeated blocks");
  cmd->add_flag("--no-axis-order", o->noAxisOrder,
                "Keep the grid's axes as they are instead of trying the order whose cells compress best");
  cmd->add_flag("--no-wedges", o->noWedges,
                "Leave sloped faces to the complementary mesh instead of fitting wedge and pyramid cells");
  cmd->add_flag("--plane-cells", o->planeCells,
                "Make plane cells (HNI version 3) where the complementary mesh crosses a cell on one or two planes, "
                "and take those faces out of it");
  cmd->add_flag("--no-align", o->noAlign,
                "Convert a building turned about the vertical in the world frame instead of its own (most of it then "
                "goes to the complementary mesh)");
  cmd->add_flag("--no-wings", o->noWings,
                "Do not convert a wing turned against the rest of the building in a frame of its own (its walls then "
                "go to the complementary mesh)");
  cmd->add_option("--block", o->blocks,
                  "Extract this box of cells as a block, x0,y0,z0:x1,y1,z1 in world metres (repeatable)");
  cmd->add_option(
         "--threads", o->threads,
         "Worker threads (0: all cores); with -o FOLDER the buildings are converted side by side, one per thread")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--png-effort", o->pngEffort,
                  "smallest: Zopfli, about a second per 150 KB of pixels; small: zlib, milliseconds, 5-15 % larger")
      ->check(CLI::IsMember({"small", "smallest"}))
      ->capture_default_str();
  cmd->footer(
      "Examples:\n  nut convert samples/obj/carpark.obj -o carpark.png --complement carpark-rest.glb --report "
      "report.json\n"
      "  nut convert samples/obj/street.obj -o street/        # one HNI per object + street/city.json\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
