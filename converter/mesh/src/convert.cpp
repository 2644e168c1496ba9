// The conversion pipeline and its report (converter/convert.hpp).
#include <converter/convert.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <optional>


#include <nlohmann/json.hpp>

#include <converter/align.hpp>
#include <converter/assemble.hpp>
#include <converter/axis_order.hpp>
#include <converter/hidden_cells.hpp>
#include <converter/mesh_lod.hpp>
#include <converter/mesh_size.hpp>
#include <converter/plane_fit.hpp>
#include <converter/share_axes.hpp>
#include <converter/sheets.hpp>
#include <converter/wings.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <scene/mesh_file.hpp>

#include "parallel.hpp"

namespace nut::converter {

namespace {

using Clock = std::chrono::steady_clock;

// A flat grid larger than this is not tried as a variant: it would not fit an HNI anyway.
constexpr std::size_t kMaxFlatCells = 2'000'000;
// The block extraction thresholds tried: on the samples 32 suits the street's houses, 2048 the
// high-rise's storeys and bays, 32768 the residential block, whose balconies cost more as blocks
// than as repeated rows of its grid. A grid too large for a flat variant skips the last: on the
// high-rise (4.1 M cells) it misses the window bays (38-49 % larger) and took a third of the time.
constexpr long long kMinSavedCellsTried[] = {32, 2048, 32768};
constexpr long long kMaxMinSavedCellsLargeGrid = 2048;
// The priced variant (BlockOptions::priced) is built for grids up to this many cells: on the house
// it is the smallest (2,482 B against 2,734); on the residential block (250,000 cells) it came out
// 12 % larger than the threshold variants.
constexpr std::size_t kMaxPricedGridCells = 100'000;
// Variants are encoded quickly first (PngEffort::Quick, a tenth of the time); only those whose
// quick PNG is within this factor of the smallest are encoded at PngEffort::Small, which decides.
// Over the samples and the external test meshes (../shared/data; 60 buildings, 1,177 variants) quick PNGs are 4-25 % larger
// than small ones, and the winner's quick PNG was at most 14 % above the smallest (a Zurich
// building): this margin chooses every one of them as judging all would, and skips a third of the
// small encodes (on the high-rise, the two variants that split into many blocks).
constexpr double kJudgedMargin = 1.2;
// The variants also start from the grid with its hidden cells filled (hidden_cells.hpp) when at
// least this share of its cells is hidden. Filling won on the samples whose grids are 47-85 %
// hidden (the street's houses 73-76 %: two of four), and nowhere below (Ingolstadt 32 %, the
// Kenney houses 25-36 %, the car park 4 %, Zurich's 49 at most 28 %), where a second start would
// only double the search (Zurich 8.3-9.4 -> 10.6-11.4 s).
constexpr double kMinHiddenShareForFill = 0.4;
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

// A grid the variants start from: the solid grid in one axis order, its hidden cells as the
// solid conversion left them or filled (hidden_cells.hpp).
struct StartingGrid {
  TurnedBlock turned;
  bool hiddenFilled = false;
};

// One way of building the hierarchy: a starting grid, and how blocks are extracted.
struct Variant {
  std::string name;
  BlockOptions options;
  const StartingGrid* grid;
  const GridSearch* search = nullptr;  // searchGrid(grid), when found for several variants
};

struct BuiltVariant {
  Result<Hierarchy> hierarchy = Error{""};
  Result<Image> image = Error{""};
  BlockStats stats;
  int split = 0;
  std::size_t quickBytes = 0;  // PngEffort::Quick
  std::size_t pngBytes = 0;    // PngEffort::Small, when judged (judgeVariants)
  double seconds = 0;          // building, compiling and encoding it

  bool judged() const { return pngBytes > 0; }
};

// Whether x ranks before y: judged variants by their small PNG, before the others by their quick one.
bool smaller(const BuiltVariant& x, const BuiltVariant& y) {
  if (!x.image || !y.image) return x.image && !y.image;
  if (x.judged() != y.judged()) return x.judged();
  return x.judged() ? x.pngBytes < y.pngBytes : x.quickBytes < y.quickBytes;
}

BuiltVariant buildVariant(const SolidGrid& grid, const Variant& v, const ConvertOptions& options) {
  const auto start = Clock::now();
  BuiltVariant b;
  const TurnedBlock& turned = v.grid->turned;
  b.hierarchy = buildHierarchy(turned.block, grid.materials, grid.originM, v.options, b.stats, grid.subBlocks, v.search);
  if (!b.hierarchy) {
    b.image = b.hierarchy.error();
    return b;
  }
  if (turned.cube != 0) wrapRoot(*b.hierarchy, grid.block.sizeM(), turned.cube, turned.offsetM);
  compactMaterials(*b.hierarchy);
  auto added = splitBlocks(*b.hierarchy);
  if (!added) {
    b.image = added.error();
    return b;
  }
  b.split = *added;
  b.image = compile(*b.hierarchy, options.compile);
  if (b.image) b.quickBytes = encodePng(*b.image, nullptr, PngEffort::Quick).size();
  b.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return b;
}

// Encodes at PngEffort::Small the variants whose quick PNG is within kJudgedMargin of the smallest.
void judgeVariants(std::vector<BuiltVariant>& built, int threads) {
  std::size_t bestQuick = SIZE_MAX;
  for (const BuiltVariant& b : built)
    if (b.image) bestQuick = std::min(bestQuick, b.quickBytes);
  parallelFor(built.size(), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      BuiltVariant& b = built[v];
      if (!b.image || b.judged() || static_cast<double>(b.quickBytes) > kJudgedMargin * static_cast<double>(bestQuick)) continue;
      const auto start = Clock::now();
      b.pngBytes = encodePng(*b.image, nullptr, PngEffort::Small).size();
      b.seconds += std::chrono::duration<double>(Clock::now() - start).count();
    }
  });
}

