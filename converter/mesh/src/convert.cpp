// The conversion pipeline and its report (converter/convert.hpp).
#include <converter/convert.hpp>

#include <chrono>
#include <cmath>
#include <functional>
#include <filesystem>
#include <optional>


#include <nlohmann/json.hpp>

#include <converter/assemble.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>

#include "parallel.hpp"

namespace nut::converter {

namespace {

using Clock = std::chrono::steady_clock;

// A flat grid larger than this is not tried as a variant: it would not fit an HNI anyway.
constexpr std::size_t kMaxFlatCells = 2'000'000;
// Builds of the grid when the HNI does not fit: as asked, slopes strict, tolerance doubled.
constexpr int kCoarserAttempts = 3;

// Times consecutive phases of the pipeline.
class Phases {
 public:
  explicit Phases(std::vector<PhaseTiming>& out) : out_(out), start_(Clock::now()) {}
  void end(const std::string& name) {
    const auto now = Clock::now();
    out_.push_back({name, std::chrono::duration<double>(now - start_).count()});
    start_ = now;
  }

 private:
  std::vector<PhaseTiming>& out_;
  Clock::time_point start_;
};

nlohmann::json vec3Json(const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

// Builds the hierarchy variants from the grid, compiles each and keeps in `out` the one whose
// pixels deflate smallest. False when none fits an HNI (lastError says why).
bool buildHni(const SolidGrid& grid, const ConvertOptions& options, Conversion& out, ConvertReport& report,
              std::string& lastError, const std::function<void(std::string_view, double)>& progress) {
  // Block extraction pays on repetitive buildings and costs headers and metadata on small ones,
  // and PNG compression already shrinks repeated rows of a flat grid; so the variants are
  // compiled and the one whose pixels deflate smallest is kept (each is reported).
  progress("hierarchy", 0);
  struct Variant {
    std::string name;
    BlockOptions options;
  };
  std::vector<Variant> variants;
  BlockOptions base = options.blocks;
  base.toleranceM = options.solid.toleranceM;
  const bool flatFeasible = grid.block.cells.size() <= kMaxFlatCells;
  if (!base.automatic || flatFeasible) {
    variants.push_back({"none", base});
    variants.back().options.automatic = false;
  }
  if (base.automatic) {
    variants.push_back({"repeats", base});
    variants.back().options.cuts = false;
    variants.push_back({"repeats+splits", base});
  }
  // Each variant is built and compiled on its own thread (they share nothing), then the smallest
  // is kept, in variant order so the choice does not depend on timing.
  struct Built {
    Result<Hierarchy> hierarchy = Error{""};
    Result<Image> image = Error{""};
    BlockStats stats;
    int split = 0;
  };
  std::vector<Built> built(variants.size());
  parallelFor(variants.size(), 1, options.solid.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      Built& b = built[v];
      b.hierarchy = buildHierarchy(grid.block, grid.materials, grid.originM, variants[v].options, b.stats);
      if (!b.hierarchy) {
        b.image = b.hierarchy.error();
        continue;
      }
      compactMaterials(*b.hierarchy);
      auto added = splitBlocks(*b.hierarchy);
      if (!added) {
        b.image = added.error();
        continue;
      }
      b.split = *added;
      b.image = compile(*b.hierarchy, options.compile);
    }
  });
  std::optional<std::size_t> chosen;
  std::size_t chosenBytes = 0;
  report.variants.clear();
  for (std::size_t v = 0; v < variants.size(); ++v) {
    Built& b = built[v];
    VariantReport entry{variants[v].name, 0, 0, 0, ""};
    if (b.image) {
      entry.blocks = static_cast<int>(b.hierarchy->blocks.size());
      entry.bytesRaw = static_cast<long long>(b.image->byteSize());
      entry.bytesPng = static_cast<long long>(encodePng(*b.image, nullptr, PngEffort::Small).size());
      if (!chosen || static_cast<std::size_t>(entry.bytesPng) < chosenBytes) {
        chosen = v;
        chosenBytes = static_cast<std::size_t>(entry.bytesPng);
        out.hierarchy = std::move(*b.hierarchy);
        out.image = std::move(*b.image);
        report.blocks = std::move(b.stats);
        report.splitBlocks = b.split;
        report.blockMode = variants[v].name;
      }
    } else {
      entry.error = b.image.error().message;
      lastError = b.image.error().message;
    }
    report.variants.push_back(entry);
  }
  progress("hierarchy", 1);
  if (!chosen) return false;
  report.hni = computeStats(out.image);
  return true;
}

}  // namespace

