// `nut convert IN.obj -o OUT.png`: converts an OBJ building into an HNI (converter/convert.hpp);
// `-o FOLDER` converts each object of the file into its own HNI and writes a city manifest.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <converter/convert.hpp>
#include <converter/district.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>

#include "commands.hpp"
#include "parallel.hpp"
#include "progress.hpp"

namespace nut::cli {

namespace {

namespace fs = std::filesystem;

struct ConvertCliOptions {
  std::string input, output, complement, report;
  double toleranceM = 0.01;
  double angleDeg = 1.0;
  bool zUp = false, quiet = false, noAutoBlocks = false, noWedges = false, noAlign = false, noAxisOrder = false,
       noWings = false, planeCells = false, packAtlases = false;
  std::vector<std::string> blocks;
  int threads = 0;
  std::string pngEffort = "smallest";
  std::string prefer = "files";
  double districtSideM = converter::kDistrictSideM;
  std::string complementFormat = "glb";  // of the complements written into a folder
  int complementLevels = 0;              // coarser levels written beside each complement
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

// Workers for `items` buildings or districts: --threads, or all cores.
std::size_t workerCount(const ConvertCliOptions& o, std::size_t items) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return std::max<std::size_t>(
      1, std::min<std::size_t>(items, o.threads > 0 ? static_cast<std::size_t>(o.threads) : cores));
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

// The building's summary on stderr; `output` is the HNI written, "" when its district holds it.
void printSummary(const converter::ConvertReport& r, const std::string& output) {
  const auto& s = r.solid;
  std::fprintf(stderr, "convert: %s: %s\n", r.name.c_str(), r.check.summary().c_str());
  if (r.sheets.found)
    std::fprintf(stderr,
                 "convert: %s: open sheets %.1f m^2 (%zu triangles) around a %s body; %s (%ju against %ju bytes)\n",
                 r.name.c_str(), r.sheets.areaM2, r.sheets.triangles, r.sheets.bodyClosed ? "closed" : "still open",
                 r.sheets.applied ? "converted as the body" : "converted as it is",
                 static_cast<std::uintmax_t>(r.sheets.applied ? r.sheets.bytesWith : r.sheets.bytesWithout),
                 static_cast<std::uintmax_t>(r.sheets.applied ? r.sheets.bytesWithout : r.sheets.bytesWith));
  std::fprintf(
      stderr,
      "convert: %s: yaw %.2f deg (%s); grid %dx%dx%d, %lld solid cells (%lld wedges, %lld plane cells), %d blocks; "
      "surface %.1f %% NUT, %.1f %% complementary mesh (%zu triangles)\n",
      r.name.c_str(), r.yawDeg, r.yawApplied ? "converted in that frame" : "not aligned", s.cells[0], s.cells[1],
      s.cells[2], s.solidCells, s.wedgeCells, s.planeCells, r.hni.blocks, s.areaM2 > 0 ? 100 * s.nutAreaM2 / s.areaM2 : 0.0,
      s.areaM2 > 0 ? 100 * s.complementAreaM2 / s.areaM2 : 0.0, r.complementTriangles);
  if (output.empty()) {
    std::fprintf(stderr, "convert: %s: converted in %.2f s\n", r.name.c_str(), r.seconds());
    return;
  }
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
  options.objective = o.prefer == "surface" ? converter::ConvertOptions::Objective::MostSurface
                                            : converter::ConvertOptions::Objective::SmallestFiles;
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

// What is kept of each building's conversion: what the manifest, the report and the summary need,
// and, with --pack-atlases, what its district needs, for the building is then not written alone.
struct ConvertedBuilding {
  std::string name, hni, complement, error;
  int exitCode = kOk;
  glm::dvec3 originM{0.0};
  WorldBox boundsM;  // the placed root block's, for the manifest (without --pack-atlases)
  std::vector<scene::ComplementLevel> complementLevels;
  converter::ConvertReport report;
  Hierarchy hierarchy;          // with --pack-atlases
  TriangleMesh complementMesh;  // with --pack-atlases
};

// Converts each object, side by side, one per worker, each on one thread (most of a small
// building's conversion keeps one core busy), and writes it into the folder unless its district
// will hold it; the results come in the objects' order whatever the timing.
std::vector<ConvertedBuilding> convertSideBySide(const ConvertCliOptions& o, std::vector<TriangleMesh>& objects,
                                                 converter::ConvertOptions perBuilding, ProgressBar& bar) {
  const std::size_t count = objects.size();
  const std::vector<std::string> stems = fileStems(objects);
  std::vector<ConvertedBuilding> buildings(count);
  perBuilding.solid.threads = 1;
  std::size_t finished = 0;
  const auto convertOne = [&](std::size_t i) {
    ConvertedBuilding& b = buildings[i];
    b.name = objects[i].name;
    auto conversion = converter::convertMesh(std::move(objects[i]), perBuilding);
    if (!conversion) {
      b.error = o.input + ": object '" + b.name + "': " + conversion.error().message;
      b.exitCode = kInvalid;
      return;
    }
    b.originM = conversion->originM;
    if (o.packAtlases) {
      b.hierarchy = std::move(conversion->hierarchy);
      b.complementMesh = std::move(conversion->complement);
    } else {
      b.boundsM = HniRayCaster(conversion->image, conversion->originM).bounds();
      const bool hasComplement = !conversion->complement.triangles.empty();
      b.hni = stems[i] + ".png";
      b.complement = hasComplement ? stems[i] + ".complement." + o.complementFormat : "";
      const std::string complement = hasComplement ? (fs::path(o.output) / b.complement).string() : "";
      if (Status s =
              converter::writeConversion(*conversion, (fs::path(o.output) / b.hni).string(), complement, effortOf(o));
          !s) {
        b.error = s.error().message;
        b.exitCode = kUnreadable;
      } else if (hasComplement) {
        auto levels = converter::writeComplementLevels(complement, conversion->complement, o.complementLevels);
        if (levels) {
          b.complementLevels = std::move(*levels);
        } else {
          b.error = levels.error().message;
          b.exitCode = kUnreadable;
        }
      }
    }
    b.report = std::move(conversion->report);
  };
  forEachInParallel(count, workerCount(o, count), convertOne, [&] { bar.updateCount("buildings", ++finished, count); });
  return buildings;
}

// A district of --pack-atlases as written: its manifest entry and what the report says of it.
struct WrittenDistrict {
  scene::CityBuilding entry;
  std::vector<std::size_t> members;
  std::uintmax_t pngBytes = 0, complementBytes = 0;
  std::size_t buildingBlocks = 0, mergedBlocks = 0;
};

// One group of districtGroups as one HNI (or halves, when it does not fit one) and one
// complementary mesh: the members' meshes together, in world coordinates as they are.
Status writeDistrict(const ConvertCliOptions& o, const std::vector<ConvertedBuilding>& buildings,
                     const std::vector<converter::PlacedHierarchy>& placed, const std::vector<std::size_t>& group,
                     const std::string& name, std::vector<WrittenDistrict>& out) {
  auto parts = converter::compileDistrict(placed, group);
  if (!parts)
    return Error{o.input + ": district " + name + " (" + buildings[group.front()].name + "): " + parts.error().message};
  for (converter::CompiledDistrict& part : *parts) {
    WrittenDistrict d;
    d.members = part.members;
    const std::string stem = name + part.suffix;
    d.entry = {stem, stem + ".png", "", part.district.originM, 0.0, part.district.boundsM};
    const std::string png = (fs::path(o.output) / d.entry.hni).string();
    if (Status s =
            writeHni(png, part.image, {stem, "nut convert --pack-atlases", "m", part.district.originM}, effortOf(o));
        !s)
      return s;
    std::vector<const TriangleMesh*> meshes;
    for (std::size_t i : part.members)
      if (!buildings[i].complementMesh.triangles.empty()) meshes.push_back(&buildings[i].complementMesh);
    if (!meshes.empty()) {
      auto merged = mergeMeshes(meshes, stem);
      if (!merged) return Error{o.input + ": district " + stem + ": " + merged.error().message};
      d.entry.complement = stem + ".complement." + o.complementFormat;
      const std::string mesh = (fs::path(o.output) / d.entry.complement).string();
      if (Status s = converter::writeComplement(mesh, *merged); !s) return s;
      auto levels = converter::writeComplementLevels(mesh, *merged, o.complementLevels);
      if (!levels) return levels.error();
      d.entry.complementLevels = std::move(*levels);
      std::error_code ec;
      d.complementBytes = fs::file_size(mesh, ec);
    }
    std::error_code ec;
    d.pngBytes = fs::file_size(png, ec);
    d.buildingBlocks = part.district.buildingBlocks;
    d.mergedBlocks = part.district.mergedBlocks;
    out.push_back(std::move(d));
  }
  return Ok{};
}

// --pack-atlases: the buildings in districts (converter/district.hpp), each written as one HNI and
// one complementary mesh, in the order of districtGroups.
Result<std::vector<WrittenDistrict>> writeDistricts(const ConvertCliOptions& o,
                                                    const std::vector<ConvertedBuilding>& buildings, ProgressBar& bar) {
  std::vector<converter::PlacedHierarchy> placed;
  std::vector<WorldBox> boxes;
  for (const ConvertedBuilding& b : buildings) {
    // Yaw 0: a turned building carries its yaw inside its HNI, which is in the world frame.
    placed.push_back({&b.hierarchy, b.originM, 0.0});
    boxes.push_back(converter::placedRootBox(b.hierarchy, b.originM, 0.0));
  }
  // Squares from the file's minimum corner: a file of buildings smaller than a square is one
  // district wherever it lies.
  glm::dvec2 corner(INFINITY);
  for (const WorldBox& box : boxes) corner = glm::min(corner, glm::dvec2(box.min.x, box.min.z));
  const std::vector<std::vector<std::size_t>> groups = converter::districtGroups(boxes, o.districtSideM, corner);
  std::vector<std::vector<WrittenDistrict>> written(groups.size());
  std::vector<Status> statuses(groups.size(), Ok{});
  std::size_t finished = 0;
  forEachInParallel(
      groups.size(), workerCount(o, groups.size()),
      [&](std::size_t i) {
        char name[32];
        std::snprintf(name, sizeof name, "d%04zu", i);
        statuses[i] = writeDistrict(o, buildings, placed, groups[i], name, written[i]);
      },
      [&] { bar.updateCount("districts", ++finished, groups.size()); });
  std::vector<WrittenDistrict> districts;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    if (!statuses[i]) return statuses[i].error();
    for (WrittenDistrict& d : written[i]) districts.push_back(std::move(d));
  }
  return districts;
}

nlohmann::json districtsJson(const std::vector<WrittenDistrict>& districts,
                             const std::vector<ConvertedBuilding>& buildings) {
  nlohmann::json out = nlohmann::json::array();
  for (const WrittenDistrict& d : districts) {
    nlohmann::json names = nlohmann::json::array();
    for (std::size_t i : d.members) names.push_back(buildings[i].name);
    out.push_back({{"name", d.entry.name},
                   {"buildings", names},
                   {"png_bytes", d.pngBytes},
                   {"complement_bytes", d.complementBytes},
                   {"building_blocks", d.buildingBlocks},
                   {"merged_blocks", d.mergedBlocks}});
  }
  return out;
}

// One HNI per object, a complementary mesh beside each that has one, and city.json; with
// --pack-atlases one HNI and one complementary mesh per district instead.
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
  nlohmann::json reports = nlohmann::json::array();
  for (const ConvertedBuilding& b : buildings) {
    if (b.exitCode != kOk) return fail(b.error, b.exitCode);
    // Yaw 0: a turned building carries its yaw inside its HNI, which is in the world frame.
    if (!o.packAtlases)
      city.buildings.push_back({b.name, b.hni, b.complement, b.originM, 0.0, b.boundsM, b.complementLevels});
    reports.push_back(nlohmann::json::parse(converter::reportJson(b.report)));
  }
  nlohmann::json report{{"objects", reports}};
  std::vector<WrittenDistrict> districts;
  if (o.packAtlases) {
    auto written = writeDistricts(o, buildings, bar);
    if (!written) return fail(written.error().message, kUnreadable);
    districts = std::move(*written);
    for (const WrittenDistrict& d : districts) city.buildings.push_back(d.entry);
    report["districts"] = districtsJson(districts, buildings);
  }
  bar.finish();
  if (!o.quiet)
    for (const ConvertedBuilding& b : buildings)
      printSummary(b.report, o.packAtlases ? "" : (fs::path(o.output) / b.hni).string());
  if (!o.quiet)
    for (const WrittenDistrict& d : districts)
      std::fprintf(stderr, "convert: wrote %s (%zu buildings, %ju bytes PNG) and %s (%ju bytes)\n",
                   (fs::path(o.output) / d.entry.hni).c_str(), d.members.size(), d.pngBytes,
                   d.entry.complement.empty() ? "no complementary mesh" : d.entry.complement.c_str(),
                   d.complementBytes);
  const std::string manifest = (fs::path(o.output) / "city.json").string();
  if (Status s = scene::writeCityJson(manifest, city); !s) return fail(s.error().message, kUnreadable);
  if (!o.report.empty())
    if (Status s = writeTextFile(o.report, report.dump(2) + "\n"); !s) return fail(s.error().message, kUnreadable);
  if (!o.quiet)
    std::fprintf(stderr, "convert: wrote %s (%zu %s)\n", manifest.c_str(), city.buildings.size(),
                 o.packAtlases ? "districts" : "buildings");
  return kOk;
}

int run(const ConvertCliOptions& o) {
  {
    std::ifstream probe(o.input, std::ios::binary);
    std::error_code ec;
    if (!probe || fs::is_directory(o.input, ec)) return fail(o.input + ": cannot open", kUnreadable);
  }
  if (o.packAtlases && writesOneHni(o.output))
    return fail("--pack-atlases packs the buildings written into a folder: give -o FOLDER, not " + o.output, kUsage);
  if (o.complementLevels > 0 && writesOneHni(o.output))
    return fail("--complement-levels lists the levels in the folder's city.json: give -o FOLDER, not " + o.output,
                kUsage);
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
  cmd->add_option("--complement-levels", o->complementLevels,
                  "With -o FOLDER: write up to N coarser levels of each complementary mesh beside it "
                  "(NAME.complement.lod1.glb, ...; OpenMesh's decimater at 5, 20, 80 cm), listed with their "
                  "measured errors in city.json; `nut render --lod auto` draws the level a pixel cannot tell apart")
      ->check(CLI::Range(0, 4))
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
  cmd->add_option("--prefer", o->prefer,
                  "Where a building is converted two ways (plane cells or not, a wing in its own frame or not), keep "
                  "the smaller files, or the larger share of the surface in the HNI; surface also converts an open "
                  "mesh as the body left once sheets hanging off it (roofs overhanging their walls) are peeled off")
      ->check(CLI::IsMember({"files", "surface"}))
      ->capture_default_str();
  cmd->add_flag(
      "--pack-atlases", o->packAtlases,
      "With -o FOLDER: write one HNI and one complementary mesh per district (--district-size) instead of one per "
      "building: the buildings' blocks merged, equal blocks stored once, fewer and smaller files");
  cmd->add_option("--district-size", o->districtSideM,
                  "With --pack-atlases: the side of a district's square on the ground, in metres (a file of buildings "
                  "far apart packs into fewer files with larger squares)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
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
      "  nut convert samples/obj/street.obj -o street/        # one HNI per object + street/city.json\n"
      "  nut convert district.obj -o district/ --plane-cells --pack-atlases   # one HNI and GLB per 256 m\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