// Builds the variants, each on its own thread (they share nothing).
std::vector<BuiltVariant> buildVariants(const SolidGrid& grid, const std::vector<Variant>& variants,
                                        const ConvertOptions& options) {
  std::vector<BuiltVariant> built(variants.size());
  parallelFor(variants.size(), 1, options.solid.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) built[v] = buildVariant(grid, variants[v], options);
  });
  return built;
}

// The variants of one starting grid: no extraction (when the grid is small enough to be
// a flat block), the priced search (`priced`, small grids), and repeats only or repeats and
// splits at each threshold, from many small blocks to a few large ones (BlockOptions::minSavedCells).
// Block extraction pays on repetitive buildings and costs headers and metadata on small ones,
// and PNG compression already shrinks repeated rows of a flat grid; so every variant is compiled
// and the smallest is kept (each is reported).
std::vector<Variant> variantsOf(const StartingGrid& g, const BlockOptions& base, std::size_t gridCells, bool priced) {
  const bool flatFeasible = gridCells <= kMaxFlatCells;
  const std::string start = (g.turned.cube == 0 ? "" : ", axes turned by rotation " + std::to_string(g.turned.cube)) +
                             (g.hiddenFilled ? ", hidden cells filled" : "");
  std::vector<Variant> list;
  if (!base.automatic || flatFeasible) {
    list.push_back({"none" + start, base, &g});
    list.back().options.automatic = false;
  }
  if (!base.automatic) return list;
  if (priced && gridCells <= kMaxPricedGridCells) {
    list.push_back({"priced" + start, base, &g});
    list.back().options.priced = true;
  }
  for (long long minSaved : kMinSavedCellsTried) {
    if (!flatFeasible && minSaved > kMaxMinSavedCellsLargeGrid) continue;
    const std::string suffix = " (>= " + std::to_string(minSaved) + " cells" + start + ")";
    list.push_back({"repeats" + suffix, base, &g});
    list.back().options.cuts = false;
    list.back().options.minSavedCells = minSaved;
    list.push_back({"repeats+splits" + suffix, base, &g});
    list.back().options.minSavedCells = minSaved;
  }
  return list;
}

// The grids the variants start from: the solid grid with its hidden cells as they are and, when
// enough of them are hidden, filled, each in every axis order (axis_order.hpp). A grid too large
// for a flat variant is tried in one axis order and one start, the filled one when enough cells
// are hidden: a second start would double the high-rise's block search. Equal neighbouring
// layers are merged once here (not with manual blocks: they are world boxes snapped to the cells
// of the grid as it is).
std::vector<StartingGrid> startingGrids(const SolidGrid& grid, const ConvertOptions& options) {
  const bool manual = !options.blocks.manual.empty();
  const std::size_t cells = grid.block.cells.size();
  std::vector<StartingGrid> grids;
  const auto add = [&](Block start, bool filled) {
    if (!manual) simplify(start);
    const std::size_t first = grids.size();
    grids.push_back({{std::move(start), 0, glm::dvec3(0.0)}, filled});
    if (!manual && cells <= kMaxFlatCells && options.axisOrder)
      for (int cube : axisOrderRotations())
        if (cube != 0) grids.push_back({turnBlock(grids[first].turned.block, cube), filled});
  };
  Block filled = grid.block;
  const bool fill = static_cast<double>(fillHiddenCells(filled, grid.materials)) >= kMinHiddenShareForFill * static_cast<double>(cells);
  if (cells <= kMaxFlatCells || !fill) add(grid.block, false);
  if (fill) add(std::move(filled), true);
  return grids;
}