double ConvertReport::seconds() const {
  double sum = 0;
  for (const PhaseTiming& p : phases) sum += p.seconds;
  return sum;
}

Result<Conversion> convertMesh(Mesh mesh, const ConvertOptions& options) {
  Conversion out;
  ConvertReport& report = out.report;
  report.name = mesh.name;
  report.inputTriangles = mesh.triangles.size();
  Phases phases(report.phases);
  const auto progress = [&](std::string_view phase, double fraction) {
    if (options.progress) options.progress(phase, fraction);
  };

  progress("check", 0);
  report.check = checkAndRepair(mesh);
  if (mesh.triangles.empty())
    return Error{mesh.name + ": nothing to convert: all " + std::to_string(report.inputTriangles) + " faces are degenerate"};
  report.insideTest = std::string("generalized winding number at cell centres (") +
                      (report.check.closed() ? "closed mesh" : "open mesh: no closed surface needed") + ")";
  phases.end("check");

  // The grid is built as asked; when no hierarchy made from it fits an HNI, it is built again
  // coarser: first keeping only slopes that became wedges everywhere, then with the tolerance
  // doubled, each time with a warning in the report.
  std::optional<SolidGrid> grid;
  std::string lastError;
  for (int coarser = 0; coarser < kCoarserAttempts; ++coarser) {
    SolidOptions solidOptions = options.solid;
    solidOptions.progress = [&](double f) { progress("solid", f); };
    if (coarser > 0) solidOptions.partialWedges = false;
    if (coarser > 1) solidOptions.toleranceM *= std::pow(2.0, coarser - 1);
    progress("solid", 0);
    auto built = buildSolidGrid(mesh, solidOptions);
    if (!built) return built.error();
    if (coarser > 0)
      report.warnings.push_back("the grid did not fit an HNI (" + lastError + "); built again with " +
                                (coarser == 1 ? std::string("only slopes that are wedges everywhere")
                                              : "tolerance " + std::to_string(solidOptions.toleranceM) + " m"));
    grid = std::move(*built);
    report.solid = grid->stats;
    out.originM = report.originM = grid->originM;
    const std::string suffix = coarser == 0 ? "" : " (coarser " + std::to_string(coarser) + ")";
    phases.end("solid" + suffix);
    const bool fits = buildHni(*grid, options, out, report, lastError, progress);
    phases.end("hierarchy" + suffix);
    if (fits) break;
    grid.reset();
  }
  if (!grid) return Error{mesh.name + ": " + lastError};
  out.complement = std::move(grid->complement);
  report.complementTriangles = out.complement.triangles.size();
  return out;
}

Status writeConversion(Conversion& conversion, const std::string& pngPath, const std::string& complementPath) {
  HniText text;
  text.name = conversion.report.name;
  text.generator = "nut convert";
  text.originM = conversion.originM;
  if (Status s = writeHni(pngPath, conversion.image, text); !s) return s;
  std::error_code ec;
  conversion.report.pngBytes = std::filesystem::file_size(pngPath, ec);
  if (!complementPath.empty()) {
    ExportedMesh mesh;
    mesh.positions = conversion.complement.positions;
    mesh.triangles = conversion.complement.triangles;
    mesh.triangleMaterial = conversion.complement.triangleMaterial;
    if (Status s = writeObj(complementPath, mesh, conversion.complement.materials); !s) return s;
  }
  return Ok{};
}

