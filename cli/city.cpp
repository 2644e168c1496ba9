// `nut city --count N --out DIR`: a city of N distinct buildings from building grammars
// (grammar/city.hpp): one HNI per building, each validated, and the city.json that places them.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include <grammar/city.hpp>
#include <grammar/derive.hpp>
#include <nut/hni.hpp>
#include <nut/png_io.hpp>
#include <scene/city.hpp>

#include "commands.hpp"
#include "progress.hpp"

namespace fs = std::filesystem;

namespace nut::cli {

namespace {

struct CityCliOptions {
  std::size_t count = 0;
  std::string out, pngEffort = "small", layout = "streets", report;
  std::vector<std::string> grammars;
  std::uint64_t seed = 0;
  int threads = 0;
  bool lod = false, quiet = false;
};

// What a worker leaves for the manifest.
struct WrittenBuilding {
  std::string error;
  int exitCode = kOk;
  glm::dvec3 positionM{0.0};
  double yawDeg = 0;
  WorldBox boundsM;
  std::size_t pixelsHash = 0, pngBytes = 0;
  std::size_t meshTriangles = 0, meshVertices = 0;  // the derivation's own mesh, for --report
};

std::string buildingName(std::size_t i) {
  char name[32];
  std::snprintf(name, sizeof name, "b%05zu", i);
  return name;
}

// Compiles, validates and writes building i of the plan, with `seedOffset` added to its seed.
WrittenBuilding writeBuilding(const CityCliOptions& o, const std::vector<grammar::Grammar>& grammars,
                              grammar::PlannedBuilding plan, std::size_t i, std::uint64_t seedOffset) {
  WrittenBuilding w;
  plan.seed += seedOffset;
  const grammar::Grammar& g = grammars[plan.grammar];
  auto built = grammar::buildCityBuilding(
      g, plan, o.lod ? std::optional<LodMeasureOptions>(LodMeasureOptions{}) : std::nullopt);
  if (!built) {
    w.error = buildingName(i) + ": " + built.error().message;
    w.exitCode = kInvalid;
    return w;
  }
  const Image& image = built->compiled.image;
  if (Status s = validate(image); !s) {
    w.error = buildingName(i) + ": " + g.file + ": the compiled HNI does not validate: " + s.error().message;
    w.exitCode = kInvalid;
    return w;
  }
  HniText text;
  text.name = buildingName(i);
  text.generator = "nut city";
  text.originM = built->compiled.originM;
  const std::string path = (fs::path(o.out) / (text.name + ".png")).string();
  if (Status s = writeHni(path, image, text, o.pngEffort == "small" ? PngEffort::Small : PngEffort::Smallest); !s) {
    w.error = s.error().message;
    w.exitCode = kUnreadable;
    return w;
  }
  std::error_code ec;
  w.pngBytes = static_cast<std::size_t>(fs::file_size(path, ec));
  w.positionM = built->positionM;
  w.yawDeg = built->yawDeg;
  w.boundsM = built->boundsM;
  w.pixelsHash = std::hash<std::string_view>{}(
      std::string_view(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size()));
  if (!o.report.empty()) {
    // What the same building costs as a mesh: the grammar's own geometry, every box closed.
    auto mesh = grammar::derivationMesh(built->compiled.derivation);
    if (!mesh) {
      w.error = buildingName(i) + ": " + g.file + ": " + mesh.error().message;
      w.exitCode = kInvalid;
      return w;
    }
    w.meshTriangles = mesh->triangles.size();
    w.meshVertices = mesh->positions.size();
  }
  return w;
}

int run(const CityCliOptions& o) {
  std::vector<std::string> files = o.grammars;
  if (files.empty())
    for (const char* name : {"marvie_building", "pga_complex_house", "pga_random_rule", "pga_random_windows"})
      files.push_back(std::string(NUT_SAMPLE_GRAMMARS) + "/" + name + ".grammar");
  std::vector<grammar::Grammar> grammars;
  for (const std::string& file : files) {
    auto g = grammar::readGrammar(file);
    if (!g) return fail(g.error().message, kInvalid);
    if (!g->size || g->size->z <= 0)
      return fail(file + ": a building grammar needs a mass as its start scope (@size W, H, D)", kInvalid);
    grammars.push_back(std::move(*g));
  }
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) return fail(o.out + ": cannot create folder (" + ec.message() + ")", kUnreadable);