// Every variant that is tried, built and judged. With several starting grids, each is probed with
// the last variant of its list (fewest, largest blocks). Of the grids with hidden cells as they
// are, and of those with hidden cells filled, the two whose probes are smallest get every variant,
// the first of them also the priced one: a probe misjudges a full search often enough that taking
// the best two over both kinds lost up to 10 % (street_d).
void buildCandidates(const SolidGrid& grid, const std::vector<StartingGrid>& starts, const BlockOptions& base,
                     const ConvertOptions& options, std::vector<Variant>& variants, std::vector<BuiltVariant>& built) {
  const std::size_t cells = grid.block.cells.size();
  std::vector<const StartingGrid*> searched{&starts[0]};
  if (starts.size() > 1) {
    for (const StartingGrid& g : starts) variants.push_back(variantsOf(g, base, cells, false).back());
    built = buildVariants(grid, variants, options);
    judgeVariants(built, options.solid.threads);
    std::vector<std::size_t> rank(starts.size());
    for (std::size_t i = 0; i < rank.size(); ++i) rank[i] = i;
    std::stable_sort(rank.begin(), rank.end(), [&](std::size_t x, std::size_t y) { return smaller(built[x], built[y]); });
    searched.clear();
    for (const std::size_t i : rank) {
      const auto alike = std::count_if(searched.begin(), searched.end(), [&](const StartingGrid* g) { return g->hiddenFilled == starts[i].hiddenFilled; });
      if (alike < 2) searched.push_back(&starts[i]);
    }
  }
  // The grids searched get every variant, which all start with the same look at the grid.
  std::vector<std::shared_ptr<const GridSearch>> searches(searched.size());
  if (base.automatic && base.manual.empty())
    parallelFor(searched.size(), 1, options.solid.threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) searches[i] = searchGrid(searched[i]->turned.block, base.toleranceM);
    });
  std::vector<Variant> more;
  for (std::size_t i = 0; i < searched.size(); ++i) {
    const bool firstOfItsKind = std::none_of(searched.begin(), searched.begin() + static_cast<std::ptrdiff_t>(i),
                                             [&](const StartingGrid* g) { return g->hiddenFilled == searched[i]->hiddenFilled; });
    std::vector<Variant> list = variantsOf(*searched[i], base, cells, firstOfItsKind);
    if (starts.size() > 1) list.pop_back();  // the probe, built already
    for (Variant& v : list) v.search = searches[i].get();
    more.insert(more.end(), list.begin(), list.end());
  }
  std::vector<BuiltVariant> moreBuilt = buildVariants(grid, more, options);
  variants.insert(variants.end(), more.begin(), more.end());
  std::move(moreBuilt.begin(), moreBuilt.end(), std::back_inserter(built));
  judgeVariants(built, options.solid.threads);  // against the best of all, probes included
}

// Reports every variant and returns the smallest, in variant order on ties so that the choice does
// not depend on timing; none when no variant compiled (lastError says why).
std::optional<std::size_t> smallestVariant(const std::vector<Variant>& variants, const std::vector<BuiltVariant>& built,
                                           ConvertReport& report, std::string& lastError) {
  std::optional<std::size_t> chosen;
  report.variants.clear();
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const BuiltVariant& b = built[v];
    VariantReport entry{variants[v].name, 0, 0, 0, 0, b.seconds, ""};
    if (b.image) {
      entry.blocks = static_cast<int>(b.hierarchy->blocks.size());
      entry.bytesRaw = static_cast<long long>(b.image->byteSize());
      entry.bytesPngQuick = static_cast<long long>(b.quickBytes);
      entry.bytesPng = static_cast<long long>(b.pngBytes);
      if (!chosen || smaller(b, built[*chosen])) chosen = v;
    } else {
      entry.error = b.image.error().message;
      lastError = b.image.error().message;
    }
    report.variants.push_back(entry);
  }
  return chosen;
}

// Axes refined to shared boundaries (share_axes.hpp) pay on some buildings and cost on others
// (the house 8 % smaller, the street 6-15 % larger: data components that were equal no longer
// are), so the refinement is tried on the kept variant and kept when its PNG is smaller: at the
// effort the variants were judged at on small grids (a quick PNG misjudged the house by 2 %),
// quick on large ones (the high-rise's small PNG takes 44 ms, 6 % of its conversion). Returns the
// number of axes refined and kept.
int shareAxesIfSmaller(BuiltVariant& b, std::size_t gridCells, const CompileOptions& compileOptions) {
  const PngEffort effort = gridCells <= kMaxPricedGridCells ? PngEffort::Small : PngEffort::Quick;
  Hierarchy shared = *b.hierarchy;
  const int refined = shareAxes(shared, compileOptions.heuristicToleranceM);
  if (refined == 0) return 0;
  auto image = compile(shared, compileOptions);
  if (!image || encodePng(*image, nullptr, effort).size() >= (effort == PngEffort::Small ? b.pngBytes : b.quickBytes)) return 0;
  *b.hierarchy = std::move(shared);
  b.image = std::move(image);
  return refined;
}