std::string reportJson(const ConvertReport& r) {
  using nlohmann::json;
  json phases = json::object();
  for (const PhaseTiming& p : r.phases) phases[p.name] = p.seconds;
  json found = json::array();
  for (const ExtractedBlock& b : r.blocks.found)
    found.push_back({{"block", b.block},
                     {"cells", b.cells},
                     {"size_m", vec3Json(b.sizeM)},
                     {"instances", b.instances},
                     {"wrap", b.wrap},
                     {"manual", b.manual},
                     {"saved_bytes_estimate", b.savedBytes}});
  json variants = json::array();
  for (const VariantReport& v : r.variants)
    variants.push_back(v.error.empty() ? json{{"name", v.name}, {"blocks", v.blocks}, {"bytes_raw", v.bytesRaw}, {"bytes_png", v.bytesPng}}
                                       : json{{"name", v.name}, {"error", v.error}});
  const SolidStats& s = r.solid;
  const double area = s.areaM2 > 0 ? s.areaM2 : 1;
  const json j = {
      {"name", r.name},
      {"origin_m", vec3Json(r.originM)},
      {"seconds", r.seconds()},
      {"phases_seconds", phases},
      {"input", {{"triangles", r.inputTriangles},
                 {"vertices", r.check.vertices},
                 {"degenerate_removed", r.check.degenerate},
                 {"slivers", r.check.slivers},
                 {"duplicate_faces", r.check.duplicateFaces},
                 {"boundary_edges", r.check.boundaryEdges},
                 {"non_manifold_edges", r.check.nonManifoldEdges},
                 {"inconsistent_edges", r.check.inconsistentEdges},
                 {"pieces", r.check.components},
                 {"flipped_faces", r.check.flippedTriangles},
                 {"closed", r.check.closed()}}},
      {"inside_test", r.insideTest},
      {"grid", {{"planes", s.planes},
                {"cells", s.cells},
                {"sweep_axis", std::string(1, "xyz"[s.sweepAxis])},
                {"slopes", s.slopes},
                {"slopes_as_wedges", s.slopesAsWedges},
                {"slope_boundaries", s.slopeBoundaries},
                {"solid_cells", s.solidCells},
                {"wedge_cells", s.wedgeCells},
                {"winding_evaluations", s.windingEvaluations},
                {"ambiguous_cells", s.ambiguousCells}}},
      {"surface", {{"area_m2", s.areaM2},
                   {"nut_m2", s.nutAreaM2},
                   {"complement_m2", s.complementAreaM2},
                   {"hidden_m2", s.hiddenAreaM2},
                   {"nut_fraction", s.nutAreaM2 / area},
                   {"complement_fraction", s.complementAreaM2 / area},
                   {"complement_triangles", r.complementTriangles}}},
      {"blocks", {{"mode", r.blockMode},
                  {"variants", variants},
                  {"found", found},
                  {"split_for_limits", r.splitBlocks},
                  {"cells_before", r.blocks.cellsBefore},
                  {"cells_after", r.blocks.cellsAfter},
                  {"bytes_estimate_before", r.blocks.bytesBefore},
                  {"bytes_estimate_after", r.blocks.bytesAfter}}},
      {"hni", {{"blocks", r.hni.blocks},
               {"cells", r.hni.cells},
               {"redirections", r.hni.redirections},
               {"materials", r.hni.materials},
               {"width", r.hni.width},
               {"height", r.hni.height},
               {"bytes_raw", r.hni.bytesRaw},
               {"bytes_png", r.pngBytes},
               {"waste_pct", r.hni.wastePct},
               {"dag_depth", r.hni.dagDepth}}},
      {"warnings", r.warnings}};
  return j.dump(2) + "\n";
}

}  // namespace nut::converter