  const std::vector<grammar::PlannedBuilding> plan = grammar::planCity(
      grammars, o.count, o.seed, o.layout == "grid" ? grammar::CityLayout::Grid : grammar::CityLayout::Streets);
  std::vector<WrittenBuilding> written(plan.size());
  ProgressBar bar(!o.quiet, "city", fs::path(o.out).filename().string());
  const auto start = std::chrono::steady_clock::now();
  std::atomic<std::size_t> next{0}, finished{0};
  std::mutex progressMutex;
  const auto work = [&] {
    for (std::size_t i; (i = next++) < plan.size();) {
      written[i] = writeBuilding(o, grammars, plan[i], i, 0);
      const std::lock_guard lock(progressMutex);
      bar.updateCount("buildings", ++finished, plan.size());
    }
  };
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min<std::size_t>(plan.size(), o.threads > 0 ? static_cast<std::size_t>(o.threads) : cores);
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  bar.finish();

  // Distinct: a building whose pixels repeat an earlier one's is derived again with another seed,
  // in index order, so the city does not depend on which thread finished first.
  std::map<std::size_t, std::size_t> firstWithHash;
  scene::CityManifest city;
  city.name = fs::path(o.out).filename().string();
  std::size_t pngBytes = 0, meshTriangles = 0, meshVertices = 0;
  for (std::size_t i = 0; i < written.size(); ++i) {
    for (std::uint64_t offset = 1; written[i].exitCode == kOk && firstWithHash.count(written[i].pixelsHash); ++offset) {
      if (offset > 16) return fail(buildingName(i) + ": no distinct building in 16 seeds", kInvalid);
      written[i] = writeBuilding(o, grammars, plan[i], i, offset);
    }
    const WrittenBuilding& w = written[i];
    if (w.exitCode != kOk) return fail(w.error, w.exitCode);
    firstWithHash.emplace(w.pixelsHash, i);
    pngBytes += w.pngBytes;
    meshTriangles += w.meshTriangles;
    meshVertices += w.meshVertices;
    city.buildings.push_back({buildingName(i), buildingName(i) + ".png", "", w.positionM, w.yawDeg, w.boundsM});
  }
  const std::string manifest = (fs::path(o.out) / "city.json").string();
  if (Status s = scene::writeCityJson(manifest, city); !s) return fail(s.error().message, kUnreadable);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.report.empty()) {
    const nlohmann::json report = {
        {"buildings", city.buildings.size()},
        {"seed", o.seed},
        {"layout", o.layout},
        {"threads", workers},
        {"seconds", seconds},
        {"buildings_per_second", static_cast<double>(city.buildings.size()) / seconds},
        {"png_bytes", pngBytes},
        {"grammar_mesh", {{"triangles", meshTriangles}, {"vertices", meshVertices}}}};
    if (Status s = writeTextFile(o.report, report.dump(2) + "\n"); !s) return fail(s.error().message, kUnreadable);
  }
  if (!o.quiet)
    std::fprintf(stderr, "city: wrote %zu buildings (%zu bytes PNG, %zu per building) and %s in %.1f s\n",
                 city.buildings.size(), pngBytes, city.buildings.empty() ? 0 : pngBytes / city.buildings.size(),
                 manifest.c_str(), seconds);
  return kOk;
}

}  // namespace

void addCityCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<CityCliOptions>();
  CLI::App* cmd = app.add_subcommand("city", "Generate a city of distinct buildings from building grammars (docs/CITY.md)");
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
      "  nut city --count 8464 --out city8464 --layout grid --report city8464.json\n"
      "  nut render city100/city.json -o city100.png --size 1280x720\n\n" +
      std::string(kExitCodesHelp));
  cmd->callback([o, &exitCode] { exitCode = run(*o); });
}

}  // namespace nut::cli