// Builds hierarchy variants from the grid, compiles each and keeps in `out` the one whose PNG is
// smallest. False when none fits an HNI (lastError says why).
bool buildHni(const SolidGrid& grid, const ConvertOptions& options, Conversion& out, ConvertReport& report,
              std::string& lastError, const std::function<void(std::string_view, double)>& progress) {
  progress("hierarchy", 0);
  BlockOptions base = options.blocks;
  base.toleranceM = options.solid.toleranceM;
  base.heuristicToleranceM = options.compile.heuristicToleranceM;
  const std::vector<StartingGrid> starts = startingGrids(grid, options);
  std::vector<Variant> variants;
  std::vector<BuiltVariant> built;
  buildCandidates(grid, starts, base, options, variants, built);
  const std::optional<std::size_t> chosen = smallestVariant(variants, built, report, lastError);
  progress("hierarchy", 1);
  if (!chosen) return false;
  BuiltVariant& b = built[*chosen];
  report.sharedAxes = shareAxesIfSmaller(b, grid.block.cells.size(), options.compile);
  out.hierarchy = std::move(*b.hierarchy);
  out.image = std::move(*b.image);
  report.blocks = std::move(b.stats);
  report.splitBlocks = b.split;
  report.blockMode = variants[*chosen].name;
  report.axisOrderCube = variants[*chosen].grid->turned.cube;
  report.hiddenCellsFilled = variants[*chosen].grid->hiddenFilled;
  report.hni = computeStats(out.image);
  return true;
}

using Progress = std::function<void(std::string_view, double)>;

// What a building's files take: its HNI as a small PNG and its complementary mesh as
// meshopt-compressed glTF with gzip (mesh_size.hpp), none when the mesh is empty.
std::uint64_t filesBytes(const Image& image, const TriangleMesh& complement) {
  return encodePng(image, nullptr, PngEffort::Small).size() +
         (complement.triangles.empty() ? 0 : measureMesh(complement).glbGzipBytes);
}

double nutShare(const SolidStats& s) { return s.areaM2 > 0 ? s.nutAreaM2 / s.areaM2 : 0.0; }

// One way of converting a building, as the choice between two sees it.
struct Outcome {
  std::uint64_t bytes;
  double nutShare;
};

// Whether `a` is kept over `b` (ConvertOptions::objective). Shares of the surface within 0.1 % of
// each other count as equal, and then the smaller files win.
bool preferred(const Outcome& a, const Outcome& b, ConvertOptions::Objective objective) {
  constexpr double kSameShare = 1e-3;
  if (objective == ConvertOptions::Objective::MostSurface && std::abs(a.nutShare - b.nutShare) > kSameShare)
    return a.nutShare > b.nutShare;
  return a.bytes < b.bytes;
}

// Converts the mesh in the frame it is in into `out`: its solid grid, and the smallest hierarchy
// made from it. When no hierarchy fits an HNI, the grid is built again coarser: first keeping
// only slopes that became wedges everywhere, then with the tolerance doubled, each time with a
// warning in the report. `enclosing`: the whole building, when the mesh is a part of it
// (wings.hpp); `part` names the part in the phases' names. out.report.check must be set.
Status convertInFrame(const TriangleMesh& mesh, const TriangleMesh* enclosing, const ConvertOptions& options, Conversion& out,
                      Phases& phases, const std::string& part, const Progress& progress) {
  ConvertReport& report = out.report;
  std::optional<SolidGrid> grid;
  std::string lastError;
  for (int coarser = 0; coarser < kCoarserAttempts; ++coarser) {
    SolidOptions solidOptions = options.solid;
    solidOptions.closedSurface = report.closedSurface();
    solidOptions.enclosing = enclosing;
    solidOptions.progress = [&](double f) { progress("solid", f); };
    if (coarser > 0) solidOptions.partialWedges = false;
    if (coarser > 1) solidOptions.toleranceM *= std::pow(2.0, coarser - 1);
    progress("solid", 0);
    SolidOptions plainOptions = solidOptions;
    plainOptions.planeCells = false;
    auto built = buildSolidGrid(mesh, plainOptions);
    if (!built) return built.error();
    // With plane cells, a second candidate: the grid built with boundaries at the planes' corners
    // (solid.hpp), when it adds any, and plane cells fitted to it.
    std::optional<SolidGrid> planeGrid;
    if (solidOptions.planeCells && !built->complement.triangles.empty()) {
      auto cornered = buildSolidGrid(mesh, solidOptions);
      planeGrid = cornered && cornered->stats.planeBoundaries > 0 ? std::move(*cornered) : *built;
      const PlaneFitStats fitted = fitPlaneCells(*planeGrid, enclosing ? *enclosing : mesh, solidOptions);
      SolidStats& s = planeGrid->stats;
      s.planeCells = fitted.planeCells;
      s.twoPlaneCells = fitted.twoPlaneCells;
      // What the mesh still draws that no cell shows: its surface less what is still drawn twice.
      s.drawnTwiceAreaM2 = std::clamp(s.drawnTwiceAreaM2 - fitted.drawnTwiceM2, 0.0, fitted.complementLeftM2);
      const double complementLeft = fitted.complementLeftM2 - s.drawnTwiceAreaM2;
      s.nutAreaM2 += std::max(0.0, s.complementAreaM2 - complementLeft);
      s.complementAreaM2 = std::min(s.complementAreaM2, complementLeft);
      // Without plane cells it is still a candidate when the planes' corners let boxes show more
      // (walls under a roof whose eaves no face ended at).
      if (fitted.planeCells == 0 && s.nutAreaM2 <= built->stats.nutAreaM2) planeGrid.reset();
    }
    if (coarser > 0)
      report.warnings.push_back("the grid did not fit an HNI (" + lastError + "); built again with " +
                                (coarser == 1 ? std::string("only slopes that are wedges everywhere")
                                              : "tolerance " + std::to_string(solidOptions.toleranceM) + " m"));
    grid = std::move(*built);
    report.solid = grid->stats;
    const SolidStats& s = grid->stats;
    report.insideTest =
        enclosing
            ? "generalized winding number of the whole building at cell centres (the building converted in two parts)"
        : report.closedSurface()
            ? "crossings counted along the lines of cell centres (closed surface, T-junctions matched); generalized "
              "winding number on " +
                  std::to_string(s.windingColumns) + " of " + std::to_string(s.columns) + " lines"
            : "generalized winding number at cell centres (open surface: no closed surface needed)";
    out.originM = report.originM = grid->originM;
    const std::string suffix = part + (coarser == 0 ? "" : " (coarser " + std::to_string(coarser) + ")");
    phases.end("solid" + suffix);
    const bool fits = buildHni(*grid, options, out, report, lastError, progress);
    // A plane cell never equals a cell elsewhere, so plane cells break the block's repeats: the
    // grid with them is kept only when it is preferred (by default, when its PNG and
    // complementary mesh together are smaller).
    if (fits && planeGrid) {
      Conversion withPlanes;
      ConvertReport planeReport = report;
      planeReport.solid = planeGrid->stats;
      std::string planeError;
      if (buildHni(*planeGrid, options, withPlanes, planeReport, planeError, progress) &&
          preferred({filesBytes(withPlanes.image, planeGrid->complement), nutShare(planeGrid->stats)},
                    {filesBytes(out.image, grid->complement), nutShare(grid->stats)}, options.objective)) {
        out.hierarchy = std::move(withPlanes.hierarchy);
        out.image = std::move(withPlanes.image);
        report = std::move(planeReport);
        grid = std::move(planeGrid);
      }
    }
    phases.end("hierarchy" + suffix);
    if (fits) break;
    grid.reset();
  }
  if (!grid) return Error{mesh.name + ": " + lastError};
  out.complement = std::move(grid->complement);
  return Ok{};
}

