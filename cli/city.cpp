// `nut city --count N --out DIR`: a city of N distinct buildings from building grammars and
// converted samples (grammar/city.hpp): one HNI per building, or per district with --pack-atlases
// (converter/district.hpp), each validated, and the city.json that places them.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#if NUT_HAVE_CONVERTER
#include <converter/convert.hpp>
#endif
#include <converter/assemble.hpp>
#include <converter/district.hpp>
#include <converter/scale_hierarchy.hpp>
#include <grammar/city.hpp>
#include <grammar/derive.hpp>
#include <nut/hni.hpp>
#include <nut/lod.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>

#include "commands.hpp"
#include "parallel.hpp"
#include "progress.hpp"

namespace fs = std::filesystem;

namespace nut::cli {

namespace {

struct CityCliOptions {
  std::size_t count = 0;
  std::string out, pngEffort = "small", layout = "streets", report;
  std::vector<std::string> grammars, mix{"grammar"};
  std::uint64_t seed = 0;
  int threads = 0;
  bool lod = false, packAtlases = false, quiet = false;
};

// The converted samples --mix converted adds: those whose HNI shows every face, so that a building
// is one file (samples/obj; the carpark leaves a complementary mesh).
constexpr std::array<const char*, 3> kConvertedSamples{"house", "residential", "highrise"};
// A converted sample is first shrunk, all axes alike, to fit a lot of this width and depth (the
// grammars' buildings are at most 20 m wide and 12 m deep before the plan's own scaling).
constexpr double kSampleFitWidthM = 20.0, kSampleFitDepthM = 12.0;

// Where the buildings come from: a building grammar, or a converted sample whose hierarchy each
// building stretches to its planned size.
struct CitySource {
  std::string name;
  std::optional<grammar::Grammar> grammar;
  Hierarchy converted;
  glm::dvec3 sizeM{0.0};                            // what the plan scales
  std::size_t meshTriangles = 0, meshVertices = 0;  // the converted sample's OBJ mesh
};

// What a worker leaves for the manifest.
struct WrittenBuilding {
  std::string error;
  int exitCode = kOk;
  grammar::LotPlacement placement;
  std::size_t pixelsHash = 0, pngBytes = 0;
  std::size_t meshTriangles = 0, meshVertices = 0;  // its source's own mesh, for --report
};

std::string buildingName(std::size_t i) {
  char name[32];
  std::snprintf(name, sizeof name, "b%05zu", i);
  return name;
}

// A building of a grammar source: compiled with the plan's seed and size, and the grammar's own
// mesh of it for the report.
Result<Image> grammarBuilding(const CityCliOptions& o, const grammar::Grammar& g, const grammar::PlannedBuilding& plan,
                              WrittenBuilding& w, HniText& text) {
  auto built = grammar::buildCityBuilding(
      g, plan, o.lod ? std::optional<LodMeasureOptions>(LodMeasureOptions{}) : std::nullopt);
  if (!built) return built.error();
  w.placement = built->placement;
  text.originM = built->compiled.originM;
  if (!o.report.empty()) {
    // What the same building costs as a mesh: the grammar's own geometry, every box closed.
    auto mesh = grammar::derivationMesh(built->compiled.derivation);
    if (!mesh) return Error{g.file + ": " + mesh.error().message};
    w.meshTriangles = mesh->triangles.size();
    w.meshVertices = mesh->positions.size();
  }
  return std::move(built->compiled.image);
}

// A building of a converted sample: its hierarchy stretched to the plan's size, standing on the
// ground. A sample whose blocks turn by a yaw stretches its width and depth alike.
Result<Image> convertedBuilding(const CityCliOptions& o, const CitySource& source, const grammar::PlannedBuilding& plan,
                                WrittenBuilding& w) {
  const glm::dvec3 sampleSize = source.converted.blocks[source.converted.root].sizeM();
  glm::dvec3 factors = plan.sizeM / sampleSize;
  auto scaled = converter::scaleHierarchy(source.converted, factors);
  if (!scaled) {
    factors.x = factors.z = std::sqrt(factors.x * factors.z);
    scaled = converter::scaleHierarchy(source.converted, factors);
  }
  if (!scaled) return Error{source.name + ": " + scaled.error().message};
  // Stretching changes how narrow a cell is against its block: split where the format needs it.
  if (auto split = converter::splitBlocks(*scaled); !split) return Error{source.name + ": " + split.error().message};
  auto image = compile(*scaled);
  if (image && o.lod) {
    measureLevelOfDetail(*scaled, *image);
    image = compile(*scaled);
  }
  if (!image) return Error{source.name + ": " + image.error().message};
  w.placement = grammar::placeOnLot(scaled->blocks[scaled->root].sizeM(), 0.0, plan);
  w.meshTriangles = source.meshTriangles;
  w.meshVertices = source.meshVertices;
  return image;
}

// Compiles, validates and writes building i of the plan, with `seedOffset` added to its seed.
WrittenBuilding writeBuilding(const CityCliOptions& o, const std::vector<CitySource>& sources,
                              grammar::PlannedBuilding plan, std::size_t i, std::uint64_t seedOffset) {
  WrittenBuilding w;
  plan.seed += seedOffset;
  const CitySource& source = sources[plan.source];
  // A converted sample varies by its size alone: a retry draws its height again.
  if (seedOffset > 0 && !source.grammar) plan.sizeM.y = grammar::redrawHeight(source.sizeM.y, plan.seed);
  HniText text;
  text.name = buildingName(i);
  text.generator = "nut city";
  auto image = source.grammar ? grammarBuilding(o, *source.grammar, plan, w, text) : convertedBuilding(o, source, plan, w);
  if (!image) {
    w.error = buildingName(i) + ": " + image.error().message;
    w.exitCode = kInvalid;
    return w;
  }
  if (Status s = validate(*image); !s) {
    w.error = buildingName(i) + ": " + source.name + ": the compiled HNI does not validate: " + s.error().message;
    w.exitCode = kInvalid;
    return w;
  }
  const std::string path = (fs::path(o.out) / (text.name + ".png")).string();
  if (Status s = writeHni(path, *image, text, o.pngEffort == "small" ? PngEffort::Small : PngEffort::Smallest); !s) {
    w.error = s.error().message;
    w.exitCode = kUnreadable;
    return w;
  }
  std::error_code ec;
  w.pngBytes = static_cast<std::size_t>(fs::file_size(path, ec));
  w.pixelsHash = std::hash<std::string_view>{}(
      std::string_view(reinterpret_cast<const char*>(image->pixels.data()), image->pixels.size()));
  return w;
}

// The sources --mix and --grammar name, grammars first.
Result<std::vector<CitySource>> readSources(const CityCliOptions& o, ProgressBar& bar) {
  std::vector<CitySource> sources;
  if (std::find(o.mix.begin(), o.mix.end(), "grammar") != o.mix.end()) {
    std::vector<std::string> files = o.grammars;
    if (files.empty())
      for (const char* name : {"marvie_building", "pga_complex_house", "pga_random_rule", "pga_random_windows"})
        files.push_back(std::string(NUT_SAMPLE_GRAMMARS) + "/" + name + ".grammar");
    for (const std::string& file : files) {
      auto g = grammar::readGrammar(file);
      if (!g) return g.error();
      if (!g->size || g->size->z <= 0)
        return Error{file + ": a building grammar needs a mass as its start scope (@size W, H, D)"};
      CitySource source{file, std::move(*g), {}, {}, 0, 0};
      source.sizeM = *source.grammar->size;
      sources.push_back(std::move(source));
    }
  }
  if (std::find(o.mix.begin(), o.mix.end(), "converted") == o.mix.end()) return sources;
#if !NUT_HAVE_CONVERTER
  (void)bar;
  return Error{"--mix converted: this nut was built without the mesh converter (NUT_BUILD_CONVERTER)"};
#else
  for (const char* name : kConvertedSamples) {
    const std::string file = std::string(NUT_SAMPLE_OBJS) + "/" + name + ".obj";
    std::vector<std::string> warnings;
    auto mesh = scene::readObjMesh(file, warnings);
    if (!mesh) return mesh.error();
    CitySource source{file, std::nullopt, {}, {}, mesh->triangles.size(), mesh->positions.size()};
    converter::ConvertOptions options;
    options.progress = [&bar, name](std::string_view phase, double fraction) {
      bar.update(std::string("converting ") + name + ": " + std::string(phase), fraction);
    };
    auto conversion = converter::convertMesh(std::move(*mesh), options);
    if (!conversion) return conversion.error();
    if (!conversion->complement.triangles.empty())
      return Error{file + ": its conversion leaves a complementary mesh, which a city building does not carry"};
    source.converted = std::move(conversion->hierarchy);
    const glm::dvec3 size = source.converted.blocks[source.converted.root].sizeM();
    source.sizeM = size * std::min({1.0, kSampleFitWidthM / size.x, kSampleFitDepthM / size.z});
    sources.push_back(std::move(source));
  }
  return sources;
#endif
}

// What a district leaves for the manifest and the report.
struct WrittenDistrict {
  Result<scene::CityBuilding> entry = Error{"not written"};
  std::size_t pngBytes = 0, buildingBlocks = 0, mergedBlocks = 0;
};

// The buildings of one district compiled as one HNI (converter/district.hpp), or, when they do
// not fit one, each half on its own.
void packDistrict(const CityCliOptions& o, const scene::CityManifest& city, const std::vector<std::size_t>& members,
                  const std::string& name, std::vector<WrittenDistrict>& out) {
  std::vector<Hierarchy> hierarchies;
  std::vector<converter::PlacedHierarchy> placed;
  hierarchies.reserve(members.size());
  const auto failed = [&](Error error) {
    WrittenDistrict d;
    d.entry = std::move(error);
    out.push_back(std::move(d));
  };
  for (std::size_t i : members) {
    const scene::CityBuilding& b = city.buildings[i];
    const std::string path = (fs::path(o.out) / b.hni).string();
    auto png = readPng(path);
    auto h = png ? decode(png->image) : Result<Hierarchy>(png.error());
    if (!h) return failed(Error{path + ": " + h.error().message});
    hierarchies.push_back(std::move(*h));
    placed.push_back({&hierarchies.back(), b.positionM, b.yawDeg});
  }
  std::vector<std::size_t> all(members.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  auto parts = converter::compileDistrict(placed, all);
  if (!parts) return failed(Error{name + " (" + city.buildings[members.front()].name + "): " + parts.error().message});
  for (converter::CompiledDistrict& part : *parts) {
    const std::string partName = name + part.suffix;
    HniText text{partName, "nut city --pack-atlases", "m", part.district.originM};
    const std::string path = (fs::path(o.out) / (partName + ".png")).string();
    if (Status s = writeHni(path, part.image, text, o.pngEffort == "small" ? PngEffort::Small : PngEffort::Smallest);
        !s)
      return failed(s.error());
    WrittenDistrict d;
    std::error_code ec;
    d.pngBytes = static_cast<std::size_t>(fs::file_size(path, ec));
    d.buildingBlocks = part.district.buildingBlocks;
    d.mergedBlocks = part.district.mergedBlocks;
    d.entry = scene::CityBuilding{partName, partName + ".png", "", part.district.originM, 0.0, part.district.boundsM};
    out.push_back(std::move(d));
  }
}

// Replaces the city's buildings by districts of them (--pack-atlases): squares of kDistrictSideM on
// the ground, by the centre of each building's box, each written as one HNI. The buildings' own
// HNIs are removed once the manifest names the districts.
struct PackedCity {
  scene::CityManifest districts;
  std::size_t pngBytes = 0, buildingBlocks = 0, mergedBlocks = 0;
};
Result<PackedCity> packDistricts(const CityCliOptions& o, const scene::CityManifest& city, std::size_t workers,
                                 ProgressBar& bar) {
  std::vector<WorldBox> boxes;
  for (const scene::CityBuilding& b : city.buildings) boxes.push_back(*b.boundsM);
  const std::vector<std::vector<std::size_t>> members =
      converter::districtGroups(boxes, converter::kDistrictSideM, glm::dvec2(0.0));
  std::vector<std::vector<WrittenDistrict>> written(members.size());
  std::size_t finished = 0;
  forEachInParallel(
      members.size(), workers,
      [&](std::size_t i) {
        char name[32];
        std::snprintf(name, sizeof name, "d%04zu", i);
        packDistrict(o, city, members[i], name, written[i]);
      },
      [&] { bar.updateCount("districts", ++finished, members.size()); });
  PackedCity packed;
  packed.districts.name = city.name;
  for (std::vector<WrittenDistrict>& parts : written)
    for (WrittenDistrict& d : parts) {
      if (!d.entry) return d.entry.error();
      packed.districts.buildings.push_back(std::move(*d.entry));
      packed.pngBytes += d.pngBytes;
      packed.buildingBlocks += d.buildingBlocks;
      packed.mergedBlocks += d.mergedBlocks;
    }
  return packed;
}

int run(const CityCliOptions& o) {
  if (!o.grammars.empty() && std::find(o.mix.begin(), o.mix.end(), "grammar") == o.mix.end())
    return fail("--grammar: the grammars are a source of --mix grammar, which --mix leaves out", kUsage);
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) return fail(o.out + ": cannot create folder (" + ec.message() + ")", kUnreadable);
  ProgressBar bar(!o.quiet, "city", fs::path(o.out).filename().string());
  auto sources = readSources(o, bar);
  if (!sources) return fail(sources.error().message, kInvalid);
  std::vector<glm::dvec3> sizes;
  for (const CitySource& source : *sources) sizes.push_back(source.sizeM);

  const std::vector<grammar::PlannedBuilding> plan = grammar::planCity(
      sizes, o.count, o.seed, o.layout == "grid" ? grammar::CityLayout::Grid : grammar::CityLayout::Streets);
  std::vector<WrittenBuilding> written(plan.size());
  const auto start = std::chrono::steady_clock::now();
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min<std::size_t>(plan.size(), o.threads > 0 ? static_cast<std::size_t>(o.threads) : cores);
  std::size_t finished = 0;
  forEachInParallel(
      plan.size(), workers, [&](std::size_t i) { written[i] = writeBuilding(o, *sources, plan[i], i, 0); },
      [&] { bar.updateCount("buildings", ++finished, plan.size()); });

  // Distinct: a building whose pixels repeat an earlier one's is derived again with another seed,
  // in index order, so the city does not depend on which thread finished first.
  std::map<std::size_t, std::size_t> firstWithHash;
  scene::CityManifest city;
  city.name = fs::path(o.out).filename().string();
  std::size_t pngBytes = 0;
  std::map<std::string, std::size_t> bySource;
  std::array<std::size_t, 2> meshTriangles{}, meshVertices{};  // grammar, converted
  for (std::size_t i = 0; i < written.size(); ++i) {
    for (std::uint64_t offset = 1; written[i].exitCode == kOk && firstWithHash.count(written[i].pixelsHash); ++offset) {
      if (offset > 16) return fail(buildingName(i) + ": no distinct building in 16 seeds", kInvalid);
      written[i] = writeBuilding(o, *sources, plan[i], i, offset);
    }
    const WrittenBuilding& w = written[i];
    if (w.exitCode != kOk) return fail(w.error, w.exitCode);
    firstWithHash.emplace(w.pixelsHash, i);
    pngBytes += w.pngBytes;
    const CitySource& source = (*sources)[plan[i].source];
    ++bySource[fs::path(source.name).stem().string()];
    meshTriangles[source.grammar ? 0 : 1] += w.meshTriangles;
    meshVertices[source.grammar ? 0 : 1] += w.meshVertices;
    city.buildings.push_back({buildingName(i), buildingName(i) + ".png", "", w.placement.positionM,
                              w.placement.yawDeg, w.placement.boundsM});
  }
  bar.finish();
  std::optional<PackedCity> packed;
  if (o.packAtlases) {
    auto p = packDistricts(o, city, workers, bar);
    bar.finish();
    if (!p) return fail(p.error().message, kInvalid);
    packed = std::move(*p);
  }
  const std::string manifest = (fs::path(o.out) / "city.json").string();
  if (Status s = scene::writeCityJson(manifest, packed ? packed->districts : city); !s)
    return fail(s.error().message, kUnreadable);
  if (packed)
    for (const scene::CityBuilding& b : city.buildings) fs::remove(fs::path(o.out) / b.hni, ec);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.report.empty()) {
    nlohmann::json report = {
        {"buildings", city.buildings.size()},
        {"seed", o.seed},
        {"layout", o.layout},
        {"sources", bySource},
        {"threads", workers},
        {"seconds", seconds},
        {"buildings_per_second", static_cast<double>(city.buildings.size()) / seconds},
        {"png_bytes", pngBytes},
        {"grammar_mesh", {{"triangles", meshTriangles[0]}, {"vertices", meshVertices[0]}}},
        {"converted_mesh", {{"triangles", meshTriangles[1]}, {"vertices", meshVertices[1]}}}};
    if (packed)
      report["districts"] = {{"count", packed->districts.buildings.size()},
                             {"png_bytes", packed->pngBytes},
                             {"building_blocks", packed->buildingBlocks},
                             {"merged_blocks", packed->mergedBlocks}};
    if (Status s = writeTextFile(o.report, report.dump(2) + "\n"); !s) return fail(s.error().message, kUnreadable);
  }
  if (!o.quiet) {
    std::fprintf(stderr, "city: wrote %zu buildings (%zu bytes PNG, %zu per building) and %s in %.1f s\n",
                 city.buildings.size(), pngBytes, city.buildings.empty() ? 0 : pngBytes / city.buildings.size(),
                 manifest.c_str(), seconds);
    if (packed)
      std::fprintf(stderr, "city: packed them into %zu districts: %zu bytes PNG (%.1f %% of one PNG per building), "
                   "%zu of %zu blocks stored once for several\n",
                   packed->districts.buildings.size(), packed->pngBytes,
                   100.0 * static_cast<double>(packed->pngBytes) / static_cast<double>(pngBytes), packed->mergedBlocks,
                   packed->buildingBlocks);
  }
  return kOk;
}

}  // namespace

void addCityCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<CityCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "city", "Generate a city of distinct buildings from building grammars and converted samples (docs/CITY.md)");
  cmd->add_option("--count", o->count, "Number of buildings")->required()->check(CLI::Range(1, 1000000));
  cmd->add_option("--out", o->out, "Output folder: one HNI per building and city.json")->required();
  cmd->add_option("--seed", o->seed, "Seed of the plan: the same seed gives the same city")->capture_default_str();
  cmd->add_option("--grammar", o->grammars,
                  "A building grammar (a W,H,D @size), taken in turn with the others (repeatable); default: the "
                  "sample buildings marvie_building, pga_complex_house, pga_random_rule, pga_random_windows");
  cmd->add_option("--layout", o->layout,
                  "streets: rows of lots up to 240 m along each street; grid: a square city of 30 m lots, a "
                  "cross street every 8 (docs/CITY.md)")
      ->check(CLI::IsMember({"streets", "grid"}))
      ->capture_default_str();
  cmd->add_option("--report", o->report,
                  "Write a JSON report: buildings per second, PNG bytes, and the triangles and vertices of the "
                  "grammar's own meshes of the same buildings")
      ->check(outputExtension(".json", "JSON"));
  cmd->add_option("--mix", o->mix,
                  "Where buildings come from, taken in turn: grammar (the --grammar files), converted (the samples "
                  "house, residential and highrise of samples/obj, converted once and stretched per building)")
      ->delimiter(',')
      ->check(CLI::IsMember({"grammar", "converted"}))
      ->capture_default_str();
  cmd->add_flag("--pack-atlases", o->packAtlases,
                "Write one HNI per district of 256 m instead of one per building: the buildings' blocks merged, "
                "equal blocks stored once (docs/CITY.md, Districts)");
  cmd->add_flag("--lod", o->lod, "Measure each building's level of detail, as nut grammar --lod");
  cmd->add_option("--png-effort", o->pngEffort,
                  "small: zlib, milliseconds per building; smallest: Zopfli, 5-15 % smaller and about 50 ms more")
      ->check(CLI::IsMember({"small", "smallest"}))
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores), one building each")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet", o->quiet, "No progress or summary on stderr");
  cmd->footer(
      "Examples:\n  nut city --count 100 --out city100 --seed 1\n"
      "  nut city --count 2116 --out mixed --layout grid --mix grammar,converted --pack-atlases\n"
      "  nut city --count 8464 --out city8464 --layout grid --report city8464.json\n"
      "  nut render city100/city.json -o city100.png --size 1280x720\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