// The part of a wing's walls on its side of the cut below which a building is not cut
// (findTurnedWing).
constexpr double kMinWingShare = 0.1;

std::uint64_t bytesOnDisk(const Conversion& c) { return filesBytes(c.image, c.complement); }

// Converts a building aligned to its frame into `out` (root origin, hierarchy, image and
// complementary mesh in that frame). When a wing turned against it is found (wings.hpp), the
// building is also converted cut in two, the wing in its own frame, and that is kept when its
// files are smaller.
Status convertBuilding(const TriangleMesh& mesh, const ConvertOptions& options, Conversion& out, Phases& phases,
                       const Progress& progress) {
  if (Status s = convertInFrame(mesh, nullptr, options, out, phases, "", progress); !s) return s;
  if (!options.turnedWings || !options.blocks.manual.empty()) return Ok{};
  const double tol = options.solid.toleranceM;
  const std::optional<WingCut> cut = findTurnedWing(mesh, options.solid.angleToleranceDeg, tol, kMinWingShare);
  if (!cut) return Ok{};
  WingReport& wing = out.report.wing;
  wing.found = true;
  wing.yawDeg = yawDegrees(cut->yaw);
  wing.axis = cut->axis;
  wing.cutM = cut->atM;
  wing.wallShare = cut->wingShare;

  // Each part reaches a tolerance across the cut, so that the cells beside it are whole in both.
  const double reach = cut->wingAbove ? tol : -tol;
  const TriangleMesh mainPart = clipToHalfSpace(mesh, cut->axis, cut->atM + reach, !cut->wingAbove);
  TriangleMesh wingPart = clipToHalfSpace(mesh, cut->axis, cut->atM - reach, cut->wingAbove);
  const YawFrame wingFrame{cut->yaw, wingPart.bounds().centre()};
  toAlignedFrame(wingPart, wingFrame);
  TriangleMesh turned = mesh;
  toAlignedFrame(turned, wingFrame);
  Conversion joined, wingOnly;
  joined.report.check = wingOnly.report.check = out.report.check;
  Status s = convertInFrame(mainPart, &mesh, options, joined, phases, " (main part)", progress);
  if (s) s = convertInFrame(wingPart, &turned, options, wingOnly, phases, " (wing)", progress);
  if (!s) {
    out.report.warnings.push_back("a wing turned by " + std::to_string(wing.yawDeg) + " degrees was not converted apart: " + s.error().message);
    return Ok{};
  }
  joined.originM = joinAtCut(joined.hierarchy, joined.originM, wingOnly.hierarchy, wingFrame, wingOnly.originM, *cut);
  auto image = compile(joined.hierarchy, options.compile);
  if (!image) {
    out.report.warnings.push_back("a wing turned by " + std::to_string(wing.yawDeg) + " degrees was not converted apart: " + image.error().message);
    return Ok{};
  }
  joined.image = std::move(*image);
  toWorldFrame(wingOnly.complement, wingFrame);
  auto complement = mergeMeshes({clipToHalfSpace(joined.complement, cut->axis, cut->atM, !cut->wingAbove),
                                 clipToHalfSpace(wingOnly.complement, cut->axis, cut->atM, cut->wingAbove)},
                                out.complement.name);
  if (!complement) return complement.error();
  joined.complement = std::move(*complement);
  wing.bytesWithout = bytesOnDisk(out);
  wing.bytesWith = bytesOnDisk(joined);
  phases.end("wing join");
  const double joinedShare = (joined.report.solid.nutAreaM2 + wingOnly.report.solid.nutAreaM2) / mesh.area();
  if (!preferred({wing.bytesWith, joinedShare}, {wing.bytesWithout, nutShare(out.report.solid)}, options.objective))
    return Ok{};
  wing.applied = true;
  // The main part's grid and hierarchy stand for the building in the report, with the surface
  // of both parts (each counts its strip across the cut: a tolerance wide).
  ConvertReport& r = out.report;
  const ConvertReport& main = joined.report;
  r.solid = main.solid;
  r.solid.areaM2 = mesh.area();
  r.solid.complementAreaM2 += wingOnly.report.solid.complementAreaM2;
  r.solid.hiddenAreaM2 += wingOnly.report.solid.hiddenAreaM2;
  r.solid.drawnTwiceAreaM2 += wingOnly.report.solid.drawnTwiceAreaM2;
  r.solid.nutAreaM2 += wingOnly.report.solid.nutAreaM2;
  r.insideTest = main.insideTest;
  r.blocks = main.blocks;
  r.variants = main.variants;
  r.blockMode = main.blockMode;
  r.axisOrderCube = main.axisOrderCube;
  r.hiddenCellsFilled = main.hiddenCellsFilled;
  r.splitBlocks = main.splitBlocks;
  r.sharedAxes = main.sharedAxes;
  r.warnings.insert(r.warnings.end(), main.warnings.begin(), main.warnings.end());
  r.warnings.insert(r.warnings.end(), wingOnly.report.warnings.begin(), wingOnly.report.warnings.end());
  wing.cells = wingOnly.report.solid.cells;
  wing.blocks = static_cast<int>(wingOnly.hierarchy.blocks.size());
  r.originM = out.originM = joined.originM;
  out.hierarchy = std::move(joined.hierarchy);
  out.image = std::move(joined.image);
  r.hni = computeStats(out.image);
  out.complement = std::move(joined.complement);
  return Ok{};
}

// Converts a checked mesh (out.report.check set) in the frame of its dominant orientation, and
// adds `sheets` (world frame) to its complementary mesh.
Status convertChecked(TriangleMesh mesh, const TriangleMesh* sheets, const ConvertOptions& options, Conversion& out,
                      const Progress& progress) {
  ConvertReport& report = out.report;
  Phases phases(report.phases);
  // A building turned about the vertical is converted in its own frame (align.hpp); a dominant
  // orientation within the angle tolerance of the axes needs no turn.
  const std::uint16_t yaw = dominantYaw(mesh, options.solid.angleToleranceDeg);
  report.yawDeg = yawDegrees(yaw);
  std::optional<YawFrame> frame;
  if (options.alignYaw && std::abs(report.yawDeg) > options.solid.angleToleranceDeg) {
    if (options.blocks.manual.empty()) {
      frame = YawFrame{yaw, mesh.bounds().centre()};
      toAlignedFrame(mesh, *frame);
    } else {
      char degrees[32];
      std::snprintf(degrees, sizeof degrees, "%.2f", report.yawDeg);
      report.warnings.push_back(std::string("the building is turned by ") + degrees +
                                " degrees but not aligned: --block boxes are world boxes");
    }
  }
  report.yawApplied = frame.has_value();

  if (Status s = convertBuilding(mesh, options, out, phases, progress); !s) return s;
  if (frame) {
    // Back to the world: the hierarchy inside a yaw redirection, compiled again, and the
    // complementary mesh turned back.
    out.originM = report.originM = wrapInWorldFrame(out.hierarchy, out.originM, *frame);
    auto image = compile(out.hierarchy, options.compile);
    if (!image) return Error{mesh.name + ": " + image.error().message};
    out.image = std::move(*image);
    report.hni = computeStats(out.image);
    toWorldFrame(out.complement, *frame);
    phases.end("align");
  }
  if (sheets) {
    auto complement = mergeMeshes(std::vector<const TriangleMesh*>{&out.complement, sheets}, out.complement.name);
    if (!complement) return Error{mesh.name + ": " + complement.error().message};
    out.complement = std::move(*complement);
    report.solid.areaM2 += sheets->area();
    report.solid.complementAreaM2 += sheets->area();
  }
  report.complementTriangles = out.complement.triangles.size();
  return Ok{};
}

}  // namespace

double ConvertReport::seconds() const {
  double sum = 0;
  for (const PhaseTiming& p : phases) sum += p.seconds;
  return sum;
}

Result<Conversion> convertMesh(TriangleMesh mesh, const ConvertOptions& options) {
  Conversion out;
  ConvertReport& report = out.report;
  report.name = mesh.name;
  report.inputTriangles = mesh.triangles.size();
  const Progress progress = [&](std::string_view phase, double fraction) {
    if (options.progress) options.progress(phase, fraction);
  };
  {
    Phases phases(report.phases);
    progress("check", 0);
    report.check = checkAndRepair(mesh);
    if (mesh.triangles.empty())
      return Error{mesh.name + ": nothing to convert: all " + std::to_string(report.inputTriangles) +
                   " faces are degenerate"};
    phases.end("check");
  }
  // An open mesh may be a body with sheets hanging off it (sheets.hpp): for the most surface, it
  // is also converted as the body, the sheets drawn as mesh. For the smallest files that is rarely
  // smaller (1 of Zurich's 38 buildings with sheets, by 125 B) and not worth the time.
  std::optional<SheetSplit> split;
  if (options.objective == ConvertOptions::Objective::MostSurface && !report.check.closedSurface) {
    Phases phases(report.phases);
    progress("sheets", 0);
    split = detachSheets(mesh, options.solid.toleranceM);
    phases.end("sheets");
  }
  const ConvertReport checked = report;
  if (Status s = convertChecked(std::move(mesh), nullptr, options, out, progress); !s) return s.error();
  if (!split) return out;

  Conversion body;
  body.report = checked;
  SheetReport& sheets = body.report.sheets;
  // Applied while the body is converted, so that closedSurface() speaks for it; decided below.
  sheets.found = sheets.applied = true;
  sheets.triangles = split->sheets.triangles.size();
  sheets.areaM2 = split->sheets.area();
  sheets.cutTriangles = split->cutTriangles;
  sheets.bodyClosed = split->closed;
  sheets.hiddenTriangles = split->hiddenTriangles;
  if (Status s = convertChecked(std::move(split->body), &split->sheets, options, body, progress); !s) {
    report.warnings.push_back("the mesh was not converted without its open sheets: " + s.error().message);
    return out;
  }
  sheets.bytesWithout = bytesOnDisk(out);
  sheets.bytesWith = bytesOnDisk(body);
  sheets.nutShareWithout = nutShare(out.report.solid);
  sheets.nutShareWith = nutShare(body.report.solid);
  sheets.applied = preferred({sheets.bytesWith, sheets.nutShareWith}, {sheets.bytesWithout, sheets.nutShareWithout},
                             options.objective);
  if (!sheets.applied) {
    report.sheets = sheets;
    return out;
  }
  return body;
}

HniText hniText(const Conversion& conversion) {
  HniText text;
  text.name = conversion.report.name;
  text.generator = "nut convert";
  text.originM = conversion.originM;
  return text;
}

Status writeConversion(Conversion& conversion, const std::string& pngPath, const std::string& complementPath,
                       PngEffort effort) {
  if (Status s = writeHni(pngPath, conversion.image, hniText(conversion), effort); !s) return s;
  std::error_code ec;
  conversion.report.pngBytes = std::filesystem::file_size(pngPath, ec);
  if (complementPath.empty()) return Ok{};
  return writeComplement(complementPath, conversion.complement);
}

Status writeComplement(const std::string& path, const TriangleMesh& mesh) {
  if (!scene::isGlbPath(path)) return writeObj(path, mesh);
  const std::vector<std::uint8_t> glb = meshoptGlb(mesh);
  return writeTextFile(path, std::string(glb.begin(), glb.end()));  // written whole, any bytes
}

Result<std::vector<scene::ComplementLevel>> writeComplementLevels(const std::string& path, const TriangleMesh& mesh,
                                                                  int levels) {
  std::vector<scene::ComplementLevel> written;
  if (levels <= 0) return written;
  MeshLodOptions options;
  options.maxLevels = levels;
  const std::filesystem::path file(path);
  for (const MeshLevel& level : meshLevels(mesh, options)) {
    const std::string name =
        file.stem().string() + ".lod" + std::to_string(written.size() + 1) + file.extension().string();
    if (Status s = writeComplement((file.parent_path() / name).string(), level.mesh); !s) return s.error();
    written.push_back({name, level.errorM});
  }
  return written;
}

namespace {

nlohmann::json wingJson(const WingReport& w) {
  if (!w.found) return nullptr;
  nlohmann::json j{{"yaw_deg", w.yawDeg},
                   {"cut", {{"axis", std::string(1, "xyz"[w.axis])}, {"at_m", w.cutM}}},
                   {"wall_share", w.wallShare},
                   {"bytes_without", w.bytesWithout},
                   {"bytes_with", w.bytesWith},
                   {"applied", w.applied}};
  if (w.applied) {
    j["cells"] = w.cells;
    j["blocks"] = w.blocks;
  }
  return j;
}

}  // namespace

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
  for (const VariantReport& v : r.variants) {
    if (!v.error.empty()) {
      variants.push_back({{"name", v.name}, {"error", v.error}});
      continue;
    }
    json entry{{"name", v.name}, {"blocks", v.blocks}, {"bytes_raw", v.bytesRaw}, {"bytes_png_quick", v.bytesPngQuick}, {"seconds", v.seconds}};
    if (v.bytesPng > 0) entry["bytes_png"] = v.bytesPng;
    variants.push_back(entry);
  }
  const SolidStats& s = r.solid;
  const double area = s.areaM2 > 0 ? s.areaM2 : 1;
  const json j = {{"name", r.name},
                  {"origin_m", vec3Json(r.originM)},
                  {"seconds", r.seconds()},
                  {"phases_seconds", phases},
                  {"input",
                   {{"triangles", r.inputTriangles},
                    {"vertices", r.check.vertices},
                    {"degenerate_removed", r.check.degenerate},
                    {"slivers", r.check.slivers},
                    {"duplicate_faces", r.check.duplicateFaces},
                    {"boundary_edges", r.check.boundaryEdges},
                    {"non_manifold_edges", r.check.nonManifoldEdges},
                    {"inconsistent_edges", r.check.inconsistentEdges},
                    {"pieces", r.check.components},
                    {"flipped_faces", r.check.flippedTriangles},
                    {"closed", r.check.closed()},
                    {"closed_surface", r.check.closedSurface}}},
                  {"sheets",
                   {{"found", r.sheets.found},
                    {"applied", r.sheets.applied},
                    {"body_closed", r.sheets.bodyClosed},
                    {"triangles", r.sheets.triangles},
                    {"area_m2", r.sheets.areaM2},
                    {"cut_triangles", r.sheets.cutTriangles},
                    {"hidden_triangles", r.sheets.hiddenTriangles},
                    {"bytes_with", r.sheets.bytesWith},
                    {"bytes_without", r.sheets.bytesWithout},
                    {"nut_share_with", r.sheets.nutShareWith},
                    {"nut_share_without", r.sheets.nutShareWithout}}},
                  {"inside_test", r.insideTest},
                  {"alignment", {{"yaw_deg", r.yawDeg}, {"applied", r.yawApplied}}},
                  {"wing", wingJson(r.wing)},
                  {"grid",
                   {{"planes", s.planes},
                    {"cells", s.cells},
                    {"sweep_axis", std::string(1, "xyz"[s.sweepAxis])},
                    {"slopes", s.slopes},
                    {"slopes_as_wedges", s.slopesAsWedges},
                    {"slope_boundaries", s.slopeBoundaries},
                    {"material_boundaries", s.materialBoundaries},
                    {"trimmed_cells", s.trimmedCells},
                    {"trim_boundaries", s.trimBoundaries},
                    {"plane_boundaries", s.planeBoundaries},
                    {"solid_cells", s.solidCells},
                    {"wedge_cells", s.wedgeCells},
                    {"quadric_cells", s.quadricCells},
                    {"sphere_octant_cells", s.sphereOctantCells},
                    {"pyramid_cells", s.pyramidCells},
                    {"plane_cells", s.planeCells},
                    {"two_plane_cells", s.twoPlaneCells},
                    {"builds", s.gridBuilds},
                    {"builds_classified", s.gridsClassified},
                    {"winding_columns", s.windingColumns},
                    {"winding_evaluations", s.windingEvaluations},
                    {"ambiguous_cells", s.ambiguousCells}}},
                  {"surface",
                   {{"area_m2", s.areaM2},
                    {"nut_m2", s.nutAreaM2},
                    {"complement_m2", s.complementAreaM2},
                    {"hidden_m2", s.hiddenAreaM2},
                    {"drawn_twice_m2", s.drawnTwiceAreaM2},
                    {"nut_fraction", s.nutAreaM2 / area},
                    {"complement_fraction", s.complementAreaM2 / area},
                    {"complement_triangles", r.complementTriangles}}},
                  {"blocks",
                   {{"mode", r.blockMode},
                    {"axis_order_rotation", r.axisOrderCube},
                    {"hidden_cells_filled", r.hiddenCellsFilled},
                    {"variants", variants},
                    {"found", found},
                    {"split_for_limits", r.splitBlocks},
                    {"axes_shared", r.sharedAxes},
                    {"cells_before", r.blocks.cellsBefore},
                    {"cells_after", r.blocks.cellsAfter},
                    {"bytes_estimate_before", r.blocks.bytesBefore},
                    {"bytes_estimate_after", r.blocks.bytesAfter}}},
                  {"hni",
                   {{"blocks", r.hni.blocks},
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
